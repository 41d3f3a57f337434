use super::*;
use crate::status::ExitStatus;
use lagrangian_correlation::Grade;
use std::collections::HashMap;
use std::sync::Arc;

/// Files held in memory, by path.
#[derive(Debug, Default)]
struct Memory(HashMap<PathBuf, String>);

impl Files for Memory {
    fn text(&self, path: &Path) -> std::io::Result<Arc<str>> {
        (self.0.get(path).map(|t| Arc::from(t.as_str())))
            .ok_or_else(|| std::io::Error::new(std::io::ErrorKind::NotFound, "not found"))
    }
}

/// A CSV of `t [ms]` and columns `(header, f(t in s))`, 0 to 60 ms every
/// 0.5 ms.
fn csv(columns: &[(&str, &dyn Fn(f64) -> f64)]) -> String {
    let mut text = String::from("t [ms]");
    for (header, _) in columns {
        text.push_str(&format!(",{header}"));
    }
    text.push('\n');
    for k in 0..=120 {
        let t = k as f64 * 0.5e-3;
        text.push_str(&format!("{}", t * 1e3));
        for (_, f) in columns {
            text.push_str(&format!(",{}", f(t)));
        }
        text.push('\n');
    }
    text
}

fn pulse(t: f64) -> f64 {
    -(std::f64::consts::PI * t / 0.06).sin().powi(2) * 30.0
}

fn files(reference: String, comparison: String) -> Memory {
    Memory(HashMap::from([
        (PathBuf::from("test.csv"), reference),
        (PathBuf::from("model.csv"), comparison),
    ]))
}

fn request(channels: &[&str]) -> CompareRequest {
    CompareRequest {
        reference: "test.csv".into(),
        comparison: "model.csv".into(),
        channels: (channels.iter().map(|c| ChannelPair::parse(c).unwrap())).collect(),
        interval: None,
    }
}

#[test]
fn pairs_are_read_as_ref_equals_comp_or_one_name() {
    let pair = ChannelPair::parse(" a [g] = a_model ").unwrap();
    assert_eq!(
        (pair.reference.as_str(), pair.comparison.as_str()),
        ("a [g]", "a_model")
    );
    let same = ChannelPair::parse("x").unwrap();
    assert_eq!(
        (same.reference.as_str(), same.comparison.as_str()),
        ("x", "x")
    );
    for bad in ["=x", "x=", "a=b=c", ""] {
        let e = ChannelPair::parse(bad).unwrap_err();
        assert_eq!(e, CompareError::BadPair { text: bad.into() });
    }
}

#[test]
fn units_of_one_dimension_convert() {
    assert_eq!(conversion("g", "g"), Some(1.0));
    assert_eq!(conversion("g", "m/s^2"), Some(9.80665));
    assert_eq!(conversion("m/s^2", "g"), Some(1.0 / 9.80665));
    assert_eq!(conversion("kN", "N"), Some(1000.0));
    assert_eq!(conversion("mm", "m"), Some(1e-3));
    assert_eq!(conversion("N", "m"), None);
    assert_eq!(conversion("furlong", "m"), None);
}

#[test]
fn channels_of_the_same_name_are_paired_and_a_zero_one_skipped() {
    let reference = csv(&[("a [g]", &pulse), ("zero [m]", &|_| 0.0)]);
    // The model's acceleration in m/s², 0.9 times the test's.
    let comparison = csv(&[
        ("zero [m]", &|t| t),
        ("a [m/s^2]", &|t| 0.9 * 9.80665 * pulse(t)),
    ]);
    let files = files(reference, comparison);
    let comparison = compare(&request(&[]), &files).unwrap();
    assert_eq!(comparison.pairs.len(), 1);
    let pair = &comparison.pairs[0];
    assert_eq!(pair.comparison.unit.as_deref(), Some("g"));
    assert!((pair.comparison.y[20] - 0.9 * pulse(0.01)).abs() < 1e-9);
    // Scaled by 0.9, in phase: the slope error is exactly 0.1.
    assert!((pair.rating.slope - 0.95).abs() < 1e-9, "{:?}", pair.rating);
    assert_eq!(pair.rating.phase, 1.0);
    assert_eq!(comparison.skipped.len(), 1);
    assert_eq!(comparison.skipped[0].name, "zero");
    let json: serde_json::Value = serde_json::from_str(&json(&comparison)).unwrap();
    assert_eq!(json["pairs"][0]["reference"], "a");
    assert_eq!(json["pairs"][0]["grade"], pair.rating.grade.name());
    assert!(
        json["skipped"][0]["reason"]
            .as_str()
            .unwrap()
            .contains("zero everywhere")
    );
}

