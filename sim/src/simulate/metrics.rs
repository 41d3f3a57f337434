//! The crash metrics of a run, accumulated sample by sample into its
//! [`Summary`].
//!
//! With the crush `c = ±q_k` of the scenario's `metrics.crush` coordinate
//! (compression positive), the vehicle's velocity towards the barrier is `ċ`
//! and its deceleration `−c̈`. Pitch angles are reported relative to the
//! static equilibrium the run started from.

use super::Sample;
use super::Summary;
use crate::ode::{Stats, hermite_weights};
use crate::pulse::{Pulse, PulseMetrics, STANDARD_GRAVITY};
use crate::scenario::Scenario;

/// One output sample as the metrics see it.
#[derive(Clone, Copy, Debug)]
pub struct SampleView<'a> {
    /// Time \[s\].
    pub t: f64,
    /// Coordinates, in the model's units (\[m\] or \[rad\]).
    pub q: &'a [f64],
    /// Velocities ([m/s] or [rad/s]).
    pub v: &'a [f64],
    /// Accelerations ([m/s²] or [rad/s²]).
    pub a: &'a [f64],
    /// Kinetic energy `T` \[J\].
    pub kinetic: f64,
    /// Potential energy `V` \[J\].
    pub potential: f64,
    /// Energy dissipated by `D` since the start \[J\].
    pub dissipated: f64,
    /// Work of the generalized forces since the start \[J\].
    pub external_work: f64,
    /// The model's outputs, in the order of
    /// [`SimulationResult::output_columns`](super::SimulationResult::output_columns).
    pub outputs: &'a [f64],
}

impl<'a> From<&'a Sample> for SampleView<'a> {
    fn from(s: &'a Sample) -> Self {
        SampleView {
            t: s.t,
            q: &s.q,
            v: &s.v,
            a: &s.a,
            kinetic: s.kinetic,
            potential: s.potential,
            dissipated: s.dissipated,
            external_work: s.external_work,
            outputs: &s.outputs,
        }
    }
}

/// Time, crush and crush rate of one sample.
#[derive(Clone, Copy, Debug)]
struct CrushPoint {
    t: f64,
    crush: f64,
    rate: f64,
}

/// The metrics of a run, accumulated sample by sample, so that a run need
/// not keep its samples (a sweep does not).
#[derive(Clone, Debug)]
pub struct Metrics {
    crush: Option<(usize, f64)>,
    pitch: Vec<(usize, f64)>,
    g: f64,
    samples: usize,
    /// `(T + V)(0)` and the scale of the energy balance.
    energy: Option<(f64, f64)>,
    energy_error: f64,
    previous: Option<CrushPoint>,
    /// The crush rate of the first sample: the impact velocity.
    first_rate: Option<f64>,
    /// The largest crush so far (the first of equals), its neighbours, and
    /// the value it was compared by (−∞ until a sample has a number).
    peak: Option<(CrushPoint, Option<CrushPoint>, Option<CrushPoint>)>,
    peak_value: f64,
    peak_index: usize,
    first_zero: Option<f64>,
    deceleration: f64,
    /// Largest speed away from the barrier since the peak.
    rebound: f64,
    pitch_extremes: Vec<f64>,
    /// Time, crush and crush acceleration of every sample, for the pulse
    /// metrics (filtering needs the whole record).
    pulse: Vec<(f64, f64, f64)>,
}

impl Metrics {
    /// Metrics of `scenario`'s crush and pitch coordinates; pitch is measured
    /// from `initial_q`, deceleration in units of `g`.
    pub fn new(scenario: &Scenario, initial_q: &[f64], g: f64) -> Metrics {
        let pitch: Vec<(usize, f64)> = scenario
            .pitch
            .iter()
            .take(2)
            .map(|&k| (k, initial_q[k]))
            .collect();
        Metrics {
            crush: scenario.crush,
            pitch_extremes: vec![0.0; pitch.len()],
            pitch,
            g,
            samples: 0,
            energy: None,
            energy_error: 0.0,
            previous: None,
            peak: None,
            peak_value: f64::NEG_INFINITY,
            peak_index: 0,
            first_zero: None,
            first_rate: None,
            deceleration: f64::NEG_INFINITY,
            rebound: 0.0,
            pulse: Vec::new(),
        }
    }

