//! `lpm simulate --iso-mme DIR`: the test it writes, read back by
//! lagrangian-crashdata, holds the run's trajectory.csv columns as the
//! scenario defines them (the pyisomme check of the same is
//! python/tests/reference/test_isomme.py).

mod common;

use common::{lpm, stderr, temporary};
use lagrangian_crashdata::isomme;
use std::collections::BTreeMap;
use std::path::Path;

/// trajectory.csv's columns by name (units dropped).
fn columns(out: &Path) -> BTreeMap<String, Vec<f64>> {
    let text = std::fs::read_to_string(out.join("trajectory.csv")).unwrap();
    let mut lines = text.lines();
    let names: Vec<String> = (lines.next().unwrap().split(','))
        .map(|n| n.split(" [").next().unwrap().to_string())
        .collect();
    let mut columns: BTreeMap<String, Vec<f64>> = BTreeMap::new();
    for line in lines {
        for (name, value) in names.iter().zip(line.split(',')) {
            columns
                .entry(name.clone())
                .or_default()
                .push(value.parse().unwrap());
        }
    }
    columns
}

/// Kamal's car (crush `xb`, a coordinate) with the barrier load of both
/// crush elements and the engine's displacement as a channel of its own.
#[test]
fn the_channels_are_the_trajectory_as_the_scenario_defines_them() {
    let dir = temporary("iso-mme-kamal");
    let (out, test_dir) = (dir.join("out"), dir.join("test"));
    let run = lpm(&[
        "simulate",
        "specs/kamal_1970.lpm",
        "--out",
        out.to_str().unwrap(),
        "--iso-mme",
        test_dir.to_str().unwrap(),
        "--set",
        "iso_mme.barrier_force=\"front.force + rails.force\"",
        "--set",
        "iso_mme.channels.xe=\"10ENGN000000DSXP\"",
        "--set",
        "iso_mme.name=\"KAMAL56\"",
    ]);
    assert!(run.status.success(), "{}", stderr(&run));
    assert!(test_dir.join("KAMAL56.mme").is_file());
    let test = isomme::read(&test_dir).unwrap();
    let c = columns(&out);
    let g = 9.80665;
    let sum =
        |a: &str, b: &str| -> Vec<f64> { c[a].iter().zip(&c[b]).map(|(x, y)| x + y).collect() };
    let expected: [(&str, &str, Vec<f64>); 5] = [
        ("10VEHCCG0000DSXP", "m", c["xb"].clone()),
        ("10VEHCCG0000VEXP", "m/s", c["xb_dot"].clone()),
        (
            "10VEHCCG0000ACXP",
            "g",
            c["xb_ddot"].iter().map(|a| a / g).collect(),
        ),
        ("B0FBAR000000FOXP", "N", sum("front.force", "rails.force")),
        ("10ENGN000000DSXP", "m", c["xe"].clone()),
    ];
    let codes: Vec<&str> = test.channels.iter().map(|ch| ch.code.as_str()).collect();
    assert_eq!(codes, expected.iter().map(|e| e.0).collect::<Vec<_>>());
    for (channel, (code, unit, values)) in test.channels.iter().zip(&expected) {
        assert_eq!(channel.unit, *unit, "{code}");
        assert_eq!((channel.t0, channel.dt), (0.0, 1e-4), "{code}");
        assert_eq!(channel.values.len(), 1501, "{code}");
        let scale = values.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for (i, (&x, &y)) in channel.values.iter().zip(values).enumerate() {
            // trajectory.csv: 11 significant digits, times to 7 decimals.
            assert!(
                (x - y).abs() <= 1e-9 * scale,
                "{code} sample {i}: {x} against {y}"
            );
            assert!(
                (channel.time(i) - c["t"][i]).abs() < 1e-9,
                "{code} sample {i}"
            );
        }
    }
    // The vehicle decelerates: a negative acceleration, ISO's x forward.
    let acceleration = &test.channels[2].values;
    assert!(acceleration.iter().copied().fold(f64::INFINITY, f64::min) < -20.0);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_run_with_nothing_to_write_is_refused_and_writes_nothing() {
    let dir = temporary("iso-mme-none");
    let (out, test_dir) = (dir.join("out"), dir.join("test"));
    let run = lpm(&[
        "simulate",
        "specs/slider_crank.lpm",
        "--out",
        out.to_str().unwrap(),
        "--iso-mme",
        test_dir.to_str().unwrap(),
    ]);
    assert_eq!(run.status.code(), Some(2), "{}", stderr(&run));
    assert!(
        stderr(&run).contains("no channel to write"),
        "{}",
        stderr(&run)
    );
    assert!(!out.join("trajectory.csv").exists() && !test_dir.exists());
    let _ = std::fs::remove_dir_all(&dir);
}
