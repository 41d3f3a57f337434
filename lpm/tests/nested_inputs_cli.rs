//! An input called inside another input's arguments: friction under a
//! contact's normal force, `rub(dot(x), press(-y, -dot(y)))`, runs, agrees
//! with the same model whose friction law is written in the spec, and
//! slides as far as the closed form says.

mod common;

use common::{lpm, stderr, temporary};
use std::path::Path;

const DIR: &str = "tests/specs/nested_inputs";
const NESTED: &str = "friction_under_contact.lpm";

/// The trajectory of `lpm simulate` of `spec` under `scenario`: its column names and
/// rows.
fn simulate(name: &str, spec: &str, scenario: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let out_dir = temporary(name);
    let (spec, scenario) = (Path::new(DIR).join(spec), Path::new(DIR).join(scenario));
    let out = lpm(&[
        "simulate".as_ref(),
        spec.as_os_str(),
        "--scenario".as_ref(),
        scenario.as_os_str(),
        "--out".as_ref(),
        out_dir.as_os_str(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = std::fs::read_to_string(out_dir.join("trajectory.csv")).unwrap();
    let mut lines = text.lines();
    let header = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    (header, rows)
}

fn column(header: &[String], rows: &[Vec<f64>], name: &str) -> Vec<f64> {
    let k = (header
        .iter()
        .position(|h| h == name || h.starts_with(&format!("{name} ["))))
    .unwrap_or_else(|| panic!("no column {name} in {header:?}"));
    rows.iter().map(|r| r[k]).collect()
}

/// The block dropped on the ground bounces on the contact and slides
/// under friction: the nested call and the law written inline give the
/// same motion (the same arithmetic in another order: agreement to the
/// integration's tolerance).
#[test]
fn friction_under_a_contact_agrees_with_the_law_written_inline() {
    let (h1, nested) = simulate("nested-dropped", NESTED, "dropped.toml");
    let (h2, inline) = simulate(
        "nested-dropped-inline",
        "friction_inline.lpm",
        "dropped_inline.toml",
    );
    assert_eq!(nested.len(), inline.len());
    for name in ["x", "y", "x_dot", "y_dot"] {
        let (a, b) = (column(&h1, &nested, name), column(&h2, &inline, name));
        let scale = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let worst = a
            .iter()
            .zip(&b)
            .fold(0.0f64, |m, (p, q)| m.max((p - q).abs()));
        assert!(worst <= 1e-8 * scale, "{name}: {worst:e} of {scale:e}");
    }
    // It bounced (left the ground after first touching it) and slid to
    // rest within the run: the friction acted under the contact's force.
    let y = column(&h1, &nested, "y");
    let touched = y.iter().position(|&v| v < 0.0).expect("never touched");
    assert!(y[touched..].iter().any(|&v| v > 1e-4), "no bounce");
    let v = column(&h1, &nested, "x_dot");
    assert!(
        v[0] == 2.0 && v.last().unwrap().abs() < 1e-3,
        "{:?}",
        v.last()
    );
}

/// Under a constant normal force `N = m·g` the block decelerates by
/// `μ·g·tanh(v/v_ε)`, and slides `∫ v dv / (μ g tanh(v/v_ε))` =
/// `v₀²/(2μg) + v_ε²·π²/(12μg)` to rest (for `v₀ ≫ v_ε`, since
/// `∫₀^∞ u (coth u − 1) du = π²/12`).
#[test]
fn a_constant_normal_force_slides_the_block_as_far_as_the_closed_form() {
    let (header, rows) = simulate("nested-constant", NESTED, "constant_push.toml");
    let (v0, mu, g, ve) = (10.0, 0.5, 9.80665, 0.001);
    let expected =
        v0 * v0 / (2.0 * mu * g) + ve * ve * std::f64::consts::PI.powi(2) / (12.0 * mu * g);
    let x = column(&header, &rows, "x");
    let slid = *x.last().unwrap();
    assert!(
        (slid - expected).abs() <= 1e-7 * expected,
        "{slid} vs {expected}"
    );
    // The push balances the weight: the block stays on the ground.
    let y = column(&header, &rows, "y");
    assert!(
        y.iter().all(|v| v.abs() < 1e-12),
        "the block left the ground"
    );
}