#[test]
fn a_channel_compared_with_itself_is_excellent() {
    let text = csv(&[("F [kN]", &|t| -pulse(t))]);
    let files = files(text.clone(), text);
    let comparison = compare(&request(&["F=F"]), &files).unwrap();
    let r = &comparison.pairs[0].rating;
    assert_eq!(
        [r.corridor, r.phase, r.magnitude, r.slope, r.overall],
        [1.0; 5]
    );
    assert_eq!(r.grade, Grade::Excellent);
    assert!(text_report(&comparison).contains("F [kN]"));
}

#[test]
fn an_unknown_channel_is_a_bad_request_with_a_suggestion() {
    let text = csv(&[("accel [g]", &pulse)]);
    let files = files(text.clone(), text);
    let e = compare(&request(&["accle=accel"]), &files).unwrap_err();
    assert_eq!(e.status(), ExitStatus::Usage);
    assert_eq!(
        e.to_string(),
        "test.csv: no channel `accle` (channels: accel); did you mean `accel`?"
    );
}

#[test]
fn units_that_do_not_convert_and_curves_that_do_not_overlap_are_data_errors() {
    let reference = csv(&[("a [g]", &pulse)]);
    let comparison = csv(&[("a [N]", &pulse)]);
    let e = compare(&request(&["a"]), &files(reference.clone(), comparison)).unwrap_err();
    assert_eq!(
        e.status(),
        ExitStatus::Failed(lagrangian_sim::simulate::FailureKind::DataFile)
    );
    assert_eq!(
        e.to_string(),
        "`a` is in g but `a` in N, which does not convert to it"
    );
    let late = "t [s],a [g]\n1,1\n2,2\n3,3\n".to_string();
    let e = compare(&request(&["a"]), &files(reference, late)).unwrap_err();
    assert_eq!(
        e.to_string(),
        "`a` against `a`: the curves share no time interval (reference 0 s to 0.06 s, comparison 1 s to 3 s)"
    );
}

#[test]
fn a_file_without_a_time_unit_is_refused_where_it_is() {
    let reference = csv(&[("a [g]", &pulse)]).replace("t [ms]", "t");
    let e = compare(&request(&[]), &files(reference, String::new())).unwrap_err();
    assert_eq!(
        e.to_string(),
        "test.csv: time column `t` needs a unit of time in brackets, e.g. `t [s]` or `t [ms]`"
    );
}

#[test]
fn plot_file_names_are_safe_and_unique() {
    let text = csv(&[("a/b [g]", &pulse), ("c [g]", &pulse)]);
    let files = files(text.clone(), text);
    let comparison = compare(&request(&["a/b", "a/b=c"]), &files).unwrap();
    let figures = plots(&comparison).unwrap();
    let names: Vec<&str> = figures.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["a_b.svg", "a_b-vs-c.svg"]);
    assert!(
        figures[0]
            .1
            .contains("a/b [g]: ISO/TS 18571 overall 1.000 (excellent)")
    );
    assert!(
        figures[0]
            .1
            .contains("corridor 1.000, phase 1.000, magnitude 1.000, slope 1.000")
    );
    assert!(figures[1].1.contains("comparison: model.csv c"));
}

#[test]
fn a_plot_shows_the_interval_rated_and_reaches_its_ends() {
    let signal = Signal {
        name: "a".into(),
        unit: None,
        t: Arc::from([0.0, 0.001, 0.002, 0.003, 0.004]),
        y: vec![0.0, 1.0, 2.0, 3.0, 4.0],
    };
    let within = points_within(&signal, (0.0015, 0.003));
    assert_eq!(within, [(1.0, 1.0), (2.0, 2.0), (3.0, 3.0)]);
    assert_eq!(points_within(&signal, (0.0, 0.004)).len(), 5);
}

#[test]
fn the_interval_asked_for_is_the_one_rated() {
    let text = csv(&[("a [g]", &pulse)]);
    let files = files(text.clone(), text);
    let request = CompareRequest {
        interval: Some((0.01, 0.03)),
        ..request(&["a"])
    };
    let comparison = compare(&request, &files).unwrap();
    let (start, end) = comparison.pairs[0].rating.interval_s;
    assert_eq!(start, 0.01);
    assert!((end - 0.03).abs() < 1e-12, "{end}");
}

#[test]
fn channels_found_by_name_none_of_which_can_be_rated_fail_with_the_first_reason() {
    let text = csv(&[("zero [m]", &|_| 0.0)]);
    let e = compare(&request(&[]), &files(text.clone(), text.clone())).unwrap_err();
    assert_eq!(
        e.status(),
        ExitStatus::Failed(lagrangian_sim::simulate::FailureKind::DataFile)
    );
    assert!(
        e.to_string()
            .starts_with("no pair of channels could be rated: `zero` against `zero`: "),
        "{e}"
    );
    let other = csv(&[("one [m]", &|t| t)]);
    let e = compare(&request(&[]), &files(text, other)).unwrap_err();
    assert_eq!(e.status(), ExitStatus::Usage);
    assert!(
        e.to_string().contains("have no channel of the same name"),
        "{e}"
    );
}
