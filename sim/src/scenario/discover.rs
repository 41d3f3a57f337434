//! Which scenario goes with a spec, and which spec with a scenario: the
//! `spec = "…"` key of a scenario file, relative to the file.

use super::{ScenarioError, ScenarioErrorKind};
use crate::files::Files;
use std::path::{Path, PathBuf};

/// The spec a scenario's text names with its `spec` key, relative to the
/// scenario file `path`; `None` without the key.
pub fn spec_named_by(path: &Path, text: &str) -> Result<Option<PathBuf>, ScenarioError> {
    let table: toml::Table = text.parse().map_err(|e: toml::de::Error| ScenarioError {
        kind: ScenarioErrorKind::Invalid,
        file: Some(path.to_path_buf()),
        location: None,
        message: e.to_string(),
        key: None,
    })?;
    let base = path.parent().unwrap_or(Path::new("."));
    Ok(table
        .get("spec")
        .and_then(|s| s.as_str())
        .map(|spec| base.join(spec)))
}

/// The scenarios beside a spec, `<spec dir>/scenarios/*.toml`, whose `spec`
/// key names it, sorted (none when the folder does not exist); their text
/// is read from `files`.
pub fn scenarios_for(files: &dyn Files, spec: &Path) -> Vec<PathBuf> {
    let Some(dir) = spec.parent().map(|d| d.join("scenarios")) else {
        return Vec::new();
    };
    let Ok(entries) = std::fs::read_dir(&dir) else {
        return Vec::new();
    };
    let target = std::fs::canonicalize(spec).ok();
    let mut found: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .filter(|p| {
            let named =
                (files.text(p).ok()).and_then(|text| spec_named_by(p, &text).ok().flatten());
            named
                .and_then(|n| std::fs::canonicalize(n).ok())
                .is_some_and(|n| Some(n) == target)
        })
        .collect();
    found.sort();
    found
}
