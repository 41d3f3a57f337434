//! What `lpm` tells a user about input it runs but does not trust: spec
//! warnings, sign sanity, tolerances and the energy balance.

mod common;

use common::{lpm, stderr, stdout, temporary};

#[test]
fn derive_prints_a_specs_warning_on_stderr_and_succeeds() {
    let dir = temporary("unit-warning");
    let spec = dir.join("partly.lpm");
    std::fs::write(
        &spec,
        "model Partly;\ncoordinates { x [m] }\nparameters { m [kg] = 1.0, k = 4.0 }\n\
         kinetic = 0.5 * m * pow(dot(x), 2);\npotential = 0.5 * k * pow(x, 2);\n",
    )
    .unwrap();
    let out = lpm(&["derive".as_ref(), spec.as_os_str()]);
    assert!(out.status.success(), "{}", stderr(&out));
    let err = stderr(&out);
    assert!(
        err.starts_with("warning: units are declared for some names but not for `k`: "),
        "{err}"
    );
    assert!(err.contains("partly.lpm:3:28"), "{err}");
    assert_eq!(err.matches("warning:").count(), 1, "{err}");
    assert!(stdout(&out).contains("M[x, x] = m"), "{}", stdout(&out));
}

/// `lpm simulate` of the paper's model into a fresh folder, with `args`
/// added; the run's output and its summary.json.
fn simulate_paper(name: &str, args: &[&str]) -> (std::process::Output, serde_json::Value) {
    let dir = temporary(name);
    let out_dir = dir.to_string_lossy().into_owned();
    let mut all = vec![
        "simulate",
        "specs/yaris_double_pendulum.lpm",
        "--out",
        &out_dir,
    ];
    all.extend(args);
    let out = lpm(&all);
    let text = std::fs::read_to_string(dir.join("summary.json")).unwrap_or_default();
    let summary = serde_json::from_str(&text).unwrap_or(serde_json::Value::Null);
    (out, summary)
}

/// The folder [`temporary`] made for `name`, without emptying it.
fn temporary_path(name: &str) -> std::path::PathBuf {
    common::scratch(name)
}

