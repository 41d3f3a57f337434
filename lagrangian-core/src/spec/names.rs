//! How the names that expansion makes are spelled while a spec is lowered
//! and as users read them: element `k` of family `x` is `x‿k` (read
//! `x[k]`), name `k` of part instance `front` is `front⁀k` (read `front.k`).
//! Both connectors are connector punctuation (which identifiers may hold)
//! that no spec name may contain.

use std::borrow::Cow;

/// Between a family's name and an element's number while lowering.
pub(super) const MARK: char = '‿';
/// Between a part instance's name and a name of its part while lowering.
pub(super) const MEMBER: char = '⁀';

/// `name` as users read it: `x‿3` is `x[3]`, `front⁀k` is `front.k`.
pub(crate) fn display_name(name: &str) -> Cow<'_, str> {
    if !name.contains([MARK, MEMBER]) {
        return Cow::Borrowed(name);
    }
    let mut out = String::with_capacity(name.len() + 2);
    let mut chars = name.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            MARK => {
                out.push('[');
                while let Some(d) = chars.next_if(|d| d.is_ascii_digit() || *d == '-') {
                    out.push(d);
                }
                out.push(']');
            }
            MEMBER => out.push('.'),
            c => out.push(c),
        }
    }
    Cow::Owned(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_element_reads_with_its_brackets() {
        assert_eq!(display_name("x‿12"), "x[12]");
        assert_eq!(display_name("x‿3_dot"), "x[3]_dot");
        assert_eq!(display_name("plain"), "plain");
    }

    #[test]
    fn a_member_reads_with_a_dot() {
        assert_eq!(display_name("front⁀k"), "front.k");
        assert_eq!(display_name("car‿2⁀wall⁀crush_dx"), "car[2].wall.crush_dx");
    }
}
