//! Runs of the `dahl` component through the simulator (moved out of
//! `components::dahl`, which must not reach the run engine above it).

use crate::scenario::{ModelNames, Scenario};
use crate::simulate::simulate;
use lagrangian_runtime::Interpreted;

/// A unit mass whose friction input slides at `V` from rest at 0.
const SLIDING: &str = "model Sliding;\n\
    coordinates { x [m], }\n\
    parameters { m [kg] = 1.0, V [m/s] = 0.01, }\n\
    inputs { friction(s [m], v [m/s]) [N], }\n\
    kinetic = 0.5 * m * pow(dot(x), 2);\n\
    force x = -friction(V * t, V);\n";

const SCENARIO: &str = "[simulation]\nt_end = 0.01\noutput_interval = 1e-4\n\
    [components.surface]\ntype = \"dahl\"\ninputs = { force = \"friction\" }\n\
    fc = 2.0\nsigma0 = 1.0e4\n";

#[test]
fn the_force_rises_to_the_coulomb_force_along_its_closed_form() {
    let model = lagrangian_core::interpret(SLIDING).unwrap();
    let names = ModelNames::of_interpreted(&model);
    let model = Interpreted::<1>::new(model).unwrap();
    let scenario = Scenario::parse(SCENARIO, None, &names, &[]).unwrap();
    let result = simulate(&model, &scenario).unwrap();
    // α = 1 from rest: dF/ds = σ0 (1 − F/Fc), F = Fc (1 − exp(−σ0 s/Fc)).
    for s in &result.samples {
        let slid = 0.01 * s.t;
        let closed = 2.0 * (1.0 - (-1.0e4 * slid / 2.0).exp());
        let force = s.components[0];
        assert!(
            (force - closed).abs() < 1e-7,
            "t = {}: {force} vs {closed}",
            s.t
        );
    }
    // All the work of sliding past the stored energy is dissipated.
    let last = result.samples.last().unwrap();
    let (force, dissipated) = (last.components[0], last.components[3]);
    // ∫F ds over s = V·t_end = 1e-4 m.
    let (fc, sigma0, slid): (f64, f64, f64) = (2.0, 1.0e4, 1e-4);
    let work = fc * slid - fc * fc / sigma0 * (1.0 - (-sigma0 * slid / fc).exp());
    let stored = 0.5 * force * force / 1.0e4;
    assert!((dissipated - (work - stored)).abs() < 1e-9, "{dissipated}");
}
