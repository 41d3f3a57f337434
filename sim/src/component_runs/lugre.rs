//! Runs of the `lugre` component through the simulator (moved out of
//! `components::lugre`, which must not reach the run engine above it).

use crate::scenario::{ModelNames, Scenario};
use crate::simulate::{SimulationResult, simulate};
use lagrangian_runtime::Interpreted;

/// A unit mass whose friction input slides at a prescribed speed `V`.
const SLIDING: &str = "model Sliding;\n\
    coordinates { x [m], }\n\
    parameters { m [kg] = 1.0, V [m/s] = 0.01, }\n\
    inputs { friction(s [m], v [m/s]) [N], }\n\
    kinetic = 0.5 * m * pow(dot(x), 2);\n\
    force x = -friction(V * t, V);\n";

/// A block of 1 kg on the surface, pulled through a spring of
/// 2 kN/m whose end moves at 0.1 m/s.
const PULLED: &str = "model Pulled;\n\
    coordinates { x [m], }\n\
    parameters { m [kg] = 1.0, k [N/m] = 2000.0, V [m/s] = 0.1, }\n\
    inputs { friction(s [m], v [m/s]) [N], }\n\
    kinetic = 0.5 * m * pow(dot(x), 2);\n\
    potential = 0.5 * k * pow(x - V * t, 2);\n\
    force x = -friction(x, dot(x));\n";

const LAW: &str = "[components.surface]\ntype = \"lugre\"\n\
    inputs = { force = \"friction\" }\n\
    fc = 1.0\nfs = 1.5\nvs = 0.001\nsigma0 = 1.0e5\nsigma1 = 316.0\nsigma2 = 0.4\n";

fn run(model: &str, simulation: &str) -> SimulationResult {
    let model = lagrangian_core::interpret(model).unwrap();
    let names = ModelNames::of_interpreted(&model);
    let model = Interpreted::<1>::new(model).unwrap();
    let text = format!("{simulation}{LAW}");
    let scenario = Scenario::parse(&text, None, &names, &[]).unwrap();
    simulate(&model, &scenario).unwrap()
}

#[test]
fn at_a_steady_speed_the_force_follows_the_stribeck_curve() {
    // Slowest: z settles in g/(σ0·v) = 0.074 s at v = 2e-4 m/s, to
    // exp(−1/0.074) ≈ 1e-6 by the end; z ≈ 1e-5 m needs a small atol.
    let simulation = "[simulation]\nt_end = 1.0\noutput_interval = 1.0\natol = 1e-14\n";
    for speed in [2e-4, 1e-3, 3e-3, 1e-2, 0.1] {
        let model = SLIDING.replace("V [m/s] = 0.01", &format!("V [m/s] = {speed}"));
        let result = run(&model, simulation);
        let force = result.samples.last().unwrap().components[0];
        let closed = 1.0 + 0.5 * (-(speed / 1e-3f64).powi(2)).exp() + 0.4 * speed;
        assert!(
            (force / closed - 1.0).abs() < 1e-5,
            "v = {speed}: {force} vs {closed}"
        );
    }
}

#[test]
fn a_block_pulled_through_a_spring_sticks_and_slips() {
    let simulation = "[simulation]\nt_end = 1.0\noutput_interval = 1e-3\n";
    let result = run(PULLED, simulation);
    let v: Vec<f64> = result.samples.iter().map(|s| s.v[0]).collect();
    // Stuck (far slower than the pull) and slipping (faster) in turn,
    // more than once.
    let stuck = |x: &f64| x.abs() < 0.01;
    let slipping = |x: &f64| *x > 0.15;
    let changes = v
        .windows(2)
        .filter(|w| stuck(&w[0]) && !stuck(&w[1]))
        .count();
    assert!(changes >= 2, "{changes} slips");
    assert!(v.iter().any(stuck) && v.iter().any(slipping));
    let (name, dissipated) = &result.summary.dissipated_by[0];
    assert_eq!(name, "surface");
    assert!(*dissipated > 0.0);
}
