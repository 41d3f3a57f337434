//! Runs of the `test_spring` components through the simulator (moved out of
//! `components::test_spring`, which must not reach the run engine above it).

use crate::scenario::{ModelNames, Scenario};
use crate::simulate::simulate;
use lagrangian_runtime::Interpreted;

/// A unit mass on the spring input.
const MASS: &str = "model Mass;\n\
    coordinates { x [m], }\n\
    parameters { m [kg] = 1.0, }\n\
    inputs { spring(x [m], v [m/s]) [N], }\n\
    kinetic = 0.5 * m * pow(dot(x), 2);\n\
    force x = spring(x, dot(x));\n";

/// From `x = 0` at 1 m/s on k = 100 N/m: `x = 0.1 sin(10 t)`, which
/// reaches 0.05 m at `t = asin(1/2)/10 = π/60`; free flight at
/// `cos(π/6)` m/s after.
const SCENARIO: &str = "[simulation]\nt_end = 0.1\n\
    [initial]\nvelocities = { x = 1.0 }\n\
    [components.link]\ntype = \"test_spring\"\ninputs = { force = \"spring\" }\n\
    stiffness = 100.0\nbreaks_at = 0.05\n";

fn mass() -> (Interpreted<1>, ModelNames) {
    let model = lagrangian_core::interpret(MASS).unwrap();
    let names = ModelNames::of_interpreted(&model);
    (Interpreted::new(model).unwrap(), names)
}

#[test]
fn a_component_registered_in_one_line_has_its_event_fire_in_a_run() {
    let (model, names) = mass();
    let scenario = Scenario::parse(SCENARIO, None, &names, &[]).unwrap();
    assert_eq!(scenario.inputs.event_count(), 1);
    let result = simulate(&model, &scenario).unwrap();
    let broke = std::f64::consts::PI / 60.0;
    let [event] = result.events.as_slice() else {
        panic!("{:?}", result.events)
    };
    assert_eq!(event.component, "link");
    assert_eq!(event.description, "breaks at x = 0.0500 m");
    assert!((event.t - broke).abs() < 1e-7, "{}", event.t);
    let last = result.samples.last().unwrap();
    let v = (std::f64::consts::PI / 6.0).cos();
    assert!((last.v[0] - v).abs() < 1e-6, "{}", last.v[0]);
    assert!((last.q[0] - (0.05 + v * (0.1 - broke))).abs() < 1e-6);
    // The summary's failure time is the component's.
    let failed = result.summary.weld_failure_time_s.unwrap();
    assert!((failed - broke).abs() < 1e-7, "{failed}");
}

#[test]
fn its_section_is_checked_like_every_other() {
    let (_, names) = mass();
    let refused = |text: &str| Scenario::parse(text, None, &names, &[]).unwrap_err();
    let e = refused(&SCENARIO.replace("breaks_at", "breaks_after"));
    assert_eq!(
        e.message,
        "unknown field `breaks_after`, expected one of `inputs`, `stiffness`, `breaks_at` (did you mean `breaks_at`?)"
    );
    let e = refused(&SCENARIO.replace("stiffness = 100.0", "stiffness = -1.0"));
    assert_eq!(
        e.message,
        "components.link.stiffness = -1: must be a positive, finite number"
    );
}
