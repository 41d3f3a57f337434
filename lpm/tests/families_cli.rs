//! A model written with indexed families runs as its written-out form:
//! the Pioneer chain of `tests/specs/pioneer_families.lpm`, under a
//! scenario whose one `[components.spring]` section binds the six springs,
//! writes the trajectory and summary of `specs/pioneer_wagon.lpm` under its
//! shipped scenario, number for number, its elements named `x[1]` …; and
//! an element is set as `--set m[2]=…` as `m2` is.

mod common;
use common::{lpm, stderr, temporary};
use std::path::Path;

const FAMILIES: [&str; 3] = [
    "tests/specs/pioneer_families.lpm",
    "--scenario",
    "tests/specs/pioneer_families.toml",
];

/// The written-out spec's name of a family element: `x[3]` is `x3`,
/// `spring[3].force` is `spring3.force` (a unit `[1]` after a space is
/// none).
fn written_out(name: &str) -> String {
    let element = name.split_once('[').and_then(|(family, rest)| {
        let (index, after) = rest.split_once(']')?;
        let named = family.ends_with(|c: char| c.is_alphanumeric() || c == '_');
        (named && index.chars().all(|c| c.is_ascii_digit())).then_some((family, index, after))
    });
    let Some((family, index, after)) = element else {
        return name.to_string();
    };
    format!("{family}{index}{}", written_out(after))
}

fn run(args: &[&str], out: &Path) -> (String, serde_json::Value) {
    let mut all: Vec<&str> = vec!["simulate"];
    all.extend(args);
    all.extend(["--out", out.to_str().unwrap()]);
    let done = lpm(&all);
    assert!(done.status.success(), "{}", stderr(&done));
    let trajectory = std::fs::read_to_string(out.join("trajectory.csv")).unwrap();
    let summary = std::fs::read_to_string(out.join("summary.json")).unwrap();
    (trajectory, serde_json::from_str(&summary).unwrap())
}

/// `summary` with every key of every object written out.
fn summary_written_out(summary: &serde_json::Value) -> serde_json::Value {
    match summary {
        serde_json::Value::Object(map) => (map.iter())
            .map(|(k, v)| (written_out(k), summary_written_out(v)))
            .collect::<serde_json::Map<_, _>>()
            .into(),
        serde_json::Value::Array(items) => items.iter().map(summary_written_out).collect(),
        serde_json::Value::String(s) => serde_json::Value::String(written_out(s)),
        other => other.clone(),
    }
}

#[test]
fn the_pioneer_chain_with_families_runs_as_the_written_out_one() {
    let dir = temporary("families-pioneer");
    let (families, family_summary) = run(&FAMILIES, &dir.join("families"));
    let (original, summary) = run(&["specs/pioneer_wagon.lpm"], &dir.join("original"));
    let (header, rows) = families.split_once('\n').unwrap();
    let (original_header, original_rows) = original.split_once('\n').unwrap();
    assert!(header.starts_with("t [s],x[1] [m],x[2] [m]"), "{header}");
    let header: Vec<String> = header.split(',').map(written_out).collect();
    assert_eq!(header.join(","), original_header);
    assert_eq!(rows, original_rows, "every sample, every column");
    assert!(family_summary["dissipated_by"].get("spring[3]").is_some());
    assert_eq!(summary_written_out(&family_summary), summary);
}

#[test]
fn an_element_is_set_by_its_name_as_a_scalar_is() {
    let dir = temporary("families-set");
    let mut args = FAMILIES.to_vec();
    args.extend(["--set", "m[2]=9000", "--set", "simulation.t_end=0.05"]);
    let (families, _) = run(&args, &dir.join("families"));
    let original = [
        "specs/pioneer_wagon.lpm",
        "--set",
        "m2=9000",
        "--set",
        "simulation.t_end=0.05",
    ];
    let (original, _) = run(&original, &dir.join("original"));
    let rows = |text: &str| text.split_once('\n').unwrap().1.to_string();
    assert_eq!(rows(&families), rows(&original));
    let unknown = lpm(&[
        "simulate",
        FAMILIES[0],
        FAMILIES[1],
        FAMILIES[2],
        "--set",
        "m[8]=9000",
        "--out",
        dir.join("bad").to_str().unwrap(),
    ]);
    assert_eq!(unknown.status.code(), Some(4), "{}", stderr(&unknown));
    assert!(stderr(&unknown).contains("m[8]"), "{}", stderr(&unknown));
}

#[test]
fn a_bad_entry_of_a_family_section_is_located_in_that_section() {
    let dir = temporary("families-bad-entry");
    let scenario = std::fs::read_to_string(format!("{}/{}", common::ROOT, FAMILIES[2])).unwrap();
    let line = 1 + scenario.lines().position(|l| l == "fy = 4.4482e6").unwrap();
    let spec = format!("{}/{}", common::ROOT, FAMILIES[0]);
    let scenario = scenario
        .replace("fy = 4.4482e6", "fy = -4.4482e6")
        .replace("\"pioneer_families.lpm\"", &format!("{spec:?}"));
    let file = dir.join("bad.toml");
    std::fs::write(&file, scenario).unwrap();
    let out = dir.join("out");
    let done = lpm(&[
        "simulate",
        &spec,
        "--scenario",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(done.status.code(), Some(4), "{}", stderr(&done));
    let expected = format!(
        "error: {}:{line}:1: components.\"spring[1]\".fy = -4448200: must be a positive, finite number",
        file.display()
    );
    assert!(stderr(&done).starts_with(&expected), "{}", stderr(&done));
    assert!(!out.exists(), "nothing written");
}

#[test]
fn the_components_supply_the_tangents_an_implicit_method_needs() {
    // TR-BDF2 calls the springs' and the wall's tangent stiffness and
    // damping. The written-out scenario binds the wall's but not the
    // springs' (the run fails without them); bound explicitly, they give
    // the run the family spec gets from `d(x), d(v)` alone.
    let dir = temporary("families-tangents");
    let settings = [
        "--set",
        "simulation.method=tr-bdf2",
        "--set",
        "simulation.t_end=0.05",
    ];
    let mut args = FAMILIES.to_vec();
    args.extend(settings);
    let (families, _) = run(&args, &dir.join("families"));
    let mut original = vec!["specs/pioneer_wagon.lpm"];
    original.extend(settings);
    let unbound = lpm(&[
        &["simulate"],
        &original[..],
        &["--out", dir.join("unbound").to_str().unwrap()],
    ]
    .concat());
    assert!(
        stderr(&unbound).contains("`spring1_stiffness` has no value"),
        "{}",
        stderr(&unbound)
    );
    let bindings: Vec<String> = (1..=6)
        .flat_map(|k| {
            [
                format!("components.spring{k}.inputs.stiffness=spring{k}_stiffness"),
                format!("components.spring{k}.inputs.damping=spring{k}_damping"),
            ]
        })
        .collect();
    for binding in &bindings {
        original.extend(["--set", binding.as_str()]);
    }
    let (original, _) = run(&original, &dir.join("original"));
    let rows = |text: &str| text.split_once('\n').unwrap().1.to_string();
    assert_eq!(rows(&families), rows(&original));
}
