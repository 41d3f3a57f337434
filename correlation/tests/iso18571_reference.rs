//! The ratings of `iso18571` against objective_rating_metrics 1.3 on the
//! curve pairs of `reference/iso18571.json` (made by
//! `reference/make_reference.py`, which says how), and closed forms.

use lagrangian_correlation::{Curve, Grade, Options, Rating, RatingError, iso18571};
use serde_json::Value;

/// The reference file, parsed.
fn reference() -> Value {
    let text = include_str!("reference/iso18571.json");
    serde_json::from_str(text).expect("the reference file is JSON")
}

fn numbers(value: &Value) -> Vec<f64> {
    let array = value.as_array().expect("an array of numbers");
    array
        .iter()
        .map(|v| v.as_f64().expect("a number"))
        .collect()
}

/// A curve's times and values: its `t`, or `start + step·k` for k < `n`
/// (the product, then the sum, as the script computes them).
fn curve_of(value: &Value) -> (Vec<f64>, Vec<f64>) {
    let y = numbers(&value["y"]);
    let t = match value.get("t") {
        Some(t) => numbers(t),
        None => {
            let (start, step) = (
                value["start"].as_f64().unwrap(),
                value["step"].as_f64().unwrap(),
            );
            let n = value["n"].as_u64().unwrap() as usize;
            (0..n).map(|k| start + step * k as f64).collect()
        }
    };
    (t, y)
}

const SCORES: [&str; 5] = ["corridor", "phase", "magnitude", "slope", "overall"];

fn scores(rating: &Rating) -> [f64; 5] {
    [
        rating.corridor,
        rating.phase,
        rating.magnitude,
        rating.slope,
        rating.overall,
    ]
}

fn rate(case: &Value) -> Rating {
    let (rt, ry) = curve_of(&case["reference"]);
    let (ct, cy) = curve_of(&case["comparison"]);
    let (reference, comparison) = (Curve { t: &rt, y: &ry }, Curve { t: &ct, y: &cy });
    iso18571(&reference, &comparison, &Options::default())
        .unwrap_or_else(|e| panic!("{}: {e}", case["name"]))
}

/// The largest difference of each score from `source`'s over the cases
/// it rated, printed as a table (`cargo test -- --nocapture`).
fn largest_differences(source: &str) -> [f64; 5] {
    let document = reference();
    let mut largest = [0.0_f64; 5];
    for case in document["cases"].as_array().unwrap() {
        let expected = &case[source];
        if expected.get("error").is_some() {
            continue;
        }
        let ours = scores(&rate(case));
        let line: Vec<String> = (SCORES.iter().zip(ours))
            .enumerate()
            .map(|(k, (name, value))| {
                let theirs = expected[name].as_f64().unwrap();
                largest[k] = largest[k].max((value - theirs).abs());
                format!("{name} {value:.6} ({:+.1e})", value - theirs)
            })
            .collect();
        println!("{:28} {}", case["name"].as_str().unwrap(), line.join("  "));
    }
    let table: Vec<String> = (SCORES.iter().zip(largest))
        .map(|(name, d)| format!("{name} {d:.1e}"))
        .collect();
    println!("largest differences from {source}: {}", table.join(", "));
    largest
}

#[test]
fn every_score_agrees_with_objective_rating_metrics() {
    let largest = largest_differences("objective_rating_metrics");
    for (name, difference) in SCORES.iter().zip(largest) {
        assert!(difference <= 1e-9, "{name}: differs by {difference:e}");
    }
}

/// pyisomme's wrapper resamples the curves itself: on the same 10 kHz
/// grid it rates the same samples, elsewhere its grid leaves out the
/// common interval's last sample (`numpy.arange`), one sample in 1100 of
/// `different_rates_and_starts`, which moves its corridor score by 6e-5
/// and its phase score by 9e-5. On two different uneven grids it fails
/// (`uneven_times`, skipped).
#[test]
fn every_score_agrees_with_pyisomme_within_its_grid() {
    let largest = largest_differences("pyisomme");
    for (name, difference) in SCORES.iter().zip(largest) {
        assert!(difference <= 2e-4, "{name}: differs by {difference:e}");
    }
}

#[test]
fn the_grade_follows_the_reference_overall_rating() {
    let document = reference();
    for case in document["cases"].as_array().unwrap() {
        let overall = case["objective_rating_metrics"]["overall"]
            .as_f64()
            .unwrap();
        assert_eq!(rate(case).grade, Grade::of(overall), "{}", case["name"]);
    }
}

/// A curve of `n` samples every 0.1 ms from 0.
fn sampled(n: usize, f: impl Fn(f64) -> f64) -> (Vec<f64>, Vec<f64>) {
    let t: Vec<f64> = (0..n).map(|k| k as f64 * 1e-4).collect();
    let y = t.iter().map(|&t| f(t)).collect();
    (t, y)
}

#[test]
fn identical_curves_score_1_everywhere() {
    let (t, y) = sampled(500, |t| (t * 60.0).sin() * (-t * 20.0).exp() + 0.2);
    let curve = Curve { t: &t, y: &y };
    let rating = iso18571(&curve, &curve, &Options::default()).unwrap();
    assert_eq!(scores(&rating), [1.0; 5]);
    assert_eq!(rating.grade, Grade::Excellent);
    assert_eq!(rating.time_shift_s, 0.0);
    assert_eq!(rating.interval_s, (0.0, t[499]));
}

#[test]
fn a_delayed_copy_scores_its_closed_forms() {
    // A bump delayed by 30 samples of 1001: the phase score is
    // (200.2 − 30) / 200.2; shifted back, the curves are the same, so
    // magnitude and slope are 1.
    let bump = |t: f64, at: f64| (-((t - at) / 0.004).powi(2)).exp();
    let (t, reference) = sampled(1001, |t| bump(t, 0.04));
    let (_, late) = sampled(1001, |t| bump(t, 0.043));
    let rating = iso18571(
        &Curve {
            t: &t,
            y: &reference,
        },
        &Curve { t: &t, y: &late },
        &Options::default(),
    )
    .unwrap();
    assert!((rating.phase - 170.2 / 200.2).abs() < 1e-12, "{rating:?}");
    assert!((rating.time_shift_s - 3e-3).abs() < 1e-15);
    assert!((rating.magnitude - 1.0).abs() < 1e-12);
    assert!((rating.slope - 1.0).abs() < 1e-9, "{rating:?}");
}

#[test]
fn the_rated_interval_can_be_narrowed() {
    let (t, y) = sampled(1001, |t| (t * 80.0).sin() + 0.3);
    let curve = Curve { t: &t, y: &y };
    let options = Options {
        interval: Some((0.02, 0.05)),
        ..Options::default()
    };
    let rating = iso18571(&curve, &curve, &options).unwrap();
    assert_eq!(rating.interval_s.0, 0.02);
    assert!((rating.interval_s.1 - 0.05).abs() < 1e-15);
    let options = Options {
        interval: Some((0.2, 0.3)),
        ..Options::default()
    };
    let e = iso18571(&curve, &curve, &options).unwrap_err();
    assert!(matches!(e, RatingError::NoCommonInterval { .. }), "{e}");
}

#[test]
fn a_zero_reference_is_refused_not_rated_nan() {
    let (t, zero) = sampled(100, |_| 0.0);
    let (_, y) = sampled(100, |t| t);
    let e = iso18571(
        &Curve { t: &t, y: &zero },
        &Curve { t: &t, y: &y },
        &Options::default(),
    )
    .unwrap_err();
    assert!(matches!(e, RatingError::Undefined { .. }), "{e}");
}
