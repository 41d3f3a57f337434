//! One run of a spec file under a scenario, and the files it writes
//! (`trajectory.csv`, `summary.json`, `plots.svg`).

use crate::compare::source::{Source, TRAJECTORY, test_signals};
use crate::compare::{ChannelPair, CompareRequest, Comparison, compare, compare_signals};
use crate::error::StudyError;
use crate::plot::{PlotSetup, figure_svg};
use crate::report::{Derived, ReportParts, report_html};
use crate::spec::{compile, find_scenario};
use lagrangian_core::Compiled;
use lagrangian_runtime::{Interpreted, InterpretedModel, WithDimension};
use lagrangian_sim::fault::Fault;
use lagrangian_sim::files::Files;
use lagrangian_sim::report::{Units, summary_json, trajectory_csv, write_all_atomically};
use lagrangian_sim::scenario::{ModelNames, Override, Scenario};
use lagrangian_sim::simulate::{SimulationError, SimulationResult, SolverError, simulate};
use std::path::{Path, PathBuf};

/// A finished simulation with what its report needs.
pub struct Simulated {
    /// The run.
    pub result: SimulationResult,
    /// The model run (interpreted), for names and units.
    pub model: InterpretedModel,
    /// The scenario it ran under.
    pub scenario: Scenario,
    /// The scenario's file, or that there was none.
    pub scenario_name: String,
    /// The spec's file.
    pub spec: PathBuf,
}

impl Simulated {
    /// The trajectory as CSV, with units in the column names (trajectory.csv).
    pub fn trajectory_csv(&self) -> String {
        trajectory_csv(&self.result, &units(&self.result, &self.model))
    }
}

/// Compiles the spec at `spec`, loads its scenario (`scenario`, else the one
/// beside the spec that names it, else the defaults) with `settings`
/// (`--set` entries) and simulates it: what `lpm simulate` does before it
/// writes its files ([`write_outputs`]). Every file is read from `files`.
pub fn simulate_spec(
    files: &dyn Files,
    spec: &Path,
    scenario: Option<&Path>,
    settings: &[Override],
) -> Result<Simulated, StudyError> {
    simulate_compiled(files, spec, scenario, settings).map(|(simulated, _)| simulated)
}

/// [`simulate_spec`], and the spec's equations and audit for the report
/// ([`crate::report`]).
pub fn simulate_for_report(
    files: &dyn Files,
    spec: &Path,
    scenario: Option<&Path>,
    settings: &[Override],
) -> Result<(Simulated, Derived), StudyError> {
    let (simulated, mut compiled) = simulate_compiled(files, spec, scenario, settings)?;
    Ok((simulated, Derived::of(&mut compiled)))
}

/// The run of [`simulate_spec`] and the spec compiled.
fn simulate_compiled(
    files: &dyn Files,
    spec: &Path,
    scenario: Option<&Path>,
    settings: &[Override],
) -> Result<(Simulated, Compiled), StudyError> {
    let (compiled, model, scenario_path, scenario) = load_spec(files, spec, scenario, settings)?;
    let result = dispatch(model.clone(), &scenario).map_err(|failure| {
        match domain_cause(&failure, &compiled, &scenario, (files, spec)) {
            Some(why) => failure.0.because(&why),
            None => failure.0,
        }
    })?;
    let scenario_name = scenario_path
        .as_ref()
        .map_or("default scenario (no scenario file)".to_string(), |p| {
            p.display().to_string()
        });
    let simulated = Simulated {
        result,
        model,
        scenario,
        scenario_name,
        spec: spec.to_path_buf(),
    };
    Ok((simulated, compiled))
}

/// Compiles the spec at `spec` and resolves its scenario (`scenario`, else
/// the one beside the spec that names it, else the defaults) with
/// `settings`: the compiled spec, its interpreted model, the scenario's file
/// and the scenario, each failing as a run fails. Every file is read from
/// `files`.
pub fn load_spec(
    files: &dyn Files,
    spec: &Path,
    scenario: Option<&Path>,
    settings: &[Override],
) -> Result<(Compiled, InterpretedModel, Option<PathBuf>, Scenario), StudyError> {
    let compiled = compile(files, spec)?;
    let model = crate::spec::interpreted(&compiled);
    let names = ModelNames::of_interpreted(&model);
    let scenario_path = match scenario {
        Some(p) => Some(p.to_path_buf()),
        None => find_scenario(files, spec)?,
    };
    let scenario = match &scenario_path {
        Some(path) => Scenario::read(files, path, &names, settings),
        None => Scenario::defaults(&names, settings),
    }
    .map_err(|e| StudyError::scenario(&e))?;
    Ok((compiled, model, scenario_path, scenario))
}

/// `simulate` on the model at its dimension.
struct Simulate<'a> {
    scenario: &'a Scenario,
}

