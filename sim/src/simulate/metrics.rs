//! The crash metrics of a run, accumulated sample by sample into its
//! [`Summary`].
//!
//! With the crush `c = Σ c_k q_k + Σ d_j o_j(q, t) + c₀` of the scenario's
//! `metrics.crush` channel (compression positive; `o_j` outputs of the
//! position, whose rates and accelerations along the motion the sample
//! brings, see [`super::output_motion`]), the vehicle's velocity towards
//! the barrier is `ċ` and its deceleration `−c̈`. Pitch angles are reported relative to the
//! static equilibrium the run started from.

use super::Sample;
use super::Summary;
use super::channels::{ChannelRecord, ChannelSummary, Channels};
use super::criteria_channels::CriteriaRecords;
use crate::ode::{Stats, hermite_weights};
use crate::pulse::{FilteredMetrics, Pulse, STANDARD_GRAVITY, grid_period};
use crate::scenario::{Columns, CoordinateCombination, Scenario};
use crate::warning::{self, ChannelPoint, Warning};

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
    /// The model's outputs, in the order of
    /// [`SimulationResult::output_columns`](super::SimulationResult::output_columns).
    pub outputs: &'a [f64],
    /// The values of the scenario's component columns.
    pub components: &'a [f64],
    /// The constraints' multipliers `λ`.
    pub multipliers: &'a [f64],
    /// The constraints' residuals `g`.
    pub residuals: &'a [f64],
    /// The rates `ȯ` and accelerations `ö` of the outputs along the motion,
    /// one per output each, where the crush channel reads an output (empty
    /// otherwise; see [`super::output_motion`]).
    pub output_motion: [&'a [f64]; 2],
}

impl<'a> SampleView<'a> {
    /// A sample of the motion and its accelerations alone: no outputs,
    /// component columns or constraints.
    pub fn of_motion(t: f64, q: &'a [f64], v: &'a [f64], a: &'a [f64]) -> SampleView<'a> {
        SampleView {
            t,
            q,
            v,
            a,
            outputs: &[],
            components: &[],
            multipliers: &[],
            residuals: &[],
            output_motion: [&[], &[]],
        }
    }
}

/// A kept sample as the metrics see it: without the outputs' rates and
/// accelerations, which a sample does not keep (a crush channel of outputs
/// reads NaN rates from it).
impl<'a> From<&'a Sample> for SampleView<'a> {
    fn from(s: &'a Sample) -> Self {
        SampleView {
            t: s.t,
            q: &s.q,
            v: &s.v,
            a: &s.a,
            outputs: &s.outputs,
            components: &s.components,
            multipliers: &s.multipliers,
            residuals: &s.residuals,
            output_motion: [&[], &[]],
        }
    }
}

/// The energies of a run at one point of its integration: the start, or
/// the end of an accepted step.
#[derive(Clone, Copy, Debug)]
pub struct EnergyPoint {
    /// Time \[s\].
    pub t: f64,
    /// Kinetic energy `T` \[J\].
    pub kinetic: f64,
    /// Potential energy `V` \[J\].
    pub potential: f64,
    /// Energy dissipated by `D` since the start \[J\].
    pub dissipated: f64,
    /// Work of the generalized forces since the start \[J\].
    pub external_work: f64,
}

