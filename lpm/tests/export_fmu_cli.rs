//! `lpm export-fmu`: what the archive holds, failures with `lpm simulate`'s
//! statuses and messages, a missing runtime named with what to build, and
//! no half-written FMU. (FMPy runs the FMU in python/tests/test_fmu.py.)

mod common;

use common::{ROOT, lpm, stderr, stdout, temporary};
use std::io::Read;
use std::path::{Path, PathBuf};

const YARIS: &str = "specs/yaris_double_pendulum.lpm";

/// The runtime cargo builds beside `lpm` (lpm depends on its crate).
/// The runtime cargo built with this `lpm` (in `deps/`; a copy beside `lpm`
/// from `cargo build -p lagrangian-fmu` has the same bytes).
fn runtime() -> PathBuf {
    let exe = Path::new(env!("CARGO_BIN_EXE_lpm"));
    exe.with_file_name("deps").join(format!(
        "{}lagrangian_fmu{}",
        std::env::consts::DLL_PREFIX,
        std::env::consts::DLL_SUFFIX
    ))
}

fn entry(archive: &mut zip::ZipArchive<std::fs::File>, name: &str) -> Vec<u8> {
    let mut bytes = Vec::new();
    archive
        .by_name(name)
        .unwrap()
        .read_to_end(&mut bytes)
        .unwrap();
    bytes
}

#[test]
fn the_fmu_holds_the_description_the_runtime_and_the_resources() {
    let dir = temporary("export-fmu");
    let out = dir.join("yaris.fmu");
    let run = export(&[YARIS, "--out", &out.display().to_string()]);
    assert!(run.status.success(), "{}", stderr(&run));
    assert!(
        stdout(&run).starts_with(&format!("wrote {}", out.display())),
        "{}",
        stdout(&run)
    );
    let mut archive = zip::ZipArchive::new(std::fs::File::open(&out).unwrap()).unwrap();
    let mut names: Vec<&str> = archive.file_names().collect();
    names.sort();
    assert_eq!(
        names,
        [
            "binaries/linux64/lagrangian_fmu.so",
            "modelDescription.xml",
            "resources/data/barrier-yaris_barrier_forces.csv",
            "resources/model.lpm",
            "resources/scenario.toml",
        ]
    );
    let library = entry(&mut archive, "binaries/linux64/lagrangian_fmu.so");
    assert_eq!(library, std::fs::read(runtime()).unwrap());
    let spec = entry(&mut archive, "resources/model.lpm");
    assert_eq!(spec, std::fs::read(Path::new(ROOT).join(YARIS)).unwrap());
    let data = entry(
        &mut archive,
        "resources/data/barrier-yaris_barrier_forces.csv",
    );
    let original = Path::new(ROOT).join("specs/data/yaris_barrier_forces.csv");
    assert_eq!(data, std::fs::read(original).unwrap());
    let scenario = String::from_utf8(entry(&mut archive, "resources/scenario.toml")).unwrap();
    assert!(
        scenario.contains("file = \"data/barrier-yaris_barrier_forces.csv\""),
        "{scenario}"
    );
    assert!(scenario.contains("spec = \"model.lpm\""), "{scenario}");
    let xml = String::from_utf8(entry(&mut archive, "modelDescription.xml")).unwrap();
    for expected in [
        "fmiVersion=\"2.0\"",
        "modelName=\"YarisDoublePendulum\"",
        "<ModelExchange modelIdentifier=\"lagrangian_fmu\"",
        "<CoSimulation modelIdentifier=\"lagrangian_fmu\"",
        // m1 at the spec's value, k_tor at the scenario's.
        "name=\"m1\" valueReference=\"9\"",
        "<Real unit=\"kg\" start=\"539.0\"/>",
        "name=\"k_tor\"",
        "<Real unit=\"N*m/rad\" start=\"0.0\"/>",
        "name=\"front_end.force\"",
        "stopTime=\"0.15\" tolerance=\"1e-8\"",
    ] {
        assert!(xml.contains(expected), "{expected} not in\n{xml}");
    }
}

