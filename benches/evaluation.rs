//! One evaluation of the paper model's accelerations q̈ = M⁻¹ f (M, f and the
//! L D Lᵀ solve): the macro-compiled code, the interpreter, a hand-written
//! implementation of the same equations (written here from the
//! SymPy-verified derivation, the way one would by hand), and CasADi's
//! generated C for the same model (benches/casadi, made by
//! benches/reference/casadi_yaris.py), with the same parameters and states.
//!
//! `cargo bench -p lagrangian --bench evaluation`; instruction counts per
//! call: `benches/reference/callgrind_qdd.sh`.

use lagrangian::nalgebra::{Matrix3, Vector3};
use lagrangian::{InputFunctions, Interpreted, LagrangianSystem, solve_mass_matrix};
use std::hint::black_box;
use std::time::Instant;

use lagrangian_casadi_peer as casadi;

mod models {
    lagrangian::lagrangian!(file = "specs/yaris_double_pendulum.lpm");
    lagrangian::lagrangian!(file = "benches/specs/pendulum_chain_20.lpm");
}
use models::YarisDoublePendulum as Yaris;

/// Cheap input values: a linear crush spring and damper, constant barrier
/// forces, a linear weld.
fn inputs(index: usize, args: &[f64]) -> f64 {
    match index {
        Yaris::INPUT_CRUSH => 8.0e5 * args[0] + 3.0e3 * args[1],
        Yaris::INPUT_WELD => 1.0e5 * args[0] + 1.0e3 * args[1],
        _ => 1.0e3,
    }
}

/// The paper's model (as in specs/yaris_double_pendulum.lpm) written by hand.
fn hand_written<I: InputFunctions>(
    p: &Yaris,
    t: f64,
    q: &Vector3<f64>,
    v: &Vector3<f64>,
    inputs: &I,
) -> (Matrix3<f64>, Vector3<f64>) {
    let (r, th1, th2) = (q[0], q[1], q[2]);
    let (rd, w1, w2) = (v[0], v[1], v[2]);
    let (s1, c1) = th1.sin_cos();
    let (s2, c2) = th2.sin_cos();
    let sd = s1 * c2 - c1 * s2; // sin(θ1 − θ2)
    let cd = c1 * c2 + s1 * s2; // cos(θ1 − θ2)
    let a = p.l0 + r; // radius of body 1
    let b = a + p.l1; // radius of the weld
    let c = a - p.l3; // radius of the front suspension
    let (m1, m2, l2) = (p.m1, p.m2, p.l2);
    let m2l2 = m2 * l2;
    let moment = m1 * a + m2 * b;
    // Suspension deflections and rates (eqs 21–22).
    let r1 = c * th1;
    let r2 = b * th1 + l2 * th2;
    let r1d = rd * th1 + c * w1;
    let r2d = rd * th1 + b * w1 + l2 * w2;
    let crush = inputs.value(Yaris::INPUT_CRUSH, &[r, rd]);
    let weld = inputs.value(Yaris::INPUT_WELD, &[th2, w2]);
    let bx1 = inputs.value(Yaris::INPUT_BARRIER_X1, &[t]);
    let bz1 = inputs.value(Yaris::INPUT_BARRIER_Z1, &[t]);
    let bx2 = inputs.value(Yaris::INPUT_BARRIER_X2, &[t]);
    let bz2 = inputs.value(Yaris::INPUT_BARRIER_Z2, &[t]);
    let m12 = m2l2 * sd;
    let m13 = m2l2 * b * cd;
    let mass = Matrix3::new(
        m1 + m2,
        0.0,
        m12,
        0.0,
        m1 * a * a + m2 * b * b + p.I1,
        m13,
        m12,
        m13,
        m2l2 * l2 + p.I2,
    );
    let f_r = moment * w1 * w1 + m2l2 * cd * w2 * w2
        - (m1 + m2) * p.g * s1
        - p.k_comp * r
        - (p.k1 * r1 + p.k2 * r2 + p.c1 * r1d + p.c2 * r2d) * th1
        - p.c_comp * rd
        - crush
        + c1 * (bx1 + bx2)
        + s1 * (bz1 + bz2);
    let f_1 = -2.0 * moment * rd * w1
        - b * m12 * w2 * w2
        - moment * p.g * c1
        - c * (p.k1 * r1 + p.c1 * r1d)
        - b * (p.k2 * r2 + p.c2 * r2d)
        - s1 * (a * bx1 + b * bx2)
        + c1 * (a * bz1 + b * bz2);
    let f_2 = -2.0 * m2l2 * cd * rd * w1 + b * m12 * w1 * w1
        - l2 * (p.k2 * r2 + p.c2 * r2d + m2 * p.g * c2)
        - p.k_tor * th2
        - p.c_tor * w2
        - weld
        + l2 * (c2 * bz2 - s2 * bx2);
    (mass, Vector3::new(f_r, f_1, f_2))
}