    /// Takes the next sample (in time order).
    pub fn push(&mut self, s: SampleView) {
        let (e0, scale) = *self.energy.get_or_insert_with(|| {
            (
                s.kinetic + s.potential,
                (s.kinetic + s.potential.abs()).max(f64::MIN_POSITIVE),
            )
        });
        let balance = (s.kinetic + s.potential + s.dissipated - s.external_work - e0).abs() / scale;
        self.energy_error = self.energy_error.max(balance);
        for ((k, q0), extreme) in self.pitch.iter().zip(&mut self.pitch_extremes) {
            let d = s.q[*k] - q0;
            if d.abs() > extreme.abs() {
                *extreme = d;
            }
        }
        if let Some((k, sign)) = self.crush {
            let point = CrushPoint {
                t: s.t,
                crush: sign * s.q[k],
                rate: sign * s.v[k],
            };
            let index = self.samples;
            self.first_rate.get_or_insert(point.rate);
            if let Some((_, _, after)) = &mut self.peak
                && index == self.peak_index + 1
            {
                *after = Some(point);
            }
            if index == 0 || point.crush > self.peak_value {
                self.peak = Some((point, self.previous, None));
                self.peak_index = index;
                self.rebound = 0.0;
            }
            if point.crush > self.peak_value {
                self.peak_value = point.crush;
            }
            self.rebound = self.rebound.max(-point.rate);
            if self.first_zero.is_none()
                && let Some(p) = self.previous
                && p.rate > 0.0
                && point.rate <= 0.0
            {
                let f = p.rate / (p.rate - point.rate);
                self.first_zero = Some(p.t + f * (point.t - p.t));
            }
            self.deceleration = self.deceleration.max(-sign * s.a[k] / self.g);
            self.pulse.push((s.t, point.crush, sign * s.a[k]));
            self.previous = Some(point);
        }
        self.samples += 1;
    }

    /// The summary, with the run's statistics and the weld's failure time.
    pub fn finish(&self, stats: &Stats, weld_failure: Option<f64>) -> Summary {
        let mut summary = Summary {
            max_theta1_deg: self.pitch_extremes.first().map(|d| d.to_degrees()),
            max_theta2_deg: self.pitch_extremes.get(1).map(|d| d.to_degrees()),
            weld_failure_time_s: weld_failure,
            steps: stats.accepted_steps,
            rejected_steps: stats.rejected_steps,
            rhs_evaluations: stats.rhs_evaluations,
            energy_balance_error_rel: self.energy_error,
            ..Summary::EMPTY
        };
        if let Some((peak, before, after)) = self.peak {
            let (t, c) = refine_peak(peak, before, after);
            summary.max_crush_m = Some(c);
            summary.time_of_max_crush_s = Some(t);
            summary.time_to_zero_velocity_s = self.first_zero;
            summary.peak_deceleration_g = Some(self.deceleration);
            summary.rebound_velocity_mps = Some(self.rebound);
            if let Some(pulse) = self.pulse_metrics() {
                summary.peak_deceleration_cfc60_g = Some(pulse.peak_deceleration_cfc60_g);
                summary.equivalent_square_wave_g = summary
                    .max_crush_m
                    .filter(|&c| c > 0.0)
                    .map(|c| pulse.impact_velocity_mps.powi(2) / (2.0 * STANDARD_GRAVITY * c));
                summary.olc_g = pulse.olc_g;
                summary.asi = pulse.asi;
            }
        }
        summary
    }

    /// The pulse metrics of the crush coordinate's samples (resampled onto
    /// an even grid when events added samples between the output times);
    /// `None` for fewer than 3 samples or a record the CFC 60 filter cannot
    /// take (sampled slower than 250 Hz).
    fn pulse_metrics(&self) -> Option<PulseMetrics> {
        let t: Vec<f64> = self.pulse.iter().map(|p| p.0).collect();
        let crush: Vec<f64> = self.pulse.iter().map(|p| p.1).collect();
        let acceleration: Vec<f64> = self.pulse.iter().map(|p| p.2).collect();
        let v0 = self.first_rate?;
        Pulse::resampled(&t, &acceleration, v0, Some(&crush))
            .and_then(|p| p.metrics())
            .ok()
    }
}

/// `(t, c)` of the crush maximum: the zero of the crush rate next to the
/// largest sample, by cubic Hermite interpolation of the crush.
fn refine_peak(
    peak: CrushPoint,
    before: Option<CrushPoint>,
    after: Option<CrushPoint>,
) -> (f64, f64) {
    let candidates = [before.map(|b| (b, peak)), after.map(|a| (peak, a))];
    for (a, b) in candidates.into_iter().flatten() {
        if a.rate >= 0.0 && b.rate <= 0.0 && a.rate != b.rate {
            let h = b.t - a.t;
            let s = a.rate / (a.rate - b.rate);
            // Hermite on [a, b] evaluated at the linear estimate of the rate's zero.
            let [w0, w1, w2, w3] = hermite_weights(s, h);
            let c = w0 * a.crush + w1 * a.rate + w2 * b.crush + w3 * b.rate;
            return (a.t + s * h, c.max(peak.crush));
        }
    }
    (peak.t, peak.crush)
}
