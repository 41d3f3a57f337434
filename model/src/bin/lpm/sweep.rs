//! `lpm sweep`: run a scenario many times with values varied, in parallel,
//! and write one row of summary metrics per run (CSV or Parquet).

use crate::commands::{Failure, compile};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use lagrangian_model::report::write_atomically;
use lagrangian_model::scenario::ModelNames;
use lagrangian_model::sweep::{
    BaseScenario, Design, Plan, Row, Settings, Shard, run_scenario, run_sweep, sweep_csv,
    sweep_parquet,
};
use lagrangian_model::{Interpreted, InterpretedModel};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Options of `lpm sweep`.
pub struct SweepOptions {
    pub scenario: PathBuf,
    pub spec: Option<PathBuf>,
    pub grid: Vec<String>,
    pub samples: Option<usize>,
    pub vary: Vec<String>,
    pub design: Design,
    pub seed: u64,
    pub settings: Vec<String>,
    pub out: PathBuf,
    pub parquet: Option<bool>,
    pub shard: Option<String>,
    pub threads: usize,
    pub quiet: bool,
}

/// The spec a scenario names with its `spec` key (relative to the scenario).
fn spec_of(scenario: &Path, text: &str) -> Result<PathBuf, Failure> {
    let table: toml::Table = text
        .parse()
        .map_err(|e| Failure::usage(format!("error: {}: {e}", scenario.display())))?;
    let spec = table.get("spec").and_then(|s| s.as_str()).ok_or_else(|| {
        Failure::usage(format!(
            "error: {} has no `spec = \"…\"` entry; name the spec with --spec",
            scenario.display()
        ))
    })?;
    Ok(scenario.parent().unwrap_or(Path::new(".")).join(spec))
}

pub fn run(options: SweepOptions) -> Result<String, Failure> {
    let usage = |m: String| Failure::usage(format!("error: {m}"));
    let plan = match (options.grid.is_empty(), options.samples) {
        (false, None) if options.vary.is_empty() => Plan::grid(&options.grid),
        (true, Some(count)) => Plan::samples(count, &options.vary, options.seed, options.design),
        (true, None) => {
            Err("give --grid KEY=VALUES or --samples N with --vary KEY=LOW:HIGH".into())
        }
        _ => Err("--grid cannot be combined with --samples/--vary".into()),
    }
    .map_err(usage)?;
    let shard = match &options.shard {
        Some(text) => Shard::parse(text).map_err(usage)?,
        None => Shard::ALL,
    };
    let parquet = match options.parquet {
        Some(p) => p,
        None => match options.out.extension().and_then(|e| e.to_str()) {
            Some("parquet") => true,
            Some("csv") => false,
            _ => {
                return Err(usage(format!(
                    "--out {}: name a .csv or .parquet file, or give --format",
                    options.out.display()
                )));
            }
        },
    };
    let text = std::fs::read_to_string(&options.scenario).map_err(|e| {
        Failure::io(format!(
            "error: cannot read {}: {e}",
            options.scenario.display()
        ))
    })?;
    let spec = match &options.spec {
        Some(spec) => spec.clone(),
        None => spec_of(&options.scenario, &text)?,
    };
    let model = InterpretedModel::from_compiled(&compile(&spec)?);
    let base = BaseScenario {
        text,
        file: Some(options.scenario.clone()),
        names: ModelNames::of_interpreted(&model),
        settings: options.settings.clone(),
    };
    let settings = Settings::new(&plan, &base, model.parameters()).map_err(usage)?;
    // A key the scenario does not know fails here, before any run starts.
    if !plan.is_empty() {
        run_scenario(&base, &settings, &plan.point(0)).map_err(usage)?;
    }
    let runs = shard.runs(plan.len());
    let bar = if options.quiet {
        ProgressBar::hidden()
    } else {
        let bar = ProgressBar::with_draw_target(
            Some(runs.len() as u64),
            ProgressDrawTarget::stderr_with_hz(4),
        );
        if let Ok(style) =
            ProgressStyle::with_template("{bar:40} {pos}/{len} runs  {per_sec}  eta {eta}")
        {
            bar.set_style(style);
        }
        bar
    };
    let start = Instant::now();
    let progress = || bar.inc(1);
    let rows = dispatch(
        model,
        &base,
        &plan,
        &settings,
        runs.clone(),
        options.threads,
        &progress,
    )?;
    bar.finish_and_clear();
    let elapsed = start.elapsed().as_secs_f64();
    let axes: Vec<String> = plan.axes().iter().map(|a| a.column()).collect();
    let bytes = if parquet {
        sweep_parquet(&axes, &rows)
    } else {
        sweep_csv(&axes, &rows)
    }
    .map_err(Failure::io)?;
    write_atomically(&options.out, &bytes).map_err(|e| {
        Failure::io(format!(
            "error: cannot write {}: {e}",
            options.out.display()
        ))
    })?;
    let failed: Vec<&Row> = rows.iter().filter(|r| r.outcome.is_err()).collect();
    let mut text = format!(
        "{} runs{} in {elapsed:.2} s ({:.0} runs/s), {} failed; wrote {}\n",
        rows.len(),
        if shard == Shard::ALL {
            String::new()
        } else {
            format!(
                " (shard {}/{}: runs {}..{} of {})",
                shard.index,
                shard.count,
                runs.start,
                runs.end,
                plan.len()
            )
        },
        rows.len() as f64 / elapsed.max(1e-9),
        failed.len(),
        options.out.display()
    );
    if let Some(first) = failed.first()
        && let Err(message) = &first.outcome
    {
        text.push_str(&format!("  first failure, run {}: {message}\n", first.run));
    }
    if !rows.is_empty() && failed.len() == rows.len() {
        return Err(Failure::evaluation(format!(
            "error: every run failed\n{text}"
        )));
    }
    Ok(text)
}

fn dispatch(
    model: InterpretedModel,
    base: &BaseScenario,
    plan: &Plan,
    settings: &Settings,
    runs: std::ops::Range<usize>,
    threads: usize,
    progress: &(dyn Fn() + Sync),
) -> Result<Vec<Row>, Failure> {
    macro_rules! dimensions {
        ($($n:literal)*) => {
            match model.dimension() {
                $($n => sweep_fixed::<$n>(model, base, plan, settings, runs, threads, progress),)*
                n => Err(Failure::usage(format!(
                    "error: lpm sweep handles models of up to 12 coordinates; this one has {n}"
                ))),
            }
        };
    }
    dimensions!(1 2 3 4 5 6 7 8 9 10 11 12)
}

fn sweep_fixed<const N: usize>(
    model: InterpretedModel,
    base: &BaseScenario,
    plan: &Plan,
    settings: &Settings,
    runs: std::ops::Range<usize>,
    threads: usize,
    progress: &(dyn Fn() + Sync),
) -> Result<Vec<Row>, Failure> {
    let system =
        Interpreted::<N>::new(model).map_err(|e| Failure::evaluation(format!("error: {e}")))?;
    run_sweep(&system, base, plan, settings, runs, threads, progress)
        .map_err(|e| Failure::evaluation(format!("error: {e}")))
}
