//! `lpm linearize`: the state-space matrices `A`, `B` of a spec about its
//! static equilibrium or a given state, and the modes of `A`.

use crate::failure::{Failure, Outcome};
use lagrangian_core::{Compiled, Model};
use lagrangian_runtime::names::closest;
use lagrangian_runtime::{Interpreted, WithDimension};
use lagrangian_sim::linearize::{
    At, Linearization, LinearizeError, json, linearize, markdown, projection_note,
};
use lagrangian_sim::report::write_atomically;
use lagrangian_sim::scenario::{ModelNames, Scenario};
use lagrangian_studies::files::Files;
use lagrangian_studies::spec::{compile, find_scenario};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Options of `lpm linearize`.
#[derive(clap::Args)]
pub struct Args {
    /// The spec file (`.lpm`).
    spec: PathBuf,
    /// The scenario (TOML): its parameters, its initial coordinates (where
    /// the equilibrium is sought from) and its components, which are part
    /// of the system; by default the one in `scenarios/` beside the spec
    /// that names it.
    #[arg(long)]
    scenario: Option<PathBuf>,
    /// Where to linearize: `equilibrium` (q̇ = 0, f = 0 for the scenario's
    /// equilibrium coordinates, all of them when it names none), or a
    /// state: `NAME=VALUE,dot(NAME)=VALUE,…` (0 where not given) or, as
    /// `eval --state` takes it, `Q1,…,QN,V1,…,VN`.
    #[arg(
        long,
        default_value = "equilibrium",
        allow_hyphen_values = true,
        value_name = "equilibrium|STATE"
    )]
    at: String,
    /// Override a parameter (`l=0.5`), give an input a constant (`push=0`),
    /// or set a scenario entry, as `simulate --set` does.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
    /// The report's format.
    #[arg(long, value_parser = ["markdown", "json"], default_value = "markdown")]
    format: String,
    /// Write the report to this file instead of stdout.
    #[arg(long)]
    out: Option<PathBuf>,
}

/// Runs `lpm linearize`.
pub fn run(args: Args, files: &Arc<dyn Files>) -> Result<Outcome, Failure> {
    let model = lagrangian_studies::spec::interpreted(&with_jacobians(
        compile(&**files, &args.spec)?,
        &args.spec,
        &**files,
    ));
    let names = ModelNames::of_interpreted(&model);
    let at = parse_at(&args.at, model.coordinates())?;
    let scenario_path = match &args.scenario {
        Some(p) => Some(p.clone()),
        None => find_scenario(&**files, &args.spec)?,
    };
    let set = Failure::overrides(&args.set)?;
    let scenario = match &scenario_path {
        Some(path) => Scenario::read(&**files, path, &names, &set),
        None => Scenario::defaults(&names, &set),
    }
    .map_err(|e| Failure::scenario(&e))?;
    let coordinates = model.coordinates().to_vec();
    let linearization = model
        .with_dimension(Linearize {
            scenario: &scenario,
            at: &at,
        })
        .map_err(Failure::model)?
        .map_err(|e| match e {
            LinearizeError::Model(e) => Failure::simulation(&e, &coordinates),
            LinearizeError::Eigenvalues(_) | LinearizeError::NoFreeCoordinates { .. } => {
                Failure::evaluation(e.to_string())
            }
        })?;
    let text = report(&linearization, &args, scenario_path.as_deref());
    // The markdown on stdout says it; JSON and a file leave stdout to the
    // report or say nothing of it.
    let note = projection_note(&linearization);
    if !note.is_empty() && (args.format == "json" || args.out.is_some()) {
        eprintln!("note: {}", note.trim());
    }
    match &args.out {
        None => Ok(Outcome::success(text)),
        Some(path) => {
            write_atomically(path, text.as_bytes())
                .map_err(|e| Failure::io(format!("cannot write {}: {e}", path.display())))?;
            Ok(Outcome::success(format!("wrote {}\n", path.display())))
        }
    }
}

/// The spec compiled with its Jacobians derived, for `A`: as it is when it
/// asks for them (`jacobians;`) or they cannot be derived (an input called
/// with the state in its arguments has no declared derivatives; `A` is
/// then found by central differences).
fn with_jacobians(compiled: Compiled, path: &Path, files: &dyn Files) -> Compiled {
    if compiled.model.jacobians {
        return compiled;
    }
    let derived = (files.text(path))
        .ok()
        .and_then(|source| Model::from_source(&source).ok())
        .and_then(|mut model| {
            model.jacobians = true;
            Compiled::new(model).ok()
        });
    derived.unwrap_or(compiled)
}

/// `linearize` on the model at its dimension.
struct Linearize<'a> {
    scenario: &'a Scenario,
    at: &'a At,
}

impl WithDimension for Linearize<'_> {
    type Output = Result<Linearization, LinearizeError>;

    fn run<const N: usize>(self, system: Interpreted<N>) -> Self::Output {
        linearize(&system, self.scenario, self.at)
    }
}

/// `--at`: `equilibrium`, named values, or eval's list of values.
fn parse_at(text: &str, coordinates: &[String]) -> Result<At, Failure> {
    if text == "equilibrium" {
        return Ok(At::Equilibrium);
    }
    let n = coordinates.len();
    let values = match text.contains('=') {
        true => named_state(text, coordinates)?,
        false => lagrangian_studies::eval::parse_state("--at", text, coordinates)?,
    };
    Ok(At::State {
        q: values[..n].to_vec(),
        qd: values[n..].to_vec(),
    })
}

/// The state of `NAME=VALUE,dot(NAME)=VALUE,…`, 0 where not given.
fn named_state(text: &str, coordinates: &[String]) -> Result<Vec<f64>, Failure> {
    let n = coordinates.len();
    let mut values = vec![0.0; 2 * n];
    for item in text.split(',').map(str::trim) {
        let (name, value) = item
            .split_once('=')
            .ok_or_else(|| Failure::usage(format!("--at: `{item}` is not NAME=VALUE")))?;
        let (name, velocity) = match name.trim().strip_prefix("dot(") {
            Some(rest) => (rest.strip_suffix(')').unwrap_or(rest), true),
            None => (name.trim(), false),
        };
        let Some(i) = coordinates.iter().position(|c| c == name) else {
            let hint = closest(name, coordinates.iter().map(String::as_str))
                .map_or(String::new(), |c| format!(" (did you mean `{c}`?)"));
            return Err(Failure::usage(format!(
                "--at: `{name}` is not a coordinate{hint}; the coordinates are {}",
                coordinates.join(", ")
            )));
        };
        let value = value.trim().parse::<f64>().map_err(|_| {
            Failure::usage(format!("--at {item}: `{}` is not a number", value.trim()))
        })?;
        values[i + if velocity { n } else { 0 }] = value;
    }
    Ok(values)
}

/// The report in the format asked for.
fn report(linearization: &Linearization, args: &Args, scenario: Option<&Path>) -> String {
    let scenario = scenario.map_or("no scenario".to_string(), |p| p.display().to_string());
    if args.format == "json" {
        let value = json(linearization);
        format!(
            "{}\n",
            serde_json::to_string_pretty(&value).unwrap_or_default()
        )
    } else {
        let title = format!("{} ({scenario})", args.spec.display());
        markdown(linearization, &title)
    }
}
