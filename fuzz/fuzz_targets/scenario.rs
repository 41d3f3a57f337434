//! Any text given as a scenario of the paper's model, or as a CSV time
//! history (barrier forces, a fit target): an error or a result, never a
//! panic. The first byte picks which reader gets the rest.

#![no_main]

use lagrangian_core::Compiled;
use lagrangian_sim::table::Table;
use lagrangian_sim::pulse::channels::from_table;
use lagrangian_sim::scenario::{ModelNames, Scenario};
use libfuzzer_sys::fuzz_target;
use std::path::Path;
use std::sync::OnceLock;

fn names() -> &'static ModelNames {
    static NAMES: OnceLock<ModelNames> = OnceLock::new();
    NAMES.get_or_init(|| {
        let source = include_str!("../../specs/yaris_double_pendulum.lpm");
        let compiled = Compiled::from_source(source).expect("the paper's spec compiles");
        ModelNames::of_interpreted(&compiled.interpreted())
    })
}

fuzz_target!(|data: &[u8]| {
    let Some((&which, rest)) = data.split_first() else {
        return;
    };
    let Ok(text) = std::str::from_utf8(rest) else {
        return;
    };
    match which % 3 {
        0 => {
            // Relative paths resolve against a directory with no data files.
            let file = Path::new("/nonexistent/scenario.toml");
            let _ = Scenario::parse(text, Some(file), names(), &[]);
        }
        1 => {
            // A `--set KEY=VALUE` on the shipped scenario.
            let base = include_str!("../../specs/scenarios/yaris_full_frontal.toml");
            let _ = Scenario::parse(base, None, names(), &[text.to_string()]);
        }
        _ => {
            if let Ok(table) = Table::parse(Path::new("fuzz.csv"), text) {
                let _ = from_table(&table);
            }
        }
    }
});
