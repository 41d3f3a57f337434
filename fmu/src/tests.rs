//! The instance logic on the paper's scenario, without the C layer:
//! Co-Simulation and Model Exchange (driven by a fixed-step RK4 with event
//! detection, as a host would) against `lagrangian_sim::simulate`, a
//! parameter set through the variables, and the state machine's refusals.

use crate::instance::{Instance, Interface, Mode};
use crate::resources::{Loaded, load_texts};
use crate::variables::{Causality, Quantity};
use lagrangian_runtime::{Interpreted, WithDimension};
use lagrangian_sim::simulate::simulate;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The paper's spec and scenario, loaded as an FMU loads its resources.
fn paper() -> Loaded {
    let spec_path = root().join("specs/yaris_double_pendulum.lpm");
    let scenario_path = root().join("specs/scenarios/yaris_full_frontal.toml");
    let spec = std::fs::read_to_string(&spec_path).unwrap();
    let scenario = std::fs::read_to_string(&scenario_path).unwrap();
    load_texts((&spec_path, &spec), Some((&scenario_path, &scenario))).unwrap()
}

fn instance(interface: Interface) -> Instance {
    let loaded = paper();
    let guid = loaded.guid.clone();
    Instance::new("test", interface, &guid, loaded).unwrap()
}

/// `lpm simulate`'s maximum crush for the paper scenario with `settings`.
fn reference_max_crush(settings: &[String]) -> f64 {
    struct Run<'a>(&'a lagrangian_sim::scenario::Scenario);
    impl WithDimension for Run<'_> {
        type Output = f64;
        fn run<const N: usize>(self, system: Interpreted<N>) -> f64 {
            let result = simulate(&system, self.0).unwrap();
            result.summary.max_crush_m.unwrap()
        }
    }
    let loaded = paper();
    let names = lagrangian_sim::scenario::ModelNames::of_interpreted(&loaded.model);
    let path = root().join("specs/scenarios/yaris_full_frontal.toml");
    let scenario = lagrangian_sim::scenario::Scenario::load(
        &path,
        &names,
        &lagrangian_sim::scenario::Override::parse_all(settings).unwrap(),
    )
    .unwrap();
    loaded.model.with_dimension(Run(&scenario)).unwrap()
}

fn crush(instance: &mut Instance) -> f64 {
    let vr = instance.variables.reference("metrics.crush").unwrap();
    let mut value = [0.0];
    instance.get_real(&[vr], &mut value).unwrap();
    value[0]
}

/// The maximum crush over a Co-Simulation run with 1 ms steps.
fn co_simulation_max_crush(instance: &mut Instance) -> f64 {
    instance.enter_initialization().unwrap();
    instance.exit_initialization().unwrap();
    let (h, steps) = (1e-3, 150);
    let mut max = crush(instance);
    for k in 0..steps {
        instance.do_step(k as f64 * h, h).unwrap();
        max = max.max(crush(instance));
    }
    max
}

#[test]
fn co_simulation_reproduces_the_simulators_maximum_crush() {
    let mut cs = instance(Interface::CoSimulation);
    let max = co_simulation_max_crush(&mut cs);
    let reference = reference_max_crush(&[]);
    // The sampling (1 ms here, 0.1 ms in lpm) misses at most the curvature
    // at the peak; the trajectory itself is the same integrator's.
    let relative = (max - reference).abs() / reference;
    assert!(relative < 2e-3, "CS {max} vs {reference}: {relative:e}");
    assert!(
        !cs.pending_events.is_empty(),
        "the crush peak and weld failure are events"
    );
}

