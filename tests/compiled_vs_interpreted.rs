//! The macro's compiled code and the run-time interpreter evaluate the same
//! optimized program, so they must agree to the last few ulps on every spec.

use lagrangian::nalgebra::SVector;
use lagrangian::{Interpreted, Jacobians, LagrangianSystem};
use lagrangian_core::random::Lcg;

mod models {
    lagrangian::lagrangian!(file = "specs/simple_pendulum.lpm");
    lagrangian::lagrangian!(file = "specs/double_pendulum.lpm");
    lagrangian::lagrangian!(file = "specs/spring_mass_damper.lpm");
    lagrangian::lagrangian!(file = "specs/elastic_pendulum.lpm");
    lagrangian::lagrangian!(file = "specs/yaris_double_pendulum.lpm");
    lagrangian::lagrangian!(file = "specs/pendulum_chain_10.lpm");
    lagrangian::lagrangian!(file = "specs/four_bar_linkage.lpm");
    lagrangian::lagrangian!(file = "specs/slider_crank.lpm");
    // Too large for the canonical form: its program comes from the derivation graph.
    lagrangian::lagrangian!(file = "tests/specs/three_link_conical_pendulum.lpm");
    // An input inside another input's arguments.
    lagrangian::lagrangian!(file = "tests/specs/nested_inputs/friction_under_contact.lpm");
    // Indexed families: elements `x[1]` … as the identifiers `x_1` ….
    lagrangian::lagrangian!(file = "tests/specs/pioneer_families.lpm");
    // Parts: `car[1].m` … as the identifiers `car_1_m` ….
    lagrangian::lagrangian!(file = "tests/specs/parts/train_parts.lpm");
}

/// Random specs from the property tests' generator (`lagrangian-core/tests/
/// random_spec`, written by its `write_macro_fixtures`), all named `Random`.
mod random {
    macro_rules! random_specs {
        ($($name:ident = $file:literal),* $(,)?) => {
            $(pub mod $name {
                lagrangian::lagrangian!(file = $file);
            })*
        };
    }
    random_specs! {
        r1 = "tests/random_specs/random_1.lpm",
        r2 = "tests/random_specs/random_2.lpm",
        r3 = "tests/random_specs/random_3.lpm",
        r4 = "tests/random_specs/random_4.lpm",
        r5 = "tests/random_specs/random_5.lpm",
        r6 = "tests/random_specs/random_6.lpm",
        r7 = "tests/random_specs/random_7.lpm",
        r8 = "tests/random_specs/random_8.lpm",
    }
}

/// Smooth, argument-dependent input values, so wrong arguments show up.
fn inputs(index: usize, args: &[f64]) -> f64 {
    args.iter()
        .enumerate()
        .fold(10.0 * (index as f64 + 1.0), |acc, (i, a)| {
            acc + (a * (i as f64 + 1.7)).sin()
        })
}

/// A vector of values in `[-scale, scale)`.
fn random_vector<const N: usize>(rng: &mut Lcg, scale: f64) -> SVector<f64, N> {
    SVector::from_fn(|_, _| scale * rng.symmetric())
}

/// Distance in units in the last place (0 for bitwise equal values).
fn ulps(a: f64, b: f64) -> u64 {
    if a == b {
        return 0;
    }
    if a.is_nan() || b.is_nan() || a.signum() != b.signum() {
        return u64::MAX;
    }
    a.to_bits().abs_diff(b.to_bits())
}

fn assert_close(what: &str, a: &[f64], b: &[f64], worst: &mut u64) {
    assert_eq!(a.len(), b.len());
    for (k, (x, y)) in a.iter().zip(b).enumerate() {
        let d = ulps(*x, *y);
        // Near zero, ulps are meaningless: accept an absolute 1e-300 too.
        assert!(
            d <= 4 || (x - y).abs() < 1e-300,
            "{what}[{k}]: compiled {x:e} vs interpreted {y:e} ({d} ulps)"
        );
        *worst = (*worst).max(if (x - y).abs() < 1e-300 { 0 } else { d });
    }
}

/// `M`, `f` and the powers from `mass_matrix_forcing_and_powers`.
fn one_pass<const N: usize, M: LagrangianSystem<N>>(
    model: &M,
    t: f64,
    q: &SVector<f64, N>,
    qd: &SVector<f64, N>,
) -> (
    lagrangian::nalgebra::SMatrix<f64, N, N>,
    SVector<f64, N>,
    [f64; 2],
) {
    let (mut mass, mut forcing) = (lagrangian::nalgebra::SMatrix::zeros(), SVector::zeros());
    let powers = model.mass_matrix_forcing_and_powers(t, q, qd, &inputs, &mut mass, &mut forcing);
    (mass, forcing, powers)
}

