//! `lpm simulate`: run a spec file under a scenario and write the results.

use crate::failure::{Failure, Outcome};
use crate::spec::{compile, find_scenario, out_dir};
use lagrangian_core::Compiled;
use lagrangian_model::{Interpreted, InterpretedModel, WithDimension};
use lagrangian_sim::fault::Fault;
use lagrangian_sim::ode::Method;
use lagrangian_sim::report::{
    Units, summary_json, text_summary, trajectory_csv, write_all_atomically,
};
use lagrangian_sim::scenario::{ModelNames, Scenario};
use lagrangian_sim::simulate::{SimulationError, SimulationResult, SolverError, simulate};
use lagrangian_studies::plot::{PlotSetup, figure_svg};
use std::path::{Path, PathBuf};

/// Options of `lpm simulate`.
#[derive(clap::Args)]
pub struct Args {
    /// The spec file (`.lpm`).
    spec: PathBuf,
    /// The scenario (TOML); by default the one in `scenarios/` beside the spec that names it.
    #[arg(long)]
    scenario: Option<PathBuf>,
    /// Override a parameter (`k1=7e4`), give an input a constant (`barrier_x1=0`)
    /// or set a scenario entry (`components.front_end.unloading=elastic`);
    /// `KEY*=FACTOR` multiplies a parameter or every number of an entry
    /// (`components.front_end.stiffness_values*=0.9`), as in `sweep --grid`.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
    /// End time \[s\].
    #[arg(long)]
    t_end: Option<f64>,
    /// Relative tolerance of the local error.
    #[arg(long)]
    rtol: Option<f64>,
    /// Absolute tolerance of the local error.
    #[arg(long)]
    atol: Option<f64>,
    /// Integration method (the scenario's `simulation.method`).
    #[arg(long, value_parser = methods())]
    method: Option<String>,
    /// Output directory (default lpm-out/NAME, NAME the spec file's stem).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Make warnings (printed on stderr, listed in summary.json) errors:
    /// the outputs are written, and lpm exits with status 9.
    #[arg(long)]
    strict: bool,
}

/// The method names `--method` takes: [`Method::NAMES`], and the former
/// names of [`Method::ALIASES`] (accepted, not listed).
fn methods() -> clap::builder::PossibleValuesParser {
    let names = Method::NAMES.map(clap::builder::PossibleValue::new);
    let aliases =
        Method::ALIASES.map(|(alias, _)| clap::builder::PossibleValue::new(alias).hide(true));
    clap::builder::PossibleValuesParser::new(names.into_iter().chain(aliases))
}

/// The settings the command line adds to the scenario's.
fn settings(options: &Args) -> Vec<String> {
    let mut settings = options.set.clone();
    settings.extend(flag_settings(options).into_iter().map(|(_, s)| s));
    settings
}

/// The settings `--t-end`, `--rtol`, `--atol` and `--method` stand for,
/// each with the flag as written in messages (`--rtol 0.9`).
fn flag_settings(options: &Args) -> Vec<(String, String)> {
    let mut settings = Vec::new();
    if let Some(t) = options.t_end {
        settings.push((format!("--t-end {t}"), format!("simulation.t_end={t}")));
    }
    if let Some(r) = options.rtol {
        settings.push((format!("--rtol {r}"), format!("simulation.rtol={r}")));
    }
    if let Some(a) = options.atol {
        settings.push((format!("--atol {a}"), format!("simulation.atol={a}")));
    }
    if let Some(m) = &options.method {
        settings.push((
            format!("--method {m}"),
            format!("simulation.method=\"{m}\""),
        ));
    }
    settings
}

/// `failure`, naming the flag a setting came from where it names the
/// setting (`--rtol 0.9: …`, not `--set simulation.rtol=0.9: …`).
fn naming_flags(failure: Failure, options: &Args) -> Failure {
    for (flag, setting) in flag_settings(options) {
        let named = format!("--set {setting}:");
        if let Some(rest) = failure.message().strip_prefix(&named) {
            return Failure::new(failure.status, format!("{flag}:{rest}"));
        }
    }
    failure
}

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
/// writes its files.
pub fn simulate_spec(
    spec: &Path,
    scenario: Option<&Path>,
    settings: &[String],
) -> Result<Simulated, Failure> {
    let (compiled, model, scenario_path, scenario) = load_spec(spec, scenario, settings)?;
    let result = dispatch(model.clone(), &scenario).map_err(|failure| {
        match domain_cause(&failure, &compiled, &scenario, spec) {
            Some(why) => failure.0.because(&why),
            None => failure.0,
        }
    })?;
    let scenario_name = scenario_path
        .as_ref()
        .map_or("default scenario (no scenario file)".to_string(), |p| {
            p.display().to_string()
        });
    Ok(Simulated {
        result,
        model,
        scenario,
        scenario_name,
    })
}

