//! Model Exchange against closed forms and `lpm simulate`: the components'
//! modes start and switch through the event indicators as the simulator
//! starts and switches them, a contact that begins at zero force included
//! (issue 33).

use crate::instance::{Instance, Interface};
use crate::resources::{Loaded, load_texts};
use std::path::{Path, PathBuf};

fn conformance(file: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../python/tests/conformance")
        .join(file)
}

/// The spec and scenario `scenario_text` (of the file `scenario`) loaded
/// as an FMU loads its resources.
fn load(spec: &Path, scenario: &Path, scenario_text: &str) -> Loaded {
    let spec_text = std::fs::read_to_string(spec).unwrap();
    load_texts((spec, &spec_text), Some((scenario, scenario_text))).unwrap()
}

fn model_exchange(loaded: Loaded) -> Instance {
    let guid = loaded.guid.clone();
    Instance::new("me", Interface::ModelExchange, &guid, loaded).unwrap()
}

/// The value of the variable `name`; `crush`, the scenario's crush signal,
/// under its name with or without the namespace of what the FMU adds
/// (`metrics.crush`).
fn read(me: &mut Instance, name: &str) -> f64 {
    let namespaced = format!("metrics.{name}");
    let vr = (me.variables.reference(name))
        .filter(|_| name != "crush")
        .or_else(|| me.variables.reference(&namespaced))
        .or_else(|| me.variables.reference(name))
        .unwrap_or_else(|| panic!("no variable {name}"));
    let mut value = [0.0];
    me.get_real(&[vr], &mut value).unwrap();
    value[0]
}

/// Drives `me` as a host without root finding does (FMPy's Euler): the
/// initial event iteration, then fixed RK4 steps of `h` to `t_end`,
/// entering event mode where an indicator changed sign within a step;
/// the largest value of `name` at the steps' ends.
pub(crate) fn max_over_run(me: &mut Instance, name: &str, h: f64, t_end: f64) -> f64 {
    me.enter_initialization().unwrap();
    me.exit_initialization().unwrap();
    me.new_discrete_states().unwrap();
    me.enter_continuous_time_mode().unwrap();
    let n = me.state_count();
    let mut g = vec![0.0; me.event_count()];
    me.event_indicators(&mut g).unwrap();
    let mut x = me.states();
    let (mut t, mut max) = (0.0, read(me, name));
    let rate = |me: &mut Instance, t: f64, x: &[f64]| {
        me.set_time(t).unwrap();
        me.set_states(x).unwrap();
        let mut dx = vec![0.0; n];
        me.derivatives(&mut dx).unwrap();
        dx
    };
    let along = |x: &[f64], k: &[f64], c: f64| -> Vec<f64> {
        x.iter().zip(k).map(|(x, k)| x + c * k).collect()
    };
    while t < t_end - 0.5 * h {
        let k1 = rate(me, t, &x);
        let k2 = rate(me, t + h / 2.0, &along(&x, &k1, h / 2.0));
        let k3 = rate(me, t + h / 2.0, &along(&x, &k2, h / 2.0));
        let k4 = rate(me, t + h, &along(&x, &k3, h));
        for i in 0..n {
            x[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
        t += h;
        me.set_time(t).unwrap();
        me.set_states(&x).unwrap();
        let before = g.clone();
        me.event_indicators(&mut g).unwrap();
        if before.iter().zip(&g).any(|(a, b)| (*a < 0.0) != (*b < 0.0)) {
            me.enter_event_mode().unwrap();
            if me.new_discrete_states().unwrap().states_changed {
                x = me.states();
            }
            me.enter_continuous_time_mode().unwrap();
            me.event_indicators(&mut g).unwrap();
        }
        max = max.max(read(me, name));
    }
    max
}

/// One mass at `v0 = 10 m/s` onto a wall through a linear crush spring
/// (`k = 4 MN/m`, no damping) at zero deflection, so at zero force, at the
/// start: the element is in contact from the start, and the maximum crush
/// is the closed form `v0·sqrt(m/k)` (0.158114 m for `m = 1000 kg`), not the
/// 1 m of a mass that flies through an element never engaged. With plastic
/// unloading the crush rate's event function is zero at the start too.
#[test]
fn a_contact_that_begins_at_zero_force_is_engaged() {
    let (spec, scenario) = (
        conformance("zero_force_contact.lpm"),
        conformance("zero_force_contact.toml"),
    );
    let closed_form = 10.0 * (1000.0f64 / 4.0e6).sqrt();
    let elastic = std::fs::read_to_string(&scenario).unwrap();
    let plastic = format!("{elastic}unloading = \"plastic\"\nunloading_stiffness = 4.0e7\n");
    for text in [elastic, plastic] {
        let loaded = load(&spec, &scenario, &text);
        let mut me = model_exchange(loaded);
        let max = max_over_run(&mut me, "crush", 1e-5, 0.1);
        let relative = (max - closed_form).abs() / closed_form;
        assert!(
            relative < 1e-6,
            "{text}: ME {max} vs {closed_form}: {relative:e}"
        );
    }
}

/// `lpm simulate`'s maximum crush and its components' dissipated energies
/// at the end of the run, for the spec and scenario of `loaded`.
fn simulated(loaded: &Loaded) -> (f64, Vec<(String, f64)>) {
    use lagrangian_runtime::{Interpreted, WithDimension};
    struct Run<'a>(&'a lagrangian_sim::scenario::Scenario);
    impl WithDimension for Run<'_> {
        type Output = (f64, Vec<(String, f64)>);
        fn run<const N: usize>(self, system: Interpreted<N>) -> Self::Output {
            let result = lagrangian_sim::simulate::simulate(&system, self.0).unwrap();
            let summary = result.summary;
            (summary.max_crush_m.unwrap(), summary.dissipated_by)
        }
    }
    let model = loaded.compiled.interpreted();
    model.with_dimension(Run(&loaded.scenario)).unwrap()
}

