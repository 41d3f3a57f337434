//! `lpm eval`: `M` and `f` at one state, by the interpreter, as JSON.

use crate::failure::{Failure, Outcome};
use crate::mass;
use crate::spec::compile;
use crate::status::ExitStatus;
use lagrangian_model::{ConstantInputs, InputFunctions, InterpretedModel};
use lagrangian_sim::scenario::{ModelNames, Scenario, Setting};
use std::path::PathBuf;

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
}

/// Runs `lpm eval`.
pub fn run(args: Args) -> Result<Outcome, Failure> {
    let compiled = compile(&args.spec)?;
    let defaults = compiled.default_parameters();
    let mut model = crate::spec::interpreted(&compiled);
    let state = parse_state("--state", &args.state, model.coordinates())?;
    let (q, qd) = state.split_at(model.dimension());
    let (inputs, set): (Box<dyn InputFunctions>, Vec<usize>) = match &args.scenario {
        Some(path) => scenario_inputs(&mut model, path, &args.set, (args.time, q, qd))?,
        None => apply_settings(&mut model, &args.set)?,
    };
    let (mass, forcing) = evaluate(&model, (args.time, q, qd), &*inputs)?;
    if !mass::positive_definite(&model, (args.time, q, qd)) {
        let why = mass::blame(&model, &defaults, &set, (args.time, q, qd))
            .map_or(String::new(), |why| format!(": {why}"));
        return Err(Failure::new(
            ExitStatus::SingularMassMatrix,
            format!("the mass matrix is singular or not positive definite at this state{why}"),
        ));
    }
    let n = model.dimension();
    let rows: Vec<Vec<f64>> = mass.chunks(n).map(<[f64]>::to_vec).collect();
    let json = serde_json::json!({ "mass_matrix": rows, "forcing": forcing });
    Ok(Outcome::success(format!(
        "{}\n",
        serde_json::to_string_pretty(&json).unwrap_or_default()
    )))
}

/// The state `Q1,…,QN,V1,…,VN` given to `flag`: two values per
/// coordinate.
pub fn parse_state(flag: &str, text: &str, coordinates: &[String]) -> Result<Vec<f64>, Failure> {
    let values = (text.split(','))
        .map(|v| {
            v.trim()
                .parse::<f64>()
                .map_err(|_| Failure::usage(format!("{flag}: `{}` is not a number", v.trim())))
        })
        .collect::<Result<Vec<f64>, Failure>>()?;
    let n = coordinates.len();
    if values.len() != 2 * n {
        return Err(Failure::usage(format!(
            "{flag} needs {} values (coordinates {} then their velocities), got {}",
            2 * n,
            coordinates.join(", "),
            values.len()
        )));
    }
    Ok(values)
}

/// `M` (row-major) and `f` at `state`, finite.
pub fn evaluate(
    model: &InterpretedModel,
    (t, q, qd): mass::State,
    inputs: &dyn InputFunctions,
) -> Result<(Vec<f64>, Vec<f64>), Failure> {
    let n = model.dimension();
    let (mut mass, mut forcing) = (vec![0.0; n * n], vec![0.0; n]);
    model
        .evaluate_dynamics(t, q, qd, inputs, &mut mass, &mut forcing)
        .map_err(|e| Failure::evaluation(e.to_string()))?;
    if mass.iter().chain(&forcing).any(|v| !v.is_finite()) {
        return Err(Failure::evaluation(format!(
            "M or f is not finite at t = {t}, state {q:?}, {qd:?}"
        )));
    }
    Ok((mass, forcing))
}

/// The scenario at `path` (with `settings`) applied to `model`: its
/// parameters set, its components bound to the inputs and put in the state
/// a run from `state` starts in. Returns the inputs and the indices of the
/// parameters it sets.
fn scenario_inputs(
    model: &mut InterpretedModel,
    path: &std::path::Path,
    settings: &[String],
    (t, q, qd): mass::State,
) -> Result<(Box<dyn InputFunctions>, Vec<usize>), Failure> {
    let names = ModelNames::of_interpreted(model);
    let scenario = Scenario::load(path, &names, settings).map_err(|e| Failure::scenario(&e))?;
    for &(i, value) in &scenario.parameters {
        model
            .set_parameter(&names.parameters[i], value)
            .map_err(|e| Failure::usage(e.to_string()))?;
    }
    let mut arguments = vec![0.0; model.input_sites().iter().map(|s| s.1).sum()];
    model
        .evaluate_input_arguments(t, q, qd, &mut arguments)
        .map_err(|e| Failure::evaluation(e.to_string()))?;
    let mut inputs = scenario.inputs.clone();
    inputs
        .start(&arguments)
        .map_err(|fault| Failure::evaluation(fault.to_string()))?;
    let set = scenario.parameters.iter().map(|&(i, _)| i).collect();
    Ok((Box::new(inputs), set))
}

/// Applies the `--set` settings: parameters to the model, input constants
/// to the inputs returned, with the indices of the parameters set. Every
/// input the dynamics calls needs a value.
pub fn apply_settings(
    model: &mut InterpretedModel,
    settings: &[String],
) -> Result<(Box<dyn InputFunctions>, Vec<usize>), Failure> {
    let names = ModelNames::of_interpreted(model);
    let mut inputs = vec![None; names.inputs.len()];
    let mut set = Vec::new();
    for setting in settings {
        match Setting::parse(setting, &names).map_err(Failure::usage)? {
            Setting::Parameter { name, value } => {
                model
                    .set_parameter(&name, value)
                    .map_err(|e| Failure::usage(e.to_string()))?;
                set.extend(names.parameters.iter().position(|p| *p == name));
            }
            Setting::InputConstant { name, value } => {
                if let Some(k) = names.inputs.iter().position(|i| *i == name) {
                    inputs[k] = Some(value);
                }
            }
            Setting::Scale { key, factor } if !key.contains('.') => {
                let k = names.parameters.iter().position(|p| *p == key);
                let value = k.map(|k| model.parameters()[k] * factor);
                model
                    .set_parameter(&key, value.unwrap_or(f64::NAN))
                    .map_err(|e| Failure::usage(e.to_string()))?;
                set.extend(k);
            }
            Setting::Entry { key, .. } | Setting::Scale { key, .. } => {
                return Err(Failure::usage(format!(
                    "--set {key}: eval takes parameters and input constants (scenario entries need --scenario)"
                )));
            }
        }
    }
    // The inputs the dynamics calls: those of its input sites.
    let called = |k: usize| model.input_sites().iter().any(|&(input, _)| input == k);
    let missing: Vec<&str> = (names.inputs.iter().enumerate())
        .filter(|&(k, _)| inputs[k].is_none() && called(k))
        .map(|(_, name)| name.as_str())
        .collect();
    if !missing.is_empty() {
        return Err(Failure::usage(format!(
            "input function(s) {} have no value; give constants with --set NAME=VALUE or use --scenario",
            missing.join(", ")
        )));
    }
    let constants = ConstantInputs(inputs.into_iter().map(|v| v.unwrap_or(f64::NAN)).collect());
    Ok((Box::new(constants), set))
}
