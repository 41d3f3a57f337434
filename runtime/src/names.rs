//! "Did you mean …?" for names: the compiler's diagnostics, the scenario
//! reader and a model's `set_parameter` suggest the closest known name.
//! Also the names of the columns every trajectory has, which the spec's own
//! names must not take.

/// The longest name compared for a suggestion (in characters): a longer
/// name, or candidate, gets none, so that a hostile name costs no time.
pub const MAX_COMPARED_LENGTH: usize = 256;

/// The closest name to `wanted` among `candidates`, for "did you mean" hints:
/// one within a third of the longer name's length in edits (at least 1).
///
/// Bounded in time: a candidate whose length differs from `wanted`'s by
/// more than the edits allowed is skipped unread, and the distance is
/// computed in a band of that width, so each candidate costs at most
/// `MAX_COMPARED_LENGTH` × (2 × allowed + 1) steps.
pub fn closest<'a>(wanted: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    let wanted: Vec<char> = wanted.chars().collect();
    if wanted.len() > MAX_COMPARED_LENGTH {
        return None;
    }
    candidates
        .into_iter()
        .filter_map(|c| {
            let length = c.chars().count();
            let allowed = (wanted.len().max(length) / 3).max(1);
            if length > MAX_COMPARED_LENGTH || length.abs_diff(wanted.len()) > allowed {
                return None;
            }
            let c_chars: Vec<char> = c.chars().collect();
            distance_within(&wanted, &c_chars, allowed).map(|d| (d, c))
        })
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| c)
}

/// Optimal-string-alignment distance: insertions, deletions, substitutions
/// and transpositions of neighbours each count 1 (`t_ned` is 1 from `t_end`).
#[cfg(test)]
fn edit_distance(a: &str, b: &str) -> usize {
    let (a, b): (Vec<char>, Vec<char>) = (a.chars().collect(), b.chars().collect());
    distance_within(&a, &b, a.len().max(b.len())).expect("no distance exceeds the longer length")
}

