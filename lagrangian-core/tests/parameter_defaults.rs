//! Parameter defaults may use the parameters declared before them.

use lagrangian_core::Compiled;

fn spec(parameters: &str) -> String {
    format!(
        "model Oscillator;
coordinates {{ x [m] }}
parameters {{ {parameters} }}
kinetic = 0.5 * m * pow(dot(x), 2);
potential = 0.5 * k * pow(x, 2);
"
    )
}

#[test]
fn a_default_uses_earlier_parameters_at_their_defaults() {
    // k = m·ω² with ω = 2π·f: 2 kg at 3 Hz.
    let source = spec("m [kg] = 2.0, f [1/s] = 3.0, k [N/m] = m * pow(2.0 * pi * f, 2)");
    let model = lagrangian_core::interpret(&source).unwrap();
    let k = model
        .parameter_names()
        .iter()
        .position(|n| n == "k")
        .unwrap();
    let expected = 2.0 * (2.0 * std::f64::consts::PI * 3.0f64).powi(2);
    assert!((model.parameters()[k] - expected).abs() < 1e-9 * expected);
}

#[test]
fn a_default_that_uses_a_parameter_declared_below_says_so() {
    let source = spec("k [N/m] = m * 100.0, m [kg] = 2.0");
    let error = match Compiled::from_source(&source) {
        Ok(_) => panic!("compiled"),
        Err(e) => e.render("oscillator.lpm", &source),
    };
    assert!(
        error.contains("error: parameter `m` is declared below"),
        "{error}"
    );
    assert!(error.contains("oscillator.lpm:3:24"), "{error}");
    assert!(
        error.contains("note: declared here\n --> oscillator.lpm:3:35"),
        "{error}"
    );
    assert!(error.contains("move `m` up"), "{error}");
    // Only that error: its dimension is not checked as well.
    assert_eq!(error.matches("error: ").count(), 1, "{error}");
}

#[test]
fn a_default_of_the_wrong_dimension_is_an_error_at_it() {
    for (parameters, message, at) in [
        (
            "l [m] = 0.5, m [kg] = l * 2, k [N/m] = 1.0",
            "the default of `m` has dimension m, but must have kg",
            "3:36",
        ),
        (
            "m [kg] = 1.0, k [N/m] = m * 4.0",
            "the default of `k` has dimension kg, but must have kg·s^-2",
            "3:38",
        ),
        (
            "m [kg] = 1.0, k [N/m] = 3.0, c [N*s/m] = k / m",
            "the default of `c` has dimension s^-2, but must have kg·s^-1",
            "3:55",
        ),
    ] {
        let source = spec(parameters);
        let error = match Compiled::from_source(&source) {
            Ok(_) => panic!("compiled: {parameters}"),
            Err(e) => e.render("oscillator.lpm", &source),
        };
        assert!(
            error.contains(&format!("error: {message}\n --> oscillator.lpm:{at}\n")),
            "{error}"
        );
    }
}

#[test]
fn a_default_of_numbers_is_in_the_declared_unit_and_pi_is_a_number() {
    // k = m·(2π f)² is kg/s² through m and f; r = 0.5π is in m.
    for parameters in [
        "m [kg] = 2.0, k [N/m] = 2.0 * 3e4",
        "m [kg] = 2.0, f [1/s] = 3.0, k [N/m] = m * pow(2.0 * pi * f, 2), r [m] = 0.5 * pi",
        "m [kg] = 2.0, m2 [kg] = m, k [N/m] = 4.0",
        "m [kg] = 2.0, k [N/m] = -4.0",
    ] {
        let source = spec(parameters);
        Compiled::from_source(&source).unwrap_or_else(|e| panic!("{parameters}: {e}"));
    }
}