/// Nanoseconds per call of `f` over one batch of `n` calls.
fn batch_ns(n: usize, f: &mut impl FnMut(usize) -> f64) -> f64 {
    let mut sink = 0.0;
    let start = Instant::now();
    for i in 0..n {
        sink += f(i);
    }
    let elapsed = start.elapsed().as_nanos() as f64 / n as f64;
    black_box(sink);
    elapsed
}

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

/// Median nanoseconds per call of `f` over 11 batches of `n` calls.
fn median_ns(n: usize, mut f: impl FnMut(usize) -> f64) -> f64 {
    batch_ns(n, &mut f);
    median((0..11).map(|_| batch_ns(n, &mut f)).collect())
}

/// Batches of each of `variants` taken in turn (so that a change of the
/// machine's speed during the run hits all alike), 31 rounds after a warm-up:
/// the time per call of each variant in each round.
fn interleaved(n: usize, variants: &mut [Box<dyn Timed + '_>]) -> Vec<Vec<f64>> {
    let mut times = vec![Vec::new(); variants.len()];
    for round in 0..32 {
        for (k, f) in variants.iter_mut().enumerate() {
            let t = f.batch_ns(n);
            if round > 0 {
                times[k].push(t);
            }
        }
    }
    times
}

/// Something timed by batches of calls: one dynamic call a batch, the calls
/// inside it compiled for the one closure.
trait Timed {
    /// Nanoseconds per call over one batch of `n` calls.
    fn batch_ns(&mut self, n: usize) -> f64;
}

impl<F: FnMut(usize) -> f64> Timed for F {
    fn batch_ns(&mut self, n: usize) -> f64 {
        batch_ns(n, self)
    }
}

/// The median over rounds of `y`'s time over `x`'s.
fn paired_ratio(x: &[f64], y: &[f64]) -> f64 {
    median(x.iter().zip(y).map(|(p, q)| q / p).collect())
}

/// The states of the paper model's bench (and of the callgrind counts).
fn yaris_states() -> Vec<(Vector3<f64>, Vector3<f64>)> {
    (0..64)
        .map(|k| {
            let x = k as f64 / 64.0;
            (
                Vector3::new(-0.5 * x, 0.1 - 0.2 * x, 0.05 * x),
                Vector3::new(-15.0 + x, 0.3 * x, -0.2 * x),
            )
        })
        .collect()
}

/// The paper model's variants, by name: q̈ of each implementation, and M, f
/// alone of the compiled model and of CasADi's C. Each returns one value of
/// its result, for the timing loop to keep.
struct Variants {
    compiled: Yaris,
    interpreted: Interpreted<3>,
    /// The interpreted model with its routines as native code (`lagrangian-jit`).
    native: Interpreted<3>,
    /// The compiled model's parameters, for CasADi's C.
    parameters: [f64; casadi::PARAMETERS],
    states: Vec<(Vector3<f64>, Vector3<f64>)>,
}

impl Variants {
    const NAMES: [&str; 7] = [
        "hand-written",
        "compiled",
        "casadi",
        "interpreted",
        "compiled-mf",
        "casadi-mf",
        "jit",
    ];

    fn new() -> Variants {
        let compiled = Yaris::default();
        let source = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/specs/yaris_double_pendulum.lpm"
        ))
        .unwrap();
        let interpreted =
            Interpreted::<3>::new(lagrangian_core::interpret(&source).unwrap()).unwrap();
        let native = Interpreted::<3>::new(native_model(&source)).unwrap();
        let parameters = compiled.parameters().try_into().unwrap();
        Variants {
            compiled,
            interpreted,
            native,
            parameters,
            states: yaris_states(),
        }
    }

    /// Variant `NAMES[V]` at state `i` (modulo the number of states).
    fn run<const V: usize>(&self, i: usize) -> f64 {
        let (q, v) = &self.states[i % self.states.len()];
        let (t, q, v) = (black_box(0.01), black_box(q), black_box(v));
        let p = black_box(&self.parameters);
        let (cq, cv) = (&(*q).into(), &(*v).into());
        match V {
            0 => {
                let (m, f) = hand_written(&self.compiled, t, q, v, &inputs);
                solve_mass_matrix(m, &f).unwrap()[0]
            }
            1 => self.compiled.accelerations(t, q, v, &inputs).unwrap()[0],
            2 => casadi::accelerations(t, cq, cv, p)[0],
            3 => self.interpreted.accelerations(t, q, v, &inputs).unwrap()[0],
            4 => {
                let (_, f) = self.compiled.mass_matrix_and_forcing_pair(t, q, v, &inputs);
                f[0]
            }
            5 => casadi::mass_forcing(t, cq, cv, p).1[0],
            _ => self.native.accelerations(t, q, v, &inputs).unwrap()[0],
        }
    }

    /// Every variant, in the order of `NAMES`.
    fn all(&self) -> Vec<Box<dyn Timed + '_>> {
        vec![
            Box::new(|i| self.run::<0>(i)),
            Box::new(|i| self.run::<1>(i)),
            Box::new(|i| self.run::<2>(i)),
            Box::new(|i| self.run::<3>(i)),
            Box::new(|i| self.run::<4>(i)),
            Box::new(|i| self.run::<5>(i)),
            Box::new(|i| self.run::<6>(i)),
        ]
    }

    /// The implementations agree before anything is timed.
    fn check(&self) {
        for (q, v) in &self.states {
            let (mh, fh) = hand_written(&self.compiled, 0.01, q, v, &inputs);
            let (mc, fc) = self
                .compiled
                .mass_matrix_and_forcing_pair(0.01, q, v, &inputs);
            assert!((mh - mc).amax() <= 1e-12 * mc.amax(), "M differs");
            assert!(
                (fh - fc).amax() <= 1e-10 * fc.amax(),
                "f differs: {fh} vs {fc}"
            );
            let a = self.compiled.accelerations(0.01, q, v, &inputs).unwrap();
            let b = self.interpreted.accelerations(0.01, q, v, &inputs).unwrap();
            assert_eq!(a, b, "compiled and interpreted agree bit for bit");
            let b = self.native.accelerations(0.01, q, v, &inputs).unwrap();
            assert_eq!(a, b, "compiled and native code agree bit for bit");
            let c = casadi::accelerations(0.01, &(*q).into(), &(*v).into(), &self.parameters);
            let c = Vector3::from(c);
            assert!((a - c).amax() <= 1e-12 * a.amax(), "CasADi's q̈ {c} vs {a}");
        }
    }
}