/// The optimal-string-alignment distance between `a` and `b` when it is at
/// most `limit`, else `None`; only the cells within `limit` of the
/// diagonal are computed (a path outside that band costs more than `limit`).
fn distance_within(a: &[char], b: &[char], limit: usize) -> Option<usize> {
    if a.len().abs_diff(b.len()) > limit {
        return None;
    }
    let beyond = limit + 1;
    // Rows i − 2, i − 1 and i of the distance table between prefixes; a
    // cell outside the band holds `beyond`.
    let mut before: Vec<usize> = vec![beyond; b.len() + 1];
    let mut previous: Vec<usize> = (0..=b.len()).map(|j| j.min(beyond)).collect();
    let mut current = vec![beyond; b.len() + 1];
    for i in 1..=a.len() {
        let (low, high) = (i.saturating_sub(limit).max(1), (i + limit).min(b.len()));
        current[0] = i.min(beyond);
        current[low - 1] = if low == 1 { current[0] } else { beyond };
        for j in low..=high {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            let mut d = (previous[j] + 1)
                .min(current[j - 1] + 1)
                .min(previous[j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                d = d.min(before[j - 2] + 1);
            }
            current[j] = d.min(beyond);
        }
        if high < b.len() {
            current[high + 1] = beyond;
        }
        std::mem::swap(&mut before, &mut previous);
        std::mem::swap(&mut previous, &mut current);
    }
    let d = previous[b.len()];
    (d <= limit).then_some(d)
}

/// The time column of a trajectory.
pub const TIME_COLUMN: &str = "t";

/// The energy columns of a trajectory (in J), after the coordinates',
/// velocities' and accelerations' columns.
pub const ENERGY_COLUMNS: [&str; 4] = [
    "kinetic_energy",
    "potential_energy",
    "dissipated_energy",
    "external_work",
];

/// The velocity column of coordinate `q`: `q_dot`.
pub fn velocity_column(q: &str) -> String {
    format!("{q}_dot")
}

/// The acceleration column of coordinate `q`: `q_ddot`.
pub fn acceleration_column(q: &str) -> String {
    format!("{q}_ddot")
}

/// What `name` is among the built-in columns of a trajectory of a model
/// with `coordinates` (the time, an energy, a coordinate's velocity or
/// acceleration), or `None` when it is none of them. A coordinate's own
/// column is not counted: it is the coordinate's name.
pub fn builtin_column<'a>(
    name: &str,
    coordinates: impl IntoIterator<Item = &'a str>,
) -> Option<String> {
    if name == TIME_COLUMN {
        return Some("the time".into());
    }
    if ENERGY_COLUMNS.contains(&name) {
        return Some(format!("the energy column `{name}`"));
    }
    coordinates.into_iter().find_map(|q| {
        if name == velocity_column(q) {
            Some(format!("the velocity of the coordinate `{q}`"))
        } else if name == acceleration_column(q) {
            Some(format!("the acceleration of the coordinate `{q}`"))
        } else {
            None
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suggests_near_names_only() {
        let names = ["theta1", "theta2", "r", "m1"];
        assert_eq!(closest("thta1", names), Some("theta1"));
        assert_eq!(closest("m2", names), Some("m1"));
        assert_eq!(closest("velocity", names), None);
        // A transposition is one edit.
        assert_eq!(closest("t_ned", ["t_end", "step", "rtol"]), Some("t_end"));
        assert_eq!(closest("thetA1", ["theta1", "theta2"]), Some("theta1"));
    }

    #[test]
    fn edit_distances() {
        for (a, b, d) in [
            ("", "", 0),
            ("", "abc", 3),
            ("abc", "abc", 0),
            ("abc", "acb", 1),
            ("ca", "abc", 3), // OSA: no edits of a transposed pair
            ("kitten", "sitting", 3),
            ("rtool", "rtol", 1),
        ] {
            assert_eq!(edit_distance(a, b), d, "{a} → {b}");
            assert_eq!(edit_distance(b, a), d, "{b} → {a}");
        }
    }

    /// The banded distance against the full table, written out here
    /// (Wagner–Fischer with the adjacent transposition of OSA), on every
    /// pair of short words over a small alphabet and every band width.
    #[test]
    fn the_banded_distance_is_the_full_distance_within_its_band() {
        fn full(a: &[char], b: &[char]) -> usize {
            let mut d = vec![vec![0; b.len() + 1]; a.len() + 1];
            for (i, row) in d.iter_mut().enumerate() {
                row[0] = i;
            }
            for (j, cell) in d[0].iter_mut().enumerate() {
                *cell = j;
            }
            for i in 1..=a.len() {
                for j in 1..=b.len() {
                    let cost = usize::from(a[i - 1] != b[j - 1]);
                    let mut v = (d[i - 1][j] + 1)
                        .min(d[i][j - 1] + 1)
                        .min(d[i - 1][j - 1] + cost);
                    if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                        v = v.min(d[i - 2][j - 2] + 1);
                    }
                    d[i][j] = v;
                }
            }
            d[a.len()][b.len()]
        }
        let words: Vec<Vec<char>> = (0..400u32)
            .map(|k| {
                let length = (k % 6) as usize;
                (0..length)
                    .map(|p| ['a', 'b', 'c'][(k as usize / 6) / 3usize.pow(p as u32) % 3])
                    .collect()
            })
            .collect();
        for a in &words {
            for b in &words {
                let exact = full(a, b);
                for limit in 0..7 {
                    let expected = (exact <= limit).then_some(exact);
                    assert_eq!(
                        distance_within(a, b, limit),
                        expected,
                        "{a:?} {b:?} {limit}"
                    );
                }
            }
        }
    }

    /// A 50 000-character name against a 50 000-character candidate, and
    /// against many candidates: answered at once (the full table would be
    /// 2.5·10⁹ cells).
    #[test]
    fn a_hostile_name_gets_no_suggestion_at_once() {
        let long = "a".repeat(50_000);
        let mut near = long.clone();
        near.push('b');
        let start = std::time::Instant::now();
        assert_eq!(closest(&long, [near.as_str(), "a"]), None);
        let many: Vec<String> = (0..10_000).map(|k| format!("name_{k}")).collect();
        assert_eq!(closest(&long, many.iter().map(String::as_str)), None);
        let limit = MAX_COMPARED_LENGTH;
        let at_limit = "x".repeat(limit);
        let one_off = format!("{}y", "x".repeat(limit - 1));
        assert_eq!(
            closest(&at_limit, [one_off.as_str()]),
            Some(one_off.as_str())
        );
        assert!(start.elapsed().as_secs_f64() < 1.0, "{:?}", start.elapsed());
    }

    #[test]
    fn built_in_columns_are_named() {
        let q = ["x", "theta"];
        assert_eq!(builtin_column("t", q), Some("the time".into()));
        assert!(builtin_column("kinetic_energy", q).is_some());
        assert!(builtin_column("external_work", q).is_some());
        assert_eq!(
            builtin_column("theta_ddot", q),
            Some("the acceleration of the coordinate `theta`".into())
        );
        assert!(builtin_column("x_dot", q).is_some());
        assert_eq!(builtin_column("y_dot", q), None);
        assert_eq!(builtin_column("x", q), None);
        assert_eq!(builtin_column("energy", q), None);
    }
}
