//! The compiled plant ([`crate::plant::compiled`]) against the
//! interpreter's: the paper's model as `lpm generate` compiles it runs a
//! Co-Simulation bit for bit as the interpreted one, and refuses resources
//! of another spec.

use crate::instance::{Instance, Interface};
use crate::plant::{PlantFactory, compiled, plant};
use crate::resources::{Loaded, load_texts};
use lagrangian_generated::yaris_double_pendulum::YarisDoublePendulum;
use std::path::Path;

fn load(spec: &str, scenario: Option<&str>) -> Loaded {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let spec_path = root.join(spec);
    let spec = std::fs::read_to_string(&spec_path).unwrap();
    let scenario = scenario.map(|s| {
        let path = root.join(s);
        let text = std::fs::read_to_string(&path).unwrap();
        (path, text)
    });
    let scenario = scenario.as_ref().map(|(p, t)| (p.as_path(), t.as_str()));
    load_texts((&spec_path, &spec), scenario).unwrap()
}

fn paper(factory: PlantFactory) -> Instance {
    let loaded = load(
        "specs/yaris_double_pendulum.lpm",
        Some("specs/scenarios/yaris_full_frontal.toml"),
    );
    let guid = loaded.guid.clone();
    Instance::with_plant("paper", Interface::CoSimulation, &guid, loaded, factory).unwrap()
}

/// Every Real variable of `instance`.
fn reals(instance: &mut Instance) -> Vec<f64> {
    let vrs: Vec<u32> = (0..instance.variables.list.len() as u32).collect();
    let mut values = vec![0.0; vrs.len()];
    instance.get_real(&vrs, &mut values).unwrap();
    values
}

#[test]
fn the_compiled_plant_runs_the_paper_scenario_bit_for_bit_as_the_interpreter() {
    let mut interpreted = paper(plant);
    let mut compiled = paper(compiled::<3, YarisDoublePendulum>);
    let m1 = interpreted.variables.reference("m1").unwrap();
    for instance in [&mut interpreted, &mut compiled] {
        instance.set_real(&[m1], &[600.0]).unwrap();
        instance.enter_initialization().unwrap();
        instance.exit_initialization().unwrap();
    }
    let h = 1e-3;
    for k in 0..150 {
        let (a, b) = (reals(&mut interpreted), reals(&mut compiled));
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&a), bits(&b), "at step {k}: {a:?}\nvs {b:?}");
        for instance in [&mut interpreted, &mut compiled] {
            instance.do_step(k as f64 * h, h).unwrap();
        }
    }
    assert_eq!(interpreted.pending_events, compiled.pending_events);
    assert!(!compiled.pending_events.is_empty());
}

#[test]
fn a_compiled_plant_refuses_the_resources_of_another_spec() {
    let loaded = load("specs/spring_mass_damper.lpm", None);
    let guid = loaded.guid.clone();
    let factory = compiled::<3, YarisDoublePendulum>;
    let refused = Instance::with_plant("other", Interface::CoSimulation, &guid, loaded, factory);
    let message = refused.err().unwrap().message;
    assert_eq!(
        message,
        "resources/model.lpm is not the spec this FMU binary was compiled from \
         (its coordinates, parameters, inputs, parameter values differ)"
    );
}
