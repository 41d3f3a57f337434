//! The subcommands, each returning the text to print or a failure.

use crate::DeriveFormat;
use lagrangian_core::Compiled;
use lagrangian_core::emit::{Notation, RustOptions, emit_file, render_equations, render_markdown};
use lagrangian_model::ConstantInputs;
use lagrangian_sim::crash::table::TableError;
use lagrangian_sim::fault::{Fault, named_values};
use lagrangian_sim::pulse::channels::ChannelError;
use lagrangian_sim::scenario::{ScenarioError, ScenarioErrorKind};
use lagrangian_sim::scenario::{setting_number, split_setting};
use lagrangian_sim::simulate::{FailureKind, SimulationError};
use std::path::Path;

/// The exit statuses of `lpm`, one per kind of failure (`lpm --help`
/// lists them).
pub mod status {
    pub const IO: u8 = 1;
    pub const USAGE: u8 = 2;
    pub const SPEC: u8 = 3;
    pub const SCENARIO: u8 = 4;
    pub const AUDIT_DISAGREES: u8 = 5;
    pub const STALE: u8 = 6;
    pub const DATA_FILE: u8 = 7;
    pub const EVALUATION: u8 = 8;
    pub const SINGULAR_MASS_MATRIX: u8 = 10;
    pub const NON_FINITE: u8 = 11;
    pub const STEP_SIZE_UNDERFLOW: u8 = 12;
    pub const MAX_STEPS: u8 = 13;
    pub const EVENT_NOT_LOCATED: u8 = 14;
    pub const TABLE_OUT_OF_RANGE: u8 = 15;
    pub const NO_EQUILIBRIUM: u8 = 16;
    pub const COMPONENT: u8 = 17;
    pub const EVERY_RUN_FAILED: u8 = 18;
    pub const FIT_FAILED: u8 = 19;
    /// Stopped by a signal (128 + SIGINT, as shells report it).
    pub const INTERRUPTED: u8 = 130;
}

/// A one-line message for stderr, the details `-v` adds, and the exit
/// status that goes with them.
pub struct Failure {
    pub message: String,
    pub details: Vec<String>,
    pub code: u8,
}

impl Failure {
    pub fn new(code: u8, message: String) -> Failure {
        Failure {
            message,
            details: Vec::new(),
            code,
        }
    }
    pub fn io(message: String) -> Failure {
        Failure::new(status::IO, message)
    }
    pub fn usage(message: String) -> Failure {
        Failure::new(status::USAGE, message)
    }
    pub fn spec(message: String) -> Failure {
        Failure::new(status::SPEC, message)
    }
    pub fn evaluation(message: String) -> Failure {
        Failure::new(status::EVALUATION, message)
    }

    /// A scenario that cannot be read (1), does not fit (4), or names a
    /// data file that cannot be used (7).
    pub fn scenario(e: &ScenarioError) -> Failure {
        let code = match e.kind {
            ScenarioErrorKind::Unreadable => status::IO,
            ScenarioErrorKind::Invalid => status::SCENARIO,
            ScenarioErrorKind::DataFile => status::DATA_FILE,
        };
        Failure::new(code, format!("error: {e}"))
    }

    /// A time-history file that cannot be read (1) or used (7).
    pub fn channels(e: &ChannelError) -> Failure {
        let code = match e {
            ChannelError::Table(TableError::Read { .. }) => status::IO,
            _ => status::DATA_FILE,
        };
        Failure::new(code, format!("error: {e}"))
    }

    /// A failed run, with the state it failed at (coordinates named) as
    /// details.
    pub fn simulation(e: &SimulationError, coordinates: &[String]) -> Failure {
        let code = match e.kind() {
            FailureKind::Scenario => status::SCENARIO,
            FailureKind::SingularMassMatrix => status::SINGULAR_MASS_MATRIX,
            FailureKind::NonFinite => status::NON_FINITE,
            FailureKind::StepSizeUnderflow => status::STEP_SIZE_UNDERFLOW,
            FailureKind::MaxSteps => status::MAX_STEPS,
            FailureKind::EventNotLocated => status::EVENT_NOT_LOCATED,
            FailureKind::TableOutOfRange => status::TABLE_OUT_OF_RANGE,
            FailureKind::NoEquilibrium => status::NO_EQUILIBRIUM,
            FailureKind::Component => status::COMPONENT,
        };
        let mut failure = Failure::new(code, format!("error: {e}"));
        failure.details.push(format!("kind: {:?}", e.kind()));
        let state = match (e.fault().and_then(Fault::state), e.reached()) {
            (Some(state), _) => Some(state),
            (None, Some(reached)) => {
                let t = reached.t;
                failure
                    .details
                    .push(format!("last accepted step ended at t = {t:e} s"));
                Some((&reached.q[..], &reached.qd[..]))
            }
            (None, None) => None,
        };
        if let Some((q, qd)) = state {
            failure
                .details
                .push(format!("coordinates: {}", named_values(coordinates, q)));
            failure
                .details
                .push(format!("velocities:  {}", named_values(coordinates, qd)));
        }
        failure
    }
}

