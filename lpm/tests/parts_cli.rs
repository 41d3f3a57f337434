//! A model built from parts runs as its written-out form: the train of
//! `tests/specs/parts/train_parts.lpm` writes the trajectory of
//! `train_written.lpm` number for number, its names `car[1].m`,
//! `front.crush`, `driver.x` …; those names are set (`--set car[1].m=…`,
//! `*=`, a quantity) and swept as the written-out `car_1_m` is; and a part
//! given the wrong ports is an error at the instance.

mod common;
use common::{lpm, stderr, temporary};
use std::path::Path;

const PARTS: [&str; 3] = [
    "tests/specs/parts/train_parts.lpm",
    "--scenario",
    "tests/specs/parts/train_parts.toml",
];
const WRITTEN: [&str; 3] = [
    "tests/specs/parts/train_written.lpm",
    "--scenario",
    "tests/specs/parts/train_written.toml",
];

/// A name as the written-out spec spells it: `car[1].m` is `car_1_m`,
/// `front.crush.force` is `front_crush.force` (a component's channel
/// keeps its dot), `x[1]_dot` is `x_1_dot`.
fn spelled(column: &str) -> String {
    let (name, unit) = column.split_once(' ').unwrap_or((column, ""));
    let (name, channel) = match name.rsplit_once('.') {
        Some((component, c))
            if ["force", "deflection", "dissipated_energy"].contains(&c)
                && (component.starts_with("front") || component.starts_with("driver.belt")) =>
        {
            (component, format!(".{c}"))
        }
        _ => (name, String::new()),
    };
    let name = name.replace('[', "_").replace(']', "").replace('.', "_");
    format!(
        "{name}{channel}{}{unit}",
        if unit.is_empty() { "" } else { " " }
    )
}

fn run(args: &[&str], settings: &[&str], out: &Path) -> String {
    let mut all: Vec<&str> = vec!["simulate"];
    all.extend(args);
    all.extend(settings);
    all.extend(["--out", out.to_str().unwrap()]);
    let done = lpm(&all);
    assert!(done.status.success(), "{}", stderr(&done));
    std::fs::read_to_string(out.join("trajectory.csv")).unwrap()
}

#[test]
fn the_train_built_from_parts_runs_as_the_written_out_one() {
    let dir = temporary("parts-train");
    let parts = run(&PARTS, &[], &dir.join("parts"));
    let written = run(&WRITTEN, &[], &dir.join("written"));
    let (header, rows) = parts.split_once('\n').unwrap();
    let (written_header, written_rows) = written.split_once('\n').unwrap();
    assert!(
        header.starts_with("t [s],x[1] [m],x[2] [m],x[3] [m],driver.x [m]"),
        "{header}"
    );
    assert!(header.contains(",front.crush [N],driver.belt [N],coupler[1].compression [m]"));
    let header: Vec<String> = header.split(',').map(spelled).collect();
    assert_eq!(header.join(","), written_header);
    assert_eq!(rows, written_rows, "every sample, every column");
}

#[test]
fn a_part_s_parameter_is_set_and_swept_by_its_name() {
    let dir = temporary("parts-set");
    let short = ["--set", "simulation.t_end=0.05"];
    let written = run(
        &WRITTEN,
        &[short[0], short[1], "--set", "car_1_m=25000"],
        &dir.join("written"),
    );
    let rows = |text: &str| text.split_once('\n').unwrap().1.to_string();
    for (k, setting) in ["car[1].m=25000", "car[1].m*=1.25", "car[1].m=\"25 t\""]
        .iter()
        .enumerate()
    {
        let parts = run(
            &PARTS,
            &[short[0], short[1], "--set", setting],
            &dir.join(format!("parts{k}")),
        );
        assert_eq!(rows(&parts), rows(&written), "--set {setting}");
    }
    // A section whose name has a dot is addressed with quotes, as TOML does.
    let written = run(
        &WRITTEN,
        &[
            short[0],
            short[1],
            "--set",
            "components.driver_belt.gap=0.05",
        ],
        &dir.join("written-gap"),
    );
    let parts = run(
        &PARTS,
        &[
            short[0],
            short[1],
            "--set",
            "components.\"driver.belt\".gap=0.05",
        ],
        &dir.join("parts-gap"),
    );
    assert_eq!(rows(&parts), rows(&written), "the belt's gap");
    let table = dir.join("sweep.csv");
    let done = lpm(&[
        "sweep",
        PARTS[2],
        "--grid",
        "car[1].m=20000,25000",
        "--set",
        "simulation.t_end=0.05",
        "--out",
        table.to_str().unwrap(),
    ]);
    assert!(done.status.success(), "{}", stderr(&done));
    let table = std::fs::read_to_string(&table).unwrap();
    assert!(table.starts_with("run,car[1].m,status,"), "{table}");
    assert!(table.contains("\n1,25000.0,ok,"), "{table}");
}

#[test]
fn a_part_given_the_wrong_ports_is_an_error_at_the_instance() {
    let dir = temporary("parts-bad");
    let spec = dir.join("bad.lpm");
    std::fs::write(
        &spec,
        "model Bad;\ncoordinates { x [m] }\npart car = mass(x, x);\n",
    )
    .unwrap();
    let done = lpm(&["derive", spec.to_str().unwrap()]);
    assert_eq!(done.status.code(), Some(3), "{}", stderr(&done));
    let expected = format!(
        "error: part `mass` has 1 port (x [m]), but 2 are given\n --> {}:3:16",
        spec.display()
    );
    assert!(stderr(&done).starts_with(&expected), "{}", stderr(&done));
}

/// The `stop` part bottoms a crush element out, as energy balance says:
/// 1000 kg at 15 m/s (112.5 kJ) into a 200 kN element (reached over its
/// first millimetre) whose stroke ends at 0.3 m, a 100 MN/m stop beyond.
/// The stop's compression `d` at rest solves
/// `½mv² = F (0.3 − 0.0005 + d) + ½ k d²`; the rebound gives back the
/// stop's energy and the 20 J the crush element's unloading (1 GN/m)
/// returns.
#[test]
fn a_stop_bottoms_a_crush_element_out_as_energy_balance_says() {
    let dir = temporary("parts-stop");
    let done = lpm(&[
        "simulate",
        "tests/specs/parts/bottoming.lpm",
        "--scenario",
        "tests/specs/parts/bottoming.toml",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(done.status.success(), "{}", stderr(&done));
    let summary = std::fs::read_to_string(dir.join("summary.json")).unwrap();
    let summary: serde_json::Value = serde_json::from_str(&summary).unwrap();
    let (m, v, force, k) = (1000.0_f64, 15.0_f64, 2.0e5_f64, 1.0e8_f64);
    let c = force * (0.3 - 0.0005) - 0.5 * m * v * v;
    let d = (-force + (force * force - 2.0 * k * c).sqrt()) / k;
    let stop_energy = 0.5 * k * d * d;
    let rebound = (2.0 * (stop_energy + force * force / 2.0e9) / m).sqrt();
    let close = |found: f64, expected: f64, what: &str| {
        let error = (found - expected).abs() / expected;
        assert!(
            error < 1e-6,
            "{what}: {found} against {expected} ({error:.1e})"
        );
    };
    close(
        summary["max_crush_m"].as_f64().unwrap(),
        0.3 + d,
        "max crush",
    );
    let stop_force = summary["channels"]["end_of_stroke.force"]["max"]
        .as_f64()
        .unwrap();
    close(stop_force, k * d, "the stop's peak force");
    close(
        summary["rebound_velocity_mps"].as_f64().unwrap(),
        rebound,
        "rebound",
    );
}
