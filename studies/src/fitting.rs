//! A fit as a host runs it: identify the crush characteristic (or listed
//! parameters) of a spec's scenario from target time histories ([`crate::fit`]),
//! and the fitted scenario, report and overlay plot it writes. The target
//! is a CSV file of time histories, or an ISO-MME test whose vehicle
//! channels are asked for by code ([`crate::test_data`]).

use crate::error::StudyError;
use crate::fit::{
    ChannelFit, ChannelRating, FitReport, FitSetup, Parameters, check_target_extent, fit,
};
use crate::plot::{PlotError, Series, panels_svg};
use crate::spec::{compile, find_scenario};
use crate::test_data::{ChannelRequest, is_iso_mme, read_iso_mme, vehicle_histories};
use lagrangian_runtime::{Interpreted, InterpretedModel, WithDimension};
use lagrangian_sim::files::Files;
use lagrangian_sim::pulse::channels::{TimeHistories, read_time_histories};
use lagrangian_sim::report::write_all_atomically;
use lagrangian_sim::scenario::{BaseScenario, ModelNames, Override, Scenario};
use std::fmt::Write;
use std::path::{Component, Path, PathBuf};
use std::sync::Arc;

/// What to fit (`lpm fit`'s options without the output's).
#[derive(Clone, Debug)]
pub struct FitRequest {
    /// The spec file (`.lpm`).
    pub spec: PathBuf,
    /// Target time histories: a CSV with units in the header, or an
    /// ISO-MME test (a folder, an `.mme` or a `.zip`).
    pub target: PathBuf,
    /// The channels of an ISO-MME target to fit to, each with the
    /// simulated quantity it is compared with (empty for a CSV target).
    pub channels: Vec<ChannelRequest>,
    /// The scenario (TOML); `None`: the one beside the spec that names it.
    pub scenario: Option<PathBuf>,
    /// What to fit: curves of crush components (`NAME.stiffness`, …, or
    /// the bare word), spec parameters, dotted scenario entries; empty:
    /// `stiffness`, `damping`.
    pub fit: Vec<String>,
    /// Settings applied before fitting, as `simulate`'s.
    pub set: Vec<Override>,
    /// Number of starts (the scenario's values, then perturbations); 0 is 1.
    pub starts: usize,
    /// Seed of the perturbed starts.
    pub seed: u64,
}

/// A finished fit: its report and what its files are made from.
pub struct Fitting {
    /// What the fit found.
    pub report: FitReport,
    setup: FitSetup,
    /// The scenario with the settings applied, before fitting.
    document: toml::Table,
    names: ModelNames,
    /// The scenario file the fit started from.
    scenario: PathBuf,
}

/// The fit `options` describe, without writing anything; `progress` sees
/// the number of simulations and the cost. Every file is read from `files`,
/// which every run of the fit shares.
pub fn fitting(
    options: &FitRequest,
    progress: &(dyn Fn(usize, f64) + Sync),
    files: &Arc<dyn Files>,
) -> Result<Fitting, StudyError> {
    let compiled = compile(&**files, &options.spec)?;
    let model = crate::spec::interpreted(&compiled);
    let names = ModelNames::of_interpreted(&model);
    let scenario_path = match &options.scenario {
        Some(p) => p.clone(),
        None => find_scenario(&**files, &options.spec)?.ok_or_else(|| {
            StudyError::usage(format!(
                "no scenario names {}; give one with --scenario",
                options.spec.display()
            ))
        })?,
    };
    let text = (files.text(&scenario_path))
        .map_err(|e| StudyError::io(format!("cannot read {}: {e}", scenario_path.display())))?;
    let target = read_target(options, files)?;
    let document =
        Scenario::document(&text, &names, &options.set).map_err(|e| StudyError::scenario(&e))?;
    let fit_names = if options.fit.is_empty() {
        vec!["stiffness".to_string(), "damping".to_string()]
    } else {
        options.fit.clone()
    };
    let parameters = Parameters::resolve(&fit_names, &document, &names, model.parameters())?;
    let base = BaseScenario {
        text: text.to_string(),
        file: Some(scenario_path.clone()),
        names: names.clone(),
        settings: options.set.clone(),
        files: Arc::clone(files),
    };
    // Check the scenario once, so that its errors read as such.
    base.resolve(&[]).map_err(|e| StudyError::scenario(&e))?;
    check_target_extent(&target, &base, parameters.entries.len())
        .map_err(|e| StudyError::data_file(format!("{}: {e}", options.target.display())))?;
    let setup = FitSetup {
        base,
        target,
        parameters,
        starts: options.starts.max(1),
        seed: options.seed,
    };
    let report = dispatch(&model, &setup, progress)?;
    Ok(Fitting {
        report,
        setup,
        document,
        names,
        scenario: scenario_path,
    })
}

