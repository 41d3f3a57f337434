//! Runs of the `kelvin_voigt` component through the simulator (moved out of
//! `components::kelvin_voigt`, which must not reach the run engine above it).

use crate::scenario::{ModelNames, Scenario};
use crate::simulate::simulate;
use lagrangian_runtime::Interpreted;

/// A 1 kg mass on the element.
const MASS: &str = "model Oscillator;\n\
    coordinates { x [m], }\n\
    parameters { m [kg] = 1.0, }\n\
    inputs { kv(x [m], v [m/s]) [N], }\n\
    kinetic = 0.5 * m * pow(dot(x), 2);\n\
    force x = -kv(x, dot(x));\n";

const SCENARIO: &str = "[simulation]\nt_end = 1.0\nrtol = 1e-10\natol = 1e-12\n\
    [initial]\ncoordinates = { x = 0.1 }\n\
    [components.mount]\ntype = \"kelvin_voigt\"\ninputs = { force = \"kv\" }\n\
    stiffness = 100.0\ndamping = 2.0\n";

fn names() -> (Interpreted<1>, ModelNames) {
    let model = lagrangian_core::interpret(MASS).unwrap();
    let names = ModelNames::of_interpreted(&model);
    (Interpreted::new(model).unwrap(), names)
}

#[test]
fn a_mass_on_it_is_the_damped_oscillator() {
    // ω₀ = 10 rad/s, ζ = c/(2√(km)) = 0.1: from rest at x₀,
    // x = x₀·e^(−ζω₀t)·(cos ω_d t + ζω₀/ω_d · sin ω_d t).
    let (model, names) = names();
    let scenario = Scenario::parse(SCENARIO, None, &names, &[]).unwrap();
    let result = simulate(&model, &scenario).unwrap();
    let last = result.samples.last().unwrap();
    let (sigma, wd) = (1.0, (100.0f64 - 1.0).sqrt());
    let t = last.t;
    let x = 0.1 * (-sigma * t).exp() * ((wd * t).cos() + sigma / wd * (wd * t).sin());
    assert!(
        (t - 1.0).abs() < 1e-12 && (last.q[0] - x).abs() < 1e-8,
        "{} vs {x}",
        last.q[0]
    );
    let columns = &result.component_columns;
    assert_eq!(columns[0], ("mount.force".into(), Some("N".into())));
    assert_eq!(columns[1], ("mount.power".into(), Some("W".into())));
    let force = 100.0 * last.q[0] + 2.0 * last.v[0];
    assert!((last.components[0] - force).abs() < 1e-9);
    assert!((last.components[1] - 2.0 * last.v[0].powi(2)).abs() < 1e-12);
}

#[test]
fn a_negative_stiffness_or_damping_is_refused() {
    let (_, names) = names();
    let refused = |text: &str| {
        Scenario::parse(text, None, &names, &[])
            .unwrap_err()
            .message
    };
    assert_eq!(
        refused(&SCENARIO.replace("stiffness = 100.0", "stiffness = -100.0")),
        "components.mount.stiffness = -100: must be a finite number ≥ 0"
    );
    assert_eq!(
        refused(&SCENARIO.replace("damping = 2.0", "damping = -2.0")),
        "components.mount.damping = -2: must be a finite number ≥ 0"
    );
}
