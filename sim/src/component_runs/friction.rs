//! Runs of the `friction` component through the simulator (moved out of
//! `components::friction`, which must not reach the run engine above it).

use crate::components::friction::*;
use crate::scenario::{ModelNames, Scenario};
use crate::simulate::simulate;
use lagrangian_runtime::Interpreted;

fn stribeck() -> Friction {
    Friction {
        coulomb: 0.3,
        stiction: 0.5,
        stribeck_velocity: 0.1,
        stribeck_exponent: 2.0,
        viscous: 4.0,
        smoothing_velocity: 1e-9,
        normal_force: None,
    }
}

#[test]
fn the_stribeck_curve_follows_its_closed_form() {
    let f = stribeck();
    // Under N = 10 N: F(v) = 10·μ(v) + 4·v, μ(v) = 0.3 + 0.2·exp(−(v/0.1)²).
    for v in [1e-6, 0.05, 0.1, 0.2, 1.0] {
        let mu = 0.3 + 0.2 * (-(v / 0.1f64).powi(2)).exp();
        let (force, _, dn) = f.force(&[v, 10.0]);
        assert!((force - (10.0 * mu + 4.0 * v)).abs() < 1e-12, "{v}");
        assert!((dn - mu).abs() < 1e-12, "{v}");
        // Odd in v.
        assert_eq!(f.force(&[-v, 10.0]).0, -force);
    }
    // At v_s the excess of stiction has fallen to 1/e.
    let (mu, _) = f.coefficient(0.1);
    assert!((mu - (0.3 + 0.2 / std::f64::consts::E)).abs() < 1e-15);
    // dμ/dv by central differences, on the falling branch.
    let (_, slope) = f.coefficient(0.07);
    let h = 1e-7;
    let fd = (f.coefficient(0.07 + h).0 - f.coefficient(0.07 - h).0) / (2.0 * h);
    assert!((slope - fd).abs() < 1e-6 * slope.abs(), "{slope} {fd}");
    assert_eq!(f.power(&[0.2, 10.0]), f.force(&[0.2, 10.0]).0 * 0.2);
}

/// A 1 kg block sliding on the floor, its friction `friction(v)`.
const BLOCK: &str = "model Block;\n\
    coordinates { x [m], }\n\
    parameters { m [kg] = 1.0, }\n\
    inputs { friction(v [m/s]) [N], }\n\
    kinetic = 0.5 * m * pow(dot(x), 2);\n\
    force x = -friction(dot(x));\n";

/// μ = 0.3 under its weight, from 2 m/s.
const SLIDING: &str = "[simulation]\nt_end = 0.8\nrtol = 1e-10\natol = 1e-12\n\
    [initial]\nvelocities = { x = 2.0 }\n\
    [components.floor]\ntype = \"friction\"\ninputs = { force = \"friction\" }\n\
    coefficient = 0.3\nsmoothing_velocity = 1e-4\nnormal_force = 9.81\n";

fn block() -> (Interpreted<1>, ModelNames) {
    let model = lagrangian_core::interpret(BLOCK).unwrap();
    let names = ModelNames::of_interpreted(&model);
    (Interpreted::new(model).unwrap(), names)
}

#[test]
fn a_sliding_block_stops_where_coulomb_says() {
    // Constant deceleration μg until v₀/(μg) = 0.6796 s, after
    // v₀²/(2μg) = 0.6796 m.
    let (model, names) = block();
    let scenario = Scenario::parse(SLIDING, None, &names, &[]).unwrap();
    let result = simulate(&model, &scenario).unwrap();
    let mu_g = 0.3 * 9.81;
    for sample in result.samples.iter().filter(|s| s.t < 0.6) {
        let x = 2.0 * sample.t - 0.5 * mu_g * sample.t * sample.t;
        assert!(
            (sample.q[0] - x).abs() < 1e-6,
            "{}: {}",
            sample.t,
            sample.q[0]
        );
    }
    let last = result.samples.last().unwrap();
    let stop = 4.0 / (2.0 * mu_g);
    assert!((last.q[0] - stop).abs() < 1e-4, "{} vs {stop}", last.q[0]);
    assert!(last.v[0].abs() < 1e-4, "{}", last.v[0]);
}

#[test]
fn bad_coefficients_are_refused() {
    let (_, names) = block();
    let refused = |from: &str, to: &str| {
        let text = SLIDING.replace(from, to);
        Scenario::parse(&text, None, &names, &[])
            .unwrap_err()
            .message
    };
    let stiction = "coefficient = 0.3\nstatic_coefficient";
    assert_eq!(
        refused("coefficient = 0.3", &format!("{stiction} = 0.2")),
        "components.floor.static_coefficient = 0.2: the static coefficient μ_s must be at least the kinetic one (coefficient = 0.3)"
    );
    assert_eq!(
        refused("coefficient = 0.3", &format!("{stiction} = 0.5")),
        "components.floor.stribeck_velocity is missing: the friction falls from the static coefficient 0.5 to 0.3 over it [m/s]"
    );
    assert_eq!(
        refused("coefficient = 0.3", "coefficient = -0.3"),
        "components.floor.coefficient = -0.3: must be a finite number ≥ 0"
    );
    assert_eq!(
        refused("smoothing_velocity = 1e-4", "smoothing_velocity = 0.0"),
        "components.floor.smoothing_velocity = 0: must be a positive, finite number"
    );
}
