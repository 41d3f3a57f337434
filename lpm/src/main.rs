//! `lpm`: derive, audit, simulate, sweep and fit lumped-parameter models
//! from spec files.
//!
//! One module per subcommand, each with its `Args` and `run`; the exit
//! statuses are [`status::ExitStatus`] (`lpm --help` prints them).

use clap::{Parser, Subcommand};
use lagrangian_studies::files::{Cached, Files};
use lpm::failure::{Failure, Outcome};
use lpm::{
    audit, chain, compare, derive, eval, fit, fmu, generate, linearize, metrics, simulate, status,
    sweep,
};
use std::process::ExitCode;
use std::sync::Arc;

#[derive(Parser)]
#[command(
    name = "lpm",
    version,
    about = "Euler–Lagrange compiler and simulator for lumped-parameter models",
    after_help = status::ExitStatus::help()
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// On failure, print the details after the one-line message.
    #[arg(short, long, global = true)]
    verbose: bool,
}

#[derive(Subcommand)]
enum Command {
    /// Print the derived equations of motion M(q) q̈ = f(q, q̇, t) and the energies.
    Derive(derive::Args),
    /// Evaluate M and f at one state with the interpreter; prints JSON.
    Eval(eval::Args),
    /// Simulate a spec under a scenario; writes trajectory.csv, summary.json
    /// and plots.svg and prints a summary.
    Simulate(simulate::Args),
    /// Run a scenario many times with values varied (a grid or a sampled
    /// design), in parallel; writes one row of summary metrics per run.
    ///
    /// KEY is anything --set takes: a parameter (`k1`), an input given a
    /// constant, or a dotted scenario entry (`initial.velocities.r`).
    /// `KEY*=…` multiplies the entry instead (every number of a list:
    /// `components.front_end.stiffness_values*=0.8:1.2`).
    Sweep(sweep::Args),
    /// Audit the spec's hand-derived equations against the derivation; exits
    /// with status 5 when an equation disagrees.
    Audit(audit::Args),
    /// Regenerate the committed files of generated/ from specs/ (or, with
    /// --check, list the stale ones and exit with status 6).
    Generate(generate::Args),
    /// Fit the crush characteristic (paper §2.1) or listed parameters to
    /// target time histories by Levenberg–Marquardt; writes the fitted
    /// scenario (fitted.toml), fit.json and an overlay plot fit.svg.
    ///
    /// The target CSV has `t [s|ms]` and any of `acceleration [g|m/s^2]`
    /// (forward positive), `deceleration`, `velocity [m/s|km/h]`, `crush
    /// [m|mm]` of the scenario's crush coordinate.
    Fit(fit::Args),
    /// Crash-pulse metrics of a pulse in a CSV file: CFC 60 peak, crush,
    /// time to zero velocity, rebound, equivalent square wave, OLC, ASI.
    ///
    /// Columns (units in brackets): `t [s|ms]`, `acceleration [g|m/s^2]`
    /// (forward positive, so negative in a frontal crash) or `deceleration
    /// [g|m/s^2]`, and optionally `velocity [m/s|km/h]`, `crush [m|mm]`.
    Metrics(metrics::Args),
    /// Rate a model's time histories against a test's by ISO/TS 18571:
    /// corridor, phase, magnitude and slope scores, the overall rating and
    /// its grade (excellent > 0.94, good > 0.8, fair > 0.58, poor), per
    /// channel pair; --out writes an overlay plot of each.
    ///
    /// REFERENCE and COMPARISON are CSV files (a `t [s|ms]` column, units
    /// in brackets) or simulation output folders (their trajectory.csv).
    Compare(compare::Args),
    /// Print the spec of an N-link planar pendulum chain.
    Chain(chain::Args),
    /// Linearize a spec about its static equilibrium (or a given state):
    /// the state-space matrices A and B of x = (q, q̇) and the modes of A
    /// (natural frequency, damping ratio, unstable or overdamped).
    Linearize(linearize::Args),
    /// Export a spec under its scenario as an FMI 2.0 FMU (Co-Simulation and
    /// Model Exchange) that runs without a compiler: the prebuilt runtime
    /// library interprets the spec and scenario packed in its resources.
    ExportFmu(fmu::Args),
}

fn run(command: Command, files: &Arc<dyn Files>) -> Result<Outcome, Failure> {
    match command {
        Command::Derive(args) => derive::run(args, files),
        Command::Eval(args) => eval::run(args, files),
        Command::Simulate(args) => simulate::run(args, files),
        Command::Sweep(args) => sweep::run(args, files),
        Command::Audit(args) => audit::run(args, files),
        Command::Generate(args) => generate::run(args),
        Command::Fit(args) => fit::run(args, files),
        Command::Metrics(args) => metrics::run(args, files),
        Command::Compare(args) => compare::run(args, files),
        Command::Chain(args) => chain::run(args),
        Command::Linearize(args) => linearize::run(args, files),
        Command::ExportFmu(args) => fmu::run(args),
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    // One cache for the command: a sweep's or a fit's runs parse each
    // table once.
    let files: Arc<dyn Files> = Arc::new(Cached::default());
    match run(cli.command, &files) {
        Ok(outcome) => {
            print!("{}", outcome.text);
            ExitCode::from(outcome.status.code())
        }
        Err(failure) => {
            eprintln!("{}", failure.text());
            if cli.verbose {
                for line in &failure.details {
                    eprintln!("  {line}");
                }
            }
            ExitCode::from(failure.status.code())
        }
    }
}
