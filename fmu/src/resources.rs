//! Loading what the FMU interprets: `resources/model.lpm` and
//! `resources/scenario.toml`, from the `fmuResourceLocation` URI the host
//! passes to `fmi2Instantiate`.

use lagrangian_core::{Compiled, SpecErrors};
use lagrangian_runtime::InterpretedModel;
use lagrangian_sim::scenario::{ModelNames, Override, Scenario, ScenarioError};
use std::path::{Path, PathBuf};

/// The spec's file name in `resources/`.
pub const SPEC_FILE: &str = "model.lpm";
/// The scenario's file name in `resources/`.
pub const SCENARIO_FILE: &str = "scenario.toml";

/// Why the resources cannot be loaded: a resource location that names no
/// folder here ([`directory_of`]), a file that cannot be read, a spec that
/// does not compile or a scenario that does not fit ([`load`]).
#[derive(Debug, thiserror::Error)]
pub enum ResourceError {
    /// A location that is not a `file:` URI.
    #[error("the resource location `{uri}` is not a file: URI")]
    NotAFileUri {
        /// The location.
        uri: String,
    },
    /// A `file:` URI of another host.
    #[error("the resource location `{uri}` names another host (`{host}`)")]
    OtherHost {
        /// The location.
        uri: String,
        /// The host it names.
        host: String,
    },
    /// A `%XX` escape that is malformed or decodes to bytes that are not
    /// UTF-8.
    #[error("the resource location `{uri}` has a bad %-escape or is not UTF-8")]
    BadEscape {
        /// The location.
        uri: String,
    },
    /// A file of the resources that cannot be read.
    #[error("cannot read {}: {error}", .path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        error: std::io::Error,
    },
    /// The spec does not compile.
    #[error("{}", .errors.render(.file, .text))]
    Spec {
        /// The spec's file, as its diagnostics name it.
        file: String,
        /// Its text, for the diagnostics' snippets.
        text: String,
        /// Its diagnostics.
        errors: SpecErrors,
    },
    /// The scenario cannot be read or does not fit the spec.
    #[error(transparent)]
    Scenario(ScenarioError),
}

/// The folder a `file:` URI names: `file:///a/b`, `file://localhost/a/b`
/// and `file:/a/b`, with `%XX` escapes decoded (a space is `%20`).
pub fn directory_of(uri: &str) -> Result<PathBuf, ResourceError> {
    let rest = uri
        .strip_prefix("file:")
        .ok_or_else(|| ResourceError::NotAFileUri {
            uri: uri.to_string(),
        })?;
    let path = match rest.strip_prefix("//") {
        Some(authority_and_path) => {
            let slash = authority_and_path
                .find('/')
                .unwrap_or(authority_and_path.len());
            let (authority, path) = authority_and_path.split_at(slash);
            if !(authority.is_empty() || authority.eq_ignore_ascii_case("localhost")) {
                return Err(ResourceError::OtherHost {
                    uri: uri.to_string(),
                    host: authority.to_string(),
                });
            }
            path
        }
        None => rest,
    };
    let decoded = percent_decode(path).ok_or_else(|| ResourceError::BadEscape {
        uri: uri.to_string(),
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
) -> Result<Loaded, ResourceError> {
    let compiled = Compiled::from_source(spec).map_err(|errors| ResourceError::Spec {
        file: spec_file.display().to_string(),
        text: spec.to_string(),
        errors,
    })?;
    let model = compiled.interpreted();
    let names = ModelNames::of_interpreted(&model);
    let resolve = |settings: &[Override]| match scenario {
        Some((path, text)) => Scenario::parse(text, Some(path), &names, settings),
        None => Scenario::defaults(&names, settings),
    };
    let first = resolve(&[]).map_err(ResourceError::Scenario)?;
    let unbound = crate::variables::unbound_inputs(&first);
    let constants: Vec<Override> = (unbound.iter())
        .map(|&i| Override::number(&model.input_names()[i], 0.0))
        .collect();
    let scenario_for_host = match constants.is_empty() {
        true => first,
        false => resolve(&constants).map_err(ResourceError::Scenario)?,
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
pub fn load(dir: &Path) -> Result<Loaded, ResourceError> {
    let read = |name: &str| {
        let path = dir.join(name);
        match std::fs::read_to_string(&path) {
            Ok(text) => Ok((path, text)),
            Err(error) => Err(ResourceError::Read { path, error }),
        }
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
            assert_eq!(directory_of(uri).unwrap(), PathBuf::from(path), "{uri}");
        }
    }

    #[test]
    fn bad_uris_are_errors_that_say_why() {
        let message = |uri: &str| directory_of(uri).unwrap_err().to_string();
        assert_eq!(
            message("file://server/share"),
            "the resource location `file://server/share` names another host (`server`)"
        );
        assert!(matches!(
            directory_of("file://server/share"),
            Err(ResourceError::OtherHost { host, .. }) if host == "server"
        ));
        assert_eq!(
            message("http://x/y"),
            "the resource location `http://x/y` is not a file: URI"
        );
        assert_eq!(
            message("file:///a%2"),
            "the resource location `file:///a%2` has a bad %-escape or is not UTF-8"
        );
        assert!(message("file:///a%zz").contains("%-escape"));
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
