//! `lpm export-fmu`: an FMI 2.0 FMU (Co-Simulation and Model Exchange) of a
//! spec under its scenario, for Simulink, Modelica tools or FMPy. The
//! exporter is the FMU crate's ([`lagrangian_fmi::exporter`]); this is its
//! command line.

use crate::failure::{Failure, Outcome};
use lagrangian_fmi::exporter::{Binary, compiled, export_with};
use std::path::PathBuf;

/// Options of `lpm export-fmu`.
#[derive(clap::Args)]
pub struct Args {
    /// The spec file (`.lpm`).
    spec: PathBuf,
    /// The scenario (TOML); by default the one in `scenarios/` beside the spec that names it.
    #[arg(long)]
    scenario: Option<PathBuf>,
    /// The FMU to write (`NAME.fmu`).
    #[arg(long)]
    out: PathBuf,
    /// The runtime library to pack (default: $LPM_FMU_RUNTIME, else the
    /// one built beside the lpm executable).
    #[arg(long)]
    runtime: Option<PathBuf>,
    /// Pack a binary of the macro-compiled model instead of the generic
    /// runtime (built by cargo against the lagrangian source tree).
    #[arg(long, conflicts_with = "runtime")]
    compiled: bool,
    /// The cargo profile of the --compiled build [default: release].
    #[arg(long, requires = "compiled")]
    profile: Option<String>,
    /// The lagrangian source tree of the --compiled build (default:
    /// $LPM_SOURCE, else the tree this lpm was built from).
    #[arg(long, requires = "compiled")]
    source: Option<PathBuf>,
}

/// Runs `lpm export-fmu`.
pub fn run(options: Args) -> Result<Outcome, Failure> {
    let build = compiled::Build {
        profile: options.profile.unwrap_or_else(|| "release".to_string()),
        source: options.source,
    };
    let binary = match options.compiled {
        true => Binary::Compiled(&build),
        false => Binary::Generic(options.runtime.as_deref()),
    };
    let exported = export_with(
        &options.spec,
        options.scenario.as_deref(),
        &options.out,
        binary,
    )?;
    Ok(Outcome::success(format!(
        "wrote {} ({} bytes): FMI 2.0 Co-Simulation and Model Exchange, {} variables, {} event indicators, binaries/{}\n",
        options.out.display(),
        exported.bytes,
        exported.variables,
        exported.event_indicators,
        exported.platform
    )))
}
