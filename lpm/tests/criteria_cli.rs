//! Injury criteria on every surface that gives them: a simulated
//! occupant's in `summary.json`, and `lpm metrics` of the same run written
//! as an ISO-MME test, agree; `lpm metrics` of a CSV pulse gives the
//! vehicle's criteria beside its pulse metrics, with the same values.
//! pyisomme's criteria on the same channels: python/tests/reference/test_criteria.py.

mod common;

use common::{lpm, temporary};
use serde_json::Value;

fn json(text: &str) -> Value {
    serde_json::from_str(text).unwrap_or_else(|e| panic!("{e}: {text}"))
}

#[test]
fn a_simulated_occupants_criteria_are_those_of_its_iso_mme_test() {
    let dir = temporary("criteria-occupant");
    let (out, test) = (dir.join("out"), dir.join("test"));
    let run = lpm(&[
        "simulate",
        "specs/yaris_occupant.lpm",
        "--out",
        out.to_str().unwrap(),
        "--iso-mme",
        test.to_str().unwrap(),
    ]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let summary = json(&std::fs::read_to_string(out.join("summary.json")).unwrap());
    let simulated = &summary["criteria"];
    // The occupant's acceleration is coded as a Hybrid III 50th's chest:
    // its 3 ms clip, the same as the channel's own clip3ms_g (one
    // definition), near the channel's CFC 180 peak.
    let clip = simulated["chest_3ms_g"].as_f64().unwrap();
    let channel = &summary["channels"]["occupant_deceleration"];
    assert_eq!(channel["clip3ms_g"].as_f64().unwrap(), clip);
    assert!(clip > 40.0 && clip <= channel["cfc180_peak_g"].as_f64().unwrap());

    let metrics = lpm(&["metrics", test.to_str().unwrap(), "--format", "json"]);
    assert!(
        metrics.status.success(),
        "{}",
        String::from_utf8_lossy(&metrics.stderr)
    );
    let measured = json(&String::from_utf8_lossy(&metrics.stdout));
    let driver = &measured["occupants"][0];
    assert_eq!(driver["dummy"], "hybrid3_50m");
    assert_eq!(&driver["criteria"], simulated);
    // The vehicle's criteria are its pulse metrics.
    for (criterion, metric) in [
        ("olc_g", "olc_g"),
        ("asi", "asi"),
        ("esw_g", "equivalent_square_wave_g"),
    ] {
        assert_eq!(
            measured["criteria"][criterion], measured[metric],
            "{criterion}"
        );
    }
    let olc = measured["olc_g"].as_f64().unwrap();
    assert!((olc - summary["olc_g"].as_f64().unwrap()).abs() < 1e-6 * olc);
}

#[test]
fn a_csv_pulse_has_the_vehicles_criteria() {
    let metrics = lpm(&[
        "metrics",
        "specs/data/yaris_pulse.csv",
        "--v0",
        "15.5556",
        "--format",
        "json",
    ]);
    assert!(
        metrics.status.success(),
        "{}",
        String::from_utf8_lossy(&metrics.stderr)
    );
    let measured = json(&String::from_utf8_lossy(&metrics.stdout));
    let criteria = measured["criteria"].as_object().unwrap();
    let keys: Vec<&str> = criteria.keys().map(String::as_str).collect();
    assert_eq!(keys, ["asi", "esw_g", "olc_g", "phd_g", "thiv_kmh"]);
    assert_eq!(criteria["olc_g"], measured["olc_g"]);
    assert!(measured.get("occupants").is_none());
}
