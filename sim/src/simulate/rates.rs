//! The accelerations of the output samples, from the dense output where it
//! is accurate.
//!
//! A sample that needs `q̈` (a deceleration channel, the outputs, a kept
//! sample) can solve `M q̈ = f` at its state: one evaluation of the model
//! with every input call. Dormand–Prince's continuous extension already
//! carries `q̈`: the time derivative of its interpolant of `q̇`, which is
//! `F` at both ends of the step and within `O(h⁴)` of `q̈` between them —
//! where `q̈` is smooth over the step. A kink of an input inside the step
//! (the slope of a time table interpolated linearly jumps at its points)
//! puts a kink in `q̈` that no polynomial over the step follows.
//!
//! So a sample takes `q̈` from the dense output when
//!
//! * the scenario lets it (`[simulation] accelerations = "interpolated"`,
//!   the default; `"exact"` solves at every sample);
//! * the model has no constraints: their multipliers and residuals come
//!   from the solve;
//! * the method's dense output gives a derivative
//!   ([`DenseStep::eval_derivative`]: Dormand–Prince, not the cubic
//!   Hermite of RK4 and TR-BDF2);
//! * every input the dynamics calls is smooth over the step as the method
//!   took it ([`DenseStep::uncut_end`]; [`Component::smoothness`]): a
//!   component smooth within every step, or a function of time with no
//!   kink inside the step. Changes of a component's regime are events,
//!   and the component continues its formula past them until the event is
//!   applied, so a step cut at one is smooth; a switching function of the
//!   model is not continued, so with one a step cut at an event is not.
//!
//! A step whose only kinks inside are those of inputs of time whose
//! smooth stand-ins its stages took ([`super::kinks`]) has a dense output
//! that follows the stand-ins: its samples take the derivative and add
//! what the kinks change ([`super::kink_rates`]).
//!
//! Otherwise the sample solves exactly. The choice depends on the step
//! alone, not on whether the samples are kept: a run's summary is the same
//! either way.
//!
//! [`Component::smoothness`]: crate::components::Component::smoothness

use super::CrashProblem;
use super::kink_rates::KinkCorrection;
use crate::components::{BoundInputs, Smoothness};
use crate::ode::{DenseStep, Part, PhaseState};
use crate::scenario::options::SampleAccelerations;
use lagrangian_runtime::LagrangianSystem;
use nalgebra::SVector;

/// Which steps' samples take `q̈` from the dense output.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct DenseAccelerations {
    /// The kinks in time of the inputs the dynamics calls, in increasing
    /// order; `None`: no step's samples (exact ones asked for, a model with
    /// constraints, or an input not known to be smooth).
    time_kinks: Option<Vec<f64>>,
    /// The model has switching functions, whose kinks a step cut at an
    /// event may have stepped across.
    switching: bool,
    /// Every kink of `time_kinks` is one the stages of a step may take a
    /// stand-in for ([`super::kinks`]): a step across one is corrected
    /// ([`super::kink_rates`]) instead of solved.
    smoothed: bool,
}

/// Where the samples of a step take `q̈` from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum StepRates {
    /// The derivative of the step's dense output.
    Interpolated,
    /// The derivative of the dense output of a step whose stages took the
    /// stand-ins of time tables, corrected for their kinks
    /// ([`super::kink_rates`]).
    Corrected,
    /// `M q̈ = f` at each sample.
    Solved,
}

impl DenseAccelerations {
    /// The choice of a run of `problem` whose scenario asks for `choice`.
    pub(super) fn of<const N: usize, S: LagrangianSystem<N>>(
        problem: &CrashProblem<N, S>,
        choice: SampleAccelerations,
    ) -> DenseAccelerations {
        let system = problem.system;
        let time_kinks = match (choice, system.constraint_count()) {
            (SampleAccelerations::Interpolated, 0) => {
                time_kinks(system, &problem.inputs, problem.time_sites())
            }
            _ => None,
        };
        let smoothed = time_kinks.as_ref() == Some(&problem.kinked().kinks());
        DenseAccelerations {
            time_kinks,
            switching: system.switching_count() > 0,
            smoothed,
        }
    }

