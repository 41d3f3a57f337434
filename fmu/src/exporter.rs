//! The FMU exporter (feature `export`) behind `lpm export-fmu` and the
//! Python package's `export_fmu`: an FMI 2.0 FMU (Co-Simulation and Model
//! Exchange) of a spec under its scenario, for Simulink, Modelica tools or
//! FMPy. It fails with the studies' [`StudyError`], as the other services
//! every host calls do.
//!
//! The FMU carries the prebuilt generic runtime (the `lagrangian-fmu`
//! cdylib, as `binaries/<platform>/lagrangian_fmu.<ext>`), which interprets
//! `resources/model.lpm` and `resources/scenario.toml` (with the data files
//! the scenario reads under `resources/data/`): no compiler is needed to
//! export. The variables and GUID come from loading the packed resources
//! exactly as the runtime will. With `--compiled`, the binary is one cargo
//! builds of the macro-compiled model instead ([`compiled`]).
//!
//! Behind a feature, off by default: the FMU binaries (`fmu/binary`, the
//! crate `--compiled` writes) link this crate without the zip writer, the
//! object reader and the studies crate the exporter needs.

mod archive;
pub mod compiled;
mod description;
mod runtime;

use crate::instance::{Instance, Interface};
use crate::resources::{SCENARIO_FILE, SPEC_FILE};
use crate::variables::first_paragraph;
use archive::Entry;
use lagrangian_runtime::{Interpreted, WithDimension};
use lagrangian_sim::files::Disk;
use lagrangian_sim::scenario::Scenario;
use lagrangian_studies::error::StudyError;
use std::path::{Path, PathBuf};

/// The FMU's `modelIdentifier`: the runtime's library name, the same for
/// every exported model.
pub const MODEL_IDENTIFIER: &str = "lagrangian_fmu";

/// The environment variable naming the runtime library.
pub const RUNTIME_VARIABLE: &str = "LPM_FMU_RUNTIME";

/// Which FMU binary an export packs.
pub enum Binary<'a> {
    /// The generic runtime, which interprets the resources: this library,
    /// else [`find_runtime`]'s.
    Generic(Option<&'a Path>),
    /// A binary of the macro-compiled model, built by cargo.
    Compiled(&'a compiled::Build),
}

/// What an export wrote.
pub struct Exported {
    /// The size of the FMU \[bytes\].
    pub bytes: u64,
    /// The number of FMI variables.
    pub variables: usize,
    /// The number of event indicators.
    pub event_indicators: usize,
    /// The binaries' platform folder (`linux64`).
    pub platform: &'static str,
}

/// Exports `spec` under `scenario` (else the one beside the spec that
/// names it, else the defaults) as the FMU `out`, packing the runtime
/// library `runtime` (else [`find_runtime`]'s). A bad spec or scenario
/// fails as in `lpm simulate`.
pub fn export(
    spec: &Path,
    scenario: Option<&Path>,
    out: &Path,
    runtime: Option<&Path>,
) -> Result<Exported, StudyError> {
    export_with(spec, scenario, out, Binary::Generic(runtime))
}

/// Exports `spec` under `scenario` as [`export`] does, packing `binary`.
pub fn export_with(
    spec: &Path,
    scenario: Option<&Path>,
    out: &Path,
    binary: Binary,
) -> Result<Exported, StudyError> {
    // From the disk, as what it packs is: the FMU holds the files there.
    let (compiled, model, scenario_path, resolved) =
        lagrangian_studies::simulate::load_spec(&Disk, spec, scenario, &[])?;
    model.with_dimension(Supported).map_err(StudyError::model)?;
    let spec_bytes = read(spec)?;
    let (library, whence) = match binary {
        Binary::Generic(runtime) => find_runtime(runtime)?,
        Binary::Compiled(build) => (
            compiled::build(spec, &String::from_utf8_lossy(&spec_bytes), build)?,
            "built by --compiled",
        ),
    };
    let library_bytes = read(&library)?;
    runtime::check(&library, whence, &library_bytes)?;
    let mut resources = vec![Entry {
        name: format!("resources/{SPEC_FILE}"),
        bytes: spec_bytes,
        executable: false,
    }];
    if let Some(path) = &scenario_path {
        resources.extend(packed_scenario(path)?);
    }
    let instance = load_packed(&resources)?;
    let summary = first_paragraph(&compiled.model.doc);
    let about = about(&compiled, &resolved, &instance, &summary);
    let xml = description::model_description(&about, &instance.variables);
    let platform = platform()?;
    let mut entries = vec![
        Entry {
            name: "modelDescription.xml".to_string(),
            bytes: xml.into_bytes(),
            executable: false,
        },
        Entry {
            name: format!(
                "binaries/{platform}/{MODEL_IDENTIFIER}{}",
                std::env::consts::DLL_SUFFIX
            ),
            bytes: library_bytes,
            executable: true,
        },
    ];
    entries.extend(resources);
    archive::write_atomically(out, &entries)?;
    let bytes = std::fs::metadata(out).map_or(0, |m| m.len());
    Ok(Exported {
        bytes,
        variables: instance.variables.list.len(),
        event_indicators: instance.event_count(),
        platform,
    })
}

/// Checks that the interpreter runs the model at its dimension.
struct Supported;

impl WithDimension for Supported {
    type Output = ();

    fn run<const N: usize>(self, _: Interpreted<N>) {}
}

/// What modelDescription.xml says besides the variables.
fn about<'a>(
    compiled: &'a lagrangian_core::Compiled,
    scenario: &Scenario,
    instance: &'a Instance,
    description: &'a str,
) -> description::About<'a> {
    description::About {
        model_name: &compiled.model.name,
        description,
        identifier: MODEL_IDENTIFIER,
        guid: instance.guid(),
        event_indicators: instance.event_count(),
        experiment: (
            scenario.t_end,
            scenario.options.rtol,
            scenario.output_interval,
        ),
    }
}