/// `evaluation count VARIANT N`: `N` calls of one variant and nothing else
/// (for benches/reference/callgrind_qdd.sh, which counts instructions).
fn count_calls(args: &[String]) {
    let variants = Variants::new();
    let k = (Variants::NAMES.iter().position(|name| *name == args[0]))
        .unwrap_or_else(|| panic!("the variants are {:?}", Variants::NAMES));
    let n: usize = args[1].parse().expect("a number of calls");
    black_box(variants.all()[k].batch_ns(n));
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if let Some(k) = args.iter().position(|a| a == "count") {
        return count_calls(&args[k + 1..]);
    }
    paper_model();
    chain_20();
}

/// The paper model's q̈ of every implementation, side by side in one run.
fn paper_model() {
    let variants = Variants::new();
    variants.check();
    let n = 50_000;
    let times = interleaved(n, &mut variants.all());
    let ns = |k: usize| median(times[k].clone());
    let ratio = |x: usize, y: usize| paired_ratio(&times[x], &times[y]);
    let [
        hand,
        compiled,
        casadi_c,
        interpreted,
        compiled_mf,
        casadi_mf,
        native,
    ] = [0, 1, 2, 3, 4, 5, 6];
    println!(
        "Batches of {n} calls taken in turn, 31 rounds; medians, and medians of paired ratios."
    );
    println!();
    println!("| implementation | q̈ = M⁻¹f (ns) | ratio |");
    println!("|---|---|---|");
    println!("| hand-written | {:.1} | 1.00 |", ns(hand));
    let (to_hand, to_casadi) = (ratio(hand, compiled), ratio(casadi_c, compiled));
    println!(
        "| compiled (lagrangian!) | {:.1} | {to_hand:.2} × hand-written, {to_casadi:.2} × CasADi |",
        ns(compiled)
    );
    println!(
        "| CasADi's C (gcc -O3) | {:.1} | {:.2} × hand-written |",
        ns(casadi_c),
        ratio(hand, casadi_c)
    );
    println!(
        "| interpreted (spec file) | {:.1} | {:.2} × compiled |",
        ns(interpreted),
        ratio(compiled, interpreted)
    );
    println!(
        "| interpreted, native code (lagrangian-jit) | {:.1} | {:.2} × compiled |",
        ns(native),
        ratio(compiled, native)
    );
    println!();
    println!(
        "M and f alone: compiled {:.1} ns, CasADi's C {:.1} ns ({:.2} × CasADi)",
        ns(compiled_mf),
        ns(casadi_mf),
        ratio(casadi_mf, compiled_mf)
    );
    let energies_ns = median_ns(n, |i| {
        let (q, v) = &variants.states[i % variants.states.len()];
        let t = black_box(0.01);
        let e = variants
            .compiled
            .energies(t, black_box(q), black_box(v), &inputs);
        e.external_power
    });
    println!("compiled energies: {energies_ns:.1} ns");
    println!();
}

