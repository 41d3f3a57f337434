//! Flores et al.'s hysteresis damping: `P = k·δⁿ·(1 + D·δ̇/v₀)` with
//!
//! `D = 8·(1 − e)/(5·e)`
//!
//! (Flores, P., Machado, M., Silva, M. T. and Martins, J. M., 2011, "On the
//! continuous contact force models for soft materials in multibody
//! dynamics", Multibody System Dynamics 25: 357–375), derived for the
//! whole range of `e`, soft materials included. For `e` below about 0.6,
//! `D > 1`: the rate cannot pass `−v₀/D`, where the force would vanish, so
//! the force fades as the rate nears it, the contact lasts longer, and the
//! bodies part at `δ = 0` a little slower than `e·v₀`.
//! `n` is the `exponent` entry (Hertz's 1.5 by default).

use super::{ContactForce, ContactLaw, LawEntries};
use crate::entry::EntryError;

/// `law = "flores"`: `exponent` optional; `e` in (0, 1].
pub(super) struct Flores;

impl ContactLaw for Flores {
    fn name(&self) -> &'static str {
        "flores"
    }

    fn reads(&self) -> &'static [&'static str] {
        &["exponent"]
    }

    fn force(&self, entries: &LawEntries, name: &str) -> Result<ContactForce, EntryError> {
        let e = entries.positive_restitution(self.name(), name)?;
        Ok(ContactForce {
            stiffness: entries.stiffness,
            exponent: entries.exponent_or_hertz(),
            viscous: 0.0,
            hysteresis: 8.0 * (1.0 - e) / (5.0 * e),
        })
    }
}
