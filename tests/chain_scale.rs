//! A model at scale written with families: the fifty-mass chain of
//! `tests/specs/chain/chain_50.lpm` (17 lines) compiles with the macro and
//! simulates under its scenario, its energy balanced, its momentum changed
//! by exactly the wall's impulse, and its rear car still at the impact
//! speed while the compression wave has not reached it.

use lagrangian::LagrangianSystem;
use lagrangian::scenario::{ModelNames, Scenario};
use lagrangian::simulate::simulate;
use std::path::Path;

mod model {
    lagrangian::lagrangian!(file = "tests/specs/chain/chain_50.lpm");
}

#[test]
fn fifty_masses_in_seventeen_lines_simulate_as_physics_says() {
    let chain = model::Chain50::default();
    assert_eq!(chain.coordinate_names()[49], "x[50]");
    let scenario = Path::new("tests/specs/chain/chain_50.toml");
    let scenario = Scenario::load(scenario, &ModelNames::of(&chain), &[]).unwrap();
    let run = simulate(&chain, &scenario).unwrap();
    assert!(
        run.summary.energy_balance_error_rel < 1e-8,
        "{}",
        run.summary.energy_balance_error_rel
    );
    let output = |name: &str| {
        run.output_columns
            .iter()
            .position(|o| o.starts_with(name))
            .unwrap()
    };
    let (momentum, wall) = (output("momentum"), output("wall_force"));
    // Δp = −∫ F_wall dt (trapezoids over 10 kHz samples; the force is smooth).
    let impulse: f64 = (run.samples.windows(2))
        .map(|w| 0.5 * (w[1].t - w[0].t) * (w[0].outputs[wall] + w[1].outputs[wall]))
        .sum();
    let (first, last) = (&run.samples[0], run.samples.last().unwrap());
    let change = last.outputs[momentum] - first.outputs[momentum];
    assert!(impulse > 1e5, "the wall stops the front: {impulse} N·s");
    assert!(
        (change + impulse).abs() < 1e-3 * impulse,
        "Δp {change} vs impulse {impulse}"
    );
    // The wave travels √(k/m) = 141 masses per second: at 0.1 s it is
    // about 14 masses in, and the rear car has not felt it.
    assert!(
        (last.v[49] - 15.0).abs() < 1e-9,
        "rear car at {} m/s",
        last.v[49]
    );
    assert!(
        (last.v[0] - 15.0).abs() > 1.0,
        "front car at {} m/s",
        last.v[0]
    );
}
