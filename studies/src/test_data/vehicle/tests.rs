use super::*;
use lagrangian_crashdata::text::Header;

const G: f64 = 9.80665;

fn code(text: &str) -> ChannelCode {
    ChannelCode::parse(text).unwrap()
}

/// A channel `code` of `f(t)` at `t0 + i·dt`, `n` samples, in `unit`.
fn channel(
    text: &str,
    unit: &str,
    (t0, dt, n): (f64, f64, usize),
    f: impl Fn(f64) -> f64,
) -> TestChannel {
    TestChannel {
        code: code(text),
        header: Header::new(),
        unit: unit.to_string(),
        t0,
        dt,
        values: (0..n).map(|i| f(t0 + i as f64 * dt)).collect(),
    }
}

fn test_of(channels: Vec<TestChannel>) -> Test {
    Test {
        name: "T1".into(),
        info: Header::new(),
        channel_info: Header::new(),
        channels,
    }
}

fn asked(texts: &[&str]) -> Vec<ChannelRequest> {
    texts
        .iter()
        .map(|t| ChannelRequest::parse(t).unwrap())
        .collect()
}

fn histories(test: &Test, texts: &[&str]) -> Result<TimeHistories, TestDataError> {
    vehicle_histories(test, Path::new("T1"), &asked(texts))
}

/// A vehicle acceleration in g (−20 g + 100 g/s · t), a velocity in km/h
/// and a crush in mm, sampled from 10 ms before first contact.
fn three_channels(velocity_dt: f64) -> Test {
    test_of(vec![
        channel("10VEHCCG0000DSXD", "mm", (-0.01, 1e-4, 401), |t| {
            1e3 * 2.0 * t
        }),
        channel("10VEHCCG0000ACXD", "g", (-0.01, 1e-4, 401), |t| {
            -20.0 + 100.0 * t
        }),
        channel("10VEHCCG0000VEXD", "km/h", (-0.01, velocity_dt, 201), |t| {
            3.6 * (15.0 - 5.0 * t)
        }),
    ])
}

#[test]
fn a_request_is_a_code_and_perhaps_a_quantity() {
    let r = ChannelRequest::parse("10VEHCCG0000ACXP").unwrap();
    assert_eq!((r.code, r.quantity), (code("10VEHCCG0000ACXP"), None));
    let r = ChannelRequest::parse("10VEHCCG0000DSXP=crush").unwrap();
    assert_eq!(r.quantity, Some(Quantity::Crush));
    assert_eq!(r.to_string(), "10VEHCCG0000DSXP=crush");
    let e = ChannelRequest::parse("10VEHCCG0000ACX").unwrap_err();
    assert!(
        matches!(
            &e,
            TestDataError::BadCode {
                error: CodeError::Length { length: 15, .. },
                ..
            }
        ),
        "{e}"
    );
    let e = ChannelRequest::parse("10VEHCCG0000ACXP=jerk").unwrap_err();
    assert!(
        matches!(&e, TestDataError::UnknownQuantity { name, .. } if name == "jerk"),
        "{e}"
    );
    assert!(
        e.to_string().contains("acceleration, velocity or crush"),
        "{e}"
    );
}

