//! Emitters: Rust source for the macro and `generated/`, equations as text or LaTeX.

pub mod backend;
mod equations;
mod markdown;
mod names;
mod notation;
pub mod pretty;
mod rust;
pub mod schedule;

pub use equations::render_equations;
pub use markdown::render_markdown;
pub use notation::{Notation, Printer, latex_name};
pub use rust::{RustOptions, emit_file, emit_model};
