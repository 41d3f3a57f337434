//! Every spec of `specs/`: its native code (this crate) and its committed
//! compiled code (`generated/`) agree bit for bit on `M`, `f`, `q̈`, the
//! energies and every other routine the model has, at random states and
//! parameters, and so does the tape on the mechanical energy (the tape's
//! derived routine); and a routine the native compiler declines still
//! runs, on the tape.

use lagrangian_core::random::Lcg;
use lagrangian_generated as generated;
use lagrangian_jit::{Options, accelerate, compile};
use lagrangian_runtime::layout::RoutineKind;
use lagrangian_runtime::nalgebra::{SMatrix, SVector};
use lagrangian_runtime::tape::{DerivedRoutine, Instruction};
use lagrangian_runtime::{Interpreted, InterpretedModel, Jacobians, LagrangianSystem};
use std::cell::Cell;
use std::path::Path;
use std::sync::Arc;

/// Smooth, argument-dependent input values, so wrong arguments show up.
fn inputs(index: usize, args: &[f64]) -> f64 {
    args.iter()
        .enumerate()
        .fold(10.0 * (index as f64 + 1.0), |acc, (i, a)| {
            acc + (a * (i as f64 + 1.7)).sin()
        })
}

fn spec_path(name: &str) -> String {
    format!("{}/../specs/{name}.lpm", env!("CARGO_MANIFEST_DIR"))
}

/// The spec `name` of `specs/`, interpreted.
fn interpreted(name: &str) -> InterpretedModel {
    let source = std::fs::read_to_string(spec_path(name)).unwrap();
    lagrangian_core::interpret(&source).unwrap()
}

fn bits(values: &[f64]) -> Vec<u64> {
    values.iter().map(|x| x.to_bits()).collect()
}

/// Asserts that the model's mechanical energy and `T`, `V` of its energies
/// at one state are, bit for bit, `expected`.
fn assert_mechanical_energy<const N: usize, M: LagrangianSystem<N>>(
    what: &str,
    model: &M,
    (t, q, qd): (f64, &SVector<f64, N>, &SVector<f64, N>),
    expected: [f64; 2],
) {
    let mechanical = model.mechanical_energy(t, q, qd, &inputs);
    let e = model.energies(t, q, qd, &inputs);
    let at = format!("at t = {t}, q = {q:?}, q̇ = {qd:?}");
    let expected = bits(&expected);
    let got = bits(&[mechanical.kinetic, mechanical.potential]);
    assert_eq!(got, expected, "{what}: mechanical energy {at}");
    let got = bits(&[e.kinetic, e.potential]);
    assert_eq!(got, expected, "{what}: T and V of the energies {at}");
}

/// Everything a model computes at one state, as bits.
fn evaluate<const N: usize, M: LagrangianSystem<N>>(
    model: &M,
    state: (f64, &SVector<f64, N>, &SVector<f64, N>, &SVector<f64, N>),
) -> Vec<(&'static str, Vec<u64>)> {
    let (t, q, qd, a) = state;
    let (mass, forcing) = model.mass_matrix_and_forcing_pair(t, q, qd, &inputs);
    let qdd = model.accelerations(t, q, qd, &inputs).ok();
    let e = model.energies(t, q, qd, &inputs);
    let energies = [
        e.kinetic,
        e.potential,
        e.dissipation,
        e.damping_power,
        e.external_power,
    ];
    let (mut m1, mut f1) = (SMatrix::<f64, N, N>::zeros(), SVector::<f64, N>::zeros());
    let powers = model.mass_matrix_forcing_and_powers(t, q, qd, &inputs, &mut m1, &mut f1);
    let mut arguments = vec![0.0; model.input_sites().iter().map(|s| s.1).sum()];
    model.input_arguments(t, q, qd, &inputs, &mut arguments);
    let mut outputs = vec![0.0; model.output_names().len()];
    model.outputs(t, q, qd, a, &inputs, &mut outputs);
    let mut switching = vec![0.0; model.switching_count()];
    model.switching_functions(t, q, qd, &inputs, &mut switching);
    let mut constraints = vec![0.0; model.constraint_count() * (N + 3)];
    model.constraints(t, q, qd, &inputs, &mut constraints);
    let mut j = Jacobians::<N>::default();
    let jacobians = model.jacobians(t, q, qd, a, &inputs, &mut j).map(|()| {
        let blocks = [&j.forcing_q, &j.forcing_qd, &j.mass_times_acceleration_q];
        blocks
            .iter()
            .flat_map(|b| b.iter().copied())
            .collect::<Vec<_>>()
    });
    vec![
        ("M", bits(mass.as_slice())),
        ("f", bits(forcing.as_slice())),
        ("q̈", qdd.map_or(vec![], |v| bits(v.as_slice()))),
        ("energies", bits(&energies)),
        ("one-pass M", bits(m1.as_slice())),
        ("one-pass f", bits(f1.as_slice())),
        ("powers", bits(&powers)),
        ("input arguments", bits(&arguments)),
        ("outputs", bits(&outputs)),
        ("switching", bits(&switching)),
        ("constraints", bits(&constraints)),
        ("jacobians", jacobians.map_or(vec![], |v| bits(&v))),
    ]
}