fn compare<const N: usize, M: LagrangianSystem<N> + Default>(spec: &str) -> u64 {
    let source = std::fs::read_to_string(spec).unwrap();
    let mut interpreted =
        Interpreted::<N>::new(lagrangian_core::interpret(&source).unwrap()).unwrap();
    let mut compiled = M::default();
    assert_eq!(
        compiled.parameters(),
        interpreted.parameters(),
        "{spec}: defaults differ"
    );
    assert_eq!(compiled.coordinate_names(), interpreted.coordinate_names());
    let mut rng = Lcg::new(7);
    let mut worst = 0;
    let names: Vec<String> = compiled
        .parameter_names()
        .iter()
        .map(|s| s.to_string())
        .collect();
    for _ in 0..200 {
        for (name, value) in names.iter().zip(compiled.parameters()) {
            let v = value * (1.0 + 0.2 * rng.symmetric()) + 0.1 * rng.symmetric();
            compiled.set_parameter(name, v).unwrap();
            interpreted.set_parameter(name, v).unwrap();
        }
        let t = rng.symmetric().abs();
        let (q, qd, qdd) = (
            random_vector::<N>(&mut rng, 1.0),
            random_vector::<N>(&mut rng, 3.0),
            random_vector::<N>(&mut rng, 5.0),
        );
        let (mc, fc) = compiled.mass_matrix_and_forcing_pair(t, &q, &qd, &inputs);
        let (mi, fi) = interpreted.mass_matrix_and_forcing_pair(t, &q, &qd, &inputs);
        assert_close("M", mc.as_slice(), mi.as_slice(), &mut worst);
        assert_close("f", fc.as_slice(), fi.as_slice(), &mut worst);
        let (ec, ei) = (
            compiled.energies(t, &q, &qd, &inputs),
            interpreted.energies(t, &q, &qd, &inputs),
        );
        let pack = |e: lagrangian::Energies| {
            [
                e.kinetic,
                e.potential,
                e.dissipation,
                e.damping_power,
                e.external_power,
            ]
        };
        assert_close("energies", &pack(ec), &pack(ei), &mut worst);
        // The one-pass routine gives the same M, f and powers as the two
        // separate routines, compiled and interpreted.
        let separate = [pack(ec)[3], pack(ec)[4]];
        for (what, combined) in [
            ("compiled one-pass", one_pass(&compiled, t, &q, &qd)),
            ("interpreted one-pass", one_pass(&interpreted, t, &q, &qd)),
        ] {
            assert_close(what, combined.0.as_slice(), mc.as_slice(), &mut worst);
            assert_close(what, combined.1.as_slice(), fc.as_slice(), &mut worst);
            assert_close(what, &combined.2, &separate, &mut worst);
        }
        // The input-argument routine reproduces the arguments the inputs receive.
        assert_eq!(compiled.input_sites(), interpreted.input_sites());
        let total: usize = compiled.input_sites().iter().map(|s| s.1).sum();
        let (mut ac, mut ai) = (vec![0.0; total], vec![0.0; total]);
        compiled.input_arguments(t, &q, &qd, &inputs, &mut ac);
        interpreted.input_arguments(t, &q, &qd, &inputs, &mut ai);
        assert_close("input arguments", &ac, &ai, &mut worst);
        let seen = std::cell::RefCell::new(vec![Vec::new(); compiled.input_names().len()]);
        let recording = |index: usize, args: &[f64]| {
            seen.borrow_mut()[index] = args.to_vec();
            inputs(index, args)
        };
        let _ = compiled.mass_matrix_and_forcing_pair(t, &q, &qd, &recording);
        let mut offset = 0;
        for &(input, arity) in compiled.input_sites() {
            assert_eq!(
                seen.borrow()[input],
                ac[offset..offset + arity],
                "{spec}: arguments of input {input}"
            );
            offset += arity;
        }
        assert_eq!(compiled.output_names(), interpreted.output_names());
        let count = compiled.output_names().len();
        let (mut oc, mut oi) = (vec![0.0; count], vec![0.0; count]);
        compiled.outputs(t, &q, &qd, &qdd, &inputs, &mut oc);
        interpreted.outputs(t, &q, &qd, &qdd, &inputs, &mut oi);
        assert_close("outputs", &oc, &oi, &mut worst);
        let (mut jc, mut ji) = (Jacobians::<N>::default(), Jacobians::<N>::default());
        let rc = compiled.jacobians(t, &q, &qd, &qdd, &inputs, &mut jc);
        let ri = interpreted.jacobians(t, &q, &qd, &qdd, &inputs, &mut ji);
        assert_eq!(rc.is_ok(), ri.is_ok());
        if rc.is_ok() {
            assert_close(
                "df/dq",
                jc.forcing_q.as_slice(),
                ji.forcing_q.as_slice(),
                &mut worst,
            );
            assert_close(
                "df/dqd",
                jc.forcing_qd.as_slice(),
                ji.forcing_qd.as_slice(),
                &mut worst,
            );
            assert_close(
                "d(Ma)/dq",
                jc.mass_times_acceleration_q.as_slice(),
                ji.mass_times_acceleration_q.as_slice(),
                &mut worst,
            );
        }
    }
    worst
}

