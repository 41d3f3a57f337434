//! Conservative specs conserve T + V under a classical RK4 integration of the
//! derived `M q̈ = f`: the drift must shrink like h⁴ and stay below 1e-9 of the
//! energy scale. A wrong sign or a missing term in f breaks this at once.

use lagrangian::nalgebra::SVector;
use lagrangian::{ConstantInputs, InputFunctions, Interpreted, LagrangianSystem};

mod models {
    lagrangian::lagrangian!(file = "specs/simple_pendulum.lpm");
    lagrangian::lagrangian!(file = "specs/double_pendulum.lpm");
    lagrangian::lagrangian!(file = "specs/elastic_pendulum.lpm");
    lagrangian::lagrangian!(file = "specs/spring_mass_damper.lpm");
    lagrangian::lagrangian!(file = "specs/pendulum_chain_10.lpm");
}

type State<const N: usize> = (SVector<f64, N>, SVector<f64, N>);

/// One classical RK4 step of `M q̈ = f` from `(q, q̇)` at `t`; also returns
/// the two midpoint stage states (for quadrature along the step).
fn rk4_step<const N: usize, S: LagrangianSystem<N>>(
    system: &S,
    inputs: &impl InputFunctions,
    t: f64,
    (q, qd): State<N>,
    h: f64,
) -> (State<N>, [State<N>; 2]) {
    let a = |t: f64, q: &SVector<f64, N>, v: &SVector<f64, N>| {
        system.accelerations(t, q, v, inputs).unwrap()
    };
    let a1 = a(t, &q, &qd);
    let (q2, v2) = (q + qd * (h / 2.0), qd + a1 * (h / 2.0));
    let a2 = a(t + h / 2.0, &q2, &v2);
    let (q3, v3) = (q + v2 * (h / 2.0), qd + a2 * (h / 2.0));
    let a3 = a(t + h / 2.0, &q3, &v3);
    let (q4, v4) = (q + v3 * h, qd + a3 * h);
    let a4 = a(t + h, &q4, &v4);
    let next = (
        q + (qd + v2 * 2.0 + v3 * 2.0 + v4) * (h / 6.0),
        qd + (a1 + a2 * 2.0 + a3 * 2.0 + a4) * (h / 6.0),
    );
    (next, [(q2, v2), (q3, v3)])
}

/// Largest |E(t) − E(0)| over the run, relative to max(|T| + |V|).
fn energy_drift<const N: usize, S: LagrangianSystem<N>>(
    system: &S,
    inputs: &impl InputFunctions,
    q0: SVector<f64, N>,
    qd0: SVector<f64, N>,
    h: f64,
    t_end: f64,
) -> f64 {
    let energy = |t: f64, q: &SVector<f64, N>, qd: &SVector<f64, N>| {
        let e = system.energies(t, q, qd, inputs);
        (e.kinetic + e.potential, e.kinetic.abs() + e.potential.abs())
    };
    let (mut q, mut qd, mut t) = (q0, qd0, 0.0);
    let (e0, mut scale) = energy(t, &q, &qd);
    let mut drift = 0.0f64;
    let steps = (t_end / h).round() as usize;
    for _ in 0..steps {
        ((q, qd), _) = rk4_step(system, inputs, t, (q, qd), h);
        t += h;
        let (e, s) = energy(t, &q, &qd);
        drift = drift.max((e - e0).abs());
        scale = scale.max(s);
    }
    drift / scale
}

/// The drift at step h and h/2: below `tolerance`, and falling at least 8× (RK4: 16×).
fn check<const N: usize, S: LagrangianSystem<N>>(
    name: &str,
    system: &S,
    inputs: &impl InputFunctions,
    q0: [f64; N],
    qd0: [f64; N],
    h: f64,
    t_end: f64,
) -> f64 {
    let (q0, qd0) = (SVector::from(q0), SVector::from(qd0));
    let coarse = energy_drift(system, inputs, q0, qd0, h, t_end);
    let fine = energy_drift(system, inputs, q0, qd0, h / 2.0, t_end);
    println!("{name}: relative energy drift {coarse:.2e} at h = {h}, {fine:.2e} at h/2");
    assert!(fine < 1e-9, "{name}: drift {fine:e}");
    assert!(
        coarse / fine > 8.0 || coarse < 1e-13,
        "{name}: drift does not converge ({coarse:e} → {fine:e})"
    );
    fine
}

fn interpreted<const N: usize>(path: &str) -> Interpreted<N> {
    let source = std::fs::read_to_string(path).unwrap();
    Interpreted::new(lagrangian_core::interpret(&source).unwrap()).unwrap()
}

