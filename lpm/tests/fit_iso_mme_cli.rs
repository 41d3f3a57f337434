//! `lpm fit --target TEST --channel CODE[=QUANTITY]`: fitting to the
//! vehicle channels of an ISO-MME test gives the fit of the same pulse as
//! a CSV; channels of several samplings, units and signs; the errors.
//!
//! The tests are written here with `lagrangian-crashdata`'s writer from
//! the shipped CSV target and from a run's trajectory.csv; REF001 is the
//! test pyisomme wrote (crashdata/tests/data/pyisomme).

mod common;

use common::{lpm, stderr, stdout, temporary};
use lagrangian_crashdata::ChannelCode;
use lagrangian_crashdata::isomme::{Channel, Test, write};
use lagrangian_crashdata::text::Header;
use std::path::{Path, PathBuf};

const SPEC: &str = "specs/yaris_double_pendulum.lpm";
const G: f64 = 9.80665;
/// The test pyisomme wrote.
const REF001: &str = "crashdata/tests/data/pyisomme/REF001";

/// One channel to write: code, unit, time of first sample, interval, values.
type Spec<'a> = (&'a str, &'a str, f64, f64, Vec<f64>);

/// Writes the ISO-MME test `T1` of `channels` as folder `dir`.
fn write_test(dir: &Path, channels: Vec<Spec>) -> PathBuf {
    let channels = channels
        .into_iter()
        .map(|(code, unit, t0, dt, values)| Channel {
            code: ChannelCode::parse(code).unwrap(),
            header: Header::new(),
            unit: unit.to_string(),
            t0,
            dt,
            values,
        })
        .collect();
    let test = Test {
        name: "T1".into(),
        info: Header::new(),
        channel_info: Header::new(),
        channels,
    };
    write(&test, dir).unwrap();
    dir.to_path_buf()
}

/// The columns of a CSV file with a header line.
fn columns(file: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(file).unwrap();
    let mut lines = text.lines();
    let header: Vec<String> = lines.next().unwrap().split(',').map(String::from).collect();
    let mut columns = vec![Vec::new(); header.len()];
    for line in lines {
        for (column, cell) in columns.iter_mut().zip(line.split(',')) {
            column.push(cell.parse().unwrap());
        }
    }
    (header, columns)
}

