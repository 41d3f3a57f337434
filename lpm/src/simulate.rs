//! `lpm simulate`: run a spec file under a scenario and write the results.

use crate::commands::{Failure, compile};
use lagrangian_model::{Interpreted, InterpretedModel, WithDimension};
use lagrangian_sim::plot::{PlotSetup, figure_svg};
use lagrangian_sim::report::{Units, summary_json, text_summary, trajectory_csv, write_atomically};
use lagrangian_sim::scenario::{ModelNames, Scenario};
use lagrangian_sim::simulate::{SimulationResult, simulate};
use std::path::{Path, PathBuf};

/// Options of `lpm simulate`.
pub struct SimulateOptions {
    pub spec: PathBuf,
    pub scenario: Option<PathBuf>,
    pub settings: Vec<String>,
    pub t_end: Option<f64>,
    pub rtol: Option<f64>,
    pub atol: Option<f64>,
    pub method: Option<String>,
    pub out: Option<PathBuf>,
}

/// The scenario beside a spec: `<spec dir>/scenarios/*.toml` whose `spec` key names it.
pub fn find_scenario(spec: &Path) -> Result<Option<PathBuf>, Failure> {
    let Some(dir) = spec.parent().map(|d| d.join("scenarios")) else {
        return Ok(None);
    };
    let Ok(entries) = std::fs::read_dir(&dir) else {
        return Ok(None);
    };
    let target = std::fs::canonicalize(spec).ok();
    let mut found: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .filter(|p| {
            let named = std::fs::read_to_string(p)
                .ok()
                .and_then(|text| text.parse::<toml::Table>().ok())
                .and_then(|t| t.get("spec").and_then(|s| s.as_str()).map(|s| dir.join(s)));
            named
                .and_then(|n| std::fs::canonicalize(n).ok())
                .is_some_and(|n| Some(n) == target)
        })
        .collect();
    found.sort();
    match found.len() {
        0 => Ok(None),
        1 => Ok(found.pop()),
        _ => Err(Failure::usage(format!(
            "error: several scenarios name {}: {}; choose one with --scenario",
            spec.display(),
            found
                .iter()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ))),
    }
}

pub fn run(options: SimulateOptions) -> Result<String, Failure> {
    let compiled = compile(&options.spec)?;
    let model = compiled.interpreted();
    let names = ModelNames::of_interpreted(&model);
    let scenario_path = match &options.scenario {
        Some(p) => Some(p.clone()),
        None => find_scenario(&options.spec)?,
    };
    let mut settings = options.settings.clone();
    if let Some(t) = options.t_end {
        settings.push(format!("simulation.t_end={t}"));
    }
    if let Some(r) = options.rtol {
        settings.push(format!("simulation.rtol={r}"));
    }
    if let Some(a) = options.atol {
        settings.push(format!("simulation.atol={a}"));
    }
    if let Some(m) = &options.method {
        settings.push(format!("simulation.method=\"{m}\""));
    }
    let scenario = match &scenario_path {
        Some(path) => Scenario::load(path, &names, &settings),
        None => Scenario::defaults(&names, &settings),
    }
    .map_err(|e| Failure::scenario(&e))?;
    let result = dispatch(model.clone(), &scenario)?;
    let scenario_name = scenario_path
        .as_ref()
        .map_or("default scenario (no scenario file)".to_string(), |p| {
            p.display().to_string()
        });
    let stem = options
        .spec
        .file_stem()
        .map_or("model".into(), |s| s.to_string_lossy().into_owned());
    let out = options
        .out
        .clone()
        .unwrap_or_else(|| Path::new("lpm-out").join(&stem));
    write_outputs(&out, &result, &model, &scenario, &scenario_name)?;
    let mut text = text_summary(&result, &scenario_name);
    text.push_str(&format!(
        "  wrote {0}/trajectory.csv, {0}/summary.json, {0}/plots.svg\n",
        out.display()
    ));
    Ok(text)
}

/// `simulate` on the model at its dimension.
struct Simulate<'a> {
    scenario: &'a Scenario,
}

impl WithDimension for Simulate<'_> {
    type Output = Result<SimulationResult, Failure>;

    fn run<const N: usize>(self, system: Interpreted<N>) -> Self::Output {
        simulate(&system, self.scenario)
            .map_err(|e| Failure::simulation(&e, system.inner().coordinates()))
    }
}

fn dispatch(model: InterpretedModel, scenario: &Scenario) -> Result<SimulationResult, Failure> {
    model
        .with_dimension(Simulate { scenario })
        .map_err(|e| Failure::usage(format!("error: {e}")))?
}

fn write_outputs(
    out: &Path,
    result: &SimulationResult,
    model: &InterpretedModel,
    scenario: &Scenario,
    scenario_name: &str,
) -> Result<(), Failure> {
    std::fs::create_dir_all(out)
        .map_err(|e| Failure::io(format!("error: cannot create {}: {e}", out.display())))?;
    let input_units = result
        .input_columns
        .iter()
        .map(|name| {
            let k = model.input_names().iter().position(|n| n == name)?;
            model.input_units()[k].clone()
        })
        .collect();
    let units = Units {
        coordinates: model.coordinate_units().to_vec(),
        inputs: input_units,
    };
    // The crush force column (the input bound to a crush element's force)
    // and the element's compression sign.
    let crush_force = result
        .input_columns
        .iter()
        .enumerate()
        .find_map(|(column, name)| {
            let k = model.input_names().iter().position(|n| n == name)?;
            Some((column, scenario.inputs.crush_force_sign(k)?))
        });
    let setup = PlotSetup {
        crush: scenario.crush,
        pitch: scenario.pitch.clone(),
        crush_force,
        g: result.g,
        title: format!("{} — {}", result.model, scenario_name),
    };
    let svg = figure_svg(result, &setup)
        .map_err(|e| Failure::io(format!("error: plotting failed: {e}")))?;
    let files = [
        ("trajectory.csv", trajectory_csv(result, &units)),
        ("summary.json", summary_json(result)),
        ("plots.svg", svg),
    ];
    for (name, contents) in files {
        let path = out.join(name);
        write_atomically(&path, contents.as_bytes())
            .map_err(|e| Failure::io(format!("error: cannot write {}: {e}", path.display())))?;
    }
    Ok(())
}
