//! A model with a non-smooth function: its switching functions are located
//! as events, so no step straddles a kink.

use lagrangian_runtime::Interpreted;
use lagrangian_sim::scenario::{ModelNames, Scenario};
use lagrangian_sim::simulate::simulate;

/// A mass that flies freely for `x < 0` and meets a one-sided spring at
/// `x = 0`: the contact force is `k·max(0, x)`, written with `abs`.
const CONTACT: &str = "
model Contact;
coordinates { x [m] }
parameters  { m [kg] = 2.0, k [N/m] = 800.0 }
kinetic   = 0.5 * m * pow(dot(x), 2);
potential = 0.5 * k * pow((x + abs(x)) / 2, 2);
";

#[test]
fn a_contact_written_with_abs_switches_at_the_analytic_times() {
    switches_at_the_analytic_times(lagrangian_core::interpret(CONTACT).unwrap());
}

/// The same on the derivation graph (the path of models too large for the
/// canonical form): its switching functions are located the same way.
#[test]
fn on_the_graph_path_the_contact_switches_at_the_same_times() {
    let model = lagrangian_core::Model::from_source(CONTACT).unwrap();
    let compiled = lagrangian_core::Compiled::on_graph(model).unwrap();
    assert!(compiled.derivation.is_none(), "derived on the graph");
    switches_at_the_analytic_times(compiled.interpreted());
}

fn switches_at_the_analytic_times(model: lagrangian_runtime::InterpretedModel) {
    assert_eq!(model.switching_count(), 1);
    let names = ModelNames::of_interpreted(&model);
    let system = Interpreted::<1>::new(model).unwrap();
    let scenario = "[simulation]\nt_end = 0.3\n\
        [initial]\ncoordinates = { x = -0.05 }\nvelocities = { x = 1.0 }\n";
    let scenario = Scenario::parse(scenario, None, &names, &[]).unwrap();
    let result = simulate(&system, &scenario).unwrap();
    // Free flight to x = 0 at 0.05 s, then half a period of ω = √(k/m) = 20
    // rad/s in contact, leaving at 0.05 + π/20 s.
    let (contact, release) = (0.05, 0.05 + std::f64::consts::PI / 20.0);
    let times: Vec<f64> = (result.events.iter())
        .filter(|e| e.component == "model")
        .map(|e| e.t)
        .collect();
    assert_eq!(times.len(), 2, "{:?}", result.events);
    assert!((times[0] - contact).abs() < 1e-6, "{times:?}");
    assert!((times[1] - release).abs() < 1e-6, "{times:?}");
    // No step across a kink: every sample on one side of it.
    let peak = result.samples.iter().fold(0.0_f64, |m, s| m.max(s.q[0]));
    assert!((peak - 1.0 / 20.0).abs() < 1e-6, "peak {peak}");
    let last = result.samples.last().unwrap();
    assert!((last.v[0] + 1.0).abs() < 1e-6, "leaves at {}", last.v[0]);
}

#[test]
fn a_smooth_model_has_no_switching_functions() {
    let spec = include_str!("../../specs/spring_mass_damper.lpm");
    let model = lagrangian_core::interpret(spec).unwrap();
    assert_eq!(model.switching_count(), 0);
}
