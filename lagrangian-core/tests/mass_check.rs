//! The compile-time check that the kinetic energy is positive definite
//! samples states inside every function's domain, and says when it cannot.

use lagrangian_core::Compiled;
use lagrangian_runtime::NoInputs;

/// A point mass in a plane with a flywheel turned through the angle
/// `th = acos(y / r)`: defined for |y| ≤ r only, where the first sample
/// state (y = 0.48) is not.
const FLYWHEEL: &str = "model AcosFlywheel;
coordinates { x [m], y [m] }
parameters  { m [kg] = 2.0, r [m] = 0.3, J [kg*m^2] = 0.01, k [N/m] = 10.0 }
let th = acos(y / r);
kinetic   = 0.5 * m * (pow(dot(x), 2) + pow(dot(y), 2)) + 0.5 * J * pow(dot(th), 2);
potential = 0.5 * k * (pow(x, 2) + pow(y, 2));
";

#[test]
fn a_kinetic_energy_with_acos_is_checked_inside_its_domain() {
    let compiled = Compiled::from_source(FLYWHEEL).unwrap();
    assert!(
        compiled.model.warnings.is_empty(),
        "{:?}",
        compiled.model.warnings
    );
    // Closed form: d(acos(y/r))/dt = −ẏ / √(r² − y²), so
    // M = diag(m, m + J / (r² − y²)).
    let model = compiled.interpreted();
    let (mut mass, mut forcing) = (vec![0.0; 4], vec![0.0; 2]);
    let y = 0.1;
    model
        .evaluate_dynamics(
            0.0,
            &[0.05, y],
            &[0.0, 0.0],
            &NoInputs,
            &mut mass,
            &mut forcing,
        )
        .unwrap();
    let expected = 2.0 + 0.01 / (0.3f64 * 0.3 - y * y);
    assert_eq!(mass[0], 2.0);
    assert!((mass[3] - expected).abs() < 1e-12 * expected, "{mass:?}");
    assert_eq!((mass[1], mass[2]), (0.0, 0.0));
}

#[test]
fn a_negative_mass_is_still_found_at_a_state_inside_the_domain() {
    let source = FLYWHEEL.replace("m [kg] = 2.0", "m [kg] = -2.0");
    let error = match Compiled::from_source(&source) {
        Ok(_) => panic!("compiled"),
        Err(e) => e.to_string(),
    };
    assert!(error.contains("is not positive definite"), "{error}");
    assert!(error.contains("non-positive pivot at `x`"), "{error}");
    // The state named is one where acos is defined: |y| ≤ r = 0.3.
    let y: f64 = error.split("y = ").nth(1).unwrap()[..5]
        .trim_end_matches(')')
        .parse()
        .unwrap();
    assert!(y.abs() <= 0.3, "{error}");
}

#[test]
fn a_kinetic_energy_defined_nowhere_is_not_checked_and_says_why() {
    let source = "model Nowhere;
coordinates { x [m] }
parameters  { m [kg] = 1.0, r [m] = 0.3 }
let th = acos(2 + pow(x / r, 2));
kinetic = 0.5 * m * pow(dot(x), 2) + 0.5 * m * r * r * pow(dot(th), 2);
";
    let compiled = Compiled::from_source(source).unwrap();
    let warnings = &compiled.model.warnings;
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    let text = warnings[0].render_warning("nowhere.lpm", source);
    assert!(
        text.starts_with("warning: the kinetic energy could not be checked for positive definiteness: at each of 64 sample states a function's argument is outside its domain (at the first, the argument of the call noted below is 3.068 but must be in [-1, 1])\n"),
        "{text}"
    );
    // 2 + (0.31 / 0.3)² = 3.0678 at the first sample state, x = 0.31.
    assert!(
        text.contains("note: the call at the first sample state\n --> nowhere.lpm:4:10"),
        "{text}"
    );
}