/// The Pioneer car's six Bouc–Wen springs carry a state each, and every
/// dissipative component the energy it has dissipated: Model Exchange
/// hands them to the host as continuous states `z` after `(q, q̇)`, so that
/// the host integrates them with the rest. Driven by fixed-step RK4 at
/// 10 µs, the maximum crush and the energies the components dissipated
/// agree with `lpm simulate`'s (DOPRI5 at rtol 1e-8; the dissipated
/// energies are the states `z` the host integrated: held at their initial
/// values, they would stay 0).
#[test]
fn internal_states_are_continuous_states_of_model_exchange() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../specs");
    let (spec, scenario) = (
        root.join("pioneer_wagon.lpm"),
        root.join("scenarios/pioneer_wagon.toml"),
    );
    let text = std::fs::read_to_string(&scenario).unwrap();
    let (reference, dissipated) = simulated(&load(&spec, &scenario, &text));
    let mut me = model_exchange(load(&spec, &scenario, &text));
    let z = me.variables.reference("spring1.z").unwrap() as usize;
    let rate = me.variables.reference("der(spring1.z)").unwrap() as usize;
    assert_eq!(me.variables.derivative_of(rate), Some(z + 1));
    let max = max_over_run(&mut me, "crush", 1e-5, 0.25);
    let relative = (max - reference).abs() / reference;
    assert!(relative < 1e-4, "ME {max} vs {reference}: {relative:e}");
    assert!(me.state_count() > 2 * me.variables.dimension + 6);
    // A component that stores nearly all it absorbs (the wall unloads
    // elastically) dissipates the difference of two large numbers: the
    // tolerance has a part of the whole energy dissipated.
    let total: f64 = dissipated.iter().map(|(_, e)| e.abs()).sum();
    for (name, energy) in dissipated {
        let host = read(&mut me, &format!("{name}.dissipated_energy"));
        let tolerance = 1e-3 * energy.abs() + 1e-5 * total;
        assert!(
            (host - energy).abs() < tolerance,
            "{name}: ME {host} J vs {energy} J"
        );
    }
}

/// `lpm simulate`'s coordinates at the end of the run of `loaded`.
fn simulated_end(loaded: &Loaded) -> Vec<f64> {
    use lagrangian_runtime::{Interpreted, WithDimension};
    struct Run<'a>(&'a lagrangian_sim::scenario::Scenario);
    impl WithDimension for Run<'_> {
        type Output = Vec<f64>;
        fn run<const N: usize>(self, system: Interpreted<N>) -> Self::Output {
            let result = lagrangian_sim::simulate::simulate(&system, self.0).unwrap();
            result.samples.last().unwrap().q.clone()
        }
    }
    let model = loaded.compiled.interpreted();
    model.with_dimension(Run(&loaded.scenario)).unwrap()
}

/// The four-bar linkage's loop constraints: Model Exchange hands the host
/// the constrained `q̈` (with the scenario's stabilization, as `lpm
/// simulate` integrates it), so a host's RK4 at 0.1 ms ends 1 s of the
/// linkage's swing where the simulator does, on the constraints.
#[test]
fn model_exchange_runs_the_constrained_accelerations() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../specs");
    let (spec, scenario) = (
        root.join("four_bar_linkage.lpm"),
        root.join("scenarios/four_bar_linkage.toml"),
    );
    let text = std::fs::read_to_string(&scenario).unwrap();
    let text = text.replace("t_end = 5.0", "t_end = 1.0");
    let reference = simulated_end(&load(&spec, &scenario, &text));
    let mut me = model_exchange(load(&spec, &scenario, &text));
    max_over_run(&mut me, "theta1", 1e-4, 1.0);
    let end = &me.states()[..reference.len()];
    for (host, simulated) in end.iter().zip(&reference) {
        assert!(
            (host - simulated).abs() < 1e-6,
            "ME {end:?} vs {reference:?}"
        );
    }
}
