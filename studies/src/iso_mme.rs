//! A run as an ISO-MME test (`lpm simulate --iso-mme DIR`): the vehicle's
//! standard channels, the barrier force and the scenario's `[iso_mme]`
//! channels, on a uniform time base.
//!
//! **Channels.** Where the scenario has a crush channel (`metrics.crush`,
//! compression positive), its motion is the vehicle's, in ISO's signs (x
//! forward: the crush grows as the car moves forward into the barrier):
//! `10VEHCCG0000DSXP` the crush \[m\], `10VEHCCG0000VEXP` its rate \[m/s\]
//! (the impact speed at the start, negative in rebound) and
//! `10VEHCCG0000ACXP` its acceleration in g (9.806 65 m/s²; negative while
//! the car decelerates) — what the summary's pulse metrics read. The
//! barrier force `B0FBAR000000FOXP` \[N\] is the scenario's
//! [`IsoMme::barrier_force`] (compression positive: the load on the
//! barrier face). Each `[iso_mme.channels]` entry adds its signal under
//! its code, in the unit of its column; one with the code of a standard
//! channel replaces it. The filter class `P` (prefiltered above CFC 1000)
//! says the samples are the run's own, unfiltered.
//!
//! **Time base.** ISO-MME's implicit time base is uniform, `t = t0 + i·dt`:
//! `dt` is the scenario's `output_interval` and `t0 = 0`. The run's samples
//! are at `k·output_interval` already (a last one within half an interval
//! of `t_end` is moved onto it), so the channel's values are the samples
//! themselves at every grid time that has one (within 10⁻⁹ of an
//! interval); a grid time between two samples (the last, moved one) would
//! be linearly interpolated, and the grid ends at the last sample.

use crate::error::StudyError;
use lagrangian_crashdata::ChannelCode;
use lagrangian_crashdata::isomme::{Channel, Test};
use lagrangian_crashdata::text::Header;
use lagrangian_sim::pulse::STANDARD_GRAVITY;
use lagrangian_sim::scenario::Scenario;
use lagrangian_sim::scenario::iso_mme::IsoMme;
use lagrangian_sim::simulate::{Sample, SimulationResult};
use std::path::Path;

/// The vehicle's crush (forward displacement) channel.
pub const VEHICLE_DISPLACEMENT: &str = "10VEHCCG0000DSXP";
/// The vehicle's velocity channel.
pub const VEHICLE_VELOCITY: &str = "10VEHCCG0000VEXP";
/// The vehicle's acceleration channel, in g.
pub const VEHICLE_ACCELERATION: &str = "10VEHCCG0000ACXP";
/// The fixed barrier's force channel.
pub const BARRIER_FORCE: &str = "B0FBAR000000FOXP";

/// A finished run and where it comes from: what its test is made of.
#[derive(Clone, Copy)]
pub struct Run<'a> {
    /// The run.
    pub result: &'a SimulationResult,
    /// The scenario it ran under.
    pub scenario: &'a Scenario,
    /// The spec's file.
    pub spec: &'a Path,
    /// The scenario's file, or that there was none.
    pub scenario_name: &'a str,
}

/// The test `run` makes (see the module); an error where it would
/// have no channel.
pub fn run_test(run: Run) -> Result<Test, StudyError> {
    let scenario = run.scenario;
    let section = &scenario.iso_mme;
    let grid = Grid::of(&run.result.samples, scenario.output_interval);
    let mut channels = standard_channels(run, &grid);
    channels.retain(|c| !section.channels.iter().any(|s| s.code == c.code));
    for entry in &section.channels {
        let values = grid.resampled(|s| entry.signal.value(&s.columns()));
        let unit = entry.signal.unit.clone().unwrap_or_default();
        let about = format!("the run's {}", entry.signal.name);
        channels.push(channel(
            entry.code,
            &entry.signal.name,
            &unit,
            &about,
            (grid.dt, values),
        ));
    }
    if channels.is_empty() {
        return Err(StudyError::usage(
            "--iso-mme: the run has no channel to write: the scenario names no crush channel \
             (metrics.crush) and no [iso_mme.channels]",
        ));
    }
    Ok(Test {
        name: test_name(run),
        info: test_info(run, section),
        channel_info: [("Instrumentation standard", "NOVALUE")]
            .into_iter()
            .collect_header(),
        channels,
    })
}