#[test]
fn a_parameter_set_through_its_value_reference_changes_the_run_as_set_does() {
    let mut cs = instance(Interface::CoSimulation);
    let vr = cs.variables.reference("m1").unwrap();
    cs.set_real(&[vr], &[700.0]).unwrap();
    let max = co_simulation_max_crush(&mut cs);
    let reference = reference_max_crush(&["m1=700".to_string()]);
    let unchanged = reference_max_crush(&[]);
    assert!((reference - unchanged).abs() > 0.01, "m1 matters");
    let relative = (max - reference).abs() / reference;
    assert!(relative < 2e-3, "CS {max} vs {reference}: {relative:e}");
}

/// The maximum crush under the fixed-step RK4 host of `me_tests` (event
/// mode where an indicator changed sign within a step, at the step's end,
/// as a host without root finding does).
fn model_exchange_max_crush(me: &mut Instance, h: f64, t_end: f64) -> f64 {
    crate::me_tests::max_over_run(me, "crush", h, t_end)
}

#[test]
fn model_exchange_reproduces_the_simulators_maximum_crush() {
    let mut me = instance(Interface::ModelExchange);
    let max = model_exchange_max_crush(&mut me, 1e-5, 0.15);
    let reference = reference_max_crush(&[]);
    let relative = (max - reference).abs() / reference;
    assert!(relative < 5e-3, "ME {max} vs {reference}: {relative:e}");
}

#[test]
fn the_variables_are_states_parameters_and_outputs_in_order() {
    let cs = instance(Interface::CoSimulation);
    let list = &cs.variables.list;
    let names: Vec<&str> = list.iter().take(9).map(|v| v.name.as_str()).collect();
    let expected = [
        "r",
        "theta1",
        "theta2",
        "der(r)",
        "der(theta1)",
        "der(theta2)",
        "der(der(r))",
        "der(der(theta1))",
        "der(der(theta2))",
    ];
    assert_eq!(names, expected);
    let m1 = &list[cs.variables.reference("m1").unwrap() as usize];
    assert_eq!(m1.causality(), Causality::Parameter);
    assert_eq!((m1.unit.as_deref(), m1.start), (Some("kg"), Some(539.0)));
    assert!(
        m1.description.starts_with("Mass of body 1"),
        "{}",
        m1.description
    );
    // The scenario's value, not the spec's default.
    let k_tor = &list[cs.variables.reference("k_tor").unwrap() as usize];
    assert_eq!(k_tor.start, Some(0.0));
    // The scenario binds every input: none is left to the host.
    assert!(list.iter().all(|v| v.causality() != Causality::Input));
    let force = cs.variables.reference("front_end.force").unwrap();
    assert_eq!(list[force as usize].causality(), Causality::Output);
    assert_eq!(cs.variables.derivative_of(3), Some(1));
    assert_eq!(cs.variables.derivative_of(6), Some(4));
    assert_eq!(list[6].quantity, Quantity::Acceleration(0));
}

#[test]
fn an_unbound_input_is_an_fmi_input_that_drives_the_model() {
    let spec = "model Block;\ncoordinates { x [m] }\nparameters { m [kg] = 2.0 }\n\
                inputs { /// Push.\n push(t [s]) [N] }\n\
                kinetic = 0.5 * m * pow(dot(x), 2);\nforce x = push(t);\n";
    let loaded = load_texts((Path::new("block.lpm"), spec), None).unwrap();
    assert_eq!(loaded.unbound, [0]);
    let guid = loaded.guid.clone();
    let mut cs = Instance::new("block", Interface::CoSimulation, &guid, loaded).unwrap();
    let push = cs.variables.reference("push").unwrap();
    assert_eq!(
        cs.variables.list[push as usize].causality(),
        Causality::Input
    );
    cs.enter_initialization().unwrap();
    cs.exit_initialization().unwrap();
    cs.set_real(&[push], &[4.0]).unwrap();
    cs.do_step(0.0, 1.0).unwrap();
    let (x, v) = (0, cs.variables.reference("der(x)").unwrap());
    let mut values = [0.0; 3];
    cs.get_real(&[x, v, push], &mut values).unwrap();
    // x = ½ (F/m) t², v = (F/m) t.
    assert!((values[0] - 1.0).abs() < 1e-9, "{values:?}");
    assert!((values[1] - 2.0).abs() < 1e-9, "{values:?}");
    assert_eq!(values[2], 4.0);
}

