//! Runs whose figures are wrong without a word unless `lpm` says so (issue
//! 34): each warns on stderr and in summary.json, and `--strict` makes it
//! an error (exit 9) with the outputs written.

mod common;

use common::{lpm, stderr, stdout, temporary};

/// `lpm simulate SPEC --out DIR ARGS…`: its output and summary.json.
fn simulate(name: &str, spec: &str, args: &[&str]) -> (std::process::Output, serde_json::Value) {
    let dir = temporary(name);
    let out_dir = dir.to_string_lossy().into_owned();
    let mut all = vec!["simulate", spec, "--out", &out_dir];
    all.extend(args);
    let out = lpm(&all);
    let text = std::fs::read_to_string(dir.join("summary.json")).unwrap_or_default();
    let summary = serde_json::from_str(&text).unwrap_or(serde_json::Value::Null);
    (out, summary)
}

const PAPER: &str = "specs/yaris_double_pendulum.lpm";

fn kinds(summary: &serde_json::Value) -> Vec<&str> {
    (summary["warnings"].as_array().unwrap().iter())
        .map(|w| w["kind"].as_str().unwrap())
        .collect()
}

#[test]
fn a_pulse_cut_short_by_t_end_says_its_crush_is_not_the_maximum() {
    let (out, summary) = simulate("m-short", PAPER, &["--set", "simulation.t_end=0.03"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        stdout(&out).contains(
            "  max dynamic crush      0.379 m (still crushing at t_end: not the maximum)\n"
        ),
        "{}",
        stdout(&out)
    );
    assert!(
        stderr(&out)
            .starts_with("warning: the crush channel `-r` is still compressing at t_end = 30.0 ms"),
        "{}",
        stderr(&out)
    );
    assert_eq!(kinds(&summary), ["still_crushing"]);
    let (strict, _) = simulate(
        "m-short-strict",
        PAPER,
        &["--set", "simulation.t_end=0.03", "--strict"],
    );
    assert_eq!(strict.status.code(), Some(9), "{}", stderr(&strict));
}

/// At 1.5 ms (667 Hz) every pulse metric is there; only CFC 180 is not,
/// and a warning says so — against the 10 kHz run's figures.
#[test]
fn a_slow_output_interval_keeps_the_metrics_and_names_the_missing_class() {
    let (out, slow) = simulate(
        "m-slow",
        PAPER,
        &["--set", "simulation.output_interval=1.5e-3"],
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let (_, fast) = simulate("m-fast", PAPER, &[]);
    for (key, tolerance) in [
        ("peak_deceleration_cfc60_g", 0.01),
        ("equivalent_square_wave_g", 1e-6),
        ("olc_g", 0.01),
        ("asi", 0.01),
    ] {
        let (s, f) = (slow[key].as_f64(), fast[key].as_f64().unwrap());
        let s = s.unwrap_or_else(|| panic!("{key} missing: {slow}"));
        assert!((s / f - 1.0).abs() < tolerance, "{key}: {s} vs {f}");
    }
    assert_eq!(kinds(&slow), ["filter_class"]);
    assert_eq!(
        slow["warnings"][0]["message"],
        "CFC 180 needs a sample rate above 748 Hz (SAE J211-1: 2.0775·CFC below half the sample \
         rate); samples every 1.5 ms give 667 Hz: OLC and ASI are those of the unfiltered crush \
         acceleration"
    );
    assert_eq!(kinds(&fast), Vec::<&str>::new());
}

#[test]
fn an_output_outside_its_domain_is_named_with_its_first_time() {
    let spec = "tests/bad_inputs/metrics_asin_output.lpm";
    let args = ["--t-end", "0.1", "--set", "initial.coordinates.theta=0.5"];
    let (out, summary) = simulate("m-asin", spec, &args);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        stderr(&out).starts_with("warning: output `phase` is NaN at t = 0.000000 s"),
        "{}",
        stderr(&out)
    );
    assert_eq!(kinds(&summary), ["non_finite"]);
    let mut strict = args.to_vec();
    strict.push("--strict");
    let (out, _) = simulate("m-asin-strict", spec, &strict);
    assert_eq!(out.status.code(), Some(9), "{}", stderr(&out));
}

/// No energy at the start: not a reason for an energy-balance warning.
#[test]
fn a_run_from_rest_has_a_small_energy_balance_error() {
    let spec = "tests/bad_inputs/metrics_at_rest.lpm";
    let (out, summary) = simulate("m-rest", spec, &["--t-end", "1", "--strict"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let error = summary["energy_balance_error_rel"].as_f64().unwrap();
    assert!(error < 1e-9, "{error}");
    assert_eq!(kinds(&summary), Vec::<&str>::new());
}

#[test]
fn a_crush_channel_that_does_not_start_at_zero_warns() {
    let (out, summary) = simulate("m-offset", PAPER, &["--set", "initial.coordinates.r=-0.01"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(kinds(&summary), ["crush_offset"]);
    assert!(
        stderr(&out).starts_with(
            "warning: the crush channel `-r` starts at 1.0000e-2 m, not 0: the max dynamic crush"
        ),
        "{}",
        stderr(&out)
    );
}

/// `lpm metrics` of a pulse sampled at 1.5 ms: the figures that need no
/// filter, and the warning for CFC 180.
#[test]
fn metrics_of_a_slow_pulse_warn_instead_of_failing() {
    let dir = temporary("m-pulse");
    let file = dir.join("slow.csv");
    let mut text = String::from("t [ms], deceleration [g]\n");
    for k in 0..=100 {
        let t = k as f64 * 1.5;
        text.push_str(&format!("{t},{}\n", if t < 100.0 { 20.0 } else { 0.0 }));
    }
    std::fs::write(&file, text).unwrap();
    let path = file.to_string_lossy().into_owned();
    let out = lpm(&["metrics", &path, "--v0", "15.5556", "--format", "json"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let m: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    // 20 g from 15.5556 m/s stops in 79.3 ms after 0.617 m; ASI 20/12.
    let esw = m["equivalent_square_wave_g"].as_f64().unwrap();
    assert!((esw - 20.0).abs() < 0.4, "{m}");
    assert!(
        (m["asi"].as_f64().unwrap() - 20.0 / 12.0).abs() < 0.03,
        "{m}"
    );
    assert!(m["peak_deceleration_cfc60_g"].as_f64().is_some(), "{m}");
    assert_eq!(m["warnings"][0]["kind"], "filter_class");
    let strict = lpm(&["metrics", &path, "--v0", "15.5556", "--strict"]);
    assert_eq!(strict.status.code(), Some(9), "{}", stderr(&strict));
}

/// A potential energy of −∞ (the spec's parameter of −1e308 times 10) named with
/// its first time, and an energy balance that is not a number instead of
/// 0: both warn.
#[test]
fn an_energy_that_is_not_a_number_is_named_and_not_balanced_to_zero() {
    let spec = "tests/bad_inputs/metrics_huge_potential.lpm";
    let args = ["--t-end", "0.1", "--set", "initial.velocities.x=1"];
    let (out, summary) = simulate("m-huge", spec, &args);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(
        kinds(&summary),
        ["energy_balance", "non_finite"],
        "{summary}"
    );
    assert!(
        stderr(&out).contains("warning: the potential energy is -inf at t = 0.000000 s"),
        "{}",
        stderr(&out)
    );
    // NaN, which JSON writes as null: not the 0 of a balanced run.
    assert!(summary["energy_balance_error_rel"].is_null(), "{summary}");
}
