//! Emitters: Rust source for the macro and `generated/`, text for `lpm derive`.

mod names;
mod rust;

pub use rust::{RustOptions, emit_file, emit_model};
