//! `lpm compare`: simulation output folders and CSV files rated by
//! ISO/TS 18571, as JSON and text, with overlay plots; bad channels.

mod common;

use common::{lpm, stderr, stdout, temporary};
use std::path::{Path, PathBuf};

/// A run of the double pendulum from `theta1` (0.3 s) into `dir/name`.
fn run(dir: &Path, name: &str, theta1: f64) -> PathBuf {
    let out = dir.join(name);
    let setting = format!("initial.coordinates.theta1={theta1}");
    let o = lpm(&[
        "simulate",
        "specs/double_pendulum.lpm",
        "--out",
        out.to_str().unwrap(),
        "--t-end",
        "0.3",
        "--set",
        &setting,
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    out
}

fn json(args: &[&str]) -> serde_json::Value {
    let o = lpm(args);
    assert!(o.status.success(), "{}", stderr(&o));
    serde_json::from_str(&stdout(&o)).expect("JSON on stdout")
}

const SCORES: [&str; 5] = ["corridor", "phase", "magnitude", "slope", "overall"];

#[test]
fn a_run_compared_with_itself_scores_1_everywhere() {
    let dir = temporary("compare-itself");
    let a = run(&dir, "a", 0.5);
    let a = a.to_str().unwrap();
    let document = json(&["compare", a, a, "--format", "json"]);
    let pairs = document["pairs"].as_array().unwrap();
    // Every column of the trajectory but the time, less the two energies
    // that stay zero (no damping, no external force): a zero reference
    // has no corridor, so those are skipped, with the reason.
    assert_eq!(pairs.len(), 11, "{document:#}");
    for pair in pairs {
        assert_eq!(pair["reference"], pair["comparison"]);
        for score in SCORES {
            assert_eq!(pair[score], 1.0, "{}: {score}", pair["reference"]);
        }
        assert_eq!(pair["grade"], "excellent");
    }
    let skipped: Vec<&str> = (document["skipped"].as_array().unwrap().iter())
        .map(|s| s["channel"].as_str().unwrap())
        .collect();
    assert_eq!(skipped, ["dissipated_energy", "external_work"]);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn two_runs_are_rated_pair_by_pair_and_plotted() {
    let dir = temporary("compare-two-runs");
    let (a, b) = (run(&dir, "a", 0.5), run(&dir, "b", 0.4));
    let (a, b) = (a.to_str().unwrap(), b.to_str().unwrap());
    let plots = dir.join("plots");
    let args = [
        "compare",
        a,
        b,
        "--channel",
        "theta1",
        "--channel",
        "x2_position [m]=x2_position",
        "--format",
        "json",
        "--out",
        plots.to_str().unwrap(),
    ];
    let document = json(&args);
    let pairs = document["pairs"].as_array().unwrap();
    assert_eq!(pairs.len(), 2);
    for pair in pairs {
        let s: Vec<f64> = SCORES.iter().map(|k| pair[k].as_f64().unwrap()).collect();
        assert!(s.iter().all(|v| (0.0..=1.0).contains(v)), "{pair}");
        // A smaller swing: no longer identical, and rated as the standard
        // weighs the scores.
        assert!(s[4] < 0.99, "{pair}");
        let weighted = 0.4 * s[0] + 0.2 * (s[1] + s[2] + s[3]);
        assert!((s[4] - weighted).abs() < 1e-12, "{pair}");
    }
    assert_eq!(pairs[1]["unit"], "m");
    for name in ["theta1.svg", "x2_position.svg"] {
        let svg = std::fs::read_to_string(plots.join(name)).unwrap();
        assert!(svg.contains(": ISO/TS 18571 overall"), "{name}");
        assert!(svg.contains("t [ms]") && svg.contains("reference: a "));
        assert!(svg.contains("comparison: b "), "{name}");
    }
    // The text lists the same pairs, one line each, with the grades.
    let o = lpm(&args[..7]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    assert!(
        text.contains("theta1 [rad]") && text.contains("x2_position [m]"),
        "{text}"
    );
    let overall = pairs[0]["overall"].as_f64().unwrap();
    assert!(text.contains(&format!("{overall:.3}")), "{text}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn csv_files_in_other_units_are_converted_before_rating() {
    let dir = temporary("compare-csv");
    let pulse = |t: f64| -30.0 * (std::f64::consts::PI * t / 0.08).sin().powi(2);
    let write = |name: &str, header: &str, scale: f64| {
        let mut text = format!("time [ms],{header}\n");
        for k in 0..=800 {
            let t = k as f64 * 1e-4;
            text.push_str(&format!("{},{}\n", t * 1e3, scale * pulse(t)));
        }
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        path
    };
    let test = write("test.csv", "a [g]", 1.0);
    let model = write("model.csv", "a [m/s^2]", 9.80665);
    let document = json(&[
        "compare",
        test.to_str().unwrap(),
        model.to_str().unwrap(),
        "--format",
        "json",
    ]);
    let pair = &document["pairs"][0];
    for score in SCORES {
        assert!((pair[score].as_f64().unwrap() - 1.0).abs() < 1e-9, "{pair}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_bad_channel_is_a_usage_error_that_names_it() {
    let dir = temporary("compare-bad-channel");
    let a = run(&dir, "a", 0.5);
    let a = a.to_str().unwrap();
    let o = lpm(&["compare", a, a, "--channel", "theta1=thetaa"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.starts_with("error: ") && e.contains("trajectory.csv: no channel `thetaa`"),
        "{e}"
    );
    assert!(e.contains("did you mean `theta1`?"), "{e}");
    assert!(stdout(&o).is_empty());
    let o = lpm(&["compare", a, a, "--channel", "=theta1"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--channel `=theta1`: expected REF=COMP"));
    // A folder that is no run's output: its trajectory cannot be read.
    let o = lpm(&["compare", a, dir.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("not a simulation output folder"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_interval_is_given_in_seconds_or_with_a_unit() {
    let dir = temporary("compare-interval");
    let a = run(&dir, "a", 0.5);
    let a = a.to_str().unwrap();
    for interval in ["0.05:0.2", "50 ms:200 ms"] {
        let args = ["compare", a, a, "--channel", "theta1", "--format", "json"];
        let document = json(&[&args[..], &["--interval", interval]].concat());
        let rated = &document["pairs"][0]["interval_s"];
        assert_eq!(rated[0], 0.05, "{interval}");
        assert!(
            (rated[1].as_f64().unwrap() - 0.2).abs() < 1e-12,
            "{interval}"
        );
    }
    let o = lpm(&["compare", a, a, "--interval", "0.2:0.1"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("the start 0.2 s is not before the end 0.1 s"),
        "{}",
        stderr(&o)
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// A run and the same run written as an ISO-MME test: the belt force by
/// its column and by its channel code, in N on both sides, rate 1 (to the
/// digits the two files keep).
#[test]
fn a_run_against_its_iso_mme_test_scores_1() {
    let dir = temporary("compare-iso-mme");
    let (out, test) = (dir.join("out"), dir.join("test"));
    let o = lpm(&[
        "simulate",
        "specs/yaris_occupant.lpm",
        "--out",
        out.to_str().unwrap(),
        "--iso-mme",
        test.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (out, test) = (out.to_str().unwrap(), test.to_str().unwrap());
    let pair = "belt_force=11SEBE000000FO0P";
    let document = json(&["compare", out, test, "--channel", pair, "--format", "json"]);
    let rated = &document["pairs"][0];
    assert_eq!(rated["comparison"], "11SEBE000000FO0P");
    for score in SCORES {
        let value = rated[score].as_f64().unwrap();
        assert!((value - 1.0).abs() < 1e-9, "{score}: {document:#}");
    }
    // A code the test does not have is named, with the nearest it has.
    let o = lpm(&[
        "compare",
        out,
        test,
        "--channel",
        "belt_force=11SEBE000000FOXP",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("11SEBE000000FO0P"), "{}", stderr(&o));
    let _ = std::fs::remove_dir_all(&dir);
}

/// An EV5 test's channels by number, in their units (`G'S` as g, `NWT` as
/// N); against itself, 1.
#[test]
fn an_ev5_test_is_a_source_of_its_numbered_channels() {
    let ev5 = "crashdata/tests/data/ev5/v99001.EV5";
    let document = json(&["compare", ev5, ev5, "--format", "json"]);
    let named: Vec<(&str, &str)> = (document["pairs"].as_array().unwrap().iter())
        .map(|p| {
            (
                p["reference"].as_str().unwrap(),
                p["unit"].as_str().unwrap(),
            )
        })
        .collect();
    assert_eq!(named, [("001", "g"), ("002", "g"), ("003", "N")]);
    for pair in document["pairs"].as_array().unwrap() {
        assert_eq!(pair["overall"], 1.0);
    }
}
