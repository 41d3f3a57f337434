//! What pyisomme writes, read here with the values pyisomme holds of it.
//!
//! `tests/reference/make_reference.py` wrote the test `REF001` with
//! pyisomme as a folder and a zip (`tests/data/pyisomme/`) and dumped what
//! pyisomme reads back of it to `reference.json`: every header line with
//! the type pyisomme parsed it to, each channel's unit, times and values.
//! Each way of giving the test (folder, `.mme`, zip) is read here and
//! compared line by line and sample by sample.

use lagrangian_crashdata::isomme::{self, Test};
use lagrangian_crashdata::text::Header;
use serde_json::Value;
use std::path::{Path, PathBuf};

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/pyisomme")
}

fn reference() -> Value {
    let text = std::fs::read_to_string(data().join("reference.json")).unwrap();
    serde_json::from_str(&text).unwrap()
}

/// Each line of `header` against pyisomme's, in order: the same name, and
/// the same value as pyisomme's parse of it gives.
fn same_lines(header: &Header, lines: &Value, what: &str) {
    let lines = lines.as_array().unwrap();
    assert_eq!(header.len(), lines.len(), "{what}: number of lines");
    for (entry, line) in header.entries().iter().zip(lines) {
        let name = line["name"].as_str().unwrap();
        assert_eq!(entry.name, name, "{what}");
        let value = entry.value.as_deref();
        let number = || value.and_then(|v| v.parse::<f64>().ok());
        let same = match line["kind"].as_str().unwrap() {
            "none" => value.is_none(),
            "str" => value == line["value"].as_str(),
            "int" | "float" => number() == line["value"].as_f64(),
            "nan" => number().is_some_and(f64::is_nan),
            "bool" => {
                value
                    == Some(if line["value"].as_bool().unwrap() {
                        "YES"
                    } else {
                        "NO"
                    })
            }
            kind => panic!("{what}: {name}: a {kind} value the test does not compare"),
        };
        assert!(
            same,
            "{what}: {name}: {value:?} against pyisomme's {}",
            line["value"]
        );
    }
}

/// The largest differences of `test`'s samples from pyisomme's, per channel:
/// `(code, values, times)`.
fn compare(test: &Test, reference: &Value) -> Vec<(String, f64, f64)> {
    assert_eq!(test.name, reference["name"].as_str().unwrap());
    same_lines(&test.info, &reference["info"], ".mme");
    same_lines(&test.channel_info, &reference["channel_info"], ".chn");
    let channels = reference["channels"].as_array().unwrap();
    assert_eq!(test.channels.len(), channels.len());
    let mut differences = Vec::new();
    for (channel, expected) in test.channels.iter().zip(channels) {
        let code = expected["code"].as_str().unwrap();
        assert_eq!(channel.code.as_str(), code);
        assert_eq!(channel.unit, expected["unit"].as_str().unwrap(), "{code}");
        same_lines(&channel.header, &expected["header"], code);
        let values = expected["values"].as_array().unwrap();
        let times = expected["times"].as_array().unwrap();
        assert_eq!(channel.values.len(), values.len(), "{code}");
        let mut largest = (0.0f64, 0.0f64);
        for (i, (&x, y)) in channel.values.iter().zip(values).enumerate() {
            match y.as_f64() {
                None => assert!(x.is_nan(), "{code} sample {i}: {x}, pyisomme has none"),
                Some(y) => largest.0 = largest.0.max((x - y).abs()),
            }
            let t = times[i].as_f64().unwrap();
            largest.1 = largest.1.max((channel.time(i) - t).abs());
        }
        differences.push((code.to_string(), largest.0, largest.1));
    }
    differences
}

#[test]
fn a_test_pyisomme_wrote_reads_with_the_values_pyisomme_holds() {
    let reference = reference();
    let folder = data().join("REF001");
    let ways = [
        ("folder", folder.clone()),
        (".mme", folder.join("REF001.mme")),
        ("zip", data().join("REF001.zip")),
    ];
    for (way, path) in ways {
        let test = isomme::read(&path).unwrap_or_else(|e| panic!("{way}: {e}"));
        for (code, values, times) in compare(&test, &reference) {
            println!(
                "{way:6} {code}: largest difference {values:.1e} in value, {times:.1e} s in time"
            );
            // Both read the same decimal text: the values are the same numbers.
            assert_eq!(values, 0.0, "{way} {code}");
            // pyisomme spaces its times by linspace, this crate by t0 + i·dt.
            assert!(times <= 1e-15, "{way} {code}: {times:e} s");
        }
    }
}

#[test]
fn the_channels_pyisomme_wrote_are_those_the_script_made() {
    // Independent of both readers: the script's own closed forms.
    let test = isomme::read(&data().join("REF001.zip")).unwrap();
    let vehicle = &test.channels[0];
    assert_eq!((vehicle.t0, vehicle.values.len()), (-0.010, 600));
    assert!((vehicle.dt - 0.0002).abs() < 1e-15);
    assert!(vehicle.values[17].is_nan());
    // At t = 0.04 s, the middle of the 80 ms half sine: −30 g and the
    // ripple 0.05·sin(2π·430·0.04).
    let i = 250;
    let t = vehicle.time(i);
    let expected = -30.0 * (std::f64::consts::PI * t / 0.08).sin()
        + 0.05 * (2.0 * std::f64::consts::PI * 430.0 * t).sin();
    // pyisomme writes seven significant digits.
    assert!(
        (vehicle.values[i] - expected).abs() < 1e-5,
        "{}",
        vehicle.values[i]
    );
    let head = &test.channels[1];
    assert_eq!(head.code.dummy().map(|d| d.code()), Some("H3"));
    assert!((head.dt - 1e-4).abs() < 1e-15 && head.t0 == -0.020);
    assert_eq!(test.info.get("Laboratory name"), Some("Prüfstand Süd"));
    let comments: Vec<_> = test.info.get_all("Comments").collect();
    assert_eq!(
        comments,
        [Some("first comment"), None, Some("third comment")]
    );
}