/// A 20-link pendulum chain (PyDy's Cython right-hand side: about 50 µs).
fn chain_20() {
    use lagrangian::NoInputs;
    use lagrangian::nalgebra::SVector;
    let compiled = models::PendulumChain20::default();
    let source = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/benches/specs/pendulum_chain_20.lpm"
    ))
    .unwrap();
    let interpreted = Interpreted::<20>::new(lagrangian_core::interpret(&source).unwrap()).unwrap();
    let native = Interpreted::<20>::new(native_model(&source)).unwrap();
    let states: Vec<(SVector<f64, 20>, SVector<f64, 20>)> = (0..16)
        .map(|k| {
            let x = k as f64 / 16.0;
            (
                SVector::from_fn(|i, _| 0.3 * ((i as f64) * 0.7 + x).sin()),
                SVector::from_fn(|i, _| 0.5 * ((i as f64) * 1.3 - x).cos()),
            )
        })
        .collect();
    for (q, v) in &states {
        let a = compiled.accelerations(0.0, q, v, &NoInputs).unwrap();
        let b = interpreted.accelerations(0.0, q, v, &NoInputs).unwrap();
        assert_eq!(a, b, "compiled and interpreted agree bit for bit");
        let b = native.accelerations(0.0, q, v, &NoInputs).unwrap();
        assert_eq!(a, b, "compiled and native code agree bit for bit");
    }
    let pick = |i: usize| &states[i % states.len()];
    let compiled_ns = median_ns(20_000, |i| {
        let (q, v) = pick(i);
        compiled
            .accelerations(0.0, black_box(q), black_box(v), &NoInputs)
            .unwrap()[0]
    });
    let interpreted_ns = median_ns(5_000, |i| {
        let (q, v) = pick(i);
        interpreted
            .accelerations(0.0, black_box(q), black_box(v), &NoInputs)
            .unwrap()[0]
    });
    let native_ns = median_ns(5_000, |i| {
        let (q, v) = pick(i);
        native
            .accelerations(0.0, black_box(q), black_box(v), &NoInputs)
            .unwrap()[0]
    });
    println!("| 20-link pendulum chain | q̈ = M⁻¹f (µs) | ratio to compiled |");
    println!("|---|---|---|");
    println!(
        "| compiled (lagrangian!) | {:.2} | 1.00 |",
        compiled_ns / 1e3
    );
    println!(
        "| interpreted (spec file) | {:.2} | {:.2} |",
        interpreted_ns / 1e3,
        interpreted_ns / compiled_ns
    );
    println!(
        "| interpreted, native code (lagrangian-jit) | {:.2} | {:.2} |",
        native_ns / 1e3,
        native_ns / compiled_ns
    );
}

/// The spec `source` interpreted, its routines compiled to native code;
/// prints how long that compilation took.
fn native_model(source: &str) -> lagrangian::InterpretedModel {
    let mut model = lagrangian_core::interpret(source).unwrap();
    let start = std::time::Instant::now();
    lagrangian_jit::accelerate(&mut model).unwrap();
    let ms = start.elapsed().as_secs_f64() * 1e3;
    eprintln!("native code for {}: {ms:.1} ms", model.name());
    model
}
