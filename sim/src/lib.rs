//! Crash simulation with `lagrangian` models, compiled or interpreted.
//!
//! * [`scenario`]: a TOML scenario — parameters, initial state, solver
//!   settings, and the crash components that supply the model's inputs
//!   ([`crash`]) — resolved against a model.
//! * [`simulate`]: static equilibrium, integration with events ([`ode`]),
//!   output samples and the summary metrics of a run; [`report`] writes them.
//! * [`linearize`]: the state-space matrices `A`, `B` of a model about its
//!   static equilibrium or a given state, and their modes.
//! * [`pulse`]: crash-pulse metrics (SAE J211 CFC filter, OLC, ASI, ESW) of a
//!   run or of a measured pulse.
//! * [`sweep`] (feature `sweep`): a scenario run many times in parallel, to a
//!   CSV or Parquet table; [`fit`] (feature `fit`): identification of the crush
//!   characteristic by Levenberg–Marquardt; [`plot`] (feature `plot`): SVG
//!   figures; [`warning`]: what a run does not stop at but should not be
//!   trusted without a look.
//!
//! ```no_run
//! use lagrangian_model::LagrangianSystem;
//! use lagrangian_sim::scenario::{ModelNames, Scenario};
//! use lagrangian_sim::simulate::simulate;
//!
//! fn run<S: LagrangianSystem<3> + Clone>(model: &S) -> Result<(), Box<dyn std::error::Error>> {
//!     let path = std::path::Path::new("specs/scenarios/yaris_full_frontal.toml");
//!     let scenario = Scenario::load(path, &ModelNames::of(model), &[])?;
//!     let result = simulate(model, &scenario)?;
//!     println!("max crush {:?} m", result.summary.max_crush_m);
//!     Ok(())
//! }
//! ```

#[cfg(test)]
mod component_runs;
pub mod crash;
pub mod curve;
pub(crate) mod entry;
pub mod failure;
pub mod fault;
#[cfg(feature = "fit")]
pub mod fit;
pub mod linearize;
pub mod model_names;
pub use lagrangian_ode as ode;
#[cfg(feature = "plot")]
pub mod plot;
pub mod pulse;
pub mod report;
pub mod scenario;
pub mod simulate;
#[cfg(feature = "sweep")]
pub mod sweep;
pub mod table;
pub mod warning;