#[test]
fn channels_of_one_sampling_are_taken_from_first_contact_in_si_units_sorted_by_quantity() {
    let test = three_channels(1e-4);
    let h = histories(
        &test,
        &["10VEHCCG0000DSXD", "10VEHCCG0000ACXD", "10VEHCCG0000VEXD"],
    )
    .unwrap();
    // From t = 0 (sample 100) to the velocity's last, 0.01 s.
    assert_eq!(h.t.len(), 101);
    assert_eq!(h.t[0], 0.0);
    assert!((h.t[100] - 0.01).abs() < 1e-15, "{}", h.t[100]);
    let quantities: Vec<Quantity> = h.channels.iter().map(|c| c.quantity).collect();
    assert_eq!(quantities, QUANTITIES);
    assert_eq!(h.channels[0].header, "10VEHCCG0000ACXD [g]");
    // Each value is the channel's own sample, converted to SI.
    let a = &test.channels[1];
    for (k, value) in h.channels[0].values.iter().enumerate() {
        assert_eq!(*value, a.values[100 + k] * G);
    }
    for (k, &t) in h.t.iter().enumerate() {
        let want = [(-20.0 + 100.0 * t) * G, 15.0 - 5.0 * t, 2.0 * t];
        for (c, want) in h.channels.iter().zip(want) {
            assert!(
                (c.values[k] - want).abs() < 1e-12 * want.abs().max(1.0),
                "{} at {t}",
                c.header
            );
        }
    }
}

#[test]
fn channels_of_other_samplings_are_put_on_the_coarsest_ones_times() {
    // The velocity every 0.2 ms: its times are the time base; the others
    // (every 0.1 ms) are interpolated at them, exactly, being linear.
    let test = three_channels(2e-4);
    let h = histories(
        &test,
        &["10VEHCCG0000ACXD", "10VEHCCG0000VEXD", "10VEHCCG0000DSXD"],
    )
    .unwrap();
    assert_eq!(h.t.len(), 151, "0 to 0.03 s every 0.2 ms");
    assert!(
        (h.t[1] - 2e-4).abs() < 1e-15 && (h.t[150] - 0.03).abs() < 1e-14,
        "{:?}",
        (h.t[1], h.t[150])
    );
    for (k, &t) in h.t.iter().enumerate() {
        let want = [(-20.0 + 100.0 * t) * G, 15.0 - 5.0 * t, 2.0 * t];
        for (c, want) in h.channels.iter().zip(want) {
            assert!(
                (c.values[k] - want).abs() < 1e-11 * want.abs().max(1.0),
                "{} at {t}",
                c.header
            );
        }
    }
}

#[test]
fn a_sample_without_a_value_is_an_error_only_where_the_fit_uses_it() {
    let mut test = three_channels(1e-4);
    test.channels[1].values[50] = f64::NAN; // t = −5 ms: left out
    assert!(histories(&test, &["10VEHCCG0000ACXD"]).is_ok());
    test.channels[1].values[150] = f64::NAN; // t = 5 ms
    let e = histories(&test, &["10VEHCCG0000ACXD"]).unwrap_err();
    assert!(
        matches!(&e, TestDataError::NoValue { time, .. } if (time - 0.005).abs() < 1e-12),
        "{e}"
    );
    assert_eq!(StudyError::from(e).status().code(), 7);
}

#[test]
fn an_unknown_code_names_the_closest_of_the_test() {
    let test = three_channels(1e-4);
    let e = histories(&test, &["10VEHCCG0000ACXP"]).unwrap_err();
    assert!(
        matches!(&e, TestDataError::UnknownCode { suggestion: Some(s), .. } if s == "10VEHCCG0000ACXD"),
        "{e}"
    );
    assert!(
        e.to_string().contains("did you mean 10VEHCCG0000ACXD?"),
        "{e}"
    );
    assert_eq!(StudyError::from(e).status().code(), 2);
    let e = histories(&test, &[]).unwrap_err();
    assert!(
        e.to_string()
            .contains("10VEHCCG0000DSXD, 10VEHCCG0000ACXD, 10VEHCCG0000VEXD"),
        "{e}"
    );
}

