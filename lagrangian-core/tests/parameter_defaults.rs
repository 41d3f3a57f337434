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
}
