//! A spec's outputs in `lpm simulate`'s trajectory.csv and `lpm derive`.

mod common;

use common::{lpm, stderr, stdout, temporary};

/// The double pendulum's outputs, named with their units after the other
/// columns, equal the lower bob's position and acceleration worked out by
/// hand from the angle columns of the same rows.
#[test]
fn trajectory_csv_has_the_output_columns_after_the_others() {
    let out = temporary("outputs-simulate");
    let run = lpm(&[
        "simulate",
        "specs/double_pendulum.lpm",
        "--out",
        out.to_str().unwrap(),
        "--t-end",
        "0.3",
        "--set",
        "initial.coordinates.theta1=0.5",
        "--set",
        "initial.velocities.theta2=-1.2",
    ]);
    assert!(run.status.success(), "{}", stderr(&run));
    let csv = std::fs::read_to_string(out.join("trajectory.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(
        header[11..],
        ["x2_position [m]", "y2_position [m]", "a2_magnitude [m/s^2]"]
    );
    assert_eq!(header[10], "external_work [J]");
    let (l1, l2) = (1.0, 1.0);
    let mut rows = 0;
    for line in lines {
        let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        let [t1, t2, w1, w2, a1, a2] = [v[1], v[2], v[3], v[4], v[5], v[6]];
        let x2 = l1 * t1.sin() + l2 * t2.sin();
        let y2 = -l1 * t1.cos() - l2 * t2.cos();
        // Differentiating x2 and y2 twice by hand.
        let ax =
            l1 * (a1 * t1.cos() - w1 * w1 * t1.sin()) + l2 * (a2 * t2.cos() - w2 * w2 * t2.sin());
        let ay =
            l1 * (a1 * t1.sin() + w1 * w1 * t1.cos()) + l2 * (a2 * t2.sin() + w2 * w2 * t2.cos());
        let expected = [x2, y2, ax.hypot(ay)];
        for (k, e) in expected.iter().enumerate() {
            // The columns carry 11 significant digits.
            assert!(
                (v[11 + k] - e).abs() < 1e-8 * e.abs().max(1.0),
                "t = {}: {} is {}, by hand {e}",
                v[0],
                header[11 + k],
                v[11 + k]
            );
        }
        rows += 1;
    }
    assert!(rows > 10, "{rows} rows");
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn derive_lists_the_outputs_with_units_and_expressions() {
    let text = stdout(&lpm(&["derive", "specs/double_pendulum.lpm"]));
    assert!(
        text.contains("\nOutputs (evaluated after the solve"),
        "{text}"
    );
    assert!(
        text.contains("  x2_position [m] = l1*sin(theta1) + l2*sin(theta2)\n"),
        "{text}"
    );
    assert!(text.contains("  a2_magnitude [m/s^2] = sqrt("), "{text}");
    assert!(text.contains("ddot(theta1)"), "{text}");
    let c = stdout(&lpm(&[
        "derive",
        "specs/double_pendulum.lpm",
        "--format",
        "c",
    ]));
    assert!(c.contains("#define DOUBLE_PENDULUM_OUTPUTS 3\n"), "{c}");
    assert!(c.contains("void double_pendulum_outputs("), "{c}");
    // A spec without outputs has no such section or function.
    let plain = stdout(&lpm(&["derive", "specs/simple_pendulum.lpm"]));
    assert!(!plain.contains("Outputs"), "{plain}");
    let c = stdout(&lpm(&[
        "derive",
        "specs/simple_pendulum.lpm",
        "--format",
        "c",
    ]));
    assert!(!c.contains("_outputs"), "{c}");
}

#[test]
fn a_bad_output_is_reported_at_its_place() {
    let dir = temporary("outputs-bad");
    let spec = dir.join("bad.lpm");
    let source = "model P;\ncoordinates { q [m] }\nparameters { m [kg] = 1.0 }\n\
                  kinetic = 0.5 * m * pow(dot(q), 2);\npotential = 0.5 * m * ddot(q);\n\
                  output speed [m/s] = dot(qq);\n";
    std::fs::write(&spec, source).unwrap();
    let run = lpm(&["derive", spec.to_str().unwrap()]);
    assert!(!run.status.success());
    let err = stderr(&run);
    assert!(
        err.contains("`ddot` is only available in `hand_derived` equations and in outputs"),
        "{err}"
    );
    assert!(err.contains("bad.lpm:5:23"), "{err}");
    assert!(err.contains("unknown name `qq`"), "{err}");
    assert!(err.contains("did you mean `q`?"), "{err}");
    assert!(err.contains("bad.lpm:6:26"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}
