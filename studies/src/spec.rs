//! What several services do with a spec file: compile it, find its
//! scenario, name an output folder after it.

use crate::error::StudyError;
use lagrangian_core::Compiled;
use lagrangian_runtime::InterpretedModel;
use lagrangian_sim::files::Files;
use lagrangian_sim::scenario::scenarios_for;
use std::path::{Path, PathBuf};

/// Reads the spec at `path` from `files` and compiles it, rendering errors
/// as `file:line:col` snippets; the spec's warnings go to stderr, rendered
/// the same way.
pub fn compile(files: &dyn Files, path: &Path) -> Result<Compiled, StudyError> {
    let source = (files.text(path))
        .map_err(|e| StudyError::io(format!("cannot read {}: {e}", path.display())))?;
    let file = path.display().to_string();
    let compiled =
        Compiled::from_source(&source).map_err(|e| StudyError::Spec(e.render(&file, &source)))?;
    for warning in &compiled.model.warnings {
        eprint!("{}", warning.render_warning(&file, &source));
    }
    Ok(compiled)
}

/// The model of a compiled spec as a host runs it: interpreted, its
/// routines compiled to native code where the `jit` feature is on (the
/// same numbers, bit for bit, several times faster); a model the native
/// compiler cannot handle stays interpreted, with a note on stderr.
pub fn interpreted(compiled: &Compiled) -> InterpretedModel {
    #[cfg_attr(not(feature = "jit"), expect(unused_mut))]
    let mut model = compiled.interpreted();
    #[cfg(feature = "jit")]
    if let Err(error) = lagrangian_jit::accelerate(&mut model) {
        eprintln!("note: {error}; interpreting the model instead");
    }
    model
}

/// The scenario beside a spec (`<spec dir>/scenarios/*.toml` whose `spec`
/// key names it); `None` when there is none, a failure when there are
/// several. The scenarios are read from `files`.
pub fn find_scenario(files: &dyn Files, spec: &Path) -> Result<Option<PathBuf>, StudyError> {
    let mut found = scenarios_for(files, spec);
    match found.len() {
        0 => Ok(None),
        1 => Ok(found.pop()),
        _ => Err(StudyError::usage(format!(
            "several scenarios name {}: {}; choose one with --scenario",
            spec.display(),
            found
                .iter()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ))),
    }
}

/// `out` if given, else `lpm-out/<spec name><suffix>`.
pub fn out_dir(out: Option<PathBuf>, spec: &Path, suffix: &str) -> PathBuf {
    out.unwrap_or_else(|| {
        let stem = spec
            .file_stem()
            .map_or("model".into(), |s| s.to_string_lossy().into_owned());
        Path::new("lpm-out").join(format!("{stem}{suffix}"))
    })
}