/// Reads and compiles a spec, rendering errors as `file:line:col` snippets.
pub fn compile(path: &Path) -> Result<Compiled, Failure> {
    let source = std::fs::read_to_string(path)
        .map_err(|e| Failure::io(format!("error: cannot read {}: {e}", path.display())))?;
    Compiled::from_source(&source)
        .map_err(|e| Failure::spec(e.render(&path.display().to_string(), &source)))
}

pub fn derive(path: &Path, format: DeriveFormat, runtime: &str) -> Result<String, Failure> {
    let mut compiled = compile(path)?;
    match format {
        DeriveFormat::Text => Ok(render_equations(&mut compiled, Notation::Text)),
        DeriveFormat::Latex => Ok(render_equations(&mut compiled, Notation::Latex)),
        DeriveFormat::Markdown => Ok(render_markdown(&mut compiled, &path.display().to_string())),
        DeriveFormat::Rust => {
            let runtime = syn::parse_str::<syn::Path>(runtime).map_err(|e| {
                Failure::usage(format!(
                    "error: --runtime `{runtime}` is not a Rust path: {e}"
                ))
            })?;
            let options = RustOptions {
                runtime: quote::ToTokens::to_token_stream(&runtime),
            };
            let header = format!(
                "// @generated by `lpm derive --format rust {}` (lagrangian {}). Do not edit.\n",
                path.display(),
                env!("CARGO_PKG_VERSION")
            );
            Ok(emit_file(compiled, &options, &header))
        }
    }
}

pub fn eval(path: &Path, state: &[f64], time: f64, settings: &[String]) -> Result<String, Failure> {
    let compiled = compile(path)?;
    let mut model = compiled.interpreted();
    let n = model.dimension();
    if state.len() != 2 * n {
        return Err(Failure::usage(format!(
            "error: --state needs {} values (coordinates {} then their velocities), got {}",
            2 * n,
            model.coordinates().join(", "),
            state.len()
        )));
    }
    let mut inputs = vec![None; model.input_names().len()];
    for setting in settings {
        let (name, value) = split_setting(setting)
            .and_then(|(name, value)| Ok((name, setting_number(name, value)?)))
            .map_err(|e| Failure::usage(format!("error: {e}")))?;
        if let Some(k) = model.input_names().iter().position(|i| i == name) {
            inputs[k] = Some(value);
        } else if let Err(e) = model.set_parameter(name, value) {
            return Err(Failure::usage(format!(
                "error: --set: {e} (inputs: {})",
                model.input_names().join(", ")
            )));
        }
    }
    let used = inputs_used(&compiled);
    let missing: Vec<&str> = model
        .input_names()
        .iter()
        .zip(&inputs)
        .zip(&used)
        .filter(|((_, v), used)| v.is_none() && **used)
        .map(|((name, _), _)| name.as_str())
        .collect();
    if !missing.is_empty() {
        return Err(Failure::usage(format!(
            "error: input function(s) {} have no value; give constants with --set NAME=VALUE",
            missing.join(", ")
        )));
    }
    let inputs = ConstantInputs(inputs.into_iter().map(|v| v.unwrap_or(f64::NAN)).collect());
    let (q, qd) = state.split_at(n);
    let (mut mass, mut forcing) = (vec![0.0; n * n], vec![0.0; n]);
    model
        .evaluate_dynamics(time, q, qd, &inputs, &mut mass, &mut forcing)
        .map_err(|e| Failure::evaluation(format!("error: {e}")))?;
    let non_finite = mass.iter().chain(&forcing).any(|v| !v.is_finite());
    if non_finite {
        return Err(Failure::evaluation(format!(
            "error: M or f is not finite at t = {time}, state {state:?}"
        )));
    }
    let rows: Vec<Vec<f64>> = mass.chunks(n).map(<[f64]>::to_vec).collect();
    let json = serde_json::json!({ "mass_matrix": rows, "forcing": forcing });
    Ok(format!(
        "{}\n",
        serde_json::to_string_pretty(&json).unwrap_or_default()
    ))
}

/// Which inputs the mass matrix and forcing actually call.
fn inputs_used(compiled: &Compiled) -> Vec<bool> {
    use lagrangian_core::program::{Op, RoutineKind};
    let mut used = vec![false; compiled.model.inputs.len()];
    if let Some(routine) = compiled.program.routine(RoutineKind::Dynamics) {
        for &r in &routine.ops {
            if let Op::Input { index, .. } = &compiled.program.ops[r as usize] {
                used[*index as usize] = true;
            }
        }
    }
    used
}

pub fn chain(links: usize) -> Result<String, Failure> {
    if links == 0 {
        return Err(Failure::usage(
            "error: a chain needs at least one link".to_string(),
        ));
    }
    Ok(lagrangian_core::examples::pendulum_chain(links))
}
