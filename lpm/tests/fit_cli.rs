//! `lpm fit`: from a pulse the tool simulated itself to a fitted scenario
//! that `lpm simulate --scenario` runs, and its errors.

mod common;

use common::{lpm, stderr, temporary};

use std::path::Path;

/// `t [ms], deceleration [g]` up to 100 ms from a trajectory.csv.
fn target_from(trajectory: &Path, target: &Path) {
    let text = std::fs::read_to_string(trajectory).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let (it, ia) = (
        header.iter().position(|h| *h == "t [s]").unwrap(),
        header.iter().position(|h| *h == "r_ddot [m/s^2]").unwrap(),
    );
    let mut out = String::from("t [ms],deceleration [g]\n");
    for line in lines {
        let cells: Vec<f64> = line.split(',').map(|c| c.parse().unwrap()).collect();
        if cells[it] > 0.1 {
            break;
        }
        // r < 0 is crush, so the vehicle's deceleration is r̈.
        out.push_str(&format!("{},{}\n", cells[it] * 1e3, cells[ia] / 9.80665));
    }
    std::fs::write(target, out).unwrap();
}

fn stiffness_values(toml_text: &str) -> Vec<f64> {
    let doc: toml::Table = toml_text.parse().unwrap();
    doc["components"]["front_end"]["stiffness_values"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_float().unwrap())
        .collect()
}

#[test]
fn a_fit_recovers_the_scenario_and_writes_a_scenario_simulate_accepts() {
    let dir = temporary("roundtrip");
    let run = lpm(&[
        "simulate",
        "specs/yaris_double_pendulum.lpm",
        "--out",
        dir.join("truth").to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", stderr(&run));
    let target = dir.join("target.csv");
    target_from(&dir.join("truth/trajectory.csv"), &target);
    let out = dir.join("fit");
    let run = lpm(&[
        "fit",
        "specs/yaris_double_pendulum.lpm",
        "--target",
        target.to_str().unwrap(),
        "--fit",
        "stiffness",
        "--set",
        "components.front_end.stiffness_values=[3e6, 2e6, 2.5e6, 0.8e6, 0.7e6, 0.45e6, 0.6e6]",
        "--starts",
        "1",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", stderr(&run));
    let text = String::from_utf8_lossy(&run.stdout);
    assert!(
        text.contains("front_end.k7") && text.contains("held: no influence"),
        "{text}"
    );
    let fitted = stiffness_values(&std::fs::read_to_string(out.join("fitted.toml")).unwrap());
    let truth = [2.4e6, 2.4e6, 2.1e6, 0.94e6, 0.567e6, 0.50e6];
    for (k, (f, t)) in fitted.iter().zip(truth).enumerate() {
        assert!((f / t - 1.0).abs() < 0.02, "k{}: {f} vs {t}\n{text}", k + 1);
    }
    assert_eq!(fitted[6], 0.6e6, "k7 is held at its start value");
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("fit.json")).unwrap()).unwrap();
    assert!(report["cost"].as_f64().unwrap() < 1e-3 * report["cost_initial"].as_f64().unwrap());
    assert!(
        std::fs::read_to_string(out.join("fit.svg"))
            .unwrap()
            .starts_with("<svg")
    );
    // The fitted scenario, written elsewhere, still finds its spec and data.
    let rerun = lpm(&[
        "simulate",
        "specs/yaris_double_pendulum.lpm",
        "--scenario",
        out.join("fitted.toml").to_str().unwrap(),
        "--out",
        dir.join("rerun").to_str().unwrap(),
    ]);
    assert!(rerun.status.success(), "{}", stderr(&rerun));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn fit_errors_name_the_problem() {
    let dir = temporary("errors");
    let target = dir.join("target.csv");
    std::fs::write(&target, "t [ms],deceleration [g]\n0,0\n1,10\n2,20\n").unwrap();
    let run = lpm(&[
        "fit",
        "specs/yaris_double_pendulum.lpm",
        "--target",
        target.to_str().unwrap(),
        "--fit",
        "stifness",
        "--quiet",
    ]);
    assert_eq!(run.status.code(), Some(2));
    assert!(
        stderr(&run).contains("--fit stifness: not a spec parameter"),
        "{}",
        stderr(&run)
    );
    let bad = dir.join("bad.csv");
    std::fs::write(&bad, "t [ms],deceleration\n0,0\n1,10\n2,20\n").unwrap();
    let run = lpm(&[
        "fit",
        "specs/yaris_double_pendulum.lpm",
        "--target",
        bad.to_str().unwrap(),
        "--quiet",
    ]);
    assert_eq!(run.status.code(), Some(7), "a data-file error");
    assert!(
        stderr(&run).contains("column `deceleration` needs a unit"),
        "{}",
        stderr(&run)
    );
    std::fs::remove_dir_all(&dir).ok();
}