fn export(args: &[&str]) -> std::process::Output {
    let mut all = vec!["export-fmu"];
    all.extend_from_slice(args);
    lpm(&all)
}

#[test]
fn a_bad_scenario_fails_as_in_lpm_simulate_and_leaves_the_old_fmu() {
    let dir = temporary("export-fmu-bad");
    let scenario = dir.join("bad.toml");
    std::fs::write(&scenario, "[simulation]\nt_end = -1.0\nrtoll = 1e-6\n").unwrap();
    let out = dir.join("old.fmu");
    std::fs::write(&out, "the old FMU").unwrap();
    let (scenario, out_s) = (scenario.display().to_string(), out.display().to_string());
    let exported = export(&[YARIS, "--scenario", &scenario, "--out", &out_s]);
    let simulated = lpm(&[
        "simulate",
        YARIS,
        "--scenario",
        &scenario,
        "--out",
        &dir.display().to_string(),
    ]);
    assert_eq!(exported.status.code(), Some(4));
    assert_eq!(exported.status.code(), simulated.status.code());
    assert_eq!(stderr(&exported), stderr(&simulated));
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "the old FMU");
    let left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(left.len(), 2, "{left:?}");
}

#[test]
fn a_missing_runtime_is_named_with_what_to_build() {
    let dir = temporary("export-fmu-runtime");
    let out = dir.join("y.fmu").display().to_string();
    let missing = dir.join("liblagrangian_fmu.so").display().to_string();
    let run = export(&[YARIS, "--out", &out, "--runtime", &missing]);
    assert_eq!(run.status.code(), Some(2));
    let message = stderr(&run);
    assert!(message.contains(&missing), "{message}");
    assert!(
        message.contains("cargo build -p lagrangian-fmu"),
        "{message}"
    );
    assert!(!Path::new(&out).exists());
}

/// A shared library that is no FMU binary: a proc-macro crate's, which
/// cargo built in the same `deps/` folder for lpm's own build (thiserror's,
/// serde's), whichever of them a build of lpm alone made.
fn some_other_library() -> PathBuf {
    let deps = runtime().parent().unwrap().to_path_buf();
    let found = std::fs::read_dir(&deps).unwrap().map(|e| e.unwrap().path());
    let mut libraries: Vec<PathBuf> = found
        .filter(|p| {
            let name = p.file_name().unwrap().to_string_lossy();
            let proc_macro = [
                "libthiserror_impl-",
                "libserde_derive-",
                "liblagrangian_macro-",
            ]
            .iter()
            .any(|prefix| name.starts_with(prefix));
            proc_macro && name.ends_with(std::env::consts::DLL_SUFFIX)
        })
        .collect();
    libraries.sort();
    libraries.pop().expect("a proc-macro library beside lpm")
}

#[test]
fn a_runtime_that_is_no_fmu_binary_is_refused_and_writes_nothing() {
    let dir = temporary("export-fmu-not-a-runtime");
    let out = dir.join("y.fmu").display().to_string();
    let cases = [
        (
            some_other_library(),
            "exports none of the 44 FMI 2.0 functions",
        ),
        (
            PathBuf::from(env!("CARGO_BIN_EXE_lpm")),
            "exports none of the 44",
        ),
    ];
    for (library, why) in cases {
        let library = library.display().to_string();
        let run = export(&[YARIS, "--out", &out, "--runtime", &library]);
        assert_eq!(run.status.code(), Some(2), "{}", stderr(&run));
        let message = stderr(&run);
        assert!(
            message.contains(&library) && message.contains(why),
            "{message}"
        );
    }
    let mut command = std::process::Command::new(env!("CARGO_BIN_EXE_lpm"));
    command
        .current_dir(ROOT)
        .args(["export-fmu", YARIS, "--out", &out]);
    let run = command
        .env("LPM_FMU_RUNTIME", "/etc/passwd")
        .output()
        .unwrap();
    assert_eq!(run.status.code(), Some(2));
    assert!(stderr(&run).contains("/etc/passwd (LPM_FMU_RUNTIME) is not a shared library"));
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
}

