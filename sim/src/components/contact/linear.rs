//! The linear spring–dashpot whose damping restitutes the requested `e`
//! exactly: `P = k·δ + c·δ̇`, `c = 2·ζ·√(k·m)`.
//!
//! A linear oscillator of mass `m` that starts at `δ = 0` with rate `v₀`
//! and lets go where its force vanishes (before `δ` is back at 0: the
//! dashpot does not pull) leaves at `e·v₀` with, for the damping ratio
//! `ζ < 1` and `s = √(1 − ζ²)`,
//!
//! `e(ζ) = exp(−ζ·(π − atan2(2ζs, 1 − 2ζ²)) / s)`
//!
//! (Schwager, T. and Pöschel, T., 2007, "Coefficient of restitution and
//! linear–dashpot model revisited", Granular Matter 9: 465–469), and for
//! `ζ > 1`, `s' = √(ζ² − 1)`, its continuation
//! `e(ζ) = exp(−(ζ/s')·artanh(2ζs'/(2ζ² − 1)))`. `e(ζ)` falls from 1 at
//! `ζ = 0` towards 0; the law solves it for `ζ` by bisection.

use super::{ContactForce, ContactLaw, LawEntries};
use crate::entry::EntryError;

/// `law = "linear"`: needs `mass`; `e` in (0, 1].
pub(super) struct Linear;

impl ContactLaw for Linear {
    fn name(&self) -> &'static str {
        "linear"
    }

    fn reads(&self) -> &'static [&'static str] {
        &["mass"]
    }

    fn force(&self, entries: &LawEntries, name: &str) -> Result<ContactForce, EntryError> {
        let mass = entries.needed_mass(self.name(), name)?;
        let e = entries.positive_restitution(self.name(), name)?;
        let k = entries.stiffness;
        Ok(ContactForce {
            stiffness: k,
            exponent: 1.0,
            viscous: 2.0 * damping_ratio(e) * (k * mass).sqrt(),
            hysteresis: 0.0,
        })
    }
}

/// The coefficient of restitution of the damping ratio `zeta` ≥ 0.
pub(super) fn restitution(zeta: f64) -> f64 {
    if zeta == 1.0 {
        return (-2.0f64).exp();
    }
    if zeta < 1.0 {
        let s = (1.0 - zeta * zeta).sqrt();
        let angle = (2.0 * zeta * s).atan2(1.0 - 2.0 * zeta * zeta);
        return (-zeta * (std::f64::consts::PI - angle) / s).exp();
    }
    let s = (zeta * zeta - 1.0).sqrt();
    (-(zeta / s) * (2.0 * zeta * s / (2.0 * zeta * zeta - 1.0)).atanh()).exp()
}

/// The damping ratio whose contact restitutes `e` in (0, 1].
fn damping_ratio(e: f64) -> f64 {
    if e >= 1.0 {
        return 0.0;
    }
    let mut high = 1.0;
    while restitution(high) > e {
        high *= 2.0;
    }
    let mut low = 0.0;
    // Each halving gains a bit; 200 reach the resolution of f64 from any
    // bracket `high` can reach.
    for _ in 0..200 {
        let mid = 0.5 * (low + high);
        if restitution(mid) > e {
            low = mid;
        } else {
            high = mid;
        }
    }
    0.5 * (low + high)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_damping_ratio_inverts_the_closed_form() {
        // Schwager and Pöschel's e(ζ) at ζ = 0.3, and its limit
        // exp(−2) at critical damping (by SciPy: 0.45097545289).
        assert!((restitution(0.3) - 0.450_975_452_89).abs() < 1e-10);
        assert!((restitution(0.999_999) - (-2.0f64).exp()).abs() < 1e-5);
        assert!((restitution(1.000_001) - (-2.0f64).exp()).abs() < 1e-5);
        for e in [0.01, 0.1, 0.135, 0.5, 0.9, 1.0] {
            let zeta = damping_ratio(e);
            assert!((restitution(zeta) - e).abs() < 1e-12, "{e}: ζ = {zeta}");
        }
        assert_eq!(damping_ratio(1.0), 0.0);
    }
}
