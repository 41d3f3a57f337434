//! Loading what the FMU interprets: `resources/model.lpm` and
//! `resources/scenario.toml`, from the `fmuResourceLocation` URI the host
//! passes to `fmi2Instantiate`.

use lagrangian_core::Compiled;
use lagrangian_model::InterpretedModel;
use lagrangian_sim::scenario::{ModelNames, Override, Scenario};
use std::path::{Path, PathBuf};

/// The spec's file name in `resources/`.
pub const SPEC_FILE: &str = "model.lpm";
/// The scenario's file name in `resources/`.
pub const SCENARIO_FILE: &str = "scenario.toml";

/// The folder a `file:` URI names: `file:///a/b`, `file://localhost/a/b`
/// and `file:/a/b`, with `%XX` escapes decoded (a space is `%20`).
pub fn directory_of(uri: &str) -> Result<PathBuf, String> {
    let rest = uri
        .strip_prefix("file:")
        .ok_or_else(|| format!("the resource location `{uri}` is not a file: URI"))?;
    let path = match rest.strip_prefix("//") {
        Some(authority_and_path) => {
            let slash = authority_and_path
                .find('/')
                .unwrap_or(authority_and_path.len());
            let (authority, path) = authority_and_path.split_at(slash);
            if !(authority.is_empty() || authority.eq_ignore_ascii_case("localhost")) {
                return Err(format!(
                    "the resource location `{uri}` names another host (`{authority}`)"
                ));
            }
            path
        }
        None => rest,
    };
    let decoded = percent_decode(path).ok_or_else(|| {
        format!("the resource location `{uri}` has a bad %-escape or is not UTF-8")
    })?;
    Ok(PathBuf::from(decoded))
}

/// `%XX` escapes decoded; `None` for a malformed escape or bytes that are
/// not UTF-8.
fn percent_decode(text: &str) -> Option<String> {
    let bytes = text.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = std::str::from_utf8(bytes.get(i + 1..i + 3)?).ok()?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).ok()
}

/// The FMU's GUID: a hash of the spec and scenario it was exported with,
/// checked again when an instance loads them (FNV-1a, 128 bits as two
/// 64-bit halves, written as a GUID).
pub fn guid(spec: &str, scenario: &str) -> String {
    let hash = |seed: u64| {
        let mut h = seed;
        for byte in spec.bytes().chain([0]).chain(scenario.bytes()) {
            h ^= u64::from(byte);
            h = h.wrapping_mul(0x0000_0100_0000_01b3);
        }
        h
    };
    let (a, b) = (hash(0xcbf2_9ce4_8422_2325), hash(0x6c62_272e_07bb_0142));
    format!(
        "{{{:08x}-{:04x}-{:04x}-{:04x}-{:012x}}}",
        a >> 32,
        (a >> 16) & 0xffff,
        a & 0xffff,
        b >> 48,
        b & 0xffff_ffff_ffff
    )
}

/// A spec compiled and its scenario resolved, with the unbound inputs bound
/// to constants the host sets.
pub struct Loaded {
    /// The compiled spec (names, units and doc comments).
    pub compiled: Compiled,
    /// The model the interpreter runs.
    pub model: InterpretedModel,
    /// The scenario, resolved against the model.
    pub scenario: Scenario,
    /// The inputs the scenario itself leaves unbound (now bound to
    /// constants, 0 at the start): the FMU's inputs.
    pub unbound: Vec<usize>,
    /// The GUID of the pair ([`guid`]).
    pub guid: String,
}

/// Compiles `spec` (the text of `spec_file`) and resolves the scenario
/// `scenario` (the text of `scenario_file`, `None`: the defaults).
pub fn load_texts(
    (spec_file, spec): (&Path, &str),
    scenario: Option<(&Path, &str)>,
) -> Result<Loaded, String> {
    let file = spec_file.display().to_string();
    let compiled = Compiled::from_source(spec).map_err(|e| e.render(&file, spec))?;
    let model = compiled.interpreted();
    let names = ModelNames::of_interpreted(&model);
    let resolve = |settings: &[Override]| match scenario {
        Some((path, text)) => Scenario::parse(text, Some(path), &names, settings),
        None => Scenario::defaults(&names, settings),
    };
    let first = resolve(&[]).map_err(|e| e.to_string())?;
    let unbound = crate::variables::unbound_inputs(&first);
    let constants: Vec<Override> = (unbound.iter())
        .map(|&i| Override::number(&model.input_names()[i], 0.0))
        .collect();
    let scenario_for_host = match constants.is_empty() {
        true => first,
        false => resolve(&constants).map_err(|e| e.to_string())?,
    };
    let scenario_text = scenario.map_or("", |(_, text)| text);
    Ok(Loaded {
        guid: guid(spec, scenario_text),
        compiled,
        model,
        scenario: scenario_for_host,
        unbound,
    })
}

/// Reads and loads `model.lpm` and `scenario.toml` (if there) of the
/// resource folder `dir`.
pub fn load(dir: &Path) -> Result<Loaded, String> {
    let read = |name: &str| {
        let path = dir.join(name);
        std::fs::read_to_string(&path)
            .map(|text| (path.clone(), text))
            .map_err(|e| format!("cannot read {}: {e}", path.display()))
    };
    let (spec_path, spec) = read(SPEC_FILE)?;
    let scenario = match dir.join(SCENARIO_FILE).exists() {
        true => Some(read(SCENARIO_FILE)?),
        false => None,
    };
    let scenario = scenario.as_ref().map(|(p, t)| (p.as_path(), t.as_str()));
    load_texts((&spec_path, &spec), scenario)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn file_uris_decode_to_paths() {
        let cases = [
            ("file:///tmp/a%20b/resources", "/tmp/a b/resources"),
            ("file://localhost/tmp/x", "/tmp/x"),
            ("file:/tmp/y/", "/tmp/y/"),
            ("file:///t%C3%A9st", "/tést"),
        ];
        for (uri, path) in cases {
            assert_eq!(directory_of(uri), Ok(PathBuf::from(path)), "{uri}");
        }
    }

    #[test]
    fn bad_uris_are_errors_that_say_why() {
        let remote = directory_of("file://server/share").unwrap_err();
        assert!(remote.contains("another host"), "{remote}");
        assert!(
            directory_of("http://x/y")
                .unwrap_err()
                .contains("not a file: URI")
        );
        assert!(
            directory_of("file:///a%2")
                .unwrap_err()
                .contains("%-escape")
        );
        assert!(
            directory_of("file:///a%zz")
                .unwrap_err()
                .contains("%-escape")
        );
    }

    #[test]
    fn the_guid_changes_with_either_text() {
        let g = guid("model A;", "");
        assert_eq!(g.len(), 38);
        assert_ne!(g, guid("model B;", ""));
        assert_ne!(g, guid("model A;", "x = 1"));
        assert_eq!(g, guid("model A;", ""));
    }

    /// A model with constraints loads: Co-Simulation and Model Exchange
    /// run the constrained accelerations (see `crate::plant`).
    #[test]
    fn a_model_with_constraints_loads() {
        let path = Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../specs/four_bar_linkage.lpm"
        ));
        let spec = std::fs::read_to_string(path).unwrap();
        let loaded = load_texts((path, &spec), None).unwrap();
        assert_eq!(loaded.model.constraint_names(), ["loop_x", "loop_y"]);
    }
}