#[test]
fn specs_whose_names_are_those_the_fmu_adds_export_under_their_own_names() {
    // car_to_car.lpm declares `output crush`, wall_impact.lpm `output
    // deceleration`; the FMU's own are `metrics.crush` and
    // `metrics.deceleration`.
    let dir = temporary("export-fmu-names");
    for (spec, own) in [
        ("specs/car_to_car.lpm", "crush"),
        ("specs/wall_impact.lpm", "deceleration"),
    ] {
        let out = dir.join("names.fmu");
        let run = export(&[spec, "--out", &out.display().to_string()]);
        assert!(run.status.success(), "{spec}: {}", stderr(&run));
        let mut archive = zip::ZipArchive::new(std::fs::File::open(&out).unwrap()).unwrap();
        let xml = String::from_utf8(entry(&mut archive, "modelDescription.xml")).unwrap();
        for name in [own, "metrics.crush", "metrics.deceleration"] {
            let attribute = format!("<ScalarVariable name=\"{name}\"");
            assert_eq!(xml.matches(&attribute).count(), 1, "{spec}: {name}\n{xml}");
        }
    }
}

/// `lpm export-fmu --compiled` with the environment `variables` set.
fn export_compiled(args: &[&str], variables: &[(&str, &Path)]) -> std::process::Output {
    let mut command = std::process::Command::new(env!("CARGO_BIN_EXE_lpm"));
    command.current_dir(ROOT).args(["export-fmu", "--compiled"]);
    command.args(args).env_remove("LPM_SOURCE");
    for (name, value) in variables {
        command.env(name, value);
    }
    command.output().unwrap()
}

#[test]
fn compiled_without_a_source_tree_says_how_to_name_one() {
    let dir = temporary("export-fmu-source");
    let out = dir.join("y.fmu").display().to_string();
    let tree = dir.join("no-tree");
    for (args, variables) in [
        (
            vec![YARIS, "--out", &out, "--source", tree.to_str().unwrap()],
            vec![],
        ),
        (
            vec![YARIS, "--out", &out],
            vec![("LPM_SOURCE", tree.as_path())],
        ),
    ] {
        let run = export_compiled(&args, &variables);
        assert_eq!(run.status.code(), Some(2), "{}", stderr(&run));
        let message = stderr(&run);
        assert!(message.contains(&tree.display().to_string()), "{message}");
        assert!(
            message.contains("name it with --source DIR or LPM_SOURCE"),
            "{message}"
        );
    }
    assert!(!Path::new(&out).exists());
}

#[test]
fn compiled_without_cargo_says_so_and_writes_no_fmu() {
    let dir = temporary("export-fmu-cargo");
    let out = dir.join("y.fmu").display().to_string();
    let cargo = dir.join("no-cargo");
    let variables = [("CARGO", cargo.as_path()), ("CARGO_TARGET_DIR", &dir)];
    let run = export_compiled(&[YARIS, "--out", &out], &variables);
    assert_eq!(run.status.code(), Some(2), "{}", stderr(&run));
    let message = stderr(&run);
    assert!(
        message.contains(&format!("`{}` cannot be run", cargo.display())),
        "{message}"
    );
    assert!(!Path::new(&out).exists());
    // The crate it would have built is there, with the model as `lpm
    // generate` emits it.
    let crates: Vec<_> = std::fs::read_dir(dir.join("lpm-export-fmu"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    assert_eq!(crates.len(), 1, "{crates:?}");
    let model = std::fs::read_to_string(crates[0].join("src/model.rs")).unwrap();
    let generated = Path::new(ROOT).join("generated/src/yaris_double_pendulum.rs");
    let generated = std::fs::read_to_string(generated).unwrap();
    let body = |text: &str| text.split_once("\n\n").unwrap().1.to_string();
    assert_eq!(body(&model), body(&generated));
}

#[test]
fn compiled_and_a_runtime_are_exclusive() {
    let run = export_compiled(&[YARIS, "--out", "x.fmu", "--runtime", "r.so"], &[]);
    assert_eq!(run.status.code(), Some(2));
    assert!(
        stderr(&run).contains("cannot be used with"),
        "{}",
        stderr(&run)
    );
}