fn read(path: &Path) -> Result<Vec<u8>, StudyError> {
    std::fs::read(path).map_err(|e| StudyError::io(format!("cannot read {}: {e}", path.display())))
}

/// The FMI 2.0 platform folder of the platform lpm was built for (the
/// runtime is built for the same one).
fn platform() -> Result<&'static str, StudyError> {
    match (std::env::consts::OS, std::env::consts::ARCH) {
        ("linux", "x86_64") => Ok("linux64"),
        ("windows", "x86_64") => Ok("win64"),
        ("macos", "x86_64" | "aarch64") => Ok("darwin64"),
        (os, arch) => Err(StudyError::usage(format!(
            "FMI 2.0 names no binaries folder for {arch}-{os}"
        ))),
    }
}

/// The runtime library's file name on this platform (`liblagrangian_fmu.so`).
pub fn runtime_file() -> String {
    runtime::library_file()
}

/// The runtime library: `runtime` if given, else `$LPM_FMU_RUNTIME`, else
/// `liblagrangian_fmu.so` (`.dll`, `.dylib`) beside the lpm executable;
/// with where it was named (for messages).
pub fn find_runtime(runtime: Option<&Path>) -> Result<(PathBuf, &'static str), StudyError> {
    let file = runtime::library_file();
    let (candidate, whence) = match (runtime, std::env::var_os(RUNTIME_VARIABLE)) {
        (Some(path), _) => (path.to_path_buf(), "--runtime"),
        (None, Some(path)) => (PathBuf::from(path), RUNTIME_VARIABLE),
        (None, None) => {
            let exe = std::env::current_exe().map_err(|e| StudyError::io(e.to_string()))?;
            let dir = exe.parent().unwrap_or(Path::new("."));
            (built_beside(dir, &file), "beside lpm")
        }
    };
    if candidate.is_file() {
        return Ok((candidate, whence));
    }
    if candidate.exists() {
        return Err(StudyError::usage(format!(
            "the FMU runtime {} ({whence}) is not a file: name the library itself, {file}",
            candidate.display()
        )));
    }
    Err(StudyError::usage(format!(
        "the FMU runtime {} does not exist: build it with `cargo build -p lagrangian-fmu` \
         (it is written beside lpm as {file}), or name it with --runtime PATH or {RUNTIME_VARIABLE}",
        candidate.display()
    )))
}