/// The vehicle's channels (of the crush channel) and the barrier force,
/// where the scenario has them.
fn standard_channels(run: Run, grid: &Grid) -> Vec<Channel> {
    let scenario = run.scenario;
    let mut channels = Vec::new();
    if let Some(crush) = &scenario.crush {
        let motion = |k: usize| grid.resampled(|s| s.crush_motion(crush)[k]);
        let name = &crush.name;
        let g = STANDARD_GRAVITY;
        let acceleration: Vec<f64> = motion(2).into_iter().map(|a| a / g).collect();
        let vehicle = [
            (
                VEHICLE_DISPLACEMENT,
                "Vehicle displacement X (crush)",
                "m",
                format!("the crush {name}"),
                motion(0),
            ),
            (
                VEHICLE_VELOCITY,
                "Vehicle velocity X",
                "m/s",
                format!("the rate of the crush {name}"),
                motion(1),
            ),
            (
                VEHICLE_ACCELERATION,
                "Vehicle acceleration X",
                "g",
                format!("the acceleration of the crush {name} / {g} m/s^2"),
                acceleration,
            ),
        ];
        for (code, title, unit, about, values) in vehicle {
            channels.push(channel(
                standard(code),
                title,
                unit,
                &about,
                (grid.dt, values),
            ));
        }
    }
    if let Some(force) = &scenario.iso_mme.barrier_force {
        let values = grid.resampled(|s| force.value(&s.columns()));
        let about = format!("the force {} (compression positive)", force.name);
        channels.push(channel(
            standard(BARRIER_FORCE),
            "Barrier force X",
            "N",
            &about,
            (grid.dt, values),
        ));
    }
    channels
}

/// A standard code of this module (valid: the tests parse each).
fn standard(code: &str) -> ChannelCode {
    ChannelCode::parse(code).unwrap_or_else(|e| unreachable!("{e}"))
}

/// A channel of `values` every `dt` from 0, its header in the order of
/// NHTSA's ISO-MME 1.6 (the writer adds the sampling and extremes).
fn channel(
    code: ChannelCode,
    title: &str,
    unit: &str,
    about: &str,
    (dt, values): (f64, Vec<f64>),
) -> Channel {
    let dimension = code.dimension().code();
    let header = [
        ("Name of the channel", title),
        ("Laboratory channel code", "NOVALUE"),
        ("Customer channel code", "NOVALUE"),
        ("Channel code", code.as_str()),
        ("Reference channel", "implicit"),
        ("Data source", "Calculation"),
        ("Test object number", "1"),
        ("Channel frequency class", "NOVALUE"),
        ("Unit", unit),
        ("Sampling interval", "NOVALUE"),
        ("Time of first sample", "NOVALUE"),
        ("Number of samples", "NOVALUE"),
        ("Dimension", dimension.as_str()),
        ("Comments", &format!("simulated: {about}")),
    ]
    .into_iter()
    .collect_header();
    Channel {
        code,
        header,
        unit: unit.to_string(),
        t0: 0.0,
        dt,
        values,
    }
}

/// The test's name: `[iso_mme] name`, else the spec's stem.
fn test_name(run: Run) -> String {
    match &run.scenario.iso_mme.name {
        Some(name) => name.clone(),
        None => (run.spec.file_stem()).map_or("run".into(), |s| s.to_string_lossy().into_owned()),
    }
}

/// The `.mme`: the section's title and laboratory, where the run comes
/// from, one test object.
fn test_info(run: Run, section: &IsoMme) -> Header {
    let scenario = run.scenario;
    let title = (section.title.clone())
        .or_else(|| Some(scenario.description.trim().to_string()).filter(|d| !d.is_empty()))
        .unwrap_or_else(|| format!("{} — {}", run.result.model, run.scenario_name));
    let name = test_name(run);
    let source = format!(
        "simulated by lpm: {} under {}",
        run.spec.display(),
        run.scenario_name
    );
    let sampling = format!(
        "samples every {} s, the run's output interval",
        scenario.output_interval
    );
    [
        ("Data format edition number", "1.6"),
        (
            "Laboratory name",
            section.laboratory.as_deref().unwrap_or("NOVALUE"),
        ),
        ("Laboratory test ref. number", name.as_str()),
        ("Title", title.as_str()),
        ("Timestamp", "NOVALUE"),
        ("Type of the test", "NOVALUE"),
        ("Date of the test", "NOVALUE"),
        ("Number of test objects", "1"),
        ("Comments", source.as_str()),
        ("Comments", sampling.as_str()),
        ("Name of test object 1", run.result.model.as_str()),
    ]
    .into_iter()
    .collect_header()
}

