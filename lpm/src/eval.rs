//! `lpm eval`: `M`, `f`, the accelerations `q̈` and, for a constrained
//! spec, the multipliers `λ` at one state, by the interpreter, as JSON or
//! text ([`lagrangian_studies::eval`] evaluates them).

use crate::failure::{Failure, Outcome};
use lagrangian_runtime::InterpretedModel;
use lagrangian_sim::scenario::Override;
use lagrangian_sim::simulate::FailureKind;
use lagrangian_sim::simulate::constrained::DEFAULT_STABILIZATION;
use lagrangian_studies::error::StudyError;
use lagrangian_studies::eval::{
    Accelerations, accelerations, apply_settings, evaluate, parse_state, scenario_inputs,
};
use lagrangian_studies::files::Files;
use lagrangian_studies::mass;
use lagrangian_studies::spec::compile;
use std::path::PathBuf;
use std::sync::Arc;

/// How `lpm eval` prints its result.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    /// One JSON object: `mass_matrix`, `forcing`, `accelerations` and, with
    /// constraints, `constraints` (names, multipliers, residuals, rates).
    Json,
    /// The accelerations and multipliers by name, with their units.
    Text,
}

/// Options of `lpm eval`.
#[derive(clap::Args)]
pub struct Args {
    /// The spec file (`.lpm`).
    spec: PathBuf,
    /// Coordinates then velocities: q1,…,qN,q̇1,…,q̇N (values may start
    /// with '-': `--state -0.1,0`).
    #[arg(
        long,
        required = true,
        allow_hyphen_values = true,
        value_name = "Q1,…,QN,V1,…,VN"
    )]
    state: String,
    /// Time.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    time: f64,
    /// A scenario: its parameters apply and its components supply the
    /// inputs, as in `simulate` (put in the state `--state` starts a run in).
    #[arg(long)]
    scenario: Option<PathBuf>,
    /// Set a parameter, or give an input function a constant value:
    /// name=value (with --scenario, anything `simulate --set` takes).
    #[arg(long = "set", value_name = "NAME=VALUE")]
    set: Vec<String>,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Json)]
    format: Format,
}

/// Runs `lpm eval`.
pub fn run(args: Args, files: &Arc<dyn Files>) -> Result<Outcome, Failure> {
    let compiled = compile(&**files, &args.spec)?;
    let defaults = compiled.default_parameters();
    let mut model = lagrangian_studies::spec::interpreted(&compiled);
    let state = parse_state("--state", &args.state, model.coordinates())?;
    let (q, qd) = state.split_at(model.dimension());
    let (inputs, set, stabilization) = match &args.scenario {
        Some(path) => {
            let set = Failure::overrides(&args.set)?;
            scenario_inputs(&**files, &mut model, path, &set, (args.time, q, qd))?
        }
        None => {
            // Without a scenario, an override that cannot be read is a bad
            // command line, as one that names no parameter is.
            let set = Override::parse_all(&args.set).map_err(|e| Failure::usage(e.to_string()))?;
            let (inputs, set) = apply_settings(&mut model, &set)?;
            (inputs, set, DEFAULT_STABILIZATION)
        }
    };
    let (mass, forcing) = evaluate(&model, (args.time, q, qd), &*inputs)?;
    if !mass::positive_definite(&model, (args.time, q, qd)) {
        let why = mass::blame(&model, &defaults, &set, (args.time, q, qd))
            .map_or(String::new(), |why| format!(": {why}"));
        return Err(Failure::from(&StudyError::run(
            FailureKind::SingularMassMatrix,
            format!("the mass matrix is singular or not positive definite at this state{why}"),
        )));
    }
    let state = (args.time, q, qd);
    let solved = accelerations(&model, &[state], &*inputs, stabilization)?.remove(0);
    let text = match args.format {
        Format::Json => {
            let json = as_json(&model, (&mass, &forcing), &solved);
            format!(
                "{}\n",
                serde_json::to_string_pretty(&json).unwrap_or_default()
            )
        }
        Format::Text => as_text(&model, args.time, &solved),
    };
    Ok(Outcome::success(text))
}

/// The JSON object `lpm eval` prints.
fn as_json(
    model: &InterpretedModel,
    (mass, forcing): (&[f64], &[f64]),
    solved: &Accelerations,
) -> serde_json::Value {
    let n = model.dimension();
    let rows: Vec<Vec<f64>> = mass.chunks(n).map(<[f64]>::to_vec).collect();
    let mut json = serde_json::json!({
        "coordinates": model.coordinates(),
        "mass_matrix": rows,
        "forcing": forcing,
        "accelerations": solved.qdd,
    });
    if !model.constraint_names().is_empty() {
        json["constraints"] = serde_json::json!({
            "names": model.constraint_names(),
            "multipliers": solved.multipliers,
            "residuals": solved.residuals,
            "rates": solved.rates,
        });
    }
    json
}

/// The accelerations and multipliers by name, with their units.
fn as_text(model: &InterpretedModel, t: f64, solved: &Accelerations) -> String {
    let unit = |u: &Option<String>, suffix: &str| match u.as_deref() {
        Some(u) => format!("{u}{suffix}"),
        None => String::new(),
    };
    let mut out = format!("accelerations at t = {t}:\n");
    let units = model.coordinate_units();
    for ((name, a), u) in model.coordinates().iter().zip(&solved.qdd).zip(units) {
        out += &format!("  {name}_ddot = {a:.9e} {}\n", unit(u, "/s^2"));
    }
    let names = model.constraint_names();
    if names.is_empty() {
        return out;
    }
    out += "constraints (multiplier λ; residual g, rate ġ):\n";
    let units = model.multiplier_units();
    for (k, name) in names.iter().enumerate() {
        let u = units.get(k).map_or(String::new(), |u| unit(u, ""));
        out += &format!(
            "  {name}: λ = {:.9e} {u}; g = {:.3e}, ġ = {:.3e}\n",
            solved.multipliers[k], solved.residuals[k], solved.rates[k]
        );
    }
    out
}
