//! `lpm simulate`: run a spec file under a scenario and write the results.

use crate::failure::{Failure, Outcome};
use lagrangian_sim::ode::Method;
use lagrangian_sim::report::text_summary;
use lagrangian_sim::scenario::Override;
use lagrangian_studies::compare::ChannelPair;
use lagrangian_studies::error::StudyError;
use lagrangian_studies::files::Files;
use lagrangian_studies::simulate::{
    Extras, TestOverlay, simulate_for_report, simulate_spec, write_outputs,
};
use lagrangian_studies::spec::out_dir;
use std::path::PathBuf;
use std::sync::Arc;

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
    /// Also write report.html: the summary, warnings, plots, events, the
    /// audit of the hand-derived equations and the equations of motion, on
    /// one self-contained page.
    #[arg(long)]
    report: bool,
    /// Also write the run as an ISO-MME test, the folder DIR: the
    /// vehicle's channels (crush, velocity, acceleration in g), the
    /// barrier force and the scenario's `[iso_mme.channels]`, every
    /// output interval from 0.
    #[arg(long, value_name = "DIR")]
    iso_mme: Option<PathBuf>,
    /// With --report: a test to rate the run against by ISO/TS 18571 and
    /// overlay in the report (an ISO-MME test, a CSV or a run's folder).
    #[arg(long, value_name = "TEST", requires = "report")]
    test: Option<PathBuf>,
    /// A test channel and the run's column it is rated against (REF=COMP,
    /// or NAME for the same name in both), as `lpm compare --channel`;
    /// by default the channels of the same name.
    #[arg(long = "test-channel", value_name = "REF=COMP", requires = "test")]
    test_channels: Vec<String>,
}

/// The method names `--method` takes: [`Method::NAMES`], and the former
/// names of [`Method::ALIASES`] (accepted, not listed).
fn methods() -> clap::builder::PossibleValuesParser {
    let names = Method::NAMES.map(clap::builder::PossibleValue::new);
    let aliases =
        Method::ALIASES.map(|(alias, _)| clap::builder::PossibleValue::new(alias).hide(true));
    clap::builder::PossibleValuesParser::new(names.into_iter().chain(aliases))
}

/// The overrides the command line adds to the scenario's: `--set`, then
/// the flags'.
fn settings(options: &Args) -> Result<Vec<Override>, Failure> {
    let mut settings = Failure::overrides(&options.set)?;
    settings.extend(flag_settings(options).into_iter().map(|(_, s)| s));
    Ok(settings)
}

/// The overrides `--t-end`, `--rtol`, `--atol` and `--method` stand for,
/// each with the flag as written in messages (`--rtol 0.9`).
fn flag_settings(options: &Args) -> Vec<(String, Override)> {
    let mut settings = Vec::new();
    let numbers = [
        ("--t-end", "simulation.t_end", options.t_end),
        ("--rtol", "simulation.rtol", options.rtol),
        ("--atol", "simulation.atol", options.atol),
    ];
    for (flag, key, value) in numbers {
        if let Some(x) = value {
            settings.push((format!("{flag} {x}"), Override::number(key, x)));
        }
    }
    if let Some(m) = &options.method {
        let method = Override::value("simulation.method", toml::Value::String(m.clone()));
        settings.push((format!("--method {m}"), method));
    }
    settings
}

/// `failure`, naming the flag a setting came from where it names the
/// setting (`--rtol 0.9: …`, not `--set simulation.rtol=0.9: …`).
fn naming_flags(failure: Failure, options: &Args) -> Failure {
    for (flag, setting) in flag_settings(options) {
        let named = format!("--set {}:", setting.text());
        if let Some(rest) = failure.message().strip_prefix(&named) {
            return Failure::new(failure.status, format!("{flag}:{rest}"));
        }
    }
    failure
}

/// Runs `lpm simulate`.
pub fn run(options: Args, files: &Arc<dyn Files>) -> Result<Outcome, Failure> {
    let settings = settings(&options)?;
    let (spec, scenario) = (&options.spec, options.scenario.as_deref());
    let (simulated, derived) = match options.report {
        true => simulate_for_report(&**files, spec, scenario, &settings)
            .map(|(simulated, derived)| (simulated, Some(derived))),
        false => simulate_spec(&**files, spec, scenario, &settings).map(|s| (s, None)),
    }
    .map_err(|e| naming_flags(Failure::from(&e), &options))?;
    let out = out_dir(options.out.clone(), &options.spec, "");
    let pairs = (options.test_channels.iter())
        .map(|text| ChannelPair::parse(text).map_err(|e| Failure::from(&StudyError::from(e))))
        .collect::<Result<Vec<_>, _>>()?;
    let test = options.test.as_deref().map(|test| TestOverlay {
        test,
        channels: &pairs,
        files: &**files,
    });
    let extras = Extras {
        report: derived.as_ref(),
        iso_mme: options.iso_mme.as_deref(),
        test,
    };
    write_outputs(&out, &simulated, extras).map_err(|e| Failure::from(&e))?;
    let mut text = text_summary(&simulated.result, &simulated.scenario_name);
    let report = match options.report {
        true => format!(", {}/report.html", out.display()),
        false => String::new(),
    };
    text.push_str(&format!(
        "  wrote {0}/trajectory.csv, {0}/summary.json, {0}/plots.svg{report}\n",
        out.display()
    ));
    if let Some(dir) = &options.iso_mme {
        text.push_str(&format!("  wrote the ISO-MME test {}\n", dir.display()));
    }
    Ok(crate::warnings::outcome(
        text,
        &simulated.result.warnings,
        options.strict,
    ))
}
