//! `lpm fit`: from a pulse the tool simulated itself to a fitted scenario
//! that `lpm simulate --scenario` runs, and its errors.

mod common;

use common::{lpm, stderr, temporary};

use std::path::Path;

/// `t [ms], deceleration [g]` up to `end` \[s\] from a trajectory.csv.
fn target_from(trajectory: &Path, target: &Path, end: f64) {
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
        if cells[it] > end + 1e-12 {
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
    target_from(&dir.join("truth/trajectory.csv"), &target, 0.1);
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

/// The largest crush of the run in `summary.json` of `dir` [m].
fn largest_crush(dir: &Path) -> f64 {
    let text = std::fs::read_to_string(dir.join("summary.json")).unwrap();
    let summary: serde_json::Value = serde_json::from_str(&text).unwrap();
    summary["max_crush_m"].as_f64().unwrap()
}

/// Fitting the breakpoints of the paper's stiffness curve to the pulse of
/// a 10 % stiffer car: the fitted run's crush decides which breakpoints
/// can matter. One beyond the segment the crush ends in (its predecessor
/// above the largest crush) has no influence at the optimum and must be
/// reported so, with no standard error, whatever it did at the start.
#[test]
fn breakpoints_beyond_the_fitted_crush_are_unidentifiable() {
    let dir = temporary("breakpoints");
    let out = dir.join("fit");
    let run = lpm(&[
        "fit",
        "specs/yaris_double_pendulum.lpm",
        "--target",
        "specs/data/yaris_pulse.csv",
        "--fit",
        "components.front_end.stiffness_breakpoints",
        "--starts",
        "1",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", stderr(&run));
    let text = String::from_utf8_lossy(&run.stdout).into_owned();
    let rerun = lpm(&[
        "simulate",
        "specs/yaris_double_pendulum.lpm",
        "--scenario",
        out.join("fitted.toml").to_str().unwrap(),
        "--out",
        dir.join("rerun").to_str().unwrap(),
    ]);
    assert!(rerun.status.success(), "{}", stderr(&rerun));
    let crush = largest_crush(&dir.join("rerun"));
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("fit.json")).unwrap()).unwrap();
    let parameters = report["parameters"].as_array().unwrap();
    let fitted: Vec<f64> = parameters
        .iter()
        .map(|p| p["fitted"].as_f64().unwrap())
        .collect();
    let mut beyond = 0;
    for (k, p) in parameters.iter().enumerate() {
        let kind = p["identifiability"]["kind"].as_str().unwrap();
        if k > 0 && fitted[k - 1] > crush {
            beyond += 1;
            assert!(
                ["no_influence_at_optimum", "held"].contains(&kind),
                "breakpoint {k} beyond the crush {crush}: {p}\n{text}"
            );
            assert!(p["standard_error"].is_null(), "{p}");
        } else if fitted[k] < crush {
            assert_eq!(
                kind, "identifiable",
                "breakpoint {k} below the crush {crush}: {p}"
            );
        }
    }
    assert!(beyond >= 2, "{crush}: {fitted:?}");
    assert!(
        text.contains("unidentifiable: no influence on the target at the optimum"),
        "{text}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// Every crush curve the messages of `--fit` suggest is one `lpm fit`
/// accepts (the Kamal model's crush components have force curves only,
/// where `--fit stiffness` used to suggest `front.stiffness`).
#[test]
fn every_curve_the_fit_suggests_is_accepted() {
    let dir = temporary("suggestions");
    let fit = |name: &str| {
        lpm(&[
            "fit",
            "specs/kamal_1970.lpm",
            "--target",
            "specs/data/yaris_pulse.csv",
            "--fit",
            name,
            "--starts",
            "1",
            "--quiet",
            "--out",
            dir.join(name).to_str().unwrap(),
        ])
    };
    let mut suggested = Vec::new();
    for name in ["stiffness", "damping", "force", "rails.stiffness"] {
        let run = fit(name);
        assert_eq!(run.status.code(), Some(2), "{name}: {}", stderr(&run));
        let message = stderr(&run);
        let (_, list) = message
            .trim_end()
            .rsplit_once(": ")
            .unwrap_or_else(|| panic!("{message}"));
        suggested.extend(list.split(", ").map(|n| n.trim_matches('`').to_string()));
    }
    suggested.sort();
    suggested.dedup();
    assert_eq!(
        suggested,
        [
            "front.damping",
            "front.force",
            "rails.damping",
            "rails.force"
        ]
    );
    for name in &suggested {
        let run = fit(name);
        assert!(
            run.status.success(),
            "{name} suggested, then: {}",
            stderr(&run)
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The ISO/TS 18571 rating `lpm compare --format json` gives `run` against
/// the shipped target, its deceleration against the run's `r_ddot`.
fn compare_rating(run: &Path) -> serde_json::Value {
    let compared = lpm(&[
        "compare",
        "specs/data/yaris_pulse.csv",
        run.to_str().unwrap(),
        "--channel",
        "deceleration=r_ddot",
        "--format",
        "json",
    ]);
    assert!(compared.status.success(), "{}", stderr(&compared));
    let json: serde_json::Value = serde_json::from_slice(&compared.stdout).unwrap();
    json["pairs"][0].clone()
}

/// The shipped fit (docs/book/fitting.md): the fitted run rates excellent
/// by ISO/TS 18571, better than the scenario's own, and the ratings the fit
/// reports are the ones `lpm compare` gives the two runs against the
/// target. Up to 1e-8: `lpm compare` reads the run's trajectory.csv, which
/// holds 11 significant digits, where the fit rates the run's own numbers.
#[test]
fn the_fit_reports_the_ratings_lpm_compare_gives_its_runs() {
    let dir = temporary("rating");
    let out = dir.join("fit");
    let run = lpm(&[
        "fit",
        "specs/yaris_double_pendulum.lpm",
        "--target",
        "specs/data/yaris_pulse.csv",
        "--fit",
        "stiffness",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", stderr(&run));
    let text = String::from_utf8_lossy(&run.stdout).into_owned();
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("fit.json")).unwrap()).unwrap();
    let channel = &report["channels"][0];
    let (initial, fitted) = (&channel["rating_initial"], &channel["rating"]);
    let overall = |r: &serde_json::Value| r["overall"].as_f64().unwrap();
    assert!(overall(fitted) > overall(initial), "{channel}");
    assert!(overall(fitted) >= 0.94, "{channel}");
    assert_eq!(fitted["grade"], "excellent", "{channel}");
    let line = format!(
        "ISO/TS 18571 deceleration [g]: overall {:.3} ({}) → {:.3} (excellent)",
        overall(initial),
        initial["grade"].as_str().unwrap(),
        overall(fitted)
    );
    assert!(text.contains(&line), "{line}\n{text}");

    let simulate = |name: &str, scenario: &[&str]| {
        let folder = dir.join(name);
        let mut args = vec!["simulate", "specs/yaris_double_pendulum.lpm"];
        args.extend(scenario);
        args.extend(["--out", folder.to_str().unwrap()]);
        let run = lpm(&args);
        assert!(run.status.success(), "{}", stderr(&run));
        compare_rating(&folder)
    };
    let fitted_toml = out.join("fitted.toml");
    let ratings = [
        (initial, simulate("initial", &[])),
        (
            fitted,
            simulate("fitted", &["--scenario", fitted_toml.to_str().unwrap()]),
        ),
    ];
    for (reported, compared) in &ratings {
        for key in ["corridor", "phase", "magnitude", "slope", "overall"] {
            let (a, b) = (reported[key].as_f64().unwrap(), compared[key].as_f64());
            assert!(
                (a - b.unwrap()).abs() < 1e-8,
                "{key}: fit {reported}, compare {compared}"
            );
        }
        for key in ["grade", "time_shift_s", "interval_s"] {
            assert_eq!(reported[key], compared[key], "{key}");
        }
    }
    assert!(
        std::fs::read_to_string(out.join("fit.svg"))
            .unwrap()
            .contains("ISO/TS 18571"),
        "the overlay's panel names the rating"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// A target of 0.8 ms (9 samples every 0.1 ms) is fitted, but it is
/// shorter than the 11 samples of the rating's 10 kHz time base: the
/// channel is reported not rated, with the reason, and the fit succeeds.
#[test]
fn a_channel_too_short_to_rate_is_reported_not_rated() {
    let dir = temporary("short");
    let run = lpm(&[
        "simulate",
        "specs/yaris_double_pendulum.lpm",
        "--out",
        dir.join("truth").to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", stderr(&run));
    let target = dir.join("target.csv");
    target_from(&dir.join("truth/trajectory.csv"), &target, 0.8e-3);
    let out = dir.join("fit");
    let run = lpm(&[
        "fit",
        "specs/yaris_double_pendulum.lpm",
        "--target",
        target.to_str().unwrap(),
        "--fit",
        "stiffness",
        "--starts",
        "1",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", stderr(&run));
    let text = String::from_utf8_lossy(&run.stdout).into_owned();
    assert!(
        text.contains("ISO/TS 18571 deceleration [g]: not rated: the common interval 0 s to 0.0008 s holds 9 samples"),
        "{text}"
    );
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("fit.json")).unwrap()).unwrap();
    for key in ["rating_initial", "rating"] {
        let rating = &report["channels"][0][key];
        assert_eq!(rating["kind"], "not_rated", "{rating}");
        assert!(rating["reason"].as_str().unwrap().contains("at least 11"));
    }
    std::fs::remove_dir_all(&dir).ok();
}
