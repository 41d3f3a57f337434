//! Lankarani and Nikravesh's hysteresis damping: `P = k·δⁿ·(1 + D·δ̇/v₀)`
//! with
//!
//! `D = 3·(1 − e²)/4`
//!
//! (Lankarani, H. M. and Nikravesh, P. E., 1990, "A contact force model
//! with hysteresis damping for impact analysis of multibody systems",
//! Journal of Mechanical Design 112: 369–376), from the energy lost in an
//! impact whose hysteresis loop is that of the elastic contact: accurate
//! for `e` near 1, with a rebound faster than `e·v₀` for small `e`. `n` is
//! the `exponent` entry (Hertz's 1.5 by default).

use super::{ContactForce, ContactLaw, LawEntries};
use crate::entry::EntryError;

/// `law = "lankarani_nikravesh"`: `exponent` optional; `e` in [0, 1].
pub(super) struct LankaraniNikravesh;

impl ContactLaw for LankaraniNikravesh {
    fn name(&self) -> &'static str {
        "lankarani_nikravesh"
    }

    fn reads(&self) -> &'static [&'static str] {
        &["exponent"]
    }

    fn force(&self, entries: &LawEntries, _name: &str) -> Result<ContactForce, EntryError> {
        let e = entries.restitution;
        Ok(ContactForce {
            stiffness: entries.stiffness,
            exponent: entries.exponent_or_hertz(),
            viscous: 0.0,
            hysteresis: 0.75 * (1.0 - e * e),
        })
    }
}