    /// Where the samples within `step` take `q̈` from: its dense output
    /// when every input is smooth over the step as the method took it, or
    /// when the only kinks inside are those of inputs of time that may
    /// have taken stand-ins.
    fn of_step<Y>(&self, step: &dyn DenseStep<Y>) -> StepRates {
        let Some(kinks) = &self.time_kinks else {
            return StepRates::Solved;
        };
        let (start, end) = (step.t0(), step.uncut_end());
        if self.switching && step.t1() < end {
            return StepRates::Solved;
        }
        // A step ended at a kink (`stop_at_kinks`) ends there to rounding.
        let slack = 64.0 * f64::EPSILON * start.abs().max(end.abs());
        let first = kinks.partition_point(|&kink| kink <= start + slack);
        match kinks.get(first).is_none_or(|&kink| kink >= end - slack) {
            true => StepRates::Interpolated,
            false if self.smoothed => StepRates::Corrected,
            false => StepRates::Solved,
        }
    }
}

/// Where the samples of one step take `q̈` from, made ready for them.
pub(super) enum SampleRates<const N: usize> {
    /// The derivative of the step's dense output.
    Interpolated,
    /// The derivative, corrected for the kinks of the time tables whose
    /// stand-ins the step's stages took.
    Corrected(KinkCorrection<N>),
    /// `M q̈ = f` at each sample.
    Solved,
}

impl<const N: usize> SampleRates<N> {
    /// Where the samples at `times` within `step` take `q̈` from (`dense`
    /// says), the kinks' correction made where they need one; solved
    /// where it cannot be made.
    pub(super) fn of<S: LagrangianSystem<N>>(
        dense: &DenseAccelerations,
        problem: &mut CrashProblem<N, S>,
        step: &dyn DenseStep<PhaseState<N>>,
        times: &[f64],
    ) -> SampleRates<N> {
        match dense.of_step(step) {
            StepRates::Interpolated => SampleRates::Interpolated,
            StepRates::Corrected if !times.is_empty() => KinkCorrection::of(problem, step, times)
                .map_or(SampleRates::Solved, SampleRates::Corrected),
            StepRates::Corrected | StepRates::Solved => SampleRates::Solved,
        }
    }

    /// `q̈` of sample `k`, at `t`, of the step (the derivative of its dense
    /// output's motion written into `rate`); `None` where it is to be
    /// solved.
    pub(super) fn at(
        &self,
        step: &dyn DenseStep<PhaseState<N>>,
        (k, t): (usize, f64),
        rate: &mut PhaseState<N>,
    ) -> Option<SVector<f64, N>> {
        match self {
            SampleRates::Interpolated => interpolated(step, t, rate),
            SampleRates::Corrected(correction) => {
                interpolated(step, t, rate).map(|a| a + correction.at(k))
            }
            SampleRates::Solved => None,
        }
    }
}

/// `q̈` at `t` from the derivative of `step`'s dense output (the
/// derivative of the motion written into `rate`), if its method gives one.
fn interpolated<const N: usize>(
    step: &dyn DenseStep<PhaseState<N>>,
    t: f64,
    rate: &mut PhaseState<N>,
) -> Option<SVector<f64, N>> {
    (step.eval_derivative_part(t, Part::Motion, rate)).then_some(rate.v)
}

