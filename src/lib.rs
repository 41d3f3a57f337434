//! Euler–Lagrange equations derived at compile time, emitted as optimized Rust.
//!
//! Declare a model — coordinates, parameters, positions, kinetic and potential
//! energy, Rayleigh dissipation, forces — and [`lagrangian!`] derives
//! `M(q) q̈ = f(q, q̇, t)` symbolically while your crate compiles, then
//! generates a struct implementing [`LagrangianSystem`].
//!
//! The crate re-exports the macro (`lagrangian-macro`, which runs the
//! compiler `lagrangian-core`), the model runtime (`lagrangian-runtime`: the
//! trait, input functions, the interpreter) and, with the default feature
//! `sim`, the crash-simulation library (`lagrangian-sim`: `scenario`,
//! `simulate`, `ode`, `components`, `pulse`, `report`) and its studies
//! (`lagrangian-studies`: `sweep`, `fit`, `plot`).
//! With `default-features = false` it is the macro and the model runtime
//! only, which depend on nalgebra and nothing heavy; `lagrangian::nalgebra`
//! is then built without its `std` feature (fixed-size matrices and vectors;
//! depend on nalgebra yourself for dynamic ones). The feature `compiler`
//! adds the compiler as `lagrangian::compiler`.
//!
//! ```
//! use lagrangian::{lagrangian, LagrangianSystem, NoInputs};
//! use lagrangian::nalgebra::Vector1;
//!
//! lagrangian! {
//!     /// A point-mass pendulum.
//!     model Pendulum;
//!     coordinates { theta [rad] }
//!     parameters { m [kg] = 1.0, l [m] = 2.0, g [m/s^2] = 9.81 }
//!     let x = l * sin(theta);
//!     let y = -l * cos(theta);
//!     kinetic = 0.5 * m * (pow(dot(x), 2) + pow(dot(y), 2));
//!     potential = m * g * y;
//! }
//!
//! let p = Pendulum::default();
//! let (q, qd) = (Vector1::new(0.3), Vector1::new(0.0));
//! let a = p.accelerations(0.0, &q, &qd, &NoInputs).unwrap();
//! assert!((a[0] + 9.81 / 2.0 * 0.3f64.sin()).abs() < 1e-12);
//! ```
//!
//! Input functions (run-time data such as a crush characteristic or a force
//! table) are declared in the spec and supplied through [`InputFunctions`]; a
//! closure `|index, args| …` is one. The generated type has an `INPUT_<NAME>`
//! constant with each input's index:
//!
//! ```
//! use lagrangian::{lagrangian, LagrangianSystem};
//! use lagrangian::nalgebra::Vector1;
//!
//! lagrangian! {
//!     model Driven;
//!     coordinates { theta [rad] }
//!     parameters { m [kg] = 1.0, l [m] = 2.0 }
//!     inputs { torque(t [s]) [N*m] }
//!     kinetic = 0.5 * m * pow(l * dot(theta), 2);
//!     force theta = torque(t);
//! }
//!
//! let model = Driven { l: 1.5, ..Default::default() };
//! let torque = |index: usize, args: &[f64]| match index {
//!     Driven::INPUT_TORQUE => 0.1 * args[0], // args[0] is t
//!     _ => f64::NAN,
//! };
//! let (q, qd) = (Vector1::new(0.2), Vector1::new(0.0));
//! let qdd = model.accelerations(2.0, &q, &qd, &torque).unwrap();
//! assert!((qdd[0] - 0.2 / (1.0 * 1.5 * 1.5)).abs() < 1e-15); // τ / (m l²)
//! let e = model.energies(2.0, &q, &Vector1::new(3.0), &torque);
//! assert!((e.external_power - 0.2 * 3.0).abs() < 1e-15); // Q·q̇
//! ```

/// The compiler itself (feature `compiler`): spec parser, symbolic engine,
/// derivation, optimizer, emitters, audit; `compiler::interpret` runs a spec
/// given as text.
#[cfg(feature = "compiler")]
pub use lagrangian_core as compiler;
pub use lagrangian_macro::lagrangian;
pub use lagrangian_runtime::*;
/// The crash-simulation library (feature `sim`, on by default): scenarios,
/// crash components, integration, pulse metrics, sweeps, fitting, plots.
#[cfg(feature = "sim")]
pub use lagrangian_sim::*;
#[cfg(feature = "sim")]
pub use lagrangian_studies::{fit, plot, sweep};

/// The Rust examples of the README, compiled and run as doctests (its spec
/// blocks, commands and outputs are checked by `lpm/tests/readme.rs`).
#[cfg(all(doctest, feature = "sim"))]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;

/// The Rust examples of the book's chapters, as doctests (see
/// `ReadmeDoctests`; `lpm/tests/readme.rs` checks that every chapter with
/// Rust blocks is here).
#[cfg(all(doctest, feature = "sim"))]
#[doc = include_str!("../docs/book/rust.md")]
pub struct BookDoctests;
