//! Crash metrics of a run (the keys of `summary.json`).
//!
//! With the crush `c = ±q_k` of the scenario's `metrics.crush` coordinate
//! (compression positive), the vehicle's velocity towards the barrier is `ċ`
//! and its deceleration `−c̈`. Pitch angles are reported relative to the
//! static equilibrium the run started from.

use super::Sample;
use crate::ode::{Stats, hermite_weights};
use crate::scenario::Scenario;
use serde::Serialize;

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Summary {
    /// Largest crush [m].
    pub max_crush_m: Option<f64>,
    pub time_of_max_crush_s: Option<f64>,
    /// First time the velocity towards the barrier reaches zero [s].
    pub time_to_zero_velocity_s: Option<f64>,
    /// The pitch deviation of largest magnitude from equilibrium, signed [°].
    pub max_theta1_deg: Option<f64>,
    pub max_theta2_deg: Option<f64>,
    /// Largest deceleration, unfiltered [g].
    pub peak_deceleration_g: Option<f64>,
    /// Largest speed away from the barrier after the peak crush [m/s].
    pub rebound_velocity_mps: Option<f64>,
    pub weld_failure_time_s: Option<f64>,
    pub steps: usize,
    pub rejected_steps: usize,
    pub rhs_evaluations: usize,
    /// `max |(T + V + dissipated − external work)(t) − (T + V)(0)| / (T(0) + |V(0)|)`.
    pub energy_balance_error_rel: f64,
}

impl Summary {
    pub fn compute(
        samples: &[Sample],
        scenario: &Scenario,
        initial_q: &[f64],
        stats: &Stats,
        weld_failure: Option<f64>,
        g: f64,
    ) -> Summary {
        let mut summary = Summary {
            max_crush_m: None,
            time_of_max_crush_s: None,
            time_to_zero_velocity_s: None,
            max_theta1_deg: None,
            max_theta2_deg: None,
            peak_deceleration_g: None,
            rebound_velocity_mps: None,
            weld_failure_time_s: weld_failure,
            steps: stats.accepted_steps,
            rejected_steps: stats.rejected_steps,
            rhs_evaluations: stats.rhs_evaluations,
            energy_balance_error_rel: energy_balance(samples),
        };
        if let Some((k, sign)) = scenario.crush
            && !samples.is_empty()
        {
            let crush: Vec<f64> = samples.iter().map(|s| sign * s.q[k]).collect();
            let rate: Vec<f64> = samples.iter().map(|s| sign * s.v[k]).collect();
            let (i_max, _) =
                crush
                    .iter()
                    .enumerate()
                    .fold((0, f64::NEG_INFINITY), |best, (i, &c)| {
                        if c > best.1 { (i, c) } else { best }
                    });
            // The peak lies where the rate crosses zero next to the largest sample.
            let (t_peak, c_peak) = refine_peak(samples, &crush, &rate, i_max);
            summary.max_crush_m = Some(c_peak);
            summary.time_of_max_crush_s = Some(t_peak);
            summary.time_to_zero_velocity_s = first_zero(samples, &rate);
            let deceleration = samples
                .iter()
                .map(|s| -sign * s.a[k] / g)
                .fold(f64::NEG_INFINITY, f64::max);
            summary.peak_deceleration_g = Some(deceleration);
            let rebound = rate[i_max..].iter().map(|r| -r).fold(0.0, f64::max);
            summary.rebound_velocity_mps = Some(rebound);
        }
        let pitch = |n: usize| {
            scenario.pitch.get(n).map(|&k| {
                let deviation = |s: &Sample| s.q[k] - initial_q[k];
                let extreme = samples
                    .iter()
                    .map(deviation)
                    .fold(0.0f64, |m, d| if d.abs() > m.abs() { d } else { m });
                extreme.to_degrees()
            })
        };
        summary.max_theta1_deg = pitch(0);
        summary.max_theta2_deg = pitch(1);
        summary
    }
}

/// The worst relative mismatch of the energy balance over the samples.
fn energy_balance(samples: &[Sample]) -> f64 {
    let Some(first) = samples.first() else {
        return 0.0;
    };
    let e0 = first.kinetic + first.potential;
    let scale = (first.kinetic + first.potential.abs()).max(f64::MIN_POSITIVE);
    samples
        .iter()
        .map(|s| (s.kinetic + s.potential + s.dissipated - s.external_work - e0).abs() / scale)
        .fold(0.0, f64::max)
}

/// `(t, c)` of the crush maximum: the zero of the crush rate between the
/// samples around the largest one, by cubic Hermite interpolation of the crush.
fn refine_peak(samples: &[Sample], crush: &[f64], rate: &[f64], i: usize) -> (f64, f64) {
    let candidates = [
        i.checked_sub(1).map(|j| (j, i)),
        (i + 1 < samples.len()).then_some((i, i + 1)),
    ];
    for (a, b) in candidates.into_iter().flatten() {
        if rate[a] >= 0.0 && rate[b] <= 0.0 && rate[a] != rate[b] {
            let h = samples[b].t - samples[a].t;
            let s = rate[a] / (rate[a] - rate[b]);
            // Hermite on [a, b] evaluated at the linear estimate of the rate's zero.
            let [w0, w1, w2, w3] = hermite_weights(s, h);
            let c = w0 * crush[a] + w1 * rate[a] + w2 * crush[b] + w3 * rate[b];
            return (samples[a].t + s * h, c.max(crush[i]));
        }
    }
    (samples[i].t, crush[i])
}

/// The first time the rate, positive at first, reaches zero (linear between samples).
fn first_zero(samples: &[Sample], rate: &[f64]) -> Option<f64> {
    (1..samples.len()).find_map(|i| {
        (rate[i - 1] > 0.0 && rate[i] <= 0.0).then(|| {
            let s = rate[i - 1] / (rate[i - 1] - rate[i]);
            samples[i - 1].t + s * (samples[i].t - samples[i - 1].t)
        })
    })
}
