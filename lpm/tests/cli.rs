//! The `lpm` binary: derive, eval and chain, their output and exit codes.

mod common;

use common::{lpm, stderr, stdout};

#[test]
fn derive_prints_the_compact_paper_mass_matrix() {
    let out = lpm(&["derive", "specs/yaris_double_pendulum.lpm"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    assert!(text.contains("M[r, r] = m1 + m2\n"), "{text}");
    assert!(text.contains("M[r, theta1] = 0\n"), "{text}");
    assert!(
        text.contains("M[theta1, theta1] = m2*(r + l0 + l1)^2 + m1*(r + l0)^2 + I1\n"),
        "{text}"
    );
}

#[test]
fn derive_latex_and_rust() {
    let latex = stdout(&lpm(&[
        "derive",
        "specs/double_pendulum.lpm",
        "--format",
        "latex",
    ]));
    assert!(
        latex.contains("\\begin{aligned}") && latex.contains("\\end{aligned}"),
        "{latex}"
    );
    assert!(latex.contains("M_{\\theta_{1} \\theta_{2}} &="), "{latex}");
    assert!(latex.contains("\\dot{\\theta}_{2}^{2}"), "{latex}");
    let rust = stdout(&lpm(&[
        "derive",
        "specs/double_pendulum.lpm",
        "--format",
        "rust",
        "--runtime",
        "::lagrangian_runtime",
    ]));
    assert!(rust.starts_with("// @generated"), "{rust}");
    syn::parse_file(&rust).expect("generated Rust parses");
    assert!(
        rust.contains("impl ::lagrangian_runtime::LagrangianSystem<2> for DoublePendulum"),
        "{rust}"
    );
    let c = stdout(&lpm(&[
        "derive",
        "specs/double_pendulum.lpm",
        "--format",
        "c",
    ]));
    assert!(c.contains("#include <math.h>"), "{c}");
    assert!(c.contains("void double_pendulum_dynamics("), "{c}");
}

#[test]
fn eval_matches_the_textbook_double_pendulum() {
    let (t1, t2, w1, w2) = (0.3f64, -0.2f64, 1.0f64, 0.5f64);
    let (m1, m2, l1, l2, g) = (1.5f64, 0.7f64, 1.2f64, 0.8f64, 9.81f64);
    let out = lpm(&[
        "eval",
        "specs/double_pendulum.lpm",
        "--state",
        "0.3,-0.2,1,0.5",
        "--set",
        "m1=1.5",
        "--set",
        "m2=0.7",
        "--set",
        "l1=1.2",
        "--set",
        "l2=0.8",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let json: serde_json::Value = serde_json::from_str(&stdout(&out)).unwrap();
    let m = |i: usize, j: usize| json["mass_matrix"][i][j].as_f64().unwrap();
    let f = |i: usize| json["forcing"][i].as_f64().unwrap();
    // Textbook: M = [[(m1+m2) l1², m2 l1 l2 c], [·, m2 l2²]],
    // f = [−m2 l1 l2 s ω2² − (m1+m2) g l1 sin θ1, m2 l1 l2 s ω1² − m2 g l2 sin θ2], s, c of θ1 − θ2.
    let (s, c) = (t1 - t2).sin_cos();
    let expected_m = [
        [(m1 + m2) * l1 * l1, m2 * l1 * l2 * c],
        [m2 * l1 * l2 * c, m2 * l2 * l2],
    ];
    let expected_f = [
        -m2 * l1 * l2 * s * w2 * w2 - (m1 + m2) * g * l1 * t1.sin(),
        m2 * l1 * l2 * s * w1 * w1 - m2 * g * l2 * t2.sin(),
    ];
    for (i, row) in expected_m.iter().enumerate() {
        for (j, expected) in row.iter().enumerate() {
            assert!((m(i, j) - expected).abs() < 1e-14, "M[{i}][{j}]");
        }
        assert!(
            (f(i) - expected_f[i]).abs() < 1e-13,
            "f[{i}] {} vs {}",
            f(i),
            expected_f[i]
        );
    }
}

#[test]
fn eval_demands_values_for_the_inputs_it_needs() {
    let out = lpm(&["eval", "specs/spring_mass_damper.lpm", "--state", "0.1,0"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("push"), "{}", stderr(&out));
    let out = lpm(&[
        "eval",
        "specs/spring_mass_damper.lpm",
        "--state",
        "0.1,0",
        "--set",
        "push=3",
    ]);
    let json: serde_json::Value = serde_json::from_str(&stdout(&out)).unwrap();
    // m ẍ = −k x + push = −100·0.1 + 3.
    assert_eq!(json["forcing"][0].as_f64(), Some(-7.0));
}

#[test]
fn bad_input_gets_distinct_exit_codes() {
    let wrong_length = lpm(&["eval", "specs/double_pendulum.lpm", "--state", "1,2,3"]);
    assert_eq!(wrong_length.status.code(), Some(2));
    assert!(
        stderr(&wrong_length).contains("needs 4 values"),
        "{}",
        stderr(&wrong_length)
    );
    let typo = lpm(&[
        "eval",
        "specs/double_pendulum.lpm",
        "--state",
        "0,0,0,0",
        "--set",
        "l3=1",
    ]);
    assert_eq!(typo.status.code(), Some(2));
    assert!(
        stderr(&typo).contains("did you mean `l1`?"),
        "{}",
        stderr(&typo)
    );
    let missing = lpm(&["derive", "specs/none.lpm"]);
    assert_eq!(missing.status.code(), Some(1));
    let bad_spec = lpm(&["derive", "lagrangian-core/tests/fixtures/unknown_name.lpm"]);
    assert_eq!(bad_spec.status.code(), Some(3));
    assert!(
        stderr(&bad_spec).contains("unknown_name.lpm:8:19"),
        "{}",
        stderr(&bad_spec)
    );
}

#[test]
fn chain_specs_compile() {
    let out = lpm(&["chain", "4"]);
    assert!(out.status.success());
    let spec = stdout(&out);
    let compiled = lagrangian_core::Compiled::from_source(&spec).unwrap();
    assert_eq!(compiled.program.dimension, 4);
    assert_eq!(lpm(&["chain", "0"]).status.code(), Some(2));
}

fn temporary_dir(name: &str) -> std::path::PathBuf {
    let dir = common::scratch(&format!("cli-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

#[test]
fn simulate_writes_the_summary_trajectory_and_plots() {
    let out = temporary_dir("simulate");
    let run = lpm(&[
        "simulate",
        "specs/yaris_double_pendulum.lpm",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", stderr(&run));
    let text = stdout(&run);
    assert!(
        text.contains("specs/scenarios/yaris_full_frontal.toml"),
        "found the default scenario: {text}"
    );
    assert!(
        text.contains("max dynamic crush") && text.contains("weld failure"),
        "{text}"
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let mut keys: Vec<&str> = summary
        .as_object()
        .unwrap()
        .keys()
        .map(String::as_str)
        .collect();
    keys.sort();
    let mut expected = vec![
        "max_crush_m",
        "time_of_max_crush_s",
        "time_to_zero_velocity_s",
        "max_theta1_deg",
        "max_theta2_deg",
        "peak_deceleration_g",
        "rebound_velocity_mps",
        "weld_failure_time_s",
        "peak_deceleration_cfc60_g",
        "equivalent_square_wave_g",
        "olc_g",
        "asi",
        "steps",
        "rejected_steps",
        "rhs_evaluations",
        "energy_balance_error_rel",
        "permanent_crush_m",
        "end_of_contact_s",
        "max_theta1_in_pulse_deg",
        "max_theta2_in_pulse_deg",
        "channels",
        // What looked wrong in the run (`[]` here: see trust_cli.rs).
        "warnings",
        // The energy each dissipative component dissipated.
        "dissipated_by",
    ];
    expected.sort();
    assert_eq!(keys, expected);
    let number = |k: &str| summary[k].as_f64().unwrap();
    // The crush element takes most of the ½·1168 kg·(15.5556 m/s)² ≈ 141 kJ,
    // the weld a little.
    let dissipated = |name: &str| summary["dissipated_by"][name].as_f64().unwrap();
    let (front_end, weld) = (dissipated("front_end"), dissipated("weld"));
    assert!((130e3..141e3).contains(&front_end), "{front_end}");
    assert!(weld > 0.0 && weld < 1e3, "{weld}");
    // ESW = v0² / (2 g C) with the scenario's 15.5556 m/s and the run's crush.
    let esw = 15.5556f64.powi(2) / (2.0 * 9.80665 * number("max_crush_m"));
    assert!((number("equivalent_square_wave_g") / esw - 1.0).abs() < 1e-9);
    // CFC 60 smooths the pulse but keeps its peak within a few per cent here.
    let ratio = number("peak_deceleration_cfc60_g") / number("peak_deceleration_g");
    assert!((0.85..1.05).contains(&ratio), "{ratio}");
    assert!(number("olc_g") > 10.0 && number("asi") > 1.0, "{summary}");
    let csv = std::fs::read_to_string(out.join("trajectory.csv")).unwrap();
    let header = csv.lines().next().unwrap();
    assert!(
        header.starts_with("t [s],r [m],theta1 [rad],theta2 [rad],r_dot [m/s],"),
        "{header}"
    );
    for column in [
        "kinetic_energy [J]",
        "dissipated_energy [J]",
        "external_work [J]",
        "crush [N]",
        "weld [N*m]",
        "barrier_z1 [N]",
        "front_end.force [N]",
        "front_end.deflection [m]",
        "weld.moment [N*m]",
        "weld.angle [rad]",
        "front_end.dissipated_energy [J]",
        "weld.dissipated_energy [J]",
    ] {
        assert!(header.contains(column), "{column} missing from {header}");
    }
    assert_eq!(csv.lines().count(), 1 + 1501, "0–150 ms at 0.1 ms");
    let svg = std::fs::read_to_string(out.join("plots.svg")).unwrap();
    assert!(svg.starts_with("<svg") && svg.contains("Crush force against crush"));
    for line in ["permanent crush", "deceleration, CFC 60"] {
        assert!(svg.contains(line), "{line} missing from plots.svg");
    }
    let readme_figure =
        std::fs::read_to_string(format!("{}/docs/yaris_full_frontal.svg", common::ROOT)).unwrap();
    assert!(
        svg == readme_figure,
        "docs/yaris_full_frontal.svg (the README's figure) is not this run's plots.svg: \
         copy lpm-out/yaris_double_pendulum/plots.svg there after `cargo run -p lpm -- simulate \
         specs/yaris_double_pendulum.lpm`"
    );
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn simulate_rejects_unknown_names_with_suggestions() {
    let out = temporary_dir("bad");
    let o = out.to_str().unwrap();
    let typo = lpm(&[
        "simulate",
        "specs/yaris_double_pendulum.lpm",
        "--out",
        o,
        "--set",
        "k9=1",
    ]);
    assert_eq!(typo.status.code(), Some(4), "a scenario error");
    assert!(
        stderr(&typo).contains("`k9` does not exist in the spec; did you mean `k1`?"),
        "{}",
        stderr(&typo)
    );
    let key = lpm(&[
        "simulate",
        "specs/yaris_double_pendulum.lpm",
        "--out",
        o,
        "--set",
        "components.front_end.unloding=\"elastic\"",
    ]);
    assert_eq!(key.status.code(), Some(4));
    assert!(
        stderr(&key).contains("unknown field `unloding`")
            && stderr(&key).contains("(did you mean `unloading`?)"),
        "{}",
        stderr(&key)
    );
    let method = lpm(&[
        "simulate",
        "specs/yaris_double_pendulum.lpm",
        "--out",
        o,
        "--set",
        "simulation.rtol=-1",
    ]);
    assert_eq!(method.status.code(), Some(4));
    assert!(
        !out.join("summary.json").exists(),
        "nothing written on failure"
    );
}

#[test]
fn simulate_runs_a_spec_without_a_scenario_given_constants() {
    let out = temporary_dir("plain");
    let run = lpm(&[
        "simulate",
        "specs/spring_mass_damper.lpm",
        "--out",
        out.to_str().unwrap(),
        "--set",
        "push=1",
        "--t-end",
        "0.5",
    ]);
    assert!(run.status.success(), "{}", stderr(&run));
    let csv = std::fs::read_to_string(out.join("trajectory.csv")).unwrap();
    // m ẍ + c ẋ + k x = 1 from rest: x(0.5 s) is close to the static 1/k = 0.01 m
    // (damped oscillation, ω = 10 rad/s, ζ = 0.025: still ringing, within ±1e-2).
    let last: Vec<f64> = csv
        .lines()
        .last()
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    let x = last[1];
    let (zeta, omega) = (0.025f64, 10.0f64);
    let wd = omega * (1.0 - zeta * zeta).sqrt();
    let t = 0.5;
    let exact = 0.01
        * (1.0 - (-zeta * omega * t).exp() * ((wd * t).cos() + zeta * omega / wd * (wd * t).sin()));
    assert!((x - exact).abs() < 1e-8, "x(0.5) = {x}, exact {exact}");
    let missing = lpm(&[
        "simulate",
        "specs/spring_mass_damper.lpm",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(
        missing.status.code(),
        Some(17),
        "a component without a value"
    );
    assert!(
        stderr(&missing).contains("input function `push` has no value"),
        "{}",
        stderr(&missing)
    );
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn audit_reports_the_paper_and_exits_with_status_5() {
    let markdown = lpm(&["audit", "specs/yaris_double_pendulum.lpm"]);
    assert_eq!(markdown.status.code(), Some(5), "{}", stderr(&markdown));
    let text = stdout(&markdown);
    assert!(
        text.starts_with("# Audit of the hand-derived equations of `YarisDoublePendulum`"),
        "{text}"
    );
    assert!(
        text.contains("Terms written with the wrong dimension"),
        "{text}"
    );
    let json = lpm(&[
        "audit",
        "specs/yaris_double_pendulum.lpm",
        "--format",
        "json",
    ]);
    assert_eq!(json.status.code(), Some(5));
    let report: serde_json::Value = serde_json::from_str(&stdout(&json)).unwrap();
    assert_eq!(report["disagrees"], true);
    assert_eq!(report["audits"].as_array().unwrap().len(), 6);
    let r = &report["audits"][0];
    assert_eq!(
        (r["part"].as_str(), r["coordinate"].as_str()),
        (Some("equation"), Some("r"))
    );
    assert!(
        r["groups"]
            .as_array()
            .unwrap()
            .iter()
            .any(|g| g["multiplies"] == "ddot(r)" && g["comparison"] == "match")
    );
    let none = lpm(&["audit", "specs/double_pendulum.lpm"]);
    assert_eq!(none.status.code(), Some(2));
    assert!(stderr(&none).contains("no `hand_derived` section"));
}

#[test]
fn generate_check_finds_the_committed_files_up_to_date() {
    let check = lpm(&["generate", "--check"]);
    assert_eq!(
        check.status.code(),
        Some(0),
        "{}{}",
        stdout(&check),
        stderr(&check)
    );
    assert!(stdout(&check).contains("up to date"));
}

#[test]
fn derive_markdown_renders_github_math() {
    let out = stdout(&lpm(&[
        "derive",
        "specs/yaris_double_pendulum.lpm",
        "--format",
        "markdown",
    ]));
    assert!(
        out.starts_with("# Equations of motion of `YarisDoublePendulum`"),
        "{out}"
    );
    assert!(out.contains("| $\\theta_{1}$ | `rad` |"), "{out}");
    assert!(out.contains("$$\nM_{r r} = m_{1} + m_{2}\n$$"), "{out}");
    assert!(
        out.contains("\\begin{aligned}"),
        "long equations are broken over lines"
    );
}
