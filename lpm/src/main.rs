//! `lpm`: derive, inspect and evaluate lumped-parameter models from spec files.
//!
//! Exit status: see [`EXIT_STATUS`] (`lpm --help` prints it).

mod audit;
mod commands;
mod fit;
mod generate;
mod metrics;
mod simulate;
mod sweep;

use clap::{Parser, Subcommand, ValueEnum};
use lagrangian_sim::ode::Method;
use std::path::PathBuf;
use std::process::ExitCode;

/// The exit statuses, for `lpm --help` (the numbers are those of
/// `commands::status`).
const EXIT_STATUS: &str = "\
Exit status:
   0  success
   1  a file cannot be read or written
   2  bad command line
   3  the spec does not compile
   4  the scenario does not fit the spec (unknown key, bad value)
   5  the audit found equations that disagree
   6  generated files are stale (generate --check)
   7  a data file (CSV) is missing columns, non-numeric or unsorted
   8  the model cannot be evaluated at the given state (eval)
  10  the mass matrix is singular or not positive definite
  11  a NaN or infinite value (M, f, acceleration, power, event)
  12  the step size fell below the minimum
  13  the step limit was reached
  14  an event could not be located
  15  a table was read outside its range (policy `error`)
  16  no static equilibrium before the impact
  17  a component could not give a value (an unbound input)
  18  every run of a sweep failed
  19  the fit failed
 130  a sweep stopped by Ctrl-C or a signal (--resume continues it)

A failure prints one line on stderr; -v adds the details (the state it
happened at, with coordinate names).";

#[derive(Parser)]
#[command(
    name = "lpm",
    version,
    about = "Euler–Lagrange compiler and simulator for lumped-parameter models",
    after_help = EXIT_STATUS
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// On failure, print the details after the one-line message.
    #[arg(short, long, global = true)]
    verbose: bool,
}

#[derive(Clone, Copy, ValueEnum)]
pub enum DeriveFormat {
    /// M, f, Q, T, V, D in the spec's own notation.
    Text,
    /// The same as a LaTeX `aligned` block.
    Latex,
    /// A Markdown document with `$$` math (GitHub renders it).
    Markdown,
    /// The Rust code the `lagrangian!` macro generates.
    Rust,
}

#[derive(Clone, Copy, ValueEnum)]
pub enum DesignArg {
    /// One run in each of N equal strata of every axis.
    LatinHypercube,
    /// Independent uniform draws.
    Random,
}