#[test]
fn pendulums_conserve_energy() {
    let none = ConstantInputs(vec![]);
    let compound = models::SimplePendulum {
        I: 0.3,
        ..Default::default()
    };
    check(
        "simple pendulum",
        &models::SimplePendulum::default(),
        &none,
        [2.5],
        [0.0],
        1e-2,
        10.0,
    );
    check(
        "compound pendulum",
        &compound,
        &none,
        [1.0],
        [1.0],
        1e-2,
        10.0,
    );
    check(
        "double pendulum (chaotic)",
        &models::DoublePendulum::default(),
        &none,
        [1.2, -0.8],
        [0.0, 2.0],
        1e-3,
        3.0,
    );
    check(
        "double pendulum, interpreted",
        &interpreted::<2>("specs/double_pendulum.lpm"),
        &none,
        [1.2, -0.8],
        [0.0, 2.0],
        1e-3,
        3.0,
    );
    let mut chain = [0.0; 10];
    for (k, q) in chain.iter_mut().enumerate() {
        *q = 0.3 * (k as f64 * 0.7).sin();
    }
    check(
        "10-link chain",
        &models::PendulumChain10::default(),
        &none,
        chain,
        [0.0; 10],
        1e-3,
        1.0,
    );
}

#[test]
fn undamped_crash_pendulum_and_oscillator_conserve_energy() {
    let elastic = models::ElasticPendulum {
        c: 0.0,
        cs: 0.0,
        ..Default::default()
    };
    check(
        "elastic pendulum (c = cs = 0)",
        &elastic,
        &ConstantInputs(vec![]),
        [-0.1, 0.05],
        [-15.6, 0.0],
        1e-3,
        0.3,
    );
    let mut interpreted = interpreted::<2>("specs/elastic_pendulum.lpm");
    interpreted.set_parameter("c", 0.0).unwrap();
    interpreted.set_parameter("cs", 0.0).unwrap();
    check(
        "elastic pendulum, interpreted",
        &interpreted,
        &ConstantInputs(vec![]),
        [-0.1, 0.05],
        [-15.6, 0.0],
        1e-3,
        0.3,
    );
    let oscillator = models::SpringMassDamper {
        c: 0.0,
        ..Default::default()
    };
    check(
        "spring-mass (c = 0, no push)",
        &oscillator,
        &ConstantInputs(vec![0.0]),
        [0.1],
        [0.0],
        1e-3,
        5.0,
    );
}

#[test]
fn damping_dissipates_what_the_dissipation_function_says() {
    // With damping, d(T + V)/dt = −Σ ∂D/∂q̇ q̇ + Σ Q q̇: check the balance by
    // integrating the reported powers along an RK4 trajectory of the oscillator.
    let system = models::SpringMassDamper::default();
    let push = |_: usize, args: &[f64]| 2.0 * (3.0 * args[0]).sin();
    let (h, mut t) = (1e-4, 0.0);
    let (mut q, mut qd) = (SVector::<f64, 1>::new(0.1), SVector::<f64, 1>::new(0.0));
    let e = |t: f64, q: &SVector<f64, 1>, qd: &SVector<f64, 1>| system.energies(t, q, qd, &push);
    let e0 = e(t, &q, &qd);
    let mut work = 0.0;
    for _ in 0..20_000 {
        let p0 = e(t, &q, &qd);
        let [(q2, v2), (q3, v3)];
        ((q, qd), [(q2, v2), (q3, v3)]) = rk4_step(&system, &push, t, (q, qd), h);
        let pm = e(t + h / 2.0, &q2, &v2);
        let pm2 = e(t + h / 2.0, &q3, &v3);
        t += h;
        let p1 = e(t, &q, &qd);
        // Simpson's rule on the net power (external − damping).
        let net = |p: lagrangian::Energies| p.external_power - p.damping_power;
        work += h / 6.0 * (net(p0) + 2.0 * net(pm) + 2.0 * net(pm2) + net(p1));
        // D is quadratic, so the damping power is 2D.
        assert!(
            (p1.damping_power - 2.0 * p1.dissipation).abs()
                < 1e-12 * p1.damping_power.abs().max(1e-12)
        );
    }
    let e1 = e(t, &q, &qd);
    let balance = (e1.kinetic + e1.potential) - (e0.kinetic + e0.potential) - work;
    println!("energy balance residual {balance:e} J over 2 s");
    assert!(balance.abs() < 1e-9, "{balance:e}");
}