#[test]
fn every_spec_agrees() {
    let worst = [
        compare::<1, models::SimplePendulum>("specs/simple_pendulum.lpm"),
        compare::<2, models::DoublePendulum>("specs/double_pendulum.lpm"),
        compare::<1, models::SpringMassDamper>("specs/spring_mass_damper.lpm"),
        compare::<2, models::ElasticPendulum>("specs/elastic_pendulum.lpm"),
        compare::<3, models::YarisDoublePendulum>("specs/yaris_double_pendulum.lpm"),
        compare::<10, models::PendulumChain10>("specs/pendulum_chain_10.lpm"),
        compare::<3, models::FourBarLinkage>("specs/four_bar_linkage.lpm"),
        compare::<3, models::SliderCrank>("specs/slider_crank.lpm"),
        compare::<2, models::FrictionUnderContact>(
            "tests/specs/nested_inputs/friction_under_contact.lpm",
        ),
        compare::<6, models::ThreeLinkConicalPendulum>(
            "tests/specs/three_link_conical_pendulum.lpm",
        ),
        compare::<7, models::PioneerWagon>("tests/specs/pioneer_families.lpm"),
        compare::<4, models::TrainParts>("tests/specs/parts/train_parts.lpm"),
    ];
    println!("worst ulp difference per spec: {worst:?}");
}

/// A model with outputs that call an input at their own arguments and use
/// the accelerations and the time (the double pendulum's have neither input
/// nor time).
mod with_outputs {
    lagrangian::lagrangian! {
        model Cart;
        coordinates { x, th }
        parameters { m = 2.0, c = 0.5 }
        inputs { push(s) }
        kinetic = 0.5 * m * pow(dot(x), 2) + 0.5 * pow(dot(th), 2) + c * dot(x) * dot(th) * cos(th);
        potential = m * (1.0 - cos(th));
        force x = push(x + th);
        /// Mass times acceleration plus a push.
        output a = m * ddot(x) + push(2.0 * x);
        output b [rad/s^2] = c * pow(dot(th), 2) + t * ddot(th) / 3.0;
    }
}

/// Outputs, compiled and interpreted, are equal bit for bit at the
/// accelerations the equations give.
#[test]
fn outputs_agree_bit_for_bit() {
    fn outputs_of<const N: usize, M: LagrangianSystem<N>>(model: &M, rng: &mut Lcg) -> Vec<f64> {
        let t = rng.symmetric().abs();
        let (q, qd) = (random_vector::<N>(rng, 1.0), random_vector::<N>(rng, 3.0));
        let qdd = model.accelerations(t, &q, &qd, &inputs).unwrap();
        let mut out = vec![0.0; model.output_names().len()];
        model.outputs(t, &q, &qd, &qdd, &inputs, &mut out);
        out
    }
    fn same<const N: usize, M: LagrangianSystem<N> + Default>(spec: &str) {
        let interpreted = Interpreted::<N>::new(lagrangian_core::interpret(spec).unwrap()).unwrap();
        let compiled = M::default();
        assert_eq!(compiled.output_names(), interpreted.output_names());
        assert!(!compiled.output_names().is_empty());
        let (mut a, mut b) = (Lcg::new(11), Lcg::new(11));
        for _ in 0..200 {
            let (c, i) = (
                outputs_of(&compiled, &mut a),
                outputs_of(&interpreted, &mut b),
            );
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&c), bits(&i), "compiled {c:?} vs interpreted {i:?}");
        }
    }
    let double = std::fs::read_to_string("specs/double_pendulum.lpm").unwrap();
    same::<2, models::DoublePendulum>(&double);
    let cart = "model Cart; coordinates { x, th } parameters { m = 2.0, c = 0.5 }
        inputs { push(s) }
        kinetic = 0.5 * m * pow(dot(x), 2) + 0.5 * pow(dot(th), 2) + c * dot(x) * dot(th) * cos(th);
        potential = m * (1.0 - cos(th));
        force x = push(x + th);
        /// Mass times acceleration plus a push.
        output a = m * ddot(x) + push(2.0 * x);
        output b [rad/s^2] = c * pow(dot(th), 2) + t * ddot(th) / 3.0;";
    same::<2, with_outputs::Cart>(cart);
    assert_eq!(with_outputs::Cart::OUTPUTS, ["a", "b"]);
}

