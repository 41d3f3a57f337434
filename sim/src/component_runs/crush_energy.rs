//! Runs of the `crush::energy` component through the simulator (moved out of
//! `components::crush::energy`, which must not reach the run engine above it).

use crate::scenario::{ModelNames, Scenario};
use crate::simulate::{SimulationResult, simulate};
use lagrangian_runtime::Interpreted;

/// A car of 860 kg on a crush element, `x` its crush.
const IMPACT: &str = "model Impact;\n\
    coordinates { x [m], }\n\
    parameters { m [kg] = 860.0, }\n\
    inputs { crush(x [m], v [m/s]) [N], }\n\
    kinetic = 0.5 * m * pow(dot(x), 2);\n\
    force x = -crush(x, dot(x));\n";

/// At 10 m/s into the curve (0, 0), (0.1 m, 170 kN), (0.5 m, 180 kN)
/// behind a gap of 2 cm: its ½·860·10² = 43 kJ are absorbed at 0.3 m
/// of deflection, 175 kN (8.5 kJ to 0.1 m, then 170 kN·u + 12.5
/// kN/m·u² for u = 0.2 m).
const WALL: &str = "[initial]\nvelocities = { x = 10.0 }\n\
    [components.wall]\ntype = \"crush\"\ninputs = { force = \"crush\" }\n\
    compression = \"positive\"\nforce_breakpoints = [0.1, 0.5]\n\
    force_values = [170e3, 180e3]\ngap = 0.02\n";

/// The run with the element's `damping` (a constant [N·s/m]) and
/// `unloading` entries, by `method`.
fn run(damping: f64, unloading: &str, method: &str) -> SimulationResult {
    let model = lagrangian_core::interpret(IMPACT).unwrap();
    let names = ModelNames::of_interpreted(&model);
    let model = Interpreted::<1>::new(model).unwrap();
    let text = format!(
        "[simulation]\nt_end = 0.1\nmethod = \"{method}\"\n{WALL}\
        damping_breakpoints = [1.0]\ndamping_values = [{damping:?}, {damping:?}]\n{unloading}\n"
    );
    let scenario = Scenario::parse(&text, None, &names, &[]).unwrap();
    simulate(&model, &scenario).unwrap()
}

/// The energy the element dissipated, from the summary, checked
/// against its trajectory column.
fn dissipated(result: &SimulationResult) -> f64 {
    let [(name, energy)] = result.summary.dissipated_by.as_slice() else {
        panic!("{:?}", result.summary.dissipated_by);
    };
    assert_eq!(name, "wall");
    let k = (result.component_columns.iter())
        .position(|(n, _)| n == "wall.dissipated_energy")
        .unwrap();
    assert_eq!(result.samples.last().unwrap().components[k], *energy);
    *energy
}

/// The kinetic energy the car lost: `½·m·(v0² − v1²)` after it left.
fn lost(result: &SimulationResult) -> f64 {
    let rebound = result.samples.last().unwrap().v[0];
    assert!(rebound < -1.0, "{rebound}: the car has not rebounded");
    0.5 * 860.0 * (100.0 - rebound * rebound)
}

const PLASTIC: &str = "unloading = \"plastic\"\nunloading_stiffness = 1e7";

#[test]
fn without_damping_the_dissipated_energy_is_the_area_of_the_loop() {
    // Loaded to 175 kN at 0.3 m, unloaded at 10 MN/m: the loop is the
    // 43 kJ under the curve less the triangle under the unloading line,
    // 175 kN²/(2·10 MN/m) = 1531.25 J.
    let area = 43_000.0 - 175e3 * 175e3 / 2e7;
    for method in ["dopri5", "tr-bdf2"] {
        let result = run(0.0, PLASTIC, method);
        let energy = dissipated(&result);
        assert!((energy / area - 1.0).abs() < 1e-6, "{method}: {energy}");
        assert!((lost(&result) / area - 1.0).abs() < 1e-6, "{method}");
    }
}

#[test]
fn with_damping_it_is_the_kinetic_energy_the_car_lost() {
    // Damper and spring together, plastic or elastic: what the element
    // did not give back. Elastic, the damper alone dissipates in
    // contact, and the separation (where the damper's pull cancels the
    // spring) takes the spring's energy with it.
    for (unloading, method) in [(PLASTIC, "dopri5"), (PLASTIC, "tr-bdf2"), ("", "dopri5")] {
        let damping = 5e3;
        let result = run(damping, unloading, method);
        let (energy, lost) = (dissipated(&result), lost(&result));
        // TR-BDF2, of order 2, closes its balances less tightly.
        let tolerance = if method == "dopri5" { 1e-6 } else { 1e-5 };
        assert!(
            (energy / lost - 1.0).abs() < tolerance,
            "{unloading:?} c = {damping}, {method}: {energy} vs {lost}"
        );
    }
}