/// `lpm fit` of the stiffness to `target` (with `extra` arguments) into
/// `out`: its fit.json.
fn fit(target: &Path, extra: &[&str], out: &Path) -> serde_json::Value {
    let mut args = vec![
        "fit",
        SPEC,
        "--target",
        target.to_str().unwrap(),
        "--fit",
        "stiffness",
        "--starts",
        "1",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend(extra);
    let run = lpm(&args);
    assert!(run.status.success(), "{}", stderr(&run));
    serde_json::from_str(&std::fs::read_to_string(out.join("fit.json")).unwrap()).unwrap()
}

fn fitted(report: &serde_json::Value) -> Vec<f64> {
    (report["parameters"].as_array().unwrap().iter())
        .map(|p| p["fitted"].as_f64().unwrap())
        .collect()
}

/// The shipped target (`t [ms], deceleration [g]` every 0.5 ms) as an
/// ISO-MME vehicle acceleration in g, forward positive (so the negated
/// deceleration), with 5 ms of pre-trigger zeros before first contact:
/// the fit finds the CSV fit's values, and the same rating.
#[test]
fn an_iso_mme_test_gives_the_fit_of_the_same_pulse_as_a_csv() {
    let dir = temporary("iso-same");
    let csv = Path::new(common::ROOT).join("specs/data/yaris_pulse.csv");
    let (header, data) = columns(&csv);
    assert_eq!(header, ["t [ms]", "deceleration [g]"]);
    for (i, t) in data[0].iter().enumerate() {
        assert!((t - 0.5 * i as f64).abs() < 1e-12, "every 0.5 ms");
    }
    let mut values = vec![0.0; 10];
    values.extend(data[1].iter().map(|d| -d));
    let test = write_test(
        &dir.join("T1"),
        vec![("10VEHCCG0000ACXD", "g", -0.005, 0.0005, values)],
    );
    let by_csv = fit(&csv, &[], &dir.join("csv"));
    let channel = ["--channel", "10VEHCCG0000ACXD"];
    let by_test = fit(&test, &channel, &dir.join("iso"));
    let by_mme = fit(&test.join("T1.mme"), &channel, &dir.join("mme"));
    let mut worst: f64 = 0.0;
    for (a, b) in fitted(&by_csv).iter().zip(fitted(&by_test)) {
        assert!((a / b - 1.0).abs() < 1e-9, "CSV {a}, ISO-MME {b}");
        worst = worst.max((a / b - 1.0).abs());
    }
    eprintln!("fitted values, CSV against ISO-MME: largest relative difference {worst:e}");
    assert_eq!(fitted(&by_test), fitted(&by_mme));
    let rating = |r: &serde_json::Value| r["channels"][0]["rating"]["overall"].as_f64().unwrap();
    assert!((rating(&by_csv) - rating(&by_test)).abs() < 1e-9);
    assert_eq!(by_test["channels"][0]["channel"], "10VEHCCG0000ACXD [g]");
    std::fs::remove_dir_all(&dir).ok();
}

/// A run's crush motion as a test of three channels at three samplings
/// and in other units than SI: the acceleration in g every 0.1 ms, the
/// velocity in km/h every 0.2 ms, the crush in mm every 0.5 ms (ISO's x
/// forward: each is the crush's, −r and its rates). From a start 15–25 %
/// off, the fit recovers the run's stiffness.
#[test]
fn channels_of_several_samplings_and_units_recover_the_scenario() {
    let dir = temporary("iso-samplings");
    let run = lpm(&[
        "simulate",
        SPEC,
        "--set",
        "simulation.t_end=0.1",
        "--out",
        dir.join("truth").to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", stderr(&run));
    let (header, data) = columns(&dir.join("truth/trajectory.csv"));
    let column = |name: &str| &data[header.iter().position(|h| h == name).unwrap()];
    let every = |k: usize, f: &dyn Fn(f64) -> f64, name: &str| -> Vec<f64> {
        column(name).iter().step_by(k).map(|&v| f(v)).collect()
    };
    let test = write_test(
        &dir.join("T1"),
        vec![
            (
                "10VEHCCG0000ACXD",
                "g",
                0.0,
                1e-4,
                every(1, &|a| -a / G, "r_ddot [m/s^2]"),
            ),
            (
                "10VEHCCG0000VEXD",
                "km/h",
                0.0,
                2e-4,
                every(2, &|v| -3.6 * v, "r_dot [m/s]"),
            ),
            (
                "10VEHCCG0000DSXD",
                "mm",
                0.0,
                5e-4,
                every(5, &|r| -1e3 * r, "r [m]"),
            ),
        ],
    );
    let start = "components.front_end.stiffness_values=[2.88e6, 2.04e6, 2.415e6, 0.752e6, 0.70875e6, 0.425e6, 0.675e6]";
    let channels = [
        "--channel",
        "10VEHCCG0000DSXD=crush",
        "--channel",
        "10VEHCCG0000ACXD",
        "--channel",
        "10VEHCCG0000VEXD",
        "--set",
        start,
    ];
    let report = fit(&test, &channels, &dir.join("fit"));
    let truth = [2.4e6, 2.4e6, 2.1e6, 0.94e6, 0.567e6, 0.50e6];
    for (k, (f, t)) in fitted(&report).iter().zip(truth).enumerate() {
        assert!((f / t - 1.0).abs() < 1e-4, "k{}: {f} vs {t}", k + 1);
        eprintln!(
            "k{}: fitted {f:e}, run's {t:e} ({:+.2e})",
            k + 1,
            f / t - 1.0
        );
    }
    // By quantity: acceleration, velocity, crush, each converted to SI.
    let channels: Vec<(&str, &str)> = (report["channels"].as_array().unwrap().iter())
        .map(|c| (c["channel"].as_str().unwrap(), c["unit"].as_str().unwrap()))
        .collect();
    assert_eq!(
        channels,
        [
            ("10VEHCCG0000ACXD [g]", "m/s^2"),
            ("10VEHCCG0000VEXD [km/h]", "m/s"),
            ("10VEHCCG0000DSXD [mm]", "m")
        ]
    );
    for c in report["channels"].as_array().unwrap() {
        assert!(c["relative_rms_error"].as_f64().unwrap() < 1e-3, "{c}");
        assert_eq!(c["rating"]["grade"], "excellent", "{c}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The vehicle acceleration pyisomme wrote (a 30 g half sine with ripple
/// every 0.2 ms from −10 ms, a NOVALUE sample before first contact), read
/// from the folder and the zip: the fit runs from t = 0 and rates better
/// than it started.
#[test]
fn a_test_pyisomme_wrote_is_fitted_from_first_contact() {
    let dir = temporary("iso-pyisomme");
    let folder = Path::new(common::ROOT).join(REF001);
    let zip = folder.with_extension("zip");
    let channel = ["--channel", "10VEHCCG0000ACXP"];
    let report = fit(&folder, &channel, &dir.join("folder"));
    assert_eq!(
        fitted(&report),
        fitted(&fit(&zip, &channel, &dir.join("zip")))
    );
    let c = &report["channels"][0];
    let overall = |key: &str| c[key]["overall"].as_f64().unwrap();
    assert!(overall("rating") > overall("rating_initial"), "{c}");
    // 0 to 109.8 ms: the samples from first contact on.
    assert_eq!(c["rating"]["interval_s"][0].as_f64(), Some(0.0), "{c}");
    let end = c["rating"]["interval_s"][1].as_f64().unwrap();
    assert!((end - 0.1098).abs() < 1e-9, "{c}");
    std::fs::remove_dir_all(&dir).ok();
}

/// Each bad `--channel` or test exits with its status and names the
/// problem.
#[test]
fn fit_errors_of_a_test_name_the_channel() {
    let dir = temporary("iso-errors");
    let refused = |target: &Path, channels: &[&str]| {
        let mut args = vec!["fit", SPEC, "--target", target.to_str().unwrap(), "--quiet"];
        for c in channels {
            args.extend(["--channel", c]);
        }
        args.extend(["--out", dir.to_str().unwrap()]);
        let run = lpm(&args);
        assert!(!run.status.success(), "{}", stdout(&run));
        (run.status.code().unwrap(), stderr(&run))
    };
    let reference = Path::new(common::ROOT).join(REF001);
    let cases: [(&[&str], i32, &str); 6] = [
        (&["10VEHCCG0000ACXD"], 2, "did you mean 10VEHCCG0000ACXP?"),
        (&["11HEAD0000H3ACXA"], 2, "is on a dummy (HEAD, Head)"),
        (&["B0FBAR000000FOXP"], 2, "is on a fixed barrier (B)"),
        (
            &["10VEHCCG0000ACXP=crush"],
            2,
            "the crush needs a displacement channel",
        ),
        (&["10VEHCCG0000ACX"], 2, "has 15 characters"),
        (&[], 2, "its vehicle x channels: 10VEHCCG0000ACXP"),
    ];
    for (channels, status, message) in cases {
        let (code, text) = refused(&reference, channels);
        assert_eq!(code, status, "{channels:?}: {text}");
        assert!(text.contains(message), "{channels:?}: {text}");
    }
    let csv = Path::new(common::ROOT).join("specs/data/yaris_pulse.csv");
    let (code, text) = refused(&csv, &["10VEHCCG0000ACXP"]);
    assert_eq!(code, 2, "{text}");
    assert!(text.contains("is a CSV file"), "{text}");
    let (code, text) = refused(&dir.join("none.mme"), &["10VEHCCG0000ACXP"]);
    assert_eq!(code, 1, "{text}");
    let wrong = write_test(
        &dir.join("wrong"),
        vec![("10VEHCCG0000ACXD", "km/h", 0.0, 1e-4, vec![1.0; 100])],
    );
    let (code, text) = refused(&wrong, &["10VEHCCG0000ACXD"]);
    assert_eq!(code, 7, "{text}");
    assert!(text.contains("Unit km/h"), "{text}");
    std::fs::remove_dir_all(&dir).ok();
}