#[test]
fn random_specs_agree() {
    let worst = [
        compare::<3, random::r1::Random>("tests/random_specs/random_1.lpm"),
        compare::<3, random::r2::Random>("tests/random_specs/random_2.lpm"),
        compare::<2, random::r3::Random>("tests/random_specs/random_3.lpm"),
        compare::<3, random::r4::Random>("tests/random_specs/random_4.lpm"),
        compare::<3, random::r5::Random>("tests/random_specs/random_5.lpm"),
        compare::<3, random::r6::Random>("tests/random_specs/random_6.lpm"),
        compare::<2, random::r7::Random>("tests/random_specs/random_7.lpm"),
        compare::<3, random::r8::Random>("tests/random_specs/random_8.lpm"),
    ];
    println!("worst ulp difference per random spec: {worst:?}");
}

#[test]
fn the_yaris_model_has_jacobians_and_input_constants() {
    use models::YarisDoublePendulum as Y;
    assert_eq!(Y::INPUT_CRUSH, 0);
    assert_eq!(Y::INPUTS[Y::INPUT_BARRIER_Z2], "barrier_z2");
    assert_eq!(Y::COORDINATES, ["r", "theta1", "theta2"]);
    let err = models::DoublePendulum::default().jacobians(
        0.0,
        &SVector::zeros(),
        &SVector::zeros(),
        &SVector::zeros(),
        &inputs,
        &mut Jacobians::default(),
    );
    assert_eq!(err, Err(lagrangian::ModelError::JacobiansNotDerived));
}

/// A driven constraint that calls an input and depends on time.
mod with_constraints {
    lagrangian::lagrangian! {
        model Driven;
        coordinates { x, y }
        parameters { m = 2.0, a = 0.3 }
        inputs { lift(s) { d(s) = 2.0 * s } }
        kinetic = 0.5 * m * (pow(dot(x), 2) + pow(dot(y), 2));
        potential = m * 9.81 * y;
        constraint track = y - a * sin(3.0 * t) * x - lift(x);
    }
}

/// The constraint terms `g`, `g_t`, `G`, `γ`, compiled and interpreted, are
/// equal bit for bit.
#[test]
fn constraints_agree_bit_for_bit() {
    fn terms<const N: usize, M: LagrangianSystem<N>>(model: &M, rng: &mut Lcg) -> Vec<u64> {
        let t = rng.symmetric().abs();
        let (q, qd) = (random_vector::<N>(rng, 1.0), random_vector::<N>(rng, 3.0));
        let mut out = vec![0.0; model.constraint_count() * (N + 3)];
        model.constraints(t, &q, &qd, &inputs, &mut out);
        out.iter().map(|x| x.to_bits()).collect()
    }
    fn same<const N: usize, M: LagrangianSystem<N> + Default>(spec: &str) {
        let interpreted = Interpreted::<N>::new(lagrangian_core::interpret(spec).unwrap()).unwrap();
        let compiled = M::default();
        assert_eq!(compiled.constraint_names(), interpreted.constraint_names());
        assert!(compiled.constraint_count() > 0);
        let (mut a, mut b) = (Lcg::new(5), Lcg::new(5));
        for _ in 0..200 {
            assert_eq!(terms(&compiled, &mut a), terms(&interpreted, &mut b));
        }
    }
    let read = |name: &str| std::fs::read_to_string(format!("specs/{name}.lpm")).unwrap();
    same::<3, models::FourBarLinkage>(&read("four_bar_linkage"));
    same::<3, models::SliderCrank>(&read("slider_crank"));
    let driven = "model Driven; coordinates { x, y } parameters { m = 2.0, a = 0.3 }
        inputs { lift(s) { d(s) = 2.0 * s } }
        kinetic = 0.5 * m * (pow(dot(x), 2) + pow(dot(y), 2));
        potential = m * 9.81 * y;
        constraint track = y - a * sin(3.0 * t) * x - lift(x);";
    same::<2, with_constraints::Driven>(driven);
}
