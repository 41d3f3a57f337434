//! What the crush element dissipates, split between its damper and its
//! spring.
//!
//! The element reports the power it absorbs, `P·δ̇` (0 separated), and the
//! elastic energy it stores in contact ([`CrushElement::stored`]); the
//! energy reported as dissipated is the work absorbed less the elastic
//! energy still stored (see [`crate::components::Dissipation::stored_energy`]).
//!
//! * The damper stores nothing: it dissipates `D·δ̇ = c(|δ̇|)·δ̇²`.
//! * With plastic unloading the spring stores, in compression, the energy
//!   of the unloading line through its current force `S`: `S²/(2·k_u)`
//!   (`½·k_u·(δ − δ_set)²` once unloading), what unloading from here
//!   would give back. Loading thus dissipates `S·δ̇·(1 − S′/k_u)`, unloading
//!   nothing.
//! * Under tension, and with elastic unloading, the spring follows its
//!   loading curve and stores `∫₀^δ S dx`.
//! * Separated it stores nothing: what the spring still held when it
//!   separated (the damper pulled its force to zero first) is dissipated
//!   there.
//!
//! Over a loading–unloading cycle to separation the energy reported is the
//! area of the force–deflection loop.

use super::{CrushElement, Phase, Unloading};
use crate::components::integral::integral;
use crate::curve::OutOfRange;

impl CrushElement {
    /// Whether the element is out of contact, where it exerts no force.
    fn separated(&self) -> bool {
        self.contact_only && !self.in_contact
    }

    /// The power the element absorbs at the input's arguments `args`: its
    /// compressive force times the deflection rate.
    pub(super) fn absorbed_power(&self, args: &[f64]) -> Result<f64, OutOfRange> {
        let (_, rate) = self.crush(args);
        Ok(self.compressive(args)?.0 * rate)
    }

    /// The elastic energy the spring stores at the input's arguments
    /// `args`, in the current regime (see the module documentation).
    pub(super) fn stored(&self, args: &[f64]) -> Result<f64, OutOfRange> {
        if self.separated() {
            return Ok(0.0);
        }
        let (delta, _) = self.crush(args);
        match (self.phase, self.unloading) {
            (Phase::Unloading { .. }, Unloading::Plastic { stiffness }) => {
                let s = self.spring(delta)?.0;
                Ok(s * s / (2.0 * stiffness))
            }
            (Phase::Loading, Unloading::Plastic { stiffness }) if delta >= 0.0 => {
                let s = self.loading.force(delta)?.0;
                Ok(s * s / (2.0 * stiffness))
            }
            (Phase::Loading, Unloading::Plastic { .. })
            | (Phase::Loading | Phase::Unloading { .. }, Unloading::Elastic) => {
                // The curve is one in |δ|: its points on both sides.
                let xs = self.loading.curve().xs();
                let breaks = xs.iter().flat_map(|&x| [x, -x]);
                integral(
                    |x| self.loading.force(x).map(|(s, _)| s),
                    0.0,
                    delta,
                    breaks,
                )
            }
        }
    }
}