/// The target of `options`: the channels asked for of an ISO-MME test, or
/// the time histories of a CSV file (which takes no `--channel`).
fn read_target(options: &FitRequest, files: &Arc<dyn Files>) -> Result<TimeHistories, StudyError> {
    let path = &options.target;
    if is_iso_mme(path) {
        let test = read_iso_mme(path)?;
        return Ok(vehicle_histories(&test, path, &options.channels)?);
    }
    if let Some(first) = options.channels.first() {
        return Err(StudyError::usage(format!(
            "--channel {first}: {} is a CSV file, whose columns are its channels (by their headers); --channel names the channels of an ISO-MME test (a folder, an .mme or a .zip)",
            path.display()
        )));
    }
    read_time_histories(&**files, path).map_err(|e| StudyError::channels(&e))
}

/// The lines `lpm fit` prints before naming its files.
pub fn summary_text(fitting: &Fitting) -> String {
    text_report(&fitting.report)
}

/// `fit` on the model at its dimension.
struct Fit<'a> {
    setup: &'a FitSetup,
    progress: &'a (dyn Fn(usize, f64) + Sync),
}

impl WithDimension for Fit<'_> {
    type Output = Result<FitReport, StudyError>;

    fn run<const N: usize>(self, system: Interpreted<N>) -> Self::Output {
        Ok(fit(&system, self.setup, self.progress)?)
    }
}

fn dispatch(
    model: &InterpretedModel,
    setup: &FitSetup,
    progress: &(dyn Fn(usize, f64) + Sync),
) -> Result<FitReport, StudyError> {
    model
        .clone()
        .with_dimension(Fit { setup, progress })
        .map_err(StudyError::model)?
}

/// The report of a fit as `lpm fit` prints it.
pub fn text_report(report: &FitReport) -> String {
    let mut out = String::new();
    let converged = report.starts.iter().filter(|s| s.converged).count();
    let _ = writeln!(
        out,
        "fit: {} simulations in {:.2} s, {} of {} starts converged; cost {:.4e} → {:.4e}",
        report.simulations,
        report.seconds,
        converged,
        report.starts.len(),
        report.cost_initial,
        report.cost
    );
    let _ = writeln!(
        out,
        "  {:<28}{:>14}{:>14}{:>22}",
        "parameter", "initial", "fitted", "standard error"
    );
    for p in &report.parameters {
        let error = match (p.identifiability.reason(), p.standard_error) {
            (Some(reason), _) => reason,
            (None, Some(se)) if p.fitted != 0.0 => {
                format!("{se:.3e} ({:.2} %)", 100.0 * se / p.fitted.abs())
            }
            (None, Some(se)) => format!("{se:.3e}"),
            (None, None) => "not determined".to_string(),
        };
        let _ = writeln!(
            out,
            "  {:<28}{:>14.5e}{:>14.5e}  {error}",
            p.name, p.initial, p.fitted
        );
    }
    for c in &report.channels {
        let _ = writeln!(
            out,
            "  residual {}: RMS {:.4e} {} ({:.2} % of the target's RMS; {:.4e} at the start)",
            c.channel,
            c.rms_error,
            c.unit,
            100.0 * c.relative_rms_error,
            c.rms_error_initial
        );
        let _ = writeln!(out, "  {}", rating_line(c));
    }
    for (a, b, rho) in &report.strong_correlations {
        let _ = writeln!(
            out,
            "  warning: {a} and {b} are correlated ({rho:+.3}): the target determines a combination of them, not each"
        );
    }
    out
}

/// The ISO/TS 18571 line of a channel: initial → fitted overall rating
/// with its grade, and the fitted rating's scores, or why it has none.
fn rating_line(c: &ChannelFit) -> String {
    let prefix = format!("ISO/TS 18571 {}:", c.channel);
    let (initial, fitted) = match (&c.rating_initial, &c.rating) {
        (_, ChannelRating::NotRated(error)) => return format!("{prefix} not rated: {error}"),
        (ChannelRating::NotRated(_), ChannelRating::Rated(fitted)) => {
            ("not rated".to_string(), fitted)
        }
        (ChannelRating::Rated(initial), ChannelRating::Rated(fitted)) => (
            format!("{:.3} ({})", initial.overall, initial.grade),
            fitted,
        ),
    };
    format!(
        "{prefix} overall {initial} → {:.3} ({}); corridor {:.3}, phase {:.3}, magnitude {:.3}, slope {:.3}",
        fitted.overall, fitted.grade, fitted.corridor, fitted.phase, fitted.magnitude, fitted.slope
    )
}