/// Compares the native code of spec `name` with its compiled model `M` at
/// random states and parameters; returns the routines the native code ran.
fn compare<const N: usize, M: LagrangianSystem<N> + Default>(name: &str) -> Vec<RoutineKind> {
    let mut model = interpreted(name);
    let code = compile(model.tape(), &Options::default()).unwrap();
    assert!(code.declined().is_empty(), "{name}: {:?}", code.declined());
    let derived: Vec<DerivedRoutine> = code.compiled_derived_routines().collect();
    assert_eq!(derived, [DerivedRoutine::MechanicalEnergy], "{name}");
    let native_routines = code.compiled_routines().collect();
    let mut tape = Interpreted::<N>::new(model.clone()).unwrap();
    model.set_native(Arc::new(code));
    let mut native = Interpreted::<N>::new(model).unwrap();
    let mut compiled = M::default();
    let names: Vec<String> = (compiled.parameter_names().iter())
        .map(|s| s.to_string())
        .collect();
    let mut rng = Lcg::new(3);
    for _ in 0..50 {
        for (name, value) in names.iter().zip(compiled.parameters()) {
            let v = value * (1.0 + 0.2 * rng.symmetric()) + 0.1 * rng.symmetric();
            compiled.set_parameter(name, v).unwrap();
            native.set_parameter(name, v).unwrap();
            tape.set_parameter(name, v).unwrap();
        }
        let t = rng.symmetric().abs();
        let mut vector = |scale: f64| SVector::<f64, N>::from_fn(|_, _| scale * rng.symmetric());
        let (q, qd, a) = (vector(1.0), vector(3.0), vector(5.0));
        let state = (t, &q, &qd, &a);
        let (want, got) = (evaluate(&compiled, state), evaluate(&native, state));
        for ((what, w), (_, g)) in want.iter().zip(&got) {
            assert_eq!(w, g, "{name}: {what} at t = {t}, q = {q:?}, q̇ = {qd:?}");
        }
        // T and V of the compiled energies, from each model's mechanical
        // energy (the compiled model's takes them from its energies).
        let e = compiled.energies(t, &q, &qd, &inputs);
        let expected = [e.kinetic, e.potential];
        let state = (t, &q, &qd);
        assert_mechanical_energy(&format!("{name} compiled"), &compiled, state, expected);
        assert_mechanical_energy(&format!("{name} native"), &native, state, expected);
        assert_mechanical_energy(&format!("{name} tape"), &tape, state, expected);
    }
    native_routines
}

#[test]
fn every_spec_agrees_bit_for_bit_with_its_compiled_code() {
    use generated::*;
    let compared = [
        (
            "car_to_car",
            compare::<3, car_to_car::CarToCar>("car_to_car"),
        ),
        (
            "double_pendulum",
            compare::<2, double_pendulum::DoublePendulum>("double_pendulum"),
        ),
        (
            "elastic_pendulum",
            compare::<2, elastic_pendulum::ElasticPendulum>("elastic_pendulum"),
        ),
        (
            "four_bar_linkage",
            compare::<3, four_bar_linkage::FourBarLinkage>("four_bar_linkage"),
        ),
        (
            "kamal_1970",
            compare::<2, kamal_1970::Kamal1970>("kamal_1970"),
        ),
        ("pendulum", compare::<1, pendulum::Pendulum>("pendulum")),
        (
            "pendulum_chain_10",
            compare::<10, pendulum_chain_10::PendulumChain10>("pendulum_chain_10"),
        ),
        (
            "pioneer_wagon",
            compare::<7, pioneer_wagon::PioneerWagon>("pioneer_wagon"),
        ),
        (
            "simple_pendulum",
            compare::<1, simple_pendulum::SimplePendulum>("simple_pendulum"),
        ),
        (
            "slider_crank",
            compare::<3, slider_crank::SliderCrank>("slider_crank"),
        ),
        (
            "spring_mass_damper",
            compare::<1, spring_mass_damper::SpringMassDamper>("spring_mass_damper"),
        ),
        (
            "wall_impact",
            compare::<1, wall_impact::WallImpact>("wall_impact"),
        ),
        (
            "yaris_double_pendulum",
            compare::<3, yaris_double_pendulum::YarisDoublePendulum>("yaris_double_pendulum"),
        ),
        (
            "yaris_occupant",
            compare::<4, yaris_occupant::YarisOccupant>("yaris_occupant"),
        ),
    ];
    for (name, routines) in &compared {
        assert!(routines.contains(&RoutineKind::Dynamics), "{name}");
        assert!(routines.contains(&RoutineKind::Energies), "{name}");
    }
    // Every spec of specs/ is compared.
    let specs_dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../specs");
    let mut on_disk: Vec<String> = (std::fs::read_dir(specs_dir).unwrap())
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|e| e == "lpm"))
        .map(|path| path.file_stem().unwrap().to_string_lossy().into_owned())
        .collect();
    on_disk.sort();
    let names: Vec<&str> = compared.iter().map(|(name, _)| *name).collect();
    assert_eq!(names, on_disk);
}

