//! `torque (φ) = T;` is the generalized force of a torque about the angle
//! φ(q): `Q_i = T ∂φ/∂q_i`, by virtual work.

use lagrangian_runtime::NoInputs;

const DOUBLE: &str = "model Double;
coordinates { theta1 [rad], theta2 [rad] }
parameters { m [kg] = 1.0, l [m] = 1.0, g [m/s^2] = 9.81, T [N*m] = 2.5 }
let x1 = l * sin(theta1);
let y1 = -l * cos(theta1);
let x2 = x1 + l * sin(theta2);
let y2 = y1 - l * cos(theta2);
kinetic = 0.5 * m * (pow(dot(x1), 2) + pow(dot(y1), 2) + pow(dot(x2), 2) + pow(dot(y2), 2));
potential = m * g * (y1 + y2);
";

/// The forcing of `DOUBLE` plus `forces`, at one state.
fn forcing(forces: &str) -> [f64; 2] {
    let model = lagrangian_core::interpret(&format!("{DOUBLE}{forces}")).unwrap();
    let (mut mass, mut f) = ([0.0; 4], [0.0; 2]);
    (model.evaluate_dynamics(0.0, &[0.3, -0.7], &[1.1, 0.4], &NoInputs, &mut mass, &mut f))
        .unwrap();
    f
}

#[test]
fn a_joint_torque_acts_on_both_links_with_opposite_signs() {
    // A motor at the elbow turning link 2 against link 1: φ = θ2 − θ1, so
    // Q = (−T, +T), written by hand as two generalized forces.
    let by_torque = forcing("torque (theta2 - theta1) = T;");
    let by_hand = forcing("force theta1 = -T;\nforce theta2 = T;");
    assert_eq!(by_torque, by_hand);
    let free = forcing("");
    assert!((by_torque[0] - (free[0] - 2.5)).abs() < 1e-12);
    assert!((by_torque[1] - (free[1] + 2.5)).abs() < 1e-12);
}

#[test]
fn a_torque_about_several_angles_is_an_error() {
    let source = format!("{DOUBLE}torque (theta1, theta2) = T;");
    let error = match lagrangian_core::Compiled::from_source(&source) {
        Ok(_) => panic!("compiled"),
        Err(e) => e.render("double.lpm", &source),
    };
    assert!(
        error.contains("a torque acts about one angle, not 2"),
        "{error}"
    );
}
