//! `lpm metrics`: a half-sine pulse written with units other than SI, against
//! the closed-form OLC and ASI of the same pulse.

mod common;

use common::lpm;

const G: f64 = 9.80665;

/// Bisection on a closed-form function.
fn bisect(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if (f(a) < 0.0) == (f(m) < 0.0) {
            a = m;
        } else {
            b = m;
        }
    }
    0.5 * (a + b)
}

#[test]
fn a_half_sine_pulse_has_its_closed_form_olc_asi_and_stopping_time() {
    // Deceleration A sin(πt/T) for 0 ≤ t ≤ T from v0 = 56 km/h; A is chosen so
    // that Δv = 2AT/π exceeds v0: the car stops at cos(πt/T) = 1 − v0 π/(A T).
    let (v0, a, tp) = (56.0 / 3.6, 35.0 * G, 0.080);
    let w = std::f64::consts::PI / tp;
    let vel = |t: f64| v0 - a / w * (1.0 - (w * t.min(tp)).cos());
    let pos = |t: f64| {
        let tt = t.min(tp);
        v0 * tt - a / w * (tt - (w * tt).sin() / w) + vel(tp) * (t - tt)
    };
    let stop = (1.0 - v0 * w / a).acos() / w;
    let t1 = bisect(|t| v0 * t - pos(t) - 0.065, 0.0, 0.2);
    let t2 = bisect(
        |t2| 0.5 * (v0 + vel(t2)) * (t2 - t1) - (pos(t2) - pos(t1)) - 0.235,
        t1 + 1e-9,
        0.3,
    );
    let olc = (v0 - vel(t2)) / (t2 - t1) / G;
    let asi = a
        * (2.0 * tp / (std::f64::consts::PI * 0.05))
        * (std::f64::consts::PI * 0.05 / (2.0 * tp)).sin()
        / (12.0 * G);

    let dir = common::temporary("metrics");
    let file = dir.join("half_sine.csv");
    let mut text = String::from("t [ms], deceleration [g], velocity [km/h]\n");
    for k in 0..=2500 {
        let t = k as f64 * 1e-4;
        let d = if t <= tp { a * (w * t).sin() } else { 0.0 };
        text.push_str(&format!(
            "{:.4},{:.12},{:.12}\n",
            t * 1e3,
            d / G,
            vel(t) * 3.6
        ));
    }
    std::fs::write(&file, text).unwrap();
    let run = lpm(&["metrics", file.to_str().unwrap(), "--format", "json"]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let m: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    let number = |k: &str| m[k].as_f64().unwrap_or_else(|| panic!("{k}: {m}"));
    assert!((number("impact_velocity_mps") - v0).abs() < 1e-9);
    // The metrics run on the CFC 180 signal, which rounds the pulse's
    // corners: allow 0.2 %.
    assert!(
        (number("olc_g") / olc - 1.0).abs() < 2e-3,
        "{} vs {olc}",
        number("olc_g")
    );
    assert!(
        (number("asi") / asi - 1.0).abs() < 2e-3,
        "{} vs {asi}",
        number("asi")
    );
    assert!((number("time_to_zero_velocity_s") - stop).abs() < 2e-4);
    assert!((number("max_dynamic_crush_m") / pos(stop) - 1.0).abs() < 2e-3);
    assert!((number("peak_deceleration_g") - 35.0).abs() < 1e-6);

    // Without a velocity column the impact velocity must be given.
    let bare = dir.join("bare.csv");
    std::fs::write(&bare, "t [s],a [g]\n0,0\n0.001,-1\n0.002,-2\n").unwrap();
    let run = lpm(&["metrics", bare.to_str().unwrap()]);
    assert_eq!(run.status.code(), Some(2));
    assert!(
        String::from_utf8_lossy(&run.stderr).contains("give it with --v0"),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    std::fs::remove_dir_all(&dir).ok();
}
