//! `lagrangian-model` is the former name of [`lagrangian_runtime`], the
//! model runtime; everything of it is here under the old name, so that
//! code that names `lagrangian_model` (`runtime = ::lagrangian_model` in a
//! `lagrangian!` call, say) keeps building.

pub use lagrangian_runtime::*;
