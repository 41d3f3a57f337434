//! Crash simulation with `lagrangian` models, compiled or interpreted.
//!
//! * [`scenario`]: a TOML scenario — parameters, initial state, solver
//!   settings, and the crash components that supply the model's inputs
//!   ([`components`]) — resolved against a model.
//! * [`simulate`]: static equilibrium, integration with events ([`ode`]),
//!   output samples and the summary metrics of a run; [`report`] writes them.
//! * [`linearize`]: the state-space matrices `A`, `B` of a model about its
//!   static equilibrium or a given state, and their modes.
//! * [`pulse`]: crash-pulse metrics (SAE J211 CFC filter, OLC, ASI, ESW) of a
//!   run or of a measured pulse.
//! * [`criteria`]: occupant and vehicle injury criteria (HIC, 3 ms clip,
//!   VC, Nij, neck and femur loads, THIV/PHD) and the limits of FMVSS 208
//!   and Euro NCAP.
//! * [`warning`]: what a run does not stop at but should not be trusted
//!   without a look.
//!
//! Sweeps, fits and plots of these runs are the `lagrangian-studies` crate's.
//!
//! ```no_run
//! use lagrangian_runtime::LagrangianSystem;
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
pub mod components;
pub mod criteria;
/// The former name of [`components`], kept for code that names it.
#[doc(hidden)]
pub use components as crash;
pub mod curve;
pub(crate) mod entry;
pub use entry::key_segments;
pub mod failure;
pub mod fault;
pub mod files;
pub mod linearize;
pub mod model_names;
pub use lagrangian_ode as ode;
pub mod pulse;
pub mod quantity;
pub mod report;
pub mod scenario;
pub mod simulate;
pub mod table;
pub mod warning;