impl WithDimension for Simulate<'_> {
    type Output = Result<SimulationResult, RunFailure>;

    fn run<const N: usize>(self, system: Interpreted<N>) -> Self::Output {
        simulate(&system, self.scenario).map_err(|e| {
            let failure = StudyError::simulation(&e, system.inner().coordinates());
            let failure = match mass_cause(&e, system.inner(), self.scenario) {
                Some(why) => failure.because(&why),
                None => failure,
            };
            let fault = match e {
                SimulationError::Solver {
                    error: SolverError::Rhs { t, error },
                    ..
                } => Some(Box::new((t, error))),
                _ => None,
            };
            (failure, fault)
        })
    }
}

/// Which call of the spec left its domain where the run turned non-finite
/// (`acos` of 2, `ln` of a negative number, a division by zero), with its
/// file:line and the value of its argument there.
fn domain_cause(
    failure: &RunFailure,
    compiled: &Compiled,
    scenario: &Scenario,
    (files, spec): (&dyn Files, &Path),
) -> Option<String> {
    let (t, Fault::NonFinite { q, qd, .. }) = failure.1.as_deref()? else {
        return None;
    };
    let model = &compiled.model;
    let mut parameters: Vec<f64> = model.parameters.iter().map(|p| p.default).collect();
    for &(i, value) in &scenario.parameters {
        parameters[i] = value;
    }
    let (check, value) = model.domain_violation(*t, q, qd, &parameters)?;
    let source = files.text(spec).ok()?;
    Some(check.describe(&spec.display().to_string(), &source, value))
}

/// Which of the scenario's parameters made the mass matrix not positive
/// definite where the run failed on it (`model`: at its defaults).
fn mass_cause(
    e: &SimulationError,
    model: &InterpretedModel,
    scenario: &Scenario,
) -> Option<String> {
    let SimulationError::Solver {
        error: SolverError::Rhs { t, error: fault },
        ..
    } = e
    else {
        return None;
    };
    let Fault::SingularMassMatrix { q, qd } = fault else {
        return None;
    };
    let defaults = model.parameters().to_vec();
    let mut with_scenario = model.clone();
    let names = model.parameter_names().to_vec();
    for &(i, value) in &scenario.parameters {
        with_scenario.set_parameter(&names[i], value).ok()?;
    }
    let set: Vec<usize> = scenario.parameters.iter().map(|&(i, _)| i).collect();
    crate::mass::blame(&with_scenario, &defaults, &set, (*t, q, qd))
}

/// The run, or its failure with the fault and the time it happened at.
type RunFailure = (StudyError, Option<Box<(f64, Fault)>>);

fn dispatch(model: InterpretedModel, scenario: &Scenario) -> Result<SimulationResult, RunFailure> {
    model
        .with_dimension(Simulate { scenario })
        .map_err(|e| (StudyError::model(e), None))?
}

/// The units of the trajectory's columns.
fn units(result: &SimulationResult, model: &InterpretedModel) -> Units {
    let input_units = result
        .input_columns
        .iter()
        .map(|name| {
            let k = model.input_names().iter().position(|n| n == name)?;
            model.input_units()[k].clone()
        })
        .collect();
    Units {
        coordinates: model.coordinate_units().to_vec(),
        inputs: input_units,
        outputs: model.output_units().to_vec(),
        multipliers: model.multiplier_units().to_vec(),
    }
}

/// What [`write_outputs`] writes besides `trajectory.csv`, `summary.json`
/// and `plots.svg`.
#[derive(Clone, Copy, Default)]
pub struct Extras<'a> {
    /// The spec's equations and audit: also `report.html`
    /// ([`crate::report`]).
    pub report: Option<&'a Derived>,
    /// A folder to write the run into as an ISO-MME test
    /// ([`crate::iso_mme`]), beside the outputs.
    pub iso_mme: Option<&'a Path>,
    /// A test the report rates the run against (ISO/TS 18571) and overlays
    /// on it; only with `report`.
    pub test: Option<TestOverlay<'a>>,
}

/// The test a report compares the run with: its file (an ISO-MME test, a
/// CSV or another run's folder) and the pairs of a test channel and a run
/// column to rate (`lpm compare`'s `--channel`).
#[derive(Clone, Copy)]
pub struct TestOverlay<'a> {
    /// The test.
    pub test: &'a Path,
    /// The pairs; empty: the channels of the same name.
    pub channels: &'a [ChannelPair],
    /// Where the test's CSV is read from.
    pub files: &'a dyn Files,
}

/// `files`, with the run's `trajectory.csv` at `path` from memory: the
/// comparison of a report reads the run before its files are written.
#[derive(Debug)]
struct WithTrajectory<'a> {
    path: PathBuf,
    text: std::sync::Arc<str>,
    files: &'a dyn Files,
}

