//! `lpm fit`: identify the crush characteristic (or listed parameters) from
//! target time histories; writes the fitted scenario, a report and an
//! overlay plot ([`lagrangian_studies::fitting`] does the work).

use crate::failure::{Failure, Outcome};
use indicatif::{ProgressBar, ProgressStyle};
use lagrangian_studies::error::StudyError;
use lagrangian_studies::files::Files;
use lagrangian_studies::fitting::{FitRequest, fitting, text_report, write_files};
use lagrangian_studies::spec::out_dir;
use lagrangian_studies::test_data::ChannelRequest;
use std::fmt::Write;
use std::path::PathBuf;
use std::sync::Arc;

/// Options of `lpm fit`.
#[derive(clap::Args)]
pub struct Args {
    /// The spec file (`.lpm`).
    pub spec: PathBuf,
    /// Target time histories: a CSV with units in the header, or an
    /// ISO-MME test (a folder, an `.mme` or a `.zip`) with `--channel`.
    #[arg(long)]
    pub target: PathBuf,
    /// A channel of an ISO-MME target to fit to, by its code, and the
    /// simulated quantity it is compared with (`acceleration`, `velocity`,
    /// `crush`; by default the code's: AC, VE, DS); repeatable.
    #[arg(long = "channel", value_name = "CODE[=QUANTITY]")]
    pub channel: Vec<String>,
    /// The scenario (TOML); by default the one beside the spec that names it.
    #[arg(long)]
    pub scenario: Option<PathBuf>,
    /// What to fit, comma-separated: a crush component's curve
    /// `NAME.stiffness`, `NAME.damping` (its k1…k7, c1…c7) or `NAME.force`
    /// (the forces of a force–deflection curve), the bare word where one
    /// crush component has that curve; spec parameters; or dotted scenario
    /// entries holding numbers (default: stiffness,damping).
    #[arg(long, value_delimiter = ',')]
    pub fit: Vec<String>,
    /// A setting applied before fitting, as in `lpm simulate --set`.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// Output directory (default lpm-out/NAME-fit, NAME the spec file's stem).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Number of starts (the scenario's values, then perturbations).
    #[arg(long, default_value_t = 4)]
    pub starts: usize,
    /// Seed of the perturbed starts.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// No progress display.
    #[arg(long)]
    pub quiet: bool,
}

impl Args {
    /// The fit these options ask for.
    pub fn request(&self) -> Result<FitRequest, Failure> {
        Ok(FitRequest {
            spec: self.spec.clone(),
            target: self.target.clone(),
            channels: (self.channel.iter())
                .map(|text| ChannelRequest::parse(text).map_err(StudyError::from))
                .collect::<Result<_, _>>()?,
            scenario: self.scenario.clone(),
            fit: self.fit.clone(),
            set: Failure::overrides(&self.set)?,
            starts: self.starts,
            seed: self.seed,
        })
    }
}

/// Runs `lpm fit`.
pub fn run(options: Args, files: &Arc<dyn Files>) -> Result<Outcome, Failure> {
    let bar = if options.quiet {
        ProgressBar::hidden()
    } else {
        ProgressBar::new_spinner()
    };
    bar.set_style(
        ProgressStyle::with_template("{spinner} {elapsed} fitting: {pos} simulations, {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_spinner()),
    );
    let progress = |simulations: usize, cost: f64| {
        bar.set_position(simulations as u64);
        bar.set_message(format!("cost {cost:.4e}"));
    };
    let fitting = fitting(&options.request()?, &progress, files)?;
    bar.finish_and_clear();

    let out = out_dir(options.out.clone(), &options.spec, "-fit");
    write_files(&fitting, &out)?;
    let mut text = text_report(&fitting.report);
    let _ = writeln!(
        text,
        "  wrote {0}/fitted.toml (lpm simulate {1} --scenario {0}/fitted.toml), {0}/fit.json, {0}/fit.svg",
        out.display(),
        options.spec.display()
    );
    Ok(Outcome::success(text))
}
