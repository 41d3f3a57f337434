//! Any text given as a spec: parsing, derivation, optimization and every
//! emitter must return a result or an error, never panic, hang or exhaust
//! memory (run with `-rss_limit_mb` and `-timeout`).

#![no_main]

use lagrangian_core::Compiled;
use lagrangian_core::emit::{Notation, RustOptions, emit_file, render_equations, render_markdown};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(source) = std::str::from_utf8(data) else {
        return;
    };
    match Compiled::from_source(source) {
        Ok(mut compiled) => {
            let _ = render_equations(&mut compiled, Notation::Text);
            let _ = render_equations(&mut compiled, Notation::Latex);
            let _ = render_markdown(&mut compiled, "fuzz.lpm");
            let _ = emit_file(compiled, &RustOptions::default(), "");
        }
        Err(errors) => {
            // Rendering points into the source: line/column arithmetic on
            // arbitrary text must hold too.
            let _ = errors.render("fuzz.lpm", source);
        }
    }
});