/// `(name, value)` pairs as a [`Header`], `NOVALUE` (or nothing) for none.
trait CollectHeader {
    fn collect_header(self) -> Header;
}

impl<'a, I: Iterator<Item = (&'a str, &'a str)>> CollectHeader for I {
    fn collect_header(self) -> Header {
        let mut header = Header::new();
        for (name, value) in self {
            header.push(name, lagrangian_crashdata::text::value_of(value));
        }
        header
    }
}

/// The uniform time base of a run's samples.
struct Grid<'a> {
    samples: &'a [Sample],
    dt: f64,
    /// The number of grid times, `i·dt` for `i` below it, up to the last
    /// sample.
    len: usize,
}

/// How close to a grid time a sample is taken as at it, in intervals.
const ON_THE_GRID: f64 = 1e-9;

impl<'a> Grid<'a> {
    fn of(samples: &'a [Sample], dt: f64) -> Grid<'a> {
        let last = samples.last().map_or(0.0, |s| s.t);
        let len = match samples.is_empty() {
            true => 0,
            false => (last / dt + ON_THE_GRID).floor() as usize + 1,
        };
        Grid { samples, dt, len }
    }

    /// `value` of the samples at each grid time: the sample's own at a
    /// sample, linear between two.
    fn resampled(&self, value: impl Fn(&Sample) -> f64) -> Vec<f64> {
        let mut values = Vec::with_capacity(self.len);
        let mut k = 0;
        for i in 0..self.len {
            let t = i as f64 * self.dt;
            while k + 1 < self.samples.len() && self.samples[k + 1].t <= t + ON_THE_GRID * self.dt {
                k += 1;
            }
            let here = &self.samples[k];
            let next = self.samples.get(k + 1);
            values.push(match next {
                Some(next) if (t - here.t).abs() > ON_THE_GRID * self.dt => {
                    let w = (t - here.t) / (next.t - here.t);
                    (1.0 - w) * value(here) + w * value(next)
                }
                _ => value(here),
            });
        }
        values
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_standard_codes_are_codes() {
        for code in [
            VEHICLE_DISPLACEMENT,
            VEHICLE_VELOCITY,
            VEHICLE_ACCELERATION,
            BARRIER_FORCE,
        ] {
            assert!(ChannelCode::parse(code).is_ok(), "{code}");
        }
    }

    fn sample(t: f64, x: f64) -> Sample {
        Sample {
            t,
            q: vec![x],
            v: vec![],
            a: vec![],
            kinetic: 0.0,
            potential: 0.0,
            dissipated: 0.0,
            external_work: 0.0,
            inputs: vec![],
            outputs: vec![],
            components: vec![],
            multipliers: vec![],
            residuals: vec![],
            crush: None,
        }
    }

    #[test]
    fn samples_on_the_grid_are_taken_as_they_are_and_a_last_one_off_it_is_left_out() {
        // Samples at k·0.1 (as a run takes them), the last moved onto 0.25.
        let samples: Vec<Sample> = [0.0, 0.1, 0.2, 0.25]
            .iter()
            .map(|&t| sample(t, 10.0 * t * t))
            .collect();
        let grid = Grid::of(&samples, 0.1);
        assert_eq!(grid.len, 3);
        let values = grid.resampled(|s| s.q[0]);
        assert_eq!(values, [0.0, 10.0 * 0.1 * 0.1, 10.0 * 0.2 * 0.2]);
        // Between two samples (a coarser run, a finer grid): linear.
        let grid = Grid::of(&samples[..3], 0.05);
        let values = grid.resampled(|s| s.q[0]);
        assert_eq!(values.len(), 5);
        assert!((values[1] - 0.05).abs() < 1e-15, "{}", values[1]);
        assert!((values[3] - 0.25).abs() < 1e-15, "{}", values[3]);
        // A time a rounding away from the grid is on it.
        let samples = [sample(0.0, 1.0), sample(0.30000000000000004, 2.0)];
        let values = Grid::of(&samples, 0.3).resampled(|s| s.q[0]);
        assert_eq!(values, [1.0, 2.0]);
    }
}
