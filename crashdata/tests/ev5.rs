//! The hand-written EV5 test `tests/data/ev5/v99001` (see its README): its
//! cards by field name and its channels against the closed forms written.

use lagrangian_crashdata::ev5;
use std::f64::consts::PI;
use std::path::{Path, PathBuf};

fn card_file() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/ev5/v99001.EV5")
}

#[test]
fn the_cards_read_by_field_name() {
    let test = ev5::read(&card_file()).unwrap();
    assert_eq!(test.name, "v99001");
    let names: Vec<&str> = test.sections.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(
        names,
        ["TEST", "VEHICLE", "BARRIER", "OCCUPANT", "INSTRUMENTATION"]
    );
    let card = test.test_card().unwrap();
    assert_eq!(card.get("CLSSPD"), Some("56.0"));
    assert_eq!(card.get("TOTCRV"), Some("4"));
    assert_eq!(card.line, 6);
    let vehicle = &test.section("VEHICLE").unwrap().cards[0];
    assert_eq!(vehicle.fields.len(), ev5::VEHICLE_FIELDS.len());
    assert_eq!(
        (vehicle.get("MAKE"), vehicle.get("CURBWT")),
        (Some("TOYOTA"), Some("1050"))
    );
    assert_eq!(vehicle.get("VEHCOM"), None);
    let occupant = &test.section("OCCUPANT").unwrap().cards[0];
    assert_eq!(
        (occupant.get("OCCTYP"), occupant.get("HIC")),
        (Some("H3"), Some("410"))
    );
    assert_eq!(
        test.section("BARRIER").unwrap().cards[0].get("BARSHP"),
        Some("LCB")
    );
}

/// A closed form of time.
type Shape = fn(f64) -> f64;

#[test]
fn the_channels_hold_their_closed_forms_on_their_time_base() {
    let test = ev5::read(&card_file()).unwrap();
    assert_eq!(test.channels.len(), 4);
    let crossmember = test.channel(1).unwrap();
    assert_eq!(crossmember.description, "LEFT REAR SEAT CROSSMEMBER X");
    assert_eq!(
        (crossmember.y_units.as_str(), crossmember.unit()),
        ("G'S", Some("g"))
    );
    assert_eq!((crossmember.first_point, crossmember.last_point), (-5, 24));
    assert!((crossmember.dt - 1e-4).abs() < 1e-18);
    assert_eq!(crossmember.card.get("SENATT"), Some("FLLR"));
    let shapes: [(u32, Shape); 3] = [
        (1, |t| -20.0 * (PI * t / 0.003).sin()),
        (2, |t| -35.0 * (PI * t / 0.003).sin().powi(2)),
        (3, |t| 1.5e5 * (PI * t / 0.003).sin()),
    ];
    for (number, shape) in shapes {
        let channel = test.channel(number).unwrap();
        let data = channel.data.as_ref().unwrap();
        assert_eq!(data.times.len(), 30);
        for (i, (&t, &y)) in data.times.iter().zip(&data.values).enumerate() {
            // The time base of the card: NFP·DELT on.
            let expected_t = (channel.first_point + i as i64) as f64 * channel.dt;
            assert!((t - expected_t).abs() < 1e-9, "{number}: {t} {expected_t}");
            let expected = if t >= 0.0 { shape(t) } else { 0.0 };
            assert!(
                (y - expected).abs() <= 5e-7,
                "{number} at {t}: {y} {expected}"
            );
        }
    }
    let belt = test.channel(4).unwrap();
    assert_eq!(
        (belt.card.get("DASTAT"), belt.unit()),
        (Some("NO"), Some("N"))
    );
    assert_eq!(belt.data, None);
    assert_eq!(test.channel(3).unwrap().unit(), Some("N"));
}

/// A copy of the sample with `edit` applied to the card file.
fn edited(case: &str, edit: impl Fn(&str) -> String) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("crashdata-ev5-{case}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let source = card_file().parent().unwrap().to_path_buf();
    for k in 1..=3 {
        let name = format!("v99001.{k:03}");
        std::fs::copy(source.join(&name), dir.join(&name)).unwrap();
    }
    let text = std::fs::read_to_string(card_file()).unwrap();
    std::fs::write(dir.join("v99001.EV5"), edit(&text)).unwrap();
    dir.join("v99001.EV5")
}

#[test]
fn a_bad_card_names_the_file_its_line_and_the_field() {
    let path = edited("delt", |t| {
        t.replacen(
            "|-5|24|100|AM|P|DRIVER HEAD X",
            "|-5|24|x|AM|P|DRIVER HEAD X",
            1,
        )
    });
    let e = ev5::read(&path).unwrap_err();
    assert_eq!(
        (e.file.as_path(), e.line, e.field.as_deref()),
        (path.as_path(), Some(15), Some("DELT"))
    );
    let _ = std::fs::remove_dir_all(path.parent().unwrap());
    let path = edited("count", |t| {
        t.replacen("|-5|24|100|AM|P|BARRIER", "|-5|25|100|AM|P|BARRIER", 1)
    });
    let e = ev5::read(&path).unwrap_err();
    assert_eq!(e.file, path.with_extension("003"));
    assert_eq!(e.field.as_deref(), Some("NLP"));
    assert!(e.problem.contains("holds 30 samples"), "{e}");
    let _ = std::fs::remove_dir_all(path.parent().unwrap());
    let path = edited("end", |t| t.replace("----- END -----", ""));
    let e = ev5::read(&path).unwrap_err();
    assert!(e.problem.contains("END"), "{e}");
    let _ = std::fs::remove_dir_all(path.parent().unwrap());
}