fn warning_kinds(summary: &serde_json::Value) -> Vec<&str> {
    summary["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .map(|w| w["kind"].as_str().unwrap())
        .collect()
}

#[test]
fn the_paper_run_is_clean_and_its_warnings_come_after_the_metrics() {
    let (out, summary) = simulate_paper("clean", &[]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(!stderr(&out).contains("warning"), "{}", stderr(&out));
    assert_eq!(summary["warnings"], serde_json::json!([]));
    let text = std::fs::read_to_string(temporary_path("clean").join("summary.json")).unwrap();
    assert!(text.starts_with("{\n  \"max_crush_m\": "), "{text}");
    assert!(text.ends_with("\n  },\n  \"warnings\": []\n}\n"), "{text}");
    // The paper's pitch is still growing at t_end (−13.6° over the run,
    // −4.8° within the pulse): its channels say so.
    for pitch in ["theta1", "theta2"] {
        assert_eq!(
            summary["channels"][pitch]["extreme_at_end"], true,
            "{pitch}"
        );
    }
    let in_pulse = summary["max_theta1_in_pulse_deg"].as_f64().unwrap();
    let over_run = summary["max_theta1_deg"].as_f64().unwrap();
    assert!(in_pulse.abs() < over_run.abs(), "{in_pulse} vs {over_run}");
}

#[test]
fn an_impact_velocity_pointing_away_warns_and_strict_fails() {
    let away = ["--set", "initial.velocities.r=15.5556"];
    let (out, summary) = simulate_paper("away", &away);
    assert!(out.status.success(), "{}", stderr(&out));
    let err = stderr(&out);
    assert!(
        err.contains(
            "warning: the impact velocity points away from the barrier: the crush channel `-r` \
             starts at rate -15.5556 m/s"
        ),
        "{err}"
    );
    assert!(
        err.contains(
            "warning: the crush channel `-r` never compresses: its largest value 0.0000e0 m"
        ),
        "{err}"
    );
    assert_eq!(warning_kinds(&summary), ["moving_away", "never_compresses"]);
    let strict = [&away[..], &["--strict"]].concat();
    let (out, summary) = simulate_paper("away-strict", &strict);
    assert_eq!(out.status.code(), Some(9), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("error: --strict: 2 warning(s)"),
        "{}",
        stderr(&out)
    );
    // The outputs are written, to be looked at.
    assert_eq!(warning_kinds(&summary).len(), 2);
}

#[test]
fn an_energy_balance_beyond_1e_3_warns_and_strict_fails() {
    let loose = ["--rtol", "0.01", "--atol", "1e-6"];
    let (out, summary) = simulate_paper("loose", &loose);
    assert!(out.status.success(), "{}", stderr(&out));
    let error = summary["energy_balance_error_rel"].as_f64().unwrap();
    assert!(error > 1e-3, "{error}");
    let message = summary["warnings"][0]["message"].as_str().unwrap();
    assert_eq!(
        message,
        format!(
            "energy balance error {error:.1e} (relative) exceeds 1e-3: the results are not \
             accurate; tighten simulation.rtol and simulation.atol"
        )
    );
    assert!(
        stderr(&out).contains(&format!("warning: {message}")),
        "{}",
        stderr(&out)
    );
    let strict = [&loose[..], &["--strict"]].concat();
    let (out, _) = simulate_paper("loose-strict", &strict);
    assert_eq!(out.status.code(), Some(9), "{}", stderr(&out));
}

/// A 20 g half-sine pulse of 100 ms from 15 m/s, its column signed by `sign`.
fn pulse_file(name: &str, header: &str, sign: f64) -> std::path::PathBuf {
    let dir = temporary(name);
    let file = dir.join("pulse.csv");
    let mut text = format!("t [s],{header}\n");
    for k in 0..=1000 {
        let t = k as f64 * 1e-4;
        let a = -20.0 * 9.80665 * (std::f64::consts::PI * t / 0.1).sin();
        text.push_str(&format!("{t},{}\n", sign * a));
    }
    std::fs::write(&file, text).unwrap();
    file
}

#[test]
fn a_flipped_acceleration_column_in_metrics_warns() {
    let good = pulse_file("pulse-good", "acceleration [m/s^2]", 1.0);
    let out = lpm(&[
        "metrics".as_ref(),
        good.as_os_str(),
        "--v0".as_ref(),
        "15".as_ref(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(!stderr(&out).contains("warning"), "{}", stderr(&out));
    // The deceleration written in an acceleration column: +12.49 m/s.
    let flipped = pulse_file("pulse-flipped", "acceleration [m/s^2]", -1.0);
    let args = [
        "metrics".as_ref(),
        flipped.as_os_str(),
        "--v0".as_ref(),
        "15".as_ref(),
    ];
    let out = lpm(&args);
    assert!(out.status.success(), "{}", stderr(&out));
    let err = stderr(&out);
    assert!(
        err.contains(
            "warning: the acceleration column `acceleration [m/s^2]` looks flipped: its integral \
             changes the velocity by +12.486 m/s, speeding the vehicle up into the barrier from \
             the impact velocity 15.000 m/s"
        ),
        "{err}"
    );
    let json = lpm(&[&args[..], &["--format".as_ref(), "json".as_ref()]].concat());
    let value: serde_json::Value = serde_json::from_str(&stdout(&json)).unwrap();
    assert_eq!(value["warnings"][0]["kind"], "flipped_acceleration");
    let strict = lpm(&[&args[..], &["--strict".as_ref()]].concat());
    assert_eq!(strict.status.code(), Some(9));
}

#[test]
fn tolerances_out_of_range_are_scenario_errors_and_nothing_is_written() {
    for (args, message) in [
        (
            ["--rtol", "1e6"],
            "error: --rtol 1000000: must be in (0, 0.1]",
        ),
        (["--rtol", "0.9"], "error: --rtol 0.9: must be in (0, 0.1]"),
        (
            ["--atol", "1e6"],
            "error: --atol 1000000: must be small against the state's scale, at most \
             1.56e-2 (1e-3 × the largest initial coordinate or velocity, 15.5556, or 1)",
        ),
    ] {
        let (out, summary) = simulate_paper("tolerance", &args);
        assert_eq!(out.status.code(), Some(4), "{args:?}: {}", stderr(&out));
        assert!(
            stderr(&out).starts_with(message),
            "{args:?}: {}",
            stderr(&out)
        );
        assert!(summary.is_null(), "{args:?}: nothing written");
    }
    // The loosest rtol allowed runs (it starts: the first step used to
    // underflow at loose tolerances) and warns of its energy balance.
    let (out, summary) = simulate_paper("loosest", &["--rtol", "0.1", "--atol", "1e-6"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(warning_kinds(&summary), ["energy_balance"]);
}

#[test]
fn eval_takes_a_state_starting_with_a_minus_sign() {
    for args in [
        ["eval", "specs/double_pendulum.lpm", "--state", "-0.1,0,0,0"],
        [
            "eval",
            "specs/double_pendulum.lpm",
            "--state=-0.1,0,0,0",
            "--time=0",
        ],
    ] {
        let out = lpm(&args);
        assert!(out.status.success(), "{args:?}: {}", stderr(&out));
        let json: serde_json::Value = serde_json::from_str(&stdout(&out)).unwrap();
        // M[0][1] = m2 l1 l2 cos(θ1 − θ2) with unit masses and lengths.
        let m01 = json["mass_matrix"][0][1].as_f64().unwrap();
        assert!((m01 - 0.1f64.cos()).abs() < 1e-15, "{m01}");
    }
    let out = lpm(&["eval", "specs/double_pendulum.lpm", "--state", "-0.1,x,0,0"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("--state: `x` is not a number"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn eval_with_a_scenario_binds_its_inputs_and_parameters() {
    let state = "-0.1,0,0,-15,0,0";
    let args = ["eval", "specs/yaris_double_pendulum.lpm", "--state", state];
    let without = lpm(&args);
    assert_eq!(without.status.code(), Some(2), "the inputs need values");
    let scenario = ["--scenario", "specs/scenarios/yaris_full_frontal.toml"];
    let out = lpm(&[&args[..], &scenario[..]].concat());
    assert!(out.status.success(), "{}", stderr(&out));
    let json: serde_json::Value = serde_json::from_str(&stdout(&out)).unwrap();
    // M[r, r] = m1 + m2; the scenario's I1, I2 in M[θ1, θ1] = m2 (r + l0 +
    // l1)² + m1 (r + l0)² + I1 at r = −0.1.
    assert_eq!(json["mass_matrix"][0][0].as_f64(), Some(539.0 + 629.0));
    let m11 = 629.0 * (0.81f64 + 0.57).powi(2) + 539.0 * 0.81f64.powi(2) + 244.6;
    let got = json["mass_matrix"][1][1].as_f64().unwrap();
    assert!((got - m11).abs() < 1e-9 * m11, "{got} vs {m11}");
    // f[r] holds the force of the scenario's front_end at 0.1 m of crush
    // (a few hundred kN), which only the bound components supply.
    let f_r = json["forcing"][0].as_f64().unwrap();
    assert!(f_r > 1e4, "{f_r}");
    // --set applies on top of the scenario, as in simulate.
    let heavier = lpm(&[&args[..], &scenario[..], &["--set", "m1=600"]].concat());
    let json: serde_json::Value = serde_json::from_str(&stdout(&heavier)).unwrap();
    assert_eq!(json["mass_matrix"][0][0].as_f64(), Some(600.0 + 629.0));
}

#[test]
fn a_negative_mass_names_the_parameter_that_set_it() {
    let out = lpm(&[
        "eval",
        "specs/double_pendulum.lpm",
        "--state",
        "0.1,0,0,0",
        "--set",
        "m1=-180",
        "--set",
        "l1=2",
    ]);
    assert_eq!(out.status.code(), Some(10));
    assert_eq!(
        stderr(&out),
        "error: the mass matrix is singular or not positive definite at this state: made so by \
         `m1 = -180` (with m1 = 1 it is positive definite at this state); check the sign of `m1`\n"
    );
}