#[derive(Subcommand)]
enum Command {
    /// Print the derived equations of motion M(q) q̈ = f(q, q̇, t) and the energies.
    Derive {
        /// The spec file (`.lpm`).
        spec: PathBuf,
        #[arg(long, value_enum, default_value = "text")]
        format: DeriveFormat,
        /// Path of the runtime crate in generated Rust (`--format rust`).
        #[arg(long, default_value = "::lagrangian")]
        runtime: String,
    },
    /// Evaluate M and f at one state with the interpreter; prints JSON.
    Eval {
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
    },
    /// Simulate a spec under a scenario; writes trajectory.csv, summary.json
    /// and plots.svg and prints a summary.
    Simulate {
        /// The spec file (`.lpm`).
        spec: PathBuf,
        /// The scenario (TOML); by default the one in `scenarios/` beside the spec that names it.
        #[arg(long)]
        scenario: Option<PathBuf>,
        /// Override a parameter (`k1=7e4`), give an input a constant (`barrier_x1=0`)
        /// or set a scenario entry (`components.front_end.unloading=elastic`).
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// End time [s].
        #[arg(long)]
        t_end: Option<f64>,
        #[arg(long)]
        rtol: Option<f64>,
        #[arg(long)]
        atol: Option<f64>,
        /// Integration method (the scenario's `simulation.method`).
        #[arg(long, value_parser = clap::builder::PossibleValuesParser::new(Method::NAMES))]
        method: Option<String>,
        /// Output directory (default lpm-out/<spec name>).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Run a scenario many times with values varied (a grid or a sampled
    /// design), in parallel; writes one row of summary metrics per run.
    ///
    /// KEY is anything --set takes: a parameter (`k1`), an input given a
    /// constant, or a dotted scenario entry (`initial.velocities.r`).
    /// `KEY*=…` multiplies the entry instead (every number of a list:
    /// `components.front_end.stiffness_values*=0.8:1.2`).
    #[command(group(clap::ArgGroup::new("plan").required(true).args(["grid", "samples"])))]
    Sweep {
        /// The scenario (TOML); its `spec` key names the model.
        scenario: PathBuf,
        /// The spec, if not the one the scenario names.
        #[arg(long)]
        spec: Option<PathBuf>,
        /// A grid axis: KEY=a,b,c or KEY=low:high:count; every combination of
        /// the axes is run, the last varying fastest.
        #[arg(long, value_name = "KEY=VALUES")]
        grid: Vec<String>,
        /// Number of sampled runs (with --vary).
        #[arg(long, requires = "vary")]
        samples: Option<usize>,
        /// A sampled axis: KEY=low:high (uniform) or KEY=low:high:log.
        #[arg(long, value_name = "KEY=LOW:HIGH", requires = "samples")]
        vary: Vec<String>,
        /// How samples are placed.
        #[arg(long, value_enum, default_value = "latin-hypercube")]
        design: DesignArg,
        /// Seed of the sampled design (run i's values depend only on seed and i).
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// A setting for every run, as in `lpm simulate --set`.
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// Output table: .csv or .parquet.
        #[arg(long)]
        out: PathBuf,
        /// Output format (default: from the --out extension).
        #[arg(long, value_parser = ["csv", "parquet"])]
        format: Option<String>,
        /// Run only block i of n of the runs (1 ≤ i ≤ n), e.g. a Slurm array
        /// task: `--shard $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT`.
        #[arg(long, value_name = "I/N")]
        shard: Option<String>,
        /// Worker threads (default: one per core).
        #[arg(long, default_value_t = 0)]
        threads: usize,
        /// No progress bar.
        #[arg(long)]
        quiet: bool,
        /// Continue an interrupted sweep from its journal (`OUT.partial`):
        /// the same command line with --resume runs only the missing runs.
        #[arg(long)]
        resume: bool,
    },
    /// Audit the spec's hand-derived equations against the derivation; exits
    /// with status 5 when an equation disagrees.
    Audit {
        /// The spec file (`.lpm`) with a `hand_derived` section.
        spec: PathBuf,
        #[arg(long, value_parser = ["markdown", "json"], default_value = "markdown")]
        format: String,
    },
    /// Regenerate the committed files of generated/ from specs/ (or, with
    /// --check, list the stale ones and exit with status 6).
    Generate {
        /// The workspace root (with specs/ and generated/).
        #[arg(long, default_value = ".")]
        root: PathBuf,
        #[arg(long)]
        check: bool,
    },
    /// Fit the crush characteristic (paper §2.1) or listed parameters to
    /// target time histories by Levenberg–Marquardt; writes the fitted
    /// scenario (fitted.toml), fit.json and an overlay plot fit.svg.
    ///
    /// The target CSV has `t [s|ms]` and any of `acceleration [g|m/s^2]`
    /// (forward positive), `deceleration`, `velocity [m/s|km/h]`, `crush
    /// [m|mm]` of the scenario's crush coordinate.
    Fit {
        /// The spec file (`.lpm`).
        spec: PathBuf,
        /// Target time histories (CSV with units in the header).
        #[arg(long)]
        target: PathBuf,
        /// The scenario (TOML); by default the one beside the spec that names it.
        #[arg(long)]
        scenario: Option<PathBuf>,
        /// What to fit, comma-separated: `stiffness`, `damping` (the crush
        /// component's k1…k7, c1…c7), spec parameters, or dotted scenario
        /// entries holding numbers (default: stiffness,damping).
        #[arg(long, value_delimiter = ',')]
        fit: Vec<String>,
        /// A setting applied before fitting, as in `lpm simulate --set`.
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// Output directory (default lpm-out/<spec name>-fit).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Number of starts (the scenario's values, then perturbations).
        #[arg(long, default_value_t = 4)]
        starts: usize,
        /// Seed of the perturbed starts.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// No progress display.
        #[arg(long)]
        quiet: bool,
    },
    /// Crash-pulse metrics of a pulse in a CSV file: CFC 60 peak, crush,
    /// time to zero velocity, rebound, equivalent square wave, OLC, ASI.
    ///
    /// Columns (units in brackets): `t [s|ms]`, `acceleration [g|m/s^2]`
    /// (forward positive, so negative in a frontal crash) or `deceleration
    /// [g|m/s^2]`, and optionally `velocity [m/s|km/h]`, `crush [m|mm]`.
    Metrics {
        file: PathBuf,
        /// Impact velocity [m/s], if the file has no velocity column.
        #[arg(long, allow_negative_numbers = true)]
        v0: Option<f64>,
        #[arg(long, value_parser = ["text", "json"], default_value = "text")]
        format: String,
    },
    /// Print the spec of an N-link planar pendulum chain.
    Chain {
        /// Number of links.
        links: usize,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let success = |text: String| (text, 0u8);
    let result = match cli.command {
        Command::Derive {
            spec,
            format,
            runtime,
        } => commands::derive(&spec, format, &runtime).map(success),
        Command::Eval {
            spec,
            state,
            time,
            set,
        } => commands::eval(&spec, &state, time, &set).map(success),
        Command::Fit {
            spec,
            target,
            scenario,
            fit,
            set,
            out,
            starts,
            seed,
            quiet,
        } => fit::run(fit::FitOptions {
            spec,
            target,
            scenario,
            fit,
            settings: set,
            out,
            starts,
            seed,
            quiet,
        })
        .map(success),
        Command::Metrics { file, v0, format } => {
            metrics::run(&file, v0, format == "json").map(success)
        }
        Command::Chain { links } => commands::chain(links).map(success),
        Command::Generate { root, check } => generate::run(&root, check),
        Command::Audit { spec, format } => audit::run(&spec, format == "json")
            .map(|(text, disagrees)| (text, if disagrees { audit::DISAGREES } else { 0 })),
        Command::Sweep {
            scenario,
            spec,
            grid,
            samples,
            vary,
            design,
            seed,
            set,
            out,
            format,
            shard,
            threads,
            quiet,
            resume,
        } => sweep::run(sweep::SweepOptions {
            scenario,
            spec,
            grid,
            samples,
            vary,
            design: match design {
                DesignArg::LatinHypercube => lagrangian_sim::sweep::Design::LatinHypercube,
                DesignArg::Random => lagrangian_sim::sweep::Design::Random,
            },
            seed,
            settings: set,
            out,
            parquet: format.map(|f| f == "parquet"),
            shard,
            threads,
            quiet,
            resume,
        })
        .map(success),
        Command::Simulate {
            spec,
            scenario,
            set,
            t_end,
            rtol,
            atol,
            method,
            out,
        } => simulate::run(simulate::SimulateOptions {
            spec,
            scenario,
            settings: set,
            t_end,
            rtol,
            atol,
            method,
            out,
        })
        .map(success),
    };
    match result {
        Ok((text, code)) => {
            print!("{text}");
            ExitCode::from(code)
        }
        Err(failure) => {
            eprintln!("{}", failure.message.trim_end());
            if cli.verbose {
                for line in &failure.details {
                    eprintln!("  {line}");
                }
            }
            ExitCode::from(failure.code)
        }
    }
}
