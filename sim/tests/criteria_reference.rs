//! The injury criteria against pyisomme's on the same channels: the samples
//! and pyisomme's values are in `reference/criteria_pyisomme.json`, written
//! by `reference/criteria_pyisomme.py`.

use lagrangian_sim::criteria::occupant::Axis;
use lagrangian_sim::criteria::{Body, Criterion, Dummy, Measure, Measured, hic, rate};
use lagrangian_sim::pulse::STANDARD_GRAVITY;
use serde_json::Value;

fn reference() -> Value {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/reference/criteria_pyisomme.json"
    );
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The channel `code` of the reference in SI units (accelerations in g
/// there).
fn samples(reference: &Value, code: &str) -> Vec<f64> {
    let scale = if &code[12..14] == "AC" {
        STANDARD_GRAVITY
    } else {
        1.0
    };
    let values = reference["channels"][code].as_array().unwrap();
    values.iter().map(|x| x.as_f64().unwrap() * scale).collect()
}

#[test]
fn criteria_agree_with_pyisomme_on_the_same_channels() {
    let reference = reference();
    let (t0, dt) = (
        reference["t0"].as_f64().unwrap(),
        reference["dt"].as_f64().unwrap(),
    );
    let layout = [
        (
            "11HEAD0000H3ACRA",
            Body::Head,
            Measure::Acceleration(Axis::Resultant),
            1000.0,
        ),
        (
            "11CHST0000H3ACRC",
            Body::Chest,
            Measure::Acceleration(Axis::Resultant),
            180.0,
        ),
        ("11CHST0000H3DSXC", Body::Chest, Measure::Deflection, 180.0),
        (
            "11NECKUP00H3FOZB",
            Body::UpperNeck,
            Measure::Force(Axis::Z),
            600.0,
        ),
        (
            "11NECKUP00H3FOXB",
            Body::UpperNeck,
            Measure::Force(Axis::X),
            600.0,
        ),
        (
            "11NECKUP00H3MOYB",
            Body::UpperNeck,
            Measure::Moment(Axis::Y),
            600.0,
        ),
    ];
    let data: Vec<Vec<f64>> = layout
        .iter()
        .map(|(code, ..)| samples(&reference, code))
        .collect();
    let channels: Vec<Measured> = (layout.iter().zip(&data))
        .map(|(&(name, body, measure, cfc), values)| Measured {
            name,
            body,
            measure,
            t0,
            dt,
            values,
            filtered: Some(cfc),
        })
        .collect();
    let criteria = rate(&channels, Some(Dummy::Hybrid3Male50));
    let theirs = &reference["pyisomme"];
    let mut report = Vec::new();
    assert!(criteria.warnings.is_empty(), "{:?}", criteria.warnings);
    // pyisomme rates HIC of a resultant over the widest windows only, and
    // those one sample shorter than the standard's (t2 < t1 + 15 ms where
    // FMVSS 208 allows t2 − t1 ≤ 15 ms). Over those windows the same
    // integrals give its values; over every window no wider than the
    // standard's, ours is at least as high (HIC36 of this head: its best
    // interval is narrower than 36 ms, as a half-sine's is, 0.67 of its
    // duration, so the widest windows miss it).
    let head = &channels[0];
    let head_g: Vec<f64> = head.values.iter().map(|a| a / STANDARD_GRAVITY).collect();
    for (key, window) in [("hic15", 0.015), ("hic36", 0.036)] {
        let criterion = Criterion::of_key(key).unwrap();
        let widest = widest_windows(&head_g, dt, window);
        let pyisomme = theirs[key].as_f64().unwrap();
        let ours = criteria.get(criterion).unwrap();
        let (t1, t2) = criteria
            .rated
            .iter()
            .find(|r| r.criterion == criterion)
            .unwrap()
            .when
            .unwrap();
        report.push(format!(
            "{key}: {ours} over [{t1:.4}, {t2:.4}] s; over pyisomme's windows {widest}, pyisomme {pyisomme}"
        ));
        assert!(
            (widest - pyisomme).abs() <= 1e-9 * pyisomme,
            "{}",
            report.join("\n")
        );
        assert!(
            ours >= widest && t2 - t1 <= window + 1e-12,
            "{}",
            report.join("\n")
        );
        let best_alone = hic(&head_g[((t1 - t0) / dt).round() as usize..], t1, dt, window).unwrap();
        assert!((best_alone.value - ours).abs() <= 1e-12 * ours);
    }
    for (key, tolerance) in [
        // The same definitions: differences are rounding.
        ("head_3ms_g", 1e-9),
        ("chest_3ms_g", 1e-9),
        ("chest_deflection_mm", 1e-12),
        ("vc_mps", 1e-9),
        ("nij", 1e-9),
        ("neck_flexion_nm", 1e-12),
        ("neck_extension_nm", 1e-12),
    ] {
        let ours = criteria.get(Criterion::of_key(key).unwrap()).unwrap();
        let pyisomme = theirs[key].as_f64().unwrap();
        let relative = (ours - pyisomme).abs() / pyisomme.abs();
        report.push(format!(
            "{key}: {ours} against pyisomme {pyisomme} ({relative:.1e})"
        ));
        assert!(relative <= tolerance, "{}", report.join("\n"));
    }
    println!("{}", report.join("\n"));
}

/// HIC over the windows `[t1, t1 + window − dt]` of every sample `t1`, the
/// windows pyisomme searches for a resultant, by the trapezoidal rule.
fn widest_windows(a: &[f64], dt: f64, window: f64) -> f64 {
    let width = (window / dt).round() as usize - 1;
    let mut best = 0.0f64;
    for i in 0..a.len() {
        let j = (i + width).min(a.len() - 1);
        if j == i {
            continue;
        }
        let integral: f64 = (i..j).map(|k| 0.5 * (a[k] + a[k + 1]) * dt).sum();
        let duration = (j - i) as f64 * dt;
        best = best.max(duration * (integral / duration).max(0.0).powf(2.5));
    }
    best
}
