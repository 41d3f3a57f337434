//! Emitters: code for the compiled program, documents for the derived
//! equations.
//!
//! Code: a program routine becomes a target-independent [`schedule`] (loads,
//! temporaries, expression trees, outputs by their layout slots); a
//! [`backend`] spells it: [`rust`](emit_model) for the macro and
//! `generated/`, [`c`] for C programs. Documents: the equations as text,
//! LaTeX or Markdown ([`render_equations`], [`render_markdown`]).

pub mod backend;
pub mod c;
mod equations;
mod markdown;
mod names;
mod notation;
mod rust;
pub mod schedule;
mod solve;
mod stub;

pub use equations::render_equations;
pub use markdown::{render_constraints, render_markdown};
pub use notation::{Notation, Printer, latex_name};
pub use rust::{RustOptions, emit_file, emit_model};
pub(crate) use stub::emit_stub;