/// A routine the compiler declines runs on the tape, with the same numbers.
#[test]
fn a_declined_routine_runs_on_the_tape() {
    let plain = interpreted("yaris_double_pendulum");
    let mut partly = plain.clone();
    let options = Options {
        max_instructions: 100,
    };
    let code = compile(partly.tape(), &options).unwrap();
    let declined: Vec<RoutineKind> = code.declined().iter().map(|d| d.0).collect();
    assert!(declined.contains(&RoutineKind::Dynamics), "{code:?}");
    assert!(code.declined()[0].1.0.contains("more than 100"));
    assert!(code.compiled_routines().count() > 0, "{code:?}");
    partly.set_native(Arc::new(code));
    let (plain, partly) = (
        Interpreted::<3>::new(plain).unwrap(),
        Interpreted::<3>::new(partly).unwrap(),
    );
    let (q, qd, a) = (
        SVector::from([-0.1, 0.2, 0.3]),
        SVector::from([1.0, -2.0, 0.5]),
        SVector::from([0.0; 3]),
    );
    assert_eq!(
        evaluate(&plain, (0.01, &q, &qd, &a)),
        evaluate(&partly, (0.01, &q, &qd, &a))
    );
}

/// A panic in an input function reaches the caller of the native code.
#[test]
fn a_panicking_input_panics_the_caller() {
    let mut model = interpreted("yaris_double_pendulum");
    accelerate(&mut model).unwrap();
    assert!(model.has_native());
    let model = Interpreted::<3>::new(model).unwrap();
    let failing = |_: usize, _: &[f64]| -> f64 { panic!("no barrier table") };
    let zero = SVector::<f64, 3>::zeros();
    let run = std::panic::AssertUnwindSafe(|| model.accelerations(0.0, &zero, &zero, &failing));
    let result = std::panic::catch_unwind(run);
    let payload = result.unwrap_err();
    assert_eq!(payload.downcast_ref::<&str>(), Some(&"no barrier table"));
}

/// The paper model's mechanical energy calls no input, on the tape and as
/// native code, while its energies call each input of their power of the
/// forces (the crush element, the barrier tables, the weld) once.
#[test]
fn the_paper_models_mechanical_energy_calls_no_input() {
    let tape = interpreted("yaris_double_pendulum");
    let energies_routine = (tape.tape().routines().iter())
        .find(|r| r.kind == RoutineKind::Energies)
        .unwrap();
    let is_call = |i: &Instruction| matches!(i, Instruction::Input { .. });
    let calls_of_energies = energies_routine.instructions.iter().filter(|i| is_call(i));
    let calls_of_energies = calls_of_energies.count();
    assert!(calls_of_energies >= 6, "{calls_of_energies}");
    let mut native = tape.clone();
    accelerate(&mut native).unwrap();
    let calls = Cell::new(0);
    let counting = |index: usize, args: &[f64]| {
        calls.set(calls.get() + 1);
        inputs(index, args)
    };
    let (q, qd) = ([-0.1, 0.2, 0.3], [1.0, -2.0, 0.5]);
    for (what, model) in [("tape", &tape), ("native", &native)] {
        let energies = model.evaluate_energies(0.01, &q, &qd, &counting).unwrap();
        assert_eq!(calls.replace(0), calls_of_energies, "{what}: energies");
        let mechanical = (model.evaluate_mechanical_energy(0.01, &q, &qd, &counting)).unwrap();
        assert_eq!(calls.get(), 0, "{what}: mechanical energy");
        assert_eq!(mechanical, energies.mechanical(), "{what}");
    }
}
