//! Runs of the `stick_slip` component through the simulator (moved out of
//! `components::stick_slip`, which must not reach the run engine above it).

use crate::scenario::{ModelNames, Scenario};
use crate::simulate::simulate;
use lagrangian_runtime::Interpreted;

/// A 1 kg block pulled by `10·t` N against its friction.
const BLOCK: &str = "model Pulled;\n\
    coordinates { x [m], }\n\
    parameters { m [kg] = 1.0, pull [N/s] = 10.0, }\n\
    inputs { friction(v [m/s], f [N]) [N], }\n\
    kinetic = 0.5 * m * pow(dot(x), 2);\n\
    force x = pull * t - friction(dot(x), pull * t);\n";

/// μ_s = 0.5, μ_k = 0.3 under its weight.
const SCENARIO: &str = "[simulation]\nt_end = 0.8\nrtol = 1e-10\natol = 1e-12\n\
    [components.floor]\ntype = \"stick_slip\"\ninputs = { force = \"friction\" }\n\
    coefficient = 0.3\nstatic_coefficient = 0.5\nnormal_force = 9.81\n";

fn block() -> (Interpreted<1>, ModelNames) {
    let model = lagrangian_core::interpret(BLOCK).unwrap();
    let names = ModelNames::of_interpreted(&model);
    (Interpreted::new(model).unwrap(), names)
}

#[test]
fn a_pulled_block_sticks_until_the_static_limit_then_slides() {
    // Still until 10·t₁ = μ_s·N (t₁ = 0.4905 s); then
    // v = 5(t² − t₁²) − μ_k·N·(t − t₁), x its integral.
    let (model, names) = block();
    let scenario = Scenario::parse(SCENARIO, None, &names, &[]).unwrap();
    let result = simulate(&model, &scenario).unwrap();
    let t1 = 0.5 * 9.81 / 10.0;
    let [breakaway] = result.events.as_slice() else {
        panic!("{:?}", result.events)
    };
    assert!((breakaway.t - t1).abs() < 1e-9, "{}", breakaway.t);
    for s in &result.samples {
        let (x, v) = match s.t <= t1 {
            true => (0.0, 0.0),
            false => {
                let dt = s.t - t1;
                let v = 5.0 * (s.t * s.t - t1 * t1) - 2.943 * dt;
                let x =
                    5.0 * (s.t.powi(3) - t1.powi(3)) / 3.0 - 5.0 * t1 * t1 * dt - 1.4715 * dt * dt;
                (x, v)
            }
        };
        assert!(
            (s.q[0] - x).abs() < 1e-8 && (s.v[0] - v).abs() < 1e-8,
            "{}",
            s.t
        );
    }
}

#[test]
fn a_sliding_block_stops_and_stays() {
    // Unpulled from 2 m/s: stops at v₀/(μ_k·g) = 0.6796 s after
    // v₀²/(2μ_k·g), and sticks there.
    let (model, names) = block();
    let text =
        format!("{SCENARIO}[parameters]\npull = 0.0\n[initial]\nvelocities = {{ x = 2.0 }}\n");
    let scenario = Scenario::parse(&text, None, &names, &[]).unwrap();
    let result = simulate(&model, &scenario).unwrap();
    let [stop] = result.events.as_slice() else {
        panic!("{:?}", result.events)
    };
    assert!((stop.t - 2.0 / 2.943).abs() < 1e-9, "{}", stop.t);
    assert_eq!(stop.description, "sticks under 0.0000 N");
    let last = result.samples.last().unwrap();
    assert!(
        (last.q[0] - 4.0 / (2.0 * 2.943)).abs() < 1e-9,
        "{}",
        last.q[0]
    );
    assert!(last.v[0].abs() < 1e-9);
}

#[test]
fn a_static_coefficient_below_the_kinetic_is_refused() {
    let (_, names) = block();
    let text = SCENARIO.replace("static_coefficient = 0.5", "static_coefficient = 0.2");
    assert_eq!(
        Scenario::parse(&text, None, &names, &[])
            .unwrap_err()
            .message,
        "components.floor.static_coefficient = 0.2: the static coefficient μ_s must be at least the kinetic one (coefficient = 0.3)"
    );
}