/// Compiles the spec at `spec` and resolves its scenario (`scenario`, else
/// the one beside the spec that names it, else the defaults) with
/// `settings`: the compiled spec, its interpreted model, the scenario's file
/// and the scenario, each failing as `lpm simulate` fails.
pub fn load_spec(
    spec: &Path,
    scenario: Option<&Path>,
    settings: &[String],
) -> Result<(Compiled, InterpretedModel, Option<PathBuf>, Scenario), Failure> {
    let compiled = compile(spec)?;
    let model = crate::spec::interpreted(&compiled);
    let names = ModelNames::of_interpreted(&model);
    let scenario_path = match scenario {
        Some(p) => Some(p.to_path_buf()),
        None => find_scenario(spec)?,
    };
    let scenario = match &scenario_path {
        Some(path) => Scenario::load(path, &names, settings),
        None => Scenario::defaults(&names, settings),
    }
    .map_err(|e| Failure::scenario(&e))?;
    Ok((compiled, model, scenario_path, scenario))
}

/// Runs `lpm simulate`.
pub fn run(options: Args) -> Result<Outcome, Failure> {
    let settings = settings(&options);
    let simulated = simulate_spec(&options.spec, options.scenario.as_deref(), &settings)
        .map_err(|f| naming_flags(f, &options))?;
    let out = out_dir(options.out.clone(), &options.spec, "");
    write_outputs(&out, &simulated)?;
    let mut text = text_summary(&simulated.result, &simulated.scenario_name);
    text.push_str(&format!(
        "  wrote {0}/trajectory.csv, {0}/summary.json, {0}/plots.svg\n",
        out.display()
    ));
    Ok(crate::warnings::outcome(
        text,
        &simulated.result.warnings,
        options.strict,
    ))
}

/// `simulate` on the model at its dimension.
struct Simulate<'a> {
    scenario: &'a Scenario,
}

impl WithDimension for Simulate<'_> {
    type Output = Result<SimulationResult, RunFailure>;

    fn run<const N: usize>(self, system: Interpreted<N>) -> Self::Output {
        simulate(&system, self.scenario).map_err(|e| {
            let failure = Failure::simulation(&e, system.inner().coordinates());
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
    spec: &Path,
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
    let source = std::fs::read_to_string(spec).ok()?;
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
type RunFailure = (Failure, Option<Box<(f64, Fault)>>);

fn dispatch(model: InterpretedModel, scenario: &Scenario) -> Result<SimulationResult, RunFailure> {
    model
        .with_dimension(Simulate { scenario })
        .map_err(|e| (Failure::model(e), None))?
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

fn write_outputs(out: &Path, simulated: &Simulated) -> Result<(), Failure> {
    let Simulated {
        result,
        model: _,
        scenario,
        scenario_name,
    } = simulated;
    std::fs::create_dir_all(out)
        .map_err(|e| Failure::io(format!("cannot create {}: {e}", out.display())))?;
    let setup = PlotSetup {
        crush: scenario.crush.clone(),
        channels: scenario.channels.clone(),
        pitch: scenario.pitch.clone(),
        force_deflection: scenario.inputs.force_deflection_columns(),
        g: lagrangian_sim::pulse::STANDARD_GRAVITY,
        title: figure_title(&result.model, scenario, scenario_name),
    };
    let svg =
        figure_svg(result, &setup).map_err(|e| Failure::io(format!("plotting failed: {e}")))?;
    let files = [
        ("trajectory.csv", simulated.trajectory_csv()),
        ("summary.json", summary_json(result)),
        ("plots.svg", svg),
    ];
    let paths: Vec<_> = files.iter().map(|(name, _)| out.join(name)).collect();
    let contents: Vec<(&Path, &[u8])> = (paths.iter().zip(&files))
        .map(|(path, (_, text))| (path.as_path(), text.as_bytes()))
        .collect();
    write_all_atomically(&contents)
        .map_err(|(path, e)| Failure::io(format!("cannot write {}: {e}", path.display())))
}

/// `model — description` of the scenario, or `model — scenario file` for a
/// scenario without a description.
fn figure_title(model: &str, scenario: &Scenario, scenario_name: &str) -> String {
    match scenario.description.trim() {
        "" => format!("{model} — {scenario_name}"),
        description => format!("{model} — {description}"),
    }
}
