//! The rates and accelerations of a model's outputs along the motion, for
//! a crush channel that reads an output of the position `o(q, t)`
//! (`metrics.crush = "intrusion"`).
//!
//! Along the motion `ȯ = ∂o/∂q·q̇ + ∂o/∂t` and
//! `ö = ∂o/∂q·q̈ + q̇ᵀ(∂²o/∂q²)q̇ + 2 ∂²o/∂q∂t·q̇ + ∂²o/∂t²`. Both are the
//! first and second derivatives at `s = 0` of `g(s) = o(p(s), t + s)` on
//! the path `p(s) = q + s q̇ + s² q̈ / 2`, which has the sample's position,
//! velocity and acceleration: the model's outputs routine evaluated at four
//! points of it gives them by the central differences of fourth order
//!
//! ```text
//! ȯ ≈ [g(−2h) − 8 g(−h) + 8 g(h) − g(2h)] / 12h              (error h⁴ g⁽⁵⁾/30)
//! ö ≈ [−g(2h) + 16 g(h) − 30 g(0) + 16 g(−h) − g(−2h)] / 12h² (error h⁴ g⁽⁶⁾/90)
//! ```
//!
//! with `g(0)` the sample's own output. The path is a polynomial of the
//! sample's state, so a kink of the motion (a contact closing) does not
//! reach the differences; a kink of the output itself (`abs`, `max`) within
//! `2h` of the state does, as it would any derivative.
//!
//! **Accuracy.** The step is `h = STEP · τ`, `τ` the time in which the
//! motion moves a coordinate by one of its units (1 m, 1 rad): the least of
//! `1/|q̇_k|` and `1/√|q̈_k|`, at most [`LONGEST`]. Truncation falls as
//! `h⁴`, rounding (about `5 ε |o| / h²` for `ö`) grows as `1/h²`; `STEP`
//! balances the two for crash-sized outputs. Measured
//! (`tests/crush_output.rs`), relative to the largest value over the run:
//! a pole intrusion curved on a 0.3 m scale, against its closed form,
//! `1.8e-9` (rate) and `2.9e-9` (acceleration, its peak too); the linear
//! output `xa - xb` of the car-to-car scenario (crush up to 1.3 m), against
//! the same crush written as coordinates, `2e-13` and `1.0e-9`, its crash
//! metrics within `5e-11`. An output curved on a scale `L` well below a
//! unit has a truncation error growing as `(1 m / L)⁴`; one that varies
//! much faster in time than the coordinates move (`∂o/∂t` on a scale
//! below `τ`) likewise as `(h/τ_o)⁴`. The cost is four evaluations of the
//! outputs routine per output sample.

use lagrangian_runtime::{LagrangianSystem, NoInputs};
use nalgebra::SVector;

/// The step of the differences as a fraction of the motion's time scale
/// (see the module documentation: truncation and rounding of `ö` both
/// about `3e-9` for crash-sized outputs).
const STEP: f64 = 3e-3;

/// The longest time scale of a motion \[s\]: the step of a state at rest.
pub const LONGEST: f64 = 1.0;

/// The rates `ȯ` and accelerations `ö` along the motion of every output
/// of `system` at `(t, q, q̇, q̈)` whose values there are `outputs` (see the
/// module documentation). Only those of the outputs of the position mean
/// what they say: the perturbed evaluations call no input function (an
/// output that does reads NaN).
pub fn output_motion<const N: usize, S: LagrangianSystem<N>>(
    system: &S,
    (t, q, v, a): (f64, &SVector<f64, N>, &SVector<f64, N>, &SVector<f64, N>),
    outputs: &[f64],
) -> [Vec<f64>; 2] {
    let h = STEP * time_scale(v.as_slice(), a.as_slice());
    let at = |s: f64| {
        let mut values = vec![f64::NAN; outputs.len()];
        let position = q + v * s + a * (0.5 * s * s);
        let velocity = v + a * s;
        system.outputs(t + s, &position, &velocity, a, &NoInputs, &mut values);
        values
    };
    let [back2, back, forth, forth2] = [-2.0 * h, -h, h, 2.0 * h].map(at);
    let rates = (0..outputs.len())
        .map(|j| (back2[j] - 8.0 * back[j] + 8.0 * forth[j] - forth2[j]) / (12.0 * h))
        .collect();
    let accelerations = (0..outputs.len())
        .map(|j| {
            let outer = forth2[j] + back2[j];
            let inner = forth[j] + back[j];
            (16.0 * inner - outer - 30.0 * outputs[j]) / (12.0 * h * h)
        })
        .collect();
    [rates, accelerations]
}

/// The time in which the motion `(q̇, q̈)` moves a coordinate by one of its
/// units, at most [`LONGEST`] (also where no rate is a number).
fn time_scale(v: &[f64], a: &[f64]) -> f64 {
    let rate = (v.iter().map(|v| v.abs()))
        .chain(a.iter().map(|a| a.abs().sqrt()))
        .fold(0.0f64, f64::max);
    (1.0 / rate).min(LONGEST)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_time_scale_is_that_of_the_fastest_coordinate_at_most_a_second() {
        assert_eq!(time_scale(&[0.5, -4.0], &[9.0, 0.0]), 0.25);
        assert_eq!(time_scale(&[0.5, 1.0], &[-100.0, 0.0]), 0.1);
        assert_eq!(time_scale(&[0.0], &[0.0]), LONGEST);
        assert_eq!(time_scale(&[f64::NAN], &[f64::NAN]), LONGEST);
        assert_eq!(time_scale(&[1e-3], &[]), LONGEST);
    }
}
