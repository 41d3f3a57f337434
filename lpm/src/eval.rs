//! `lpm eval`: `M` and `f` at one state, by the interpreter, as JSON.

use crate::failure::{Failure, Outcome};
use crate::spec::compile;
use lagrangian_model::{ConstantInputs, InterpretedModel};
use lagrangian_sim::scenario::{ModelNames, Setting};
use std::path::PathBuf;

/// Options of `lpm eval`.
#[derive(clap::Args)]
pub struct Args {
    /// The spec file (`.lpm`).
    spec: PathBuf,
    /// Coordinates then velocities: q1,…,qN,q̇1,…,q̇N.
    #[arg(
        long,
        value_delimiter = ',',
        allow_negative_numbers = true,
        required = true
    )]
    state: Vec<f64>,
    /// Time.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    time: f64,
    /// Set a parameter, or give an input function a constant value: name=value.
    #[arg(long = "set", value_name = "NAME=VALUE")]
    set: Vec<String>,
}

/// Runs `lpm eval`.
pub fn run(args: Args) -> Result<Outcome, Failure> {
    let mut model = compile(&args.spec)?.interpreted();
    let n = model.dimension();
    if args.state.len() != 2 * n {
        return Err(Failure::usage(format!(
            "--state needs {} values (coordinates {} then their velocities), got {}",
            2 * n,
            model.coordinates().join(", "),
            args.state.len()
        )));
    }
    let inputs = apply_settings(&mut model, &args.set)?;
    let (q, qd) = args.state.split_at(n);
    let (mut mass, mut forcing) = (vec![0.0; n * n], vec![0.0; n]);
    model
        .evaluate_dynamics(args.time, q, qd, &inputs, &mut mass, &mut forcing)
        .map_err(|e| Failure::evaluation(e.to_string()))?;
    if mass.iter().chain(&forcing).any(|v| !v.is_finite()) {
        return Err(Failure::evaluation(format!(
            "M or f is not finite at t = {}, state {:?}",
            args.time, args.state
        )));
    }
    let rows: Vec<Vec<f64>> = mass.chunks(n).map(<[f64]>::to_vec).collect();
    let json = serde_json::json!({ "mass_matrix": rows, "forcing": forcing });
    Ok(Outcome::success(format!(
        "{}\n",
        serde_json::to_string_pretty(&json).unwrap_or_default()
    )))
}

/// Applies the `--set` settings: parameters to the model, input constants
/// to the inputs returned. Every input the dynamics calls needs a value.
fn apply_settings(
    model: &mut InterpretedModel,
    settings: &[String],
) -> Result<ConstantInputs, Failure> {
    let names = ModelNames::of_interpreted(model);
    let mut inputs = vec![None; names.inputs.len()];
    for setting in settings {
        match Setting::parse(setting, &names).map_err(Failure::usage)? {
            Setting::Parameter { name, value } => model
                .set_parameter(&name, value)
                .map_err(|e| Failure::usage(e.to_string()))?,
            Setting::InputConstant { name, value } => {
                if let Some(k) = names.inputs.iter().position(|i| *i == name) {
                    inputs[k] = Some(value);
                }
            }
            Setting::Entry { key, .. } => {
                return Err(Failure::usage(format!(
                    "--set {key}: eval takes parameters and input constants, not scenario entries"
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
            "input function(s) {} have no value; give constants with --set NAME=VALUE",
            missing.join(", ")
        )));
    }
    Ok(ConstantInputs(
        inputs.into_iter().map(|v| v.unwrap_or(f64::NAN)).collect(),
    ))
}