impl Files for WithTrajectory<'_> {
    fn text(&self, path: &Path) -> std::io::Result<std::sync::Arc<str>> {
        match path == self.path {
            true => Ok(std::sync::Arc::clone(&self.text)),
            false => self.files.text(path),
        }
    }
}

/// The run compared with the test of `overlay`: the test the reference;
/// the comparison the run as an ISO-MME test (channels by their codes,
/// signed as ISO signs them) where the test is one, else the run's
/// trajectory (`text`, not yet written to `out`).
fn against_test(
    overlay: &TestOverlay,
    out: &Path,
    text: &str,
    run: crate::iso_mme::Run,
) -> Result<Comparison, StudyError> {
    if crate::test_data::is_iso_mme(overlay.test) {
        let reference = Source::at(overlay.test).read(overlay.files)?;
        let name = out.join("(the run as an ISO-MME test)");
        let comparison = test_signals(&crate::iso_mme::run_test(run)?, &name)?;
        return compare_signals(reference, comparison, overlay.channels, None);
    }
    let path = out.join(TRAJECTORY);
    let files = WithTrajectory {
        path: path.clone(),
        text: text.into(),
        files: overlay.files,
    };
    let request = CompareRequest {
        reference: overlay.test.to_path_buf(),
        comparison: path,
        channels: overlay.channels.to_vec(),
        interval: None,
    };
    compare(&request, &files)
}

/// Writes `trajectory.csv`, `summary.json` and `plots.svg` of `simulated`
/// (and what `extras` asks for) into `out` (created if need be), all or
/// none; the ISO-MME test is a folder of its own, written whole or not at
/// all after the files.
pub fn write_outputs(out: &Path, simulated: &Simulated, extras: Extras) -> Result<(), StudyError> {
    let Simulated {
        result, scenario, ..
    } = simulated;
    // Checked before anything is written.
    let iso_mme = (extras.iso_mme)
        .map(|dir| crate::iso_mme::run_test(run_parts(simulated)).map(|test| (dir, test)))
        .transpose()?;
    std::fs::create_dir_all(out)
        .map_err(|e| StudyError::io(format!("cannot create {}: {e}", out.display())))?;
    let setup = PlotSetup {
        crush: scenario.crush.clone(),
        channels: scenario.channels.clone(),
        pitch: scenario.pitch.clone(),
        force_deflection: scenario.inputs.force_deflection_columns(),
        g: lagrangian_sim::pulse::STANDARD_GRAVITY,
        title: figure_title(&result.model, scenario, &simulated.scenario_name),
    };
    let svg =
        figure_svg(result, &setup).map_err(|e| StudyError::io(format!("plotting failed: {e}")))?;
    let trajectory = simulated.trajectory_csv();
    let comparison = match (extras.report, &extras.test) {
        (Some(_), Some(overlay)) => Some(against_test(
            overlay,
            out,
            &trajectory,
            run_parts(simulated),
        )?),
        _ => None,
    };
    let mut files = vec![
        ("trajectory.csv", trajectory),
        ("summary.json", summary_json(result)),
    ];
    if let Some(derived) = extras.report {
        let parts = ReportParts {
            result,
            scenario_name: &simulated.scenario_name,
            derived,
            spec: &simulated.spec.display().to_string(),
            plots_svg: &svg,
            test: comparison.as_ref(),
        };
        files.push(("report.html", report_html(&parts)));
    }
    files.push(("plots.svg", svg));
    let paths: Vec<_> = files.iter().map(|(name, _)| out.join(name)).collect();
    let contents: Vec<(&Path, &[u8])> = (paths.iter().zip(&files))
        .map(|(path, (_, text))| (path.as_path(), text.as_bytes()))
        .collect();
    write_all_atomically(&contents)
        .map_err(|(path, e)| StudyError::io(format!("cannot write {}: {e}", path.display())))?;
    if let Some((dir, test)) = iso_mme {
        lagrangian_crashdata::isomme::write(&test, dir)
            .map_err(|e| StudyError::io(e.to_string()))?;
    }
    Ok(())
}

/// What the ISO-MME test of a run is made of.
fn run_parts(simulated: &Simulated) -> crate::iso_mme::Run<'_> {
    crate::iso_mme::Run {
        result: &simulated.result,
        scenario: &simulated.scenario,
        spec: &simulated.spec,
        scenario_name: &simulated.scenario_name,
    }
}

/// `model — description` of the scenario, or `model — scenario file` for a
/// scenario without a description.
fn figure_title(model: &str, scenario: &Scenario, scenario_name: &str) -> String {
    match scenario.description.trim() {
        "" => format!("{model} — {scenario_name}"),
        description => format!("{model} — {description}"),
    }
}
