//! Anagnostopoulos's linear viscoelastic impact element:
//! `P = k·δ + c·δ̇`, `c = 2·ζ·√(k·m)` with the damping ratio
//!
//! `ζ = −ln e / √(π² + ln² e)`
//!
//! (Anagnostopoulos, S. A., 1988, "Pounding of buildings in series during
//! earthquakes", Earthquake Engineering and Structural Dynamics 16:
//! 443–456; and 2004, "Equivalent viscous damping for modeling inelastic
//! impacts in earthquake pounding problems", ibid. 33: 897–902), `m` the
//! effective mass `m₁·m₂/(m₁ + m₂)`. The ratio is exact for a contact that
//! lasts the damped oscillator's half period, pulling at its end; here the
//! contact pushes only and lets go where the force vanishes, earlier, so
//! the rebound is a little faster than `e·v₀` for small `e` (the `linear`
//! law's damping restitutes `e` exactly).

use super::{ContactForce, ContactLaw, LawEntries};
use crate::entry::EntryError;

/// `law = "anagnostopoulos"`: needs `mass`; `e` in (0, 1].
pub(super) struct Anagnostopoulos;

impl ContactLaw for Anagnostopoulos {
    fn name(&self) -> &'static str {
        "anagnostopoulos"
    }

    fn reads(&self) -> &'static [&'static str] {
        &["mass"]
    }

    fn force(&self, entries: &LawEntries, name: &str) -> Result<ContactForce, EntryError> {
        let mass = entries.needed_mass(self.name(), name)?;
        let ln = entries.positive_restitution(self.name(), name)?.ln();
        let zeta = -ln / (std::f64::consts::PI.powi(2) + ln * ln).sqrt();
        let k = entries.stiffness;
        Ok(ContactForce {
            stiffness: k,
            exponent: 1.0,
            viscous: 2.0 * zeta * (k * mass).sqrt(),
            hysteresis: 0.0,
        })
    }
}