#[test]
fn calls_out_of_order_and_bad_references_are_errors_that_say_why() {
    let mut cs = instance(Interface::CoSimulation);
    let early = cs.do_step(0.0, 1e-3).unwrap_err();
    assert!(
        early.message.contains("not allowed in state instantiated"),
        "{early:?}"
    );
    let mut value = [0.0];
    assert!(
        cs.get_real(&[0], &mut value).is_err(),
        "read before initialization"
    );
    let output = cs.variables.reference("metrics.crush").unwrap();
    let set = cs.set_real(&[output], &[1.0]).unwrap_err();
    assert!(
        set.message.contains("`metrics.crush`") && set.message.contains("output"),
        "{set:?}"
    );
    cs.enter_initialization().unwrap();
    cs.exit_initialization().unwrap();
    let unknown = cs.get_real(&[9999], &mut value).unwrap_err();
    assert!(
        unknown.message.contains("unknown value reference 9999"),
        "{unknown:?}"
    );
    let wrong_time = cs.do_step(0.5, 1e-3).unwrap_err();
    assert!(
        wrong_time.message.contains("the FMU is at t = 0"),
        "{wrong_time:?}"
    );
    cs.do_step(0.0, 1e-3).unwrap();
    cs.reset();
    assert_eq!((cs.mode(), cs.time()), (Mode::Instantiated, 0.0));
}

#[test]
fn a_saved_state_restores_the_run() {
    let mut cs = instance(Interface::CoSimulation);
    cs.enter_initialization().unwrap();
    cs.exit_initialization().unwrap();
    cs.do_step(0.0, 0.02).unwrap();
    let saved = cs.snapshot();
    cs.do_step(0.02, 0.03).unwrap();
    let later = crush(&mut cs);
    cs.restore(&saved);
    assert_eq!(cs.time(), 0.02);
    cs.do_step(0.02, 0.03).unwrap();
    assert_eq!(crush(&mut cs), later);
}

#[test]
fn a_guid_of_another_export_is_refused() {
    let loaded = paper();
    let wrong = Instance::new("x", Interface::CoSimulation, "{0}", loaded)
        .err()
        .unwrap();
    assert!(wrong.message.contains("different exports"), "{wrong:?}");
}

/// The variable names of the shipped spec `name` under its scenario.
fn names(spec: &str, scenario: &str) -> Result<Vec<String>, Box<dyn std::error::Error>> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../specs");
    let (spec_path, scenario_path) = (root.join(spec), root.join("scenarios").join(scenario));
    let spec = std::fs::read_to_string(&spec_path).unwrap();
    let scenario = std::fs::read_to_string(&scenario_path).unwrap();
    let loaded = load_texts((&spec_path, &spec), Some((&scenario_path, &scenario)))?;
    let model = &loaded.compiled.model;
    let variables = crate::variables::Variables::new(model, &loaded.scenario, &loaded.unbound)?;
    Ok(variables.list.into_iter().map(|v| v.name).collect())
}

#[test]
fn a_spec_output_called_crush_or_deceleration_keeps_its_name_beside_the_fmus() {
    let car_to_car = names("car_to_car.lpm", "car_to_car.toml").unwrap();
    let wall = names("wall_impact.lpm", "wall_impact.toml").unwrap();
    for name in [
        "crush",
        "metrics.crush",
        "metrics.deceleration",
        "front_a.force",
    ] {
        assert!(
            car_to_car.contains(&name.to_string()),
            "{name}: {car_to_car:?}"
        );
    }
    for name in ["deceleration", "metrics.crush", "metrics.deceleration"] {
        assert!(wall.contains(&name.to_string()), "{name}: {wall:?}");
    }
}
