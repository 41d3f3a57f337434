//! Hunt and Crossley's hysteresis damping: `P = k·δⁿ·(1 + D·δ̇/v₀)` with
//!
//! `D = 3·(1 − e)/2`
//!
//! (Hunt, K. H. and Crossley, F. R. E., 1975, "Coefficient of restitution
//! interpreted as damping in vibroimpact", Journal of Applied Mechanics 42:
//! 440–445: their `e = 1 − (2/3)·α·v₀`, with `α = D/v₀`), derived for `e`
//! near 1; the rebound is faster than `e·v₀` the further `e` is from 1.
//! `n` is the `exponent` entry (Hertz's 1.5 by default).

use super::{ContactForce, ContactLaw, LawEntries};
use crate::entry::EntryError;

/// `law = "hunt_crossley"`: `exponent` optional; `e` in [0, 1].
pub(super) struct HuntCrossley;

impl ContactLaw for HuntCrossley {
    fn name(&self) -> &'static str {
        "hunt_crossley"
    }

    fn reads(&self) -> &'static [&'static str] {
        &["exponent"]
    }

    fn force(&self, entries: &LawEntries, _name: &str) -> Result<ContactForce, EntryError> {
        Ok(ContactForce {
            stiffness: entries.stiffness,
            exponent: entries.exponent_or_hertz(),
            viscous: 0.0,
            hysteresis: 1.5 * (1.0 - entries.restitution),
        })
    }
}