/// The runtime `file` built beside the executable in `dir`: cargo writes it
/// to `dir/deps` whenever it builds `lpm` (which links the same crate), and
/// copies it to `dir` on `cargo build -p lagrangian-fmu`; the newer of the
/// two is the one of the current sources.
fn built_beside(dir: &Path, file: &str) -> PathBuf {
    let modified = |p: &PathBuf| std::fs::metadata(p).and_then(|m| m.modified()).ok();
    let candidates = [dir.join(file), dir.join("deps").join(file)];
    let newest = candidates
        .iter()
        .filter(|p| p.is_file())
        .max_by_key(|p| modified(p));
    newest.unwrap_or(&candidates[0]).clone()
}

/// `resources/scenario.toml` and the data files it reads: the scenario
/// with its `spec` key naming `model.lpm` and each component's `file`
/// moved under `data/` (as `data/COMPONENT-NAME`).
fn packed_scenario(path: &Path) -> Result<Vec<Entry>, StudyError> {
    let text = String::from_utf8(read(path)?)
        .map_err(|_| StudyError::io(format!("{} is not UTF-8", path.display())))?;
    let mut document: toml::Table = text
        .parse()
        .map_err(|e| StudyError::invalid_scenario(format!("{}: {e}", path.display())))?;
    if document.contains_key("spec") {
        document.insert("spec".into(), SPEC_FILE.into());
    }
    let base = path.parent().unwrap_or(Path::new("."));
    let mut entries = Vec::new();
    let components = document
        .get_mut("components")
        .and_then(|c| c.as_table_mut());
    for (name, section) in components.into_iter().flatten() {
        let Some(file) = section.get_mut("file") else {
            continue;
        };
        let Some(original) = file.as_str() else {
            continue;
        };
        let source = base.join(original);
        let stem = source
            .file_name()
            .map_or("data".into(), |n| n.to_string_lossy().into_owned());
        let packed = format!("data/{name}-{stem}");
        entries.push(Entry {
            name: format!("resources/{packed}"),
            bytes: read(&source)?,
            executable: false,
        });
        *file = packed.into();
    }
    let header = format!(
        "# {}, packed by lpm export-fmu: `spec` is the packed model.lpm and the\n\
         # data files are under data/.\n",
        path.display()
    );
    let body = toml::to_string(&document).map_err(|e| StudyError::io(e.to_string()))?;
    entries.insert(
        0,
        Entry {
            name: format!("resources/{SCENARIO_FILE}"),
            bytes: format!("{header}{body}").into_bytes(),
            executable: false,
        },
    );
    Ok(entries)
}

/// Loads the packed resources as the runtime will (from a temporary
/// folder): the instance whose variables and GUID the description lists.
fn load_packed(resources: &[Entry]) -> Result<Instance, StudyError> {
    let stamp = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos());
    let dir = std::env::temp_dir().join(format!("lpm-export-fmu-{}-{stamp}", std::process::id()));
    let loaded = stage_and_load(&dir, resources);
    let _ = std::fs::remove_dir_all(&dir);
    let loaded = loaded?;
    let guid = loaded.guid.clone();
    Instance::new("export", Interface::CoSimulation, &guid, loaded)
        .map_err(|f| StudyError::invalid_scenario(f.message))
}

fn stage_and_load(dir: &Path, resources: &[Entry]) -> Result<crate::resources::Loaded, StudyError> {
    for entry in resources {
        let relative = entry.name.strip_prefix("resources/").unwrap_or(&entry.name);
        let path = dir.join(relative);
        let written = std::fs::create_dir_all(path.parent().unwrap_or(dir))
            .and_then(|()| std::fs::write(&path, &entry.bytes));
        written.map_err(|e| StudyError::io(format!("cannot write {}: {e}", path.display())))?;
    }
    crate::resources::load(dir).map_err(|message| {
        StudyError::invalid_scenario(format!("the packed resources do not load: {message}"))
    })
}
