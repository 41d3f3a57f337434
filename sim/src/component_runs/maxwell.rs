//! Runs of the `maxwell` component through the simulator (moved out of
//! `components::maxwell`, which must not reach the run engine above it).

use crate::scenario::{ModelNames, Scenario};
use crate::simulate::simulate;
use lagrangian_runtime::Interpreted;

/// A unit mass whose element is held at a step deflection `U` from
/// `t = 0`.
const HELD: &str = "model Held;\n\
    coordinates { x [m], }\n\
    parameters { m [kg] = 1.0, U [m] = 0.01, }\n\
    inputs { element(u [m]) [N], }\n\
    kinetic = 0.5 * m * pow(dot(x), 2);\n\
    force x = -element(U);\n";

const SCENARIO: &str = "[simulation]\nt_end = 0.05\noutput_interval = 0.001\n\
    [metrics]\ndisplacement = [\"relax.dashpot\"]\n\
    [components.relax]\ntype = \"maxwell\"\ninputs = { force = \"element\" }\n\
    stiffness = 2.0e4\ndamping = 200.0\n";

#[test]
fn under_a_step_deflection_the_force_relaxes_exponentially() {
    let model = lagrangian_core::interpret(HELD).unwrap();
    let names = ModelNames::of_interpreted(&model);
    let model = Interpreted::<1>::new(model).unwrap();
    for method in ["dopri5", "tr-bdf2"] {
        let text = SCENARIO.replace("[metrics]", &format!("method = \"{method}\"\n[metrics]"));
        let scenario = Scenario::parse(&text, None, &names, &[]).unwrap();
        let result = simulate(&model, &scenario).unwrap();
        let names: Vec<&str> = (result.component_columns.iter())
            .map(|(n, _)| n.as_str())
            .collect();
        assert_eq!(
            names,
            [
                "relax.force",
                "relax.deflection",
                "relax.dashpot",
                "relax.dissipated_energy"
            ]
        );
        let (k, c, u0) = (2.0e4, 200.0, 0.01);
        let tolerance = if method == "dopri5" { 1e-7 } else { 1e-4 };
        for s in &result.samples {
            let expected = k * u0 * (-k * s.t / c).exp();
            let force = s.components[0];
            assert!(
                (force - expected).abs() < tolerance * k * u0,
                "{method} t = {}: {force} vs {expected}",
                s.t
            );
            // What the dashpot dissipated is what the spring lost.
            let dissipated = 0.5 * k * u0 * u0 * (1.0 - (-2.0 * k * s.t / c).exp());
            let error = (s.components[3] - dissipated).abs();
            assert!(
                error < tolerance * 0.5 * k * u0 * u0,
                "{method} t = {}",
                s.t
            );
        }
        // The state is a channel like any column: the dashpot creeps
        // to u0·(1 − exp(−k t/c)) by the end.
        let channel = &result.summary.channels.0[0];
        let creep = u0 * (1.0 - (-k * 0.05 / c).exp());
        let max = channel.get("max").unwrap();
        assert!(
            (max - creep).abs() < tolerance * u0,
            "{method}: {max} vs {creep}"
        );
    }
}