/// The files of a fit for directory `out` (which exists): `fitted.toml`
/// (its relative paths rebased to `out`), `fit.json` and `fit.svg`, with
/// their contents.
pub fn outputs(fitting: &Fitting, out: &Path) -> Result<[(&'static str, String); 3], StudyError> {
    let Fitting {
        report,
        setup,
        document,
        names,
        scenario,
    } = fitting;
    let values: Vec<f64> = report.parameters.iter().map(|p| p.fitted).collect();
    let mut fitted = document.clone();
    setup.parameters.write_into(&mut fitted, &values, names);
    rebase_paths(
        &mut fitted,
        scenario.parent().unwrap_or(Path::new(".")),
        out,
    );
    let header = format!(
        "# Fitted by `lpm fit` from {} to {}: the scenario with the fitted values\n# (cost {:.4e}). Relative paths start from this file.\n",
        scenario.display(),
        setup.target_description(),
        report.cost
    );
    let toml_text = header
        + &toml::to_string(&fitted)
            .map_err(|e| StudyError::io(format!("cannot write the scenario: {e}")))?;
    let json = serde_json::to_string_pretty(report).unwrap_or_default() + "\n";
    let svg = overlay(report, &setup.target)
        .map_err(|e| StudyError::io(format!("plotting failed: {e}")))?;
    Ok([
        ("fitted.toml", toml_text),
        ("fit.json", json),
        ("fit.svg", svg),
    ])
}

/// Writes the files of a fit into directory `out`, creating it, and
/// returns them as [`outputs`] does.
pub fn write_files(
    fitting: &Fitting,
    out: &Path,
) -> Result<[(&'static str, String); 3], StudyError> {
    let io = |path: &Path, e: std::io::Error| {
        StudyError::io(format!("cannot write {}: {e}", path.display()))
    };
    // Before `outputs`: rebasing the fitted scenario's paths needs `out`.
    std::fs::create_dir_all(out).map_err(|e| io(out, e))?;
    let files = outputs(fitting, out)?;
    let paths: Vec<PathBuf> = files.iter().map(|(name, _)| out.join(name)).collect();
    let contents: Vec<(&Path, &[u8])> = (paths.iter().zip(&files))
        .map(|(path, (_, text))| (path.as_path(), text.as_bytes()))
        .collect();
    write_all_atomically(&contents).map_err(|(path, e)| io(&path, e))?;
    Ok(files)
}

trait Describe {
    fn target_description(&self) -> String;
}

impl Describe for FitSetup {
    fn target_description(&self) -> String {
        let channels: Vec<&str> = self
            .target
            .channels
            .iter()
            .map(|c| c.header.as_str())
            .collect();
        format!("target {}", channels.join(", "))
    }
}

/// Rewrites the relative paths of a scenario (`spec`, `components.*.file`)
/// written in `from` so that they hold for a file written in `to`.
fn rebase_paths(document: &mut toml::Table, from: &Path, to: &Path) {
    let rebase = |value: &mut toml::Value| {
        if let Some(p) = value.as_str().map(PathBuf::from)
            && p.is_relative()
            && let (Ok(target), Ok(dir)) = (
                std::fs::canonicalize(from.join(&p)),
                std::fs::canonicalize(to),
            )
        {
            *value = toml::Value::String(relative(&target, &dir).display().to_string());
        }
    };
    if let Some(v) = document.get_mut("spec") {
        rebase(v);
    }
    if let Some(toml::Value::Table(components)) = document.get_mut("components") {
        for (_, c) in components.iter_mut() {
            if let Some(v) = c.get_mut("file") {
                rebase(v);
            }
        }
    }
}

/// `target` relative to directory `dir` (both absolute).
fn relative(target: &Path, dir: &Path) -> PathBuf {
    let t: Vec<Component> = target.components().collect();
    let d: Vec<Component> = dir.components().collect();
    let common = t.iter().zip(&d).take_while(|(a, b)| a == b).count();
    let mut out = PathBuf::new();
    for _ in common..d.len() {
        out.push("..");
    }
    for c in &t[common..] {
        out.push(c);
    }
    out
}

fn overlay(report: &FitReport, target: &TimeHistories) -> Result<String, PlotError> {
    let panels: Vec<(String, String, String, Vec<Series>)> = (target.channels.iter())
        .zip(&report.curves)
        .zip(&report.channels)
        .map(|((c, (initial, fitted)), quality)| {
            let line = |values: &[f64]| -> Vec<(f64, f64)> {
                target
                    .t
                    .iter()
                    .map(|t| t * 1e3)
                    .zip(values.iter().copied())
                    .collect()
            };
            (
                panel_title(quality),
                "t [ms]".to_string(),
                format!("{} [{}]", c.quantity.name(), c.quantity.si_unit()),
                vec![
                    ("target".to_string(), line(&c.values)),
                    ("initial".to_string(), line(initial)),
                    ("fitted".to_string(), line(fitted)),
                ],
            )
        })
        .collect();
    panels_svg("lpm fit: target, initial and fitted", &panels)
}

/// A channel's panel title: its header and its ISO/TS 18571 overall
/// ratings, initial → fitted, where they were rated.
fn panel_title(c: &ChannelFit) -> String {
    let overall = |r: &ChannelRating| r.rating().map(|r| format!("{:.3}", r.overall));
    match (overall(&c.rating_initial), &c.rating) {
        (Some(initial), ChannelRating::Rated(fitted)) => format!(
            "{}: ISO/TS 18571 {initial} → {:.3} ({})",
            c.channel, fitted.overall, fitted.grade
        ),
        (None, ChannelRating::Rated(fitted)) => format!(
            "{}: ISO/TS 18571 {:.3} ({})",
            c.channel, fitted.overall, fitted.grade
        ),
        (_, ChannelRating::NotRated(_)) => c.channel.clone(),
    }
}