/// The kinks in time of the inputs the dynamics of `system` calls, in
/// increasing order; `None` when one of them is not known to be smooth
/// within a step: unbound, of [`Smoothness::Unknown`], or with kinks in an
/// argument other than the time (`time_sites`: [`super::stops::time_sites`]).
fn time_kinks<const N: usize, S: LagrangianSystem<N>>(
    system: &S,
    inputs: &BoundInputs,
    time_sites: &[bool],
) -> Option<Vec<f64>> {
    let mut kinks = Vec::new();
    for (&(input, _), &is_time) in system.input_sites().iter().zip(time_sites) {
        let binding = (*inputs.bindings.get(input)?)?;
        let component = &inputs.components.get(binding.component)?.component;
        let smoothness = component.smoothness();
        match (&smoothness, smoothness.kinks()) {
            (Smoothness::Smooth, _) => {}
            (_, Some(points)) if points.is_empty() || is_time => kinks.extend(points),
            _ => return None,
        }
    }
    kinks.sort_by(f64::total_cmp);
    kinks.dedup();
    Some(kinks)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ode;
    use crate::scenario::Choice;
    use crate::scenario::{ModelNames, Scenario};
    use crate::simulate::{SimulationResult, simulate};
    use lagrangian_runtime::Interpreted;
    use std::path::Path;

    const SPRING: &str = include_str!("../../../specs/spring_mass_damper.lpm");

    /// `m ẍ + c ẋ + k x = push(t)`: m = 1 kg, k = 100 N/m, c = 0.5 N·s/m.
    fn spring() -> (Interpreted<1>, ModelNames) {
        let model = lagrangian_core::interpret(SPRING).unwrap();
        let names = ModelNames::of_interpreted(&model);
        (Interpreted::new(model).unwrap(), names)
    }

    /// The spring's runs under the scenario `text` (read as if from `dir`),
    /// with interpolated and with exact accelerations.
    fn runs(text: &str, dir: Option<&Path>) -> [SimulationResult; 2] {
        let (model, names) = spring();
        let file = dir.map(|dir| dir.join("s.toml"));
        ["interpolated", "exact"].map(|choice| {
            let setting = [format!("simulation.accelerations={choice}")];
            let scenario = Scenario::parse(
                text,
                file.as_deref(),
                &names,
                &crate::scenario::Override::parse_all(&setting).unwrap(),
            )
            .unwrap();
            simulate(&model, &scenario).unwrap()
        })
    }

    #[test]
    fn a_damped_oscillator_samples_the_closed_form_acceleration() {
        // Pushed by F = 1 N from rest at x = 0: x = F/k + e^(−σt)(A cos ωt +
        // B sin ωt) with σ = c/2m, ω = √(k/m − σ²), A = −F/k, B = σA/ω, and
        // ẍ = (F − c ẋ − k x)/m.
        let text = "[simulation]\nt_end = 0.5\noutput_interval = 1e-3\n\
            [components.c]\ntype = \"constant\"\nvalues = { push = 1.0 }\n";
        let [interpolated, exact] = runs(text, None);
        let (sigma, omega) = (0.25f64, (100.0f64 - 0.0625).sqrt());
        let (a, b) = (-0.01, -0.0025 / omega);
        let closed = |t: f64| {
            let (decay, (sin, cos)) = ((-sigma * t).exp(), (omega * t).sin_cos());
            let x = 0.01 + decay * (a * cos + b * sin);
            let v = decay * ((omega * b - sigma * a) * cos - (sigma * b + omega * a) * sin);
            1.0 - 0.5 * v - 100.0 * x
        };
        let (mut from_dense, mut worst) = (0, [0.0f64; 2]);
        for (i, e) in interpolated.samples.iter().zip(&exact.samples) {
            let want = closed(i.t);
            for (worst, got) in worst.iter_mut().zip([i.a[0], e.a[0]]) {
                *worst = worst.max((got - want).abs());
            }
            from_dense += usize::from(i.a != e.a);
        }
        // |ẍ| ≤ 1 m/s² at the default rtol 1e-8: the interpolated within
        // 2e-7, the solved within 2e-8.
        assert!(worst[0] < 2e-7 && worst[1] < 2e-8, "{worst:?}");
        assert_eq!(interpolated.samples.len(), 501);
        assert!(
            from_dense > 450,
            "{from_dense} of 501 samples from the dense output"
        );
    }

    /// The steps of the spring's run pushed by `push.csv` in `dir` under
    /// `text`: `(t0, t1, uncut end)`.
    fn steps(text: &str, dir: &Path) -> Vec<(f64, f64, f64)> {
        let (model, names) = spring();
        let scenario = Scenario::parse(text, Some(&dir.join("s.toml")), &names, &[]).unwrap();
        let mut problem = CrashProblem::new(&model, scenario.inputs.clone());
        problem.time_kinks(scenario.time_kinks);
        let y0 = PhaseState::zeros();
        problem.start(0.0, &y0).unwrap();
        let mut steps = Vec::new();
        ode::integrate(
            scenario.method,
            &mut problem,
            (0.0, y0),
            scenario.t_end,
            &scenario.options,
            &mut |_, step| steps.push((step.t0(), step.t1(), step.uncut_end())),
        )
        .unwrap();
        steps
    }

    #[test]
    fn the_samples_of_a_step_across_a_kink_of_a_time_table_are_solved() {
        let dir = std::env::temp_dir().join(format!("lagrangian-rates-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        // Kinks at 10, 20 and 30 ms, which steps straddle, their stages
        // seeing the kinks (smoothed ones: `kinks::tests`).
        let table = "t,F\n0,0\n0.01,50\n0.02,-20\n0.03,0\n0.05,0\n";
        std::fs::write(dir.join("push.csv"), table).unwrap();
        let text = "[simulation]\nt_end = 0.05\noutput_interval = 1e-4\ntime_kinks = \"exact\"\n\
            [components.table]\ntype = \"table\"\nfile = \"push.csv\"\ncolumns = { push = \"F\" }\n";
        let [interpolated, exact] = runs(text, Some(&dir));
        let steps = steps(text, &dir);
        let straddles = |&(t0, _, end): &(f64, f64, f64)| {
            [0.01, 0.02, 0.03]
                .iter()
                .any(|&kink| t0 < kink && kink < end)
        };
        let scale = exact
            .samples
            .iter()
            .fold(0.0f64, |m, s| m.max(s.a[0].abs()));
        let (mut solved, mut from_dense) = (0, 0);
        for (i, e) in interpolated.samples.iter().zip(&exact.samples).skip(1) {
            let step = steps.iter().find(|step| step.1 >= i.t).unwrap();
            if straddles(step) {
                assert_eq!(i.a, e.a, "t = {}", i.t);
                solved += 1;
            } else {
                assert!((i.a[0] - e.a[0]).abs() < 1e-7 * scale, "t = {}", i.t);
                from_dense += usize::from(i.a != e.a);
            }
        }
        assert!(
            solved >= 3 && from_dense > 300,
            "{solved} solved, {from_dense} interpolated"
        );
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn the_paper_scenario_interpolates_between_the_kinks_of_its_barrier_table() {
        let model =
            lagrangian_core::interpret(include_str!("../../../specs/yaris_double_pendulum.lpm"))
                .unwrap();
        let names = ModelNames::of_interpreted(&model);
        let system = Interpreted::<3>::new(model).unwrap();
        let file = Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../specs/scenarios/yaris_full_frontal.toml"
        ));
        let choice = |settings: &[&str]| {
            let settings: Vec<String> = settings.iter().map(|s| s.to_string()).collect();
            let scenario = Scenario::load(
                file,
                &names,
                &crate::scenario::Override::parse_all(&settings).unwrap(),
            )
            .unwrap();
            let problem = CrashProblem::new(&system, scenario.inputs.clone());
            DenseAccelerations::of(&problem, scenario.accelerations)
        };
        let kinks = choice(&[]).time_kinks.unwrap();
        // The barrier's half sine: a point every millisecond for 80 ms.
        assert!(
            kinks.len() > 50 && kinks.windows(2).all(|w| w[0] < w[1]),
            "{kinks:?}"
        );
        assert_eq!(choice(&["simulation.accelerations=exact"]).time_kinks, None);
        // A crush element that steps across its kinks is not known smooth.
        let unheld = choice(&["components.front_end.stop_at_kinks=false"]);
        assert_eq!(unheld.time_kinks, None);
        // A smooth barrier has kinks only where its table ends.
        let smooth = choice(&["components.barrier.interpolation=pchip"]);
        assert_eq!(smooth.time_kinks.unwrap().len(), 2);
    }

    #[test]
    fn the_choice_is_read_by_name() {
        for &choice in SampleAccelerations::ALL {
            assert_eq!(SampleAccelerations::parse(choice.name()), Some(choice));
        }
        assert_eq!(SampleAccelerations::parse("dense"), None);
        let (_, names) = spring();
        let text = "[simulation]\naccelerations = \"dense\"\n\
            [components.c]\ntype = \"constant\"\nvalues = { push = 1.0 }\n";
        let error = Scenario::parse(text, None, &names, &[]).unwrap_err();
        assert!(
            error
                .message
                .contains("simulation.accelerations = `dense`; use interpolated, exact"),
            "{error:?}"
        );
    }
}