#[test]
fn a_channel_the_crush_motion_cannot_be_compared_with_is_refused() {
    let test = test_of(vec![
        channel("11HEAD0000H3ACXA", "g", (0.0, 1e-4, 100), |_| 1.0),
        channel("10VEHCCG0000ACZD", "g", (0.0, 1e-4, 100), |_| 1.0),
        channel("10VEHCCG0000AC1D", "g", (0.0, 1e-4, 100), |_| 1.0),
        channel("10VEHCCG0000FOXD", "N", (0.0, 1e-4, 100), |_| 1.0),
        channel("10VEHCCG0000ACXD", "g", (0.0, 1e-4, 100), |_| 1.0),
        channel("10SILBLE0000ACXD", "g", (0.0, 1e-4, 100), |_| 1.0),
        channel("11OCCU000000ACXP", "g", (0.0, 1e-4, 100), |_| 1.0),
        channel("B0FBAR000000FOXP", "N", (0.0, 1e-4, 100), |_| 1.0),
    ]);
    let refused = |text: &str| histories(&test, &[text]).unwrap_err();
    let e = refused("11HEAD0000H3ACXA");
    assert!(e.to_string().contains("is on a dummy (HEAD, Head)"), "{e}");
    let e = refused("11OCCU000000ACXP");
    assert!(matches!(&e, TestDataError::NotVehicle { .. }), "{e}");
    let e = refused("B0FBAR000000FOXP");
    assert!(e.to_string().contains("is on a fixed barrier (B)"), "{e}");
    assert!(
        matches!(refused("10VEHCCG0000ACZD"), TestDataError::NotLongitudinal { direction, .. } if direction.starts_with("vertical"))
    );
    assert!(matches!(
        refused("10VEHCCG0000AC1D"),
        TestDataError::NotLongitudinal { .. }
    ));
    let e = refused("10VEHCCG0000FOXD");
    assert!(
        matches!(
            &e,
            TestDataError::Dimension {
                found: "a force",
                ..
            }
        ),
        "{e}"
    );
    let e = refused("10VEHCCG0000ACXD=velocity");
    assert!(
        e.to_string()
            .contains("the velocity needs a velocity channel (VE, VA or VD)"),
        "{e}"
    );
    let e = histories(&test, &["10VEHCCG0000ACXD", "10SILBLE0000ACXD"]).unwrap_err();
    assert!(
        matches!(
            e,
            TestDataError::Duplicate {
                quantity: Quantity::Acceleration,
                ..
            }
        ),
        "{e}"
    );
    assert_eq!(StudyError::from(e).status().code(), 2);
}

#[test]
fn a_unit_of_another_dimension_or_none_is_a_data_files_error() {
    let test = test_of(vec![
        channel("10VEHCCG0000ACXD", "m/s", (0.0, 1e-4, 100), |_| 1.0),
        channel("10VEHCCG0000VEXD", "", (0.0, 1e-4, 100), |_| 1.0),
    ]);
    let e = histories(&test, &["10VEHCCG0000ACXD"]).unwrap_err();
    assert!(
        matches!(&e, TestDataError::Unit { unit, .. } if unit == "m/s"),
        "{e}"
    );
    assert!(e.to_string().contains("needs an acceleration"), "{e}");
    assert_eq!(StudyError::from(e).status().code(), 7);
    let e = histories(&test, &["10VEHCCG0000VEXD"]).unwrap_err();
    assert!(matches!(&e, TestDataError::NoUnit { .. }), "{e}");
}

#[test]
fn channels_that_end_before_first_contact_share_no_time() {
    let test = test_of(vec![channel(
        "10VEHCCG0000ACXD",
        "g",
        (-0.02, 1e-4, 100),
        |_| 1.0,
    )]);
    let e = histories(&test, &["10VEHCCG0000ACXD"]).unwrap_err();
    assert!(matches!(&e, TestDataError::NoCommonTime { .. }), "{e}");
    let test = test_of(vec![channel(
        "10VEHCCG0000ACXD",
        "g",
        (-0.01, 0.005, 4),
        |_| 1.0,
    )]);
    let e = histories(&test, &["10VEHCCG0000ACXD"]).unwrap_err();
    assert!(
        matches!(&e, TestDataError::TooFewTimes { times: 2, .. }),
        "{e}"
    );
}