/// Keeps in `firsts` the first time each of `values` (at time `t`) is
/// not finite, with its value; none while no sample has values.
fn first_non_finite(firsts: &mut Vec<Option<(f64, f64)>>, t: f64, values: &[f64]) {
    if values.is_empty() {
        return;
    }
    firsts.resize(values.len(), None);
    for (first, &value) in firsts.iter_mut().zip(values) {
        if first.is_none() && !value.is_finite() {
            *first = Some((t, value));
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
/// not keep its samples (a sweep does not): each sample adds what the
/// metrics read of it to their records, and [`Metrics::finish`] reads them
/// in one pass each.
#[derive(Clone, Debug)]
pub struct Metrics {
    /// The crush channel's combination of coordinates and outputs, and its
    /// offset.
    crush: Option<(CoordinateCombination, f64)>,
    pitch: Vec<(usize, f64)>,
    /// `(T + V)(0)`.
    initial_energy: Option<f64>,
    /// The largest `|T + V + D − W − (T + V)(0)|` so far \[J\] (NaN once
    /// one is not a number).
    energy_residual: f64,
    /// The run's energy scale so far: the largest of `T + |V|`, `|D|` and
    /// `|W|` over the points of the balance \[J\].
    energy_scale: f64,
    /// The first point at which each term of the balance (`T`, `V`, `D`,
    /// `W`) is not finite: time and value.
    energy_not_finite: [Option<(f64, f64)>; 4],
    /// The first sample at which each output is not finite: time and
    /// value (empty while no sample has outputs).
    outputs_not_finite: Vec<Option<(f64, f64)>>,
    /// Likewise for each of the components' columns.
    components_not_finite: Vec<Option<(f64, f64)>>,
    /// The times of the samples.
    times: Vec<f64>,
    /// The deviations from equilibrium of the pitch coordinates, by
    /// sample, for their extremes over the run and within the pulse (whose
    /// end is known at the end); as many deviations as pitch coordinates,
    /// the rest 0.
    pitch_history: Vec<[f64; 2]>,
    /// Time, crush and crush rate of every sample, for the crush metrics,
    /// the pulse metrics (filtering needs the whole record) and the crush
    /// at the end of contact.
    crush_history: Vec<CrushPoint>,
    /// The crush acceleration of every sample of `crush_history`.
    crush_acceleration: Vec<f64>,
    /// The records of the scenario's channels.
    channels: Vec<ChannelRecord>,
    /// The records of the occupant channels the criteria read.
    occupant: CriteriaRecords,
}

impl Metrics {
    /// Metrics of `scenario`'s crush and pitch coordinates; pitch is measured
    /// from `initial_q`, deceleration in units of standard gravity (never a
    /// parameter of the model: a spec's `g` may be anything).
    pub fn new(scenario: &Scenario, initial_q: &[f64]) -> Metrics {
        let pitch: Vec<(usize, f64)> = scenario
            .pitch
            .iter()
            .take(2)
            .map(|&k| (k, initial_q[k]))
            .collect();
        let samples = expected_samples(scenario);
        let crush = scenario.crush.as_ref();
        let history = |wanted: bool| if wanted { samples } else { 0 };
        Metrics {
            crush: crush.map(|c| (c.coordinate_combination(), c.offset)),
            times: Vec::with_capacity(samples),
            pitch_history: Vec::with_capacity(history(!pitch.is_empty())),
            crush_history: Vec::with_capacity(history(crush.is_some())),
            crush_acceleration: Vec::with_capacity(history(crush.is_some())),
            pitch,
            initial_energy: None,
            energy_residual: 0.0,
            energy_scale: 0.0,
            energy_not_finite: [None; 4],
            outputs_not_finite: Vec::new(),
            components_not_finite: Vec::new(),
            channels: (scenario.channels.iter().cloned())
                .map(|channel| ChannelRecord::new(channel, samples))
                .collect(),
            occupant: CriteriaRecords::new(scenario, samples),
        }
    }

    /// Takes a point of the energy balance `T + V + D − W = (T + V)(0)`:
    /// the start of the run first, then the end of every accepted step (in
    /// time order). The balance is measured where the integration put the
    /// state, not between the ends of a step where the samples interpolate.
    pub fn energy_at(&mut self, e: EnergyPoint) {
        let terms = [e.kinetic, e.potential, e.dissipated, e.external_work];
        for (first, value) in self.energy_not_finite.iter_mut().zip(terms) {
            if first.is_none() && !value.is_finite() {
                *first = Some((e.t, value));
            }
        }
        let e0 = *self.initial_energy.get_or_insert(e.kinetic + e.potential);
        let residual = (e.kinetic + e.potential + e.dissipated - e.external_work - e0).abs();
        // NaN stays: a balance that is not a number is not 0.
        self.energy_residual = match residual.is_nan() {
            true => f64::NAN,
            false => self.energy_residual.max(residual),
        };
        let scale = (e.kinetic + e.potential.abs())
            .max(e.dissipated.abs())
            .max(e.external_work.abs());
        self.energy_scale = self.energy_scale.max(scale);
    }

    /// The relative energy balance error: the largest residual over the
    /// run's energy scale (0 for a run that has no energy at all).
    fn energy_error(&self) -> f64 {
        match self.energy_residual == 0.0 {
            true => 0.0,
            false => self.energy_residual / self.energy_scale.max(f64::MIN_POSITIVE),
        }
    }

    /// The terms of the energy balance, the outputs and the components'
    /// columns that are not finite somewhere, each at the first time it is
    /// not (`outputs`: the names of the model's outputs; `components`: of
    /// the components' columns, `NAME.QUANTITY`).
    pub fn non_finite_warnings(&self, outputs: &[&str], components: &[String]) -> Vec<Warning> {
        const TERMS: [&str; 4] = [
            "the kinetic energy",
            "the potential energy",
            "the dissipated energy",
            "the external work",
        ];
        let energies = TERMS
            .iter()
            .map(|t| t.to_string())
            .zip(self.energy_not_finite);
        let outputs = (outputs.iter())
            .map(|name| format!("output `{name}`"))
            .zip(self.outputs_not_finite.iter().copied());
        let components = (components.iter())
            .map(|name| format!("component column `{name}`"))
            .zip(self.components_not_finite.iter().copied());
        (outputs.chain(components).chain(energies))
            .filter_map(|(what, first)| {
                first.map(|(t, value)| Warning::NonFinite { what, t, value })
            })
            .collect()
    }

    /// Takes the next sample (in time order).
    pub fn push(&mut self, s: SampleView) {
        self.times.push(s.t);
        first_non_finite(&mut self.outputs_not_finite, s.t, s.outputs);
        first_non_finite(&mut self.components_not_finite, s.t, s.components);
        if !self.pitch.is_empty() {
            let mut deviations = [0.0; 2];
            for (d, (k, q0)) in deviations.iter_mut().zip(&self.pitch) {
                *d = s.q[*k] - q0;
            }
            self.pitch_history.push(deviations);
        }
        if let Some((crush, offset)) = &self.crush {
            let [rates, accelerations] = s.output_motion;
            let [crush, rate, acceleration] =
                crush.of([s.q, s.v, s.a], [s.outputs, rates, accelerations]);
            // `−0` of a crush `-r` stays as it was without an offset.
            let crush = if *offset == 0.0 {
                crush
            } else {
                crush + offset
            };
            let t = s.t;
            self.crush_history.push(CrushPoint { t, crush, rate });
            self.crush_acceleration.push(acceleration);
        }
        if !self.channels.is_empty() || !self.occupant.is_empty() {
            let columns = Columns {
                q: s.q,
                v: s.v,
                a: s.a,
                outputs: s.outputs,
                components: s.components,
                multipliers: s.multipliers,
                residuals: s.residuals,
            };
            for channel in &mut self.channels {
                channel.push(&columns);
            }
            self.occupant.push(&columns);
        }
    }

    /// The crush, crush rate and crush acceleration of the last sample
    /// taken, where the scenario has a crush channel.
    pub fn last_crush(&self) -> Option<[f64; 3]> {
        let p = self.crush_history.last()?;
        Some([p.crush, p.rate, *self.crush_acceleration.last()?])
    }

    /// The summary, with the run's statistics, the weld's failure time and
    /// the end of the contact (the end of the pulse).
    pub fn finish(
        &self,
        stats: &Stats,
        weld_failure: Option<f64>,
        end_of_contact: Option<f64>,
    ) -> Summary {
        let (over_run, in_pulse) = self.pitch_extremes(end_of_contact);
        let in_pulse = |k: usize| {
            in_pulse
                .as_ref()
                .and_then(|e| e.get(k))
                .map(|d| d.to_degrees())
        };
        let mut summary = Summary {
            max_theta1_deg: over_run.first().map(|d| d.to_degrees()),
            max_theta2_deg: over_run.get(1).map(|d| d.to_degrees()),
            max_theta1_in_pulse_deg: in_pulse(0),
            max_theta2_in_pulse_deg: in_pulse(1),
            end_of_contact_s: end_of_contact,
            permanent_crush_m: end_of_contact.and_then(|t| self.crush_at(t)),
            weld_failure_time_s: weld_failure,
            steps: stats.accepted_steps,
            rejected_steps: stats.rejected_steps,
            rhs_evaluations: stats.rhs_evaluations,
            energy_balance_error_rel: self.energy_error(),
            channels: Channels(self.channel_summaries()),
            criteria: self.occupant.criteria(&self.times),
            ..Summary::EMPTY
        };
        if let Some(peak) = Peak::of(&self.crush_history) {
            let (t, c) = peak.refined();
            summary.max_crush_m = Some(c);
            summary.time_of_max_crush_s = Some(t);
            summary.time_to_zero_velocity_s = first_zero(&self.crush_history);
            summary.peak_deceleration_g = Some(self.peak_deceleration());
            summary.rebound_velocity_mps = Some(peak.rebound);
            let (start, end) = (
                self.crush_history[0],
                self.crush_history[self.crush_history.len() - 1],
            );
            summary.still_crushing =
                (self.crush_history.len() > 1) && warning::is_still_crushing(end.rate, start.rate);
            let v0 = self.crush_history[0].rate;
            summary.equivalent_square_wave_g = (summary.max_crush_m)
                .filter(|&c| c > 0.0)
                .map(|c| v0.powi(2) / (2.0 * STANDARD_GRAVITY * c));
            if let Some(pulse) = self.pulse_metrics() {
                summary.peak_deceleration_cfc60_g = pulse.peak_deceleration_cfc60_g;
                summary.olc_g = pulse.olc.map(|o| o.deceleration / STANDARD_GRAVITY);
                summary.asi = pulse.asi.map(|(asi, _)| asi);
            }
        }
        summary
    }

    /// The metrics of the scenario's channels.
    fn channel_summaries(&self) -> Vec<ChannelSummary> {
        let summary = |c: &ChannelRecord| c.summary(&self.times);
        self.channels.iter().map(summary).collect()
    }

    /// The largest deceleration of the crush coordinate \[g\]: `−c̈ / g₀`
    /// over the samples (−∞ when none is a number).
    fn peak_deceleration(&self) -> f64 {
        let decelerations = self
            .crush_acceleration
            .iter()
            .map(|a| -a / STANDARD_GRAVITY);
        decelerations.fold(f64::NEG_INFINITY, f64::max)
    }

    /// The pitch deviations of largest magnitude over the run and, given
    /// the end of the pulse, up to it: one scan, the run's continuing from
    /// the pulse's.
    fn pitch_extremes(&self, end_of_pulse: Option<f64>) -> (Vec<f64>, Option<Vec<f64>>) {
        let mut extremes = vec![0.0f64; self.pitch.len()];
        let mut times = &self.times[..self.pitch_history.len()];
        let mut history = self.pitch_history.as_slice();
        let in_pulse = end_of_pulse.map(|end| {
            let within = times.iter().take_while(|&&t| t <= end).count();
            widen_extremes(&mut extremes, &history[..within]);
            (times, history) = (&times[within..], &history[within..]);
            extremes.clone()
        });
        // Up to the first time that is not a number, if any.
        let until_end = times.iter().take_while(|&&t| t <= f64::INFINITY).count();
        widen_extremes(&mut extremes, &history[..until_end]);
        (extremes, in_pulse)
    }

    /// The crush at time `t`, by cubic Hermite interpolation of the samples
    /// around it (crush and rate); `None` outside the samples.
    fn crush_at(&self, t: f64) -> Option<f64> {
        let h = &self.crush_history;
        let k = h.iter().position(|p| p.t >= t)?;
        if k == 0 {
            return (h[0].t == t).then_some(h[0].crush);
        }
        let (a, b) = (h[k - 1], h[k]);
        let step = b.t - a.t;
        let [w0, w1, w2, w3] = hermite_weights((t - a.t) / step, step);
        Some(w0 * a.crush + w1 * a.rate + w2 * b.crush + w3 * b.rate)
    }

    /// The filter classes of the crush channel's pulse metrics and of the
    /// channels' metrics that the samples' rate cannot give: the rate of
    /// the even grid the records are resampled onto.
    pub fn filter_warnings(&self) -> Vec<Warning> {
        if self.times.len() < 3 {
            return Vec::new();
        }
        let mut needs = Vec::new();
        if !self.crush_history.is_empty() {
            needs.push((60.0, "the CFC 60 peak deceleration is not computed".into()));
            needs.push((
                180.0,
                "OLC and ASI are those of the unfiltered crush acceleration".into(),
            ));
        }
        needs.extend(self.channels.iter().flat_map(ChannelRecord::filter_needs));
        crate::pulse::cfc::filter_classes(grid_period(&self.times), &needs)
    }

    /// The sanity warnings of the crush channel (named `channel` in them):
    /// moving away from the barrier at the start, not starting at 0, never
    /// compressing, still compressing at the end.
    pub fn crush_warnings(&self, channel: &str) -> Vec<Warning> {
        let history = &self.crush_history;
        let (Some(start), Some(end), Some(peak)) =
            (history.first(), history.last(), Peak::of(history))
        else {
            return Vec::new();
        };
        let point = |p: &CrushPoint| ChannelPoint {
            t: p.t,
            value: p.crush,
            rate: p.rate,
        };
        let first = point(start);
        let away = warning::moving_away(channel, first);
        let offset = warning::crush_offset(channel, first);
        let flat = warning::never_compresses(channel, first, peak.largest);
        let still = (history.len() > 1)
            .then(|| warning::still_crushing(channel, point(end), start.rate))
            .flatten();
        [away, offset, flat, still].into_iter().flatten().collect()
    }

    /// The pulse metrics of the crush coordinate's acceleration (resampled
    /// onto an even grid when the last sample came closer than an output
    /// interval), each filter class where the sample rate gives it; `None`
    /// for fewer than 3 samples, or samples that are not finite. No metric read takes the crush itself:
    /// it goes along only where its resampled values could fail the pulse's
    /// check (crush beyond [`CRUSH_BOUND`]: they cannot when every sample
    /// is within it).
    fn pulse_metrics(&self) -> Option<FilteredMetrics> {
        let v0 = self.crush_history.first()?.rate;
        let bounded = (self.crush_history.iter()).all(|p| p.crush.abs() <= CRUSH_BOUND);
        let crush: Option<Vec<f64>> =
            (!bounded).then(|| self.crush_history.iter().map(|p| p.crush).collect());
        let t = &self.times[..self.crush_history.len()];
        let pulse = Pulse::resampled(t, &self.crush_acceleration, v0, crush.as_deref());
        pulse.and_then(|p| p.filtered_metrics()).ok()
    }
}

/// Widens `extremes` to the pitch deviations of larger magnitude among
/// `history`'s, the first of equals.
fn widen_extremes(extremes: &mut [f64], history: &[[f64; 2]]) {
    for deviations in history {
        for (extreme, &d) in extremes.iter_mut().zip(deviations.iter()) {
            if d.abs() > extreme.abs() {
                *extreme = d;
            }
        }
    }
}

/// The number of output samples `scenario` asks for (the sampler's bound),
/// to reserve the records for; at most [`RESERVED_SAMPLES`], beyond which the
/// records grow as they fill.
fn expected_samples(scenario: &Scenario) -> usize {
    let bound = (scenario.t_end / scenario.output_interval + 1.0).ceil();
    if bound >= 0.0 {
        bound.min(RESERVED_SAMPLES as f64) as usize
    } else {
        0 // NaN
    }
}

/// A crush within which linear interpolation between samples stays finite
/// \[m\].
const CRUSH_BOUND: f64 = 1e300;

/// The most samples a record reserves room for at the start of a run.
const RESERVED_SAMPLES: usize = 1 << 16;

/// The largest crush of a run: its sample, with the samples before and
/// after it, and the rebound that follows.
#[derive(Clone, Copy, Debug)]
struct Peak {
    at: CrushPoint,
    before: Option<CrushPoint>,
    after: Option<CrushPoint>,
    /// The largest crush that is a number (−∞ if none is).
    largest: f64,
    /// The largest speed away from the barrier from the peak on (0 if
    /// none).
    rebound: f64,
}

impl Peak {
    /// The peak of the crush `history`: the first sample of largest crush
    /// (the first sample while none is a number); `None` without samples.
    fn of(history: &[CrushPoint]) -> Option<Peak> {
        let first = *history.first()?;
        let (mut index, mut largest) = (0, first.crush.max(f64::NEG_INFINITY));
        for (k, p) in history.iter().enumerate().skip(1) {
            if p.crush > largest {
                (index, largest) = (k, p.crush);
            }
        }
        let rebound = (history[index..].iter()).fold(0.0f64, |m, p| m.max(-p.rate));
        Some(Peak {
            at: history[index],
            before: index.checked_sub(1).map(|k| history[k]),
            after: history.get(index + 1).copied(),
            largest,
            rebound,
        })
    }

    /// `(t, c)` of the crush maximum: the zero of the crush rate next to
    /// the largest sample, by cubic Hermite interpolation of the crush.
    fn refined(&self) -> (f64, f64) {
        let peak = self.at;
        let candidates = [
            self.before.map(|b| (b, peak)),
            self.after.map(|a| (peak, a)),
        ];
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
}

/// The first time the crush rate falls from positive to zero or below,
/// interpolated linearly between the two samples.
fn first_zero(history: &[CrushPoint]) -> Option<f64> {
    let w = history
        .windows(2)
        .find(|w| w[0].rate > 0.0 && w[1].rate <= 0.0)?;
    let (p, point) = (w[0], w[1]);
    let f = p.rate / (p.rate - point.rate);
    Some(p.t + f * (point.t - p.t))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Why the crush may stay out of the pulse within the bound: its
    /// resampled values are finite, so the pulse's check passes them.
    #[test]
    fn crush_within_the_bound_resamples_to_finite_values() {
        let t = [0.0, 1e-4, 1.5e-4, 2.5e-4, 4e-4, 4.5e-4];
        let crush = t.map(|t| if t < 2e-4 { CRUSH_BOUND } else { -CRUSH_BOUND });
        let pulse = Pulse::resampled(&t, &[0.0; 6], 1.0, Some(&crush)).unwrap();
        let resampled = pulse.crush.unwrap();
        assert!(resampled.iter().all(|c| c.is_finite()), "{resampled:?}");
        assert!(
            resampled
                .iter()
                .any(|&c| c != CRUSH_BOUND && c != -CRUSH_BOUND)
        );
        // Beyond it they may not be: the run's pulse takes the crush along.
        let far = t.map(|t| if t < 2e-4 { f64::MAX } else { -f64::MAX });
        let pulse = Pulse::resampled(&t, &[0.0; 6], 1.0, Some(&far)).unwrap();
        assert!(pulse.crush.unwrap().iter().any(|c| !c.is_finite()));
    }

    #[test]
    fn extremes_widen_to_the_first_deviation_of_larger_magnitude() {
        let history = [[0.1, -0.2], [-0.3, 0.2], [0.3, -0.5], [0.05, 0.0]];
        let mut extremes = [0.0; 2];
        widen_extremes(&mut extremes, &history[..2]);
        assert_eq!(extremes, [-0.3, -0.2]);
        widen_extremes(&mut extremes, &history[2..]);
        assert_eq!(extremes, [-0.3, -0.5]);
        let mut one = [0.0];
        widen_extremes(&mut one, &history);
        assert_eq!(one, [-0.3]);
    }

    /// `(t, crush, rate)` points.
    fn points(rows: &[(f64, f64, f64)]) -> Vec<CrushPoint> {
        (rows.iter())
            .map(|&(t, crush, rate)| CrushPoint { t, crush, rate })
            .collect()
    }

    /// The peak is the first sample of largest crush (the first sample
    /// while none is a number); the rebound the fastest retreat from it on;
    /// the first zero of the rate interpolated between its samples.
    #[test]
    fn the_peak_is_the_first_largest_crush_and_the_rebound_follows_it() {
        let nan = f64::NAN;
        let history = points(&[
            (0.0, nan, 3.0),
            (1.0, 0.2, 2.0),
            (2.0, 0.5, -1.0),
            (3.0, 0.5, -4.0),
            (4.0, 0.4, nan),
            (5.0, 0.1, -2.0),
        ]);
        let peak = Peak::of(&history).unwrap();
        assert_eq!(
            (peak.at.t, peak.before.unwrap().t, peak.after.unwrap().t),
            (2.0, 1.0, 3.0)
        );
        assert_eq!((peak.rebound, peak.largest), (4.0, 0.5));
        // Between (1, 2) and (2, −1) the rate is 0 a third of the way on.
        assert_eq!(first_zero(&history), Some(1.0 + 2.0 / 3.0));
        // All NaN: the first sample, no neighbour before it; a run that
        // only retreats has no zero, and a rebound of its fastest retreat.
        let lost = points(&[(0.0, nan, -1.0), (1.0, nan, -3.0)]);
        let peak = Peak::of(&lost).unwrap();
        assert_eq!(
            (peak.at.t, peak.before.is_none(), peak.rebound),
            (0.0, true, 3.0)
        );
        assert_eq!(peak.largest, f64::NEG_INFINITY);
        assert_eq!(first_zero(&lost), None);
        assert!(Peak::of(&[]).is_none());
    }
}
