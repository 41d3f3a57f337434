//! The functions of the spec language: values and derivatives against
//! SymPy (`tests/reference/functions_reference.py`), and the compiled code
//! against the interpreter, bit for bit, on a spec that uses every one.

use lagrangian::nalgebra::SVector;
use lagrangian::{Interpreted, Jacobians, LagrangianSystem};
use lagrangian_core::expr::{Evaluator, Func, Store, SymbolKind, no_inputs};
use lagrangian_core::random::Lcg;
use serde_json::Value;

mod models {
    lagrangian::lagrangian!(file = "tests/functions/all_functions.lpm");
}

/// Within 1e-14, relative: the reference is exact to 30 digits, libm is
/// within an ulp or two, and a derivative such as `(1 − u²)^(−1/2)` near
/// `u = 1` loses a few more to rounding in `f64`; a wrong formula is off by
/// far more.
fn close(a: f64, b: f64) -> bool {
    a == b || (a - b).abs() <= 1e-14 * a.abs().max(b.abs())
}

#[test]
fn values_and_derivatives_match_sympy() {
    let text = std::fs::read_to_string("tests/reference/functions_reference.json").unwrap();
    let reference: Value = serde_json::from_str(&text).unwrap();
    let reference = reference.as_object().unwrap();
    let mut checked = 0;
    for f in Func::ALL {
        let Some(points) = reference.get(f.name()) else {
            assert!(
                matches!(f, Func::Sin | Func::Cos | Func::Exp | Func::Ln),
                "no reference for {}",
                f.name()
            );
            continue;
        };
        let mut store = Store::new();
        let symbols: Vec<_> = ["x", "y"]
            .iter()
            .enumerate()
            .map(|(i, name)| store.symbol(name, SymbolKind::Coordinate(i)))
            .take(f.arity())
            .collect();
        let args: Vec<_> = symbols.iter().map(|s| s.1).collect();
        let call = store.apply(f, &args);
        let partials: Vec<_> = symbols.iter().map(|s| store.diff(call, s.0)).collect();
        for point in points.as_array().unwrap() {
            let at: Vec<f64> = (point["args"].as_array().unwrap().iter())
                .map(|v| v.as_f64().unwrap())
                .collect();
            let mut evaluator = Evaluator::new(&store, at.clone(), &no_inputs);
            let value = evaluator.eval(call);
            let expected = point["value"].as_f64().unwrap();
            assert!(
                close(value, expected),
                "{}{at:?} = {value}, SymPy {expected}",
                f.name()
            );
            for (k, &d) in partials.iter().enumerate() {
                let got = evaluator.eval(d);
                let expected = point["partials"][k].as_f64().unwrap();
                assert!(
                    close(got, expected),
                    "∂{}/∂arg{k} at {at:?} = {got}, SymPy {expected}",
                    f.name()
                );
            }
            checked += 1;
        }
    }
    assert!(checked >= 30, "{checked} points");
}

/// The spec has no input functions.
fn inputs(_: usize, _: &[f64]) -> f64 {
    f64::NAN
}

fn bits(values: &[f64]) -> Vec<u64> {
    values.iter().map(|x| x.to_bits()).collect()
}

#[test]
fn compiled_and_interpreted_agree_bit_for_bit() {
    let source = std::fs::read_to_string("tests/functions/all_functions.lpm").unwrap();
    let model = lagrangian_core::interpret(&source).unwrap();
    let interpreted = Interpreted::<2>::new(model).unwrap();
    let compiled = models::AllFunctions::default();
    assert_eq!(compiled.switching_count(), interpreted.switching_count());
    // |x − y|, min, max, sign(x), |ẏ| and the branches of their derivatives.
    assert!(
        compiled.switching_count() >= 5,
        "{}",
        compiled.switching_count()
    );
    let mut rng = Lcg::new(3);
    for _ in 0..300 {
        let t = rng.symmetric().abs();
        let q = SVector::<f64, 2>::from_fn(|_, _| rng.symmetric());
        let qd = SVector::<f64, 2>::from_fn(|_, _| 3.0 * rng.symmetric());
        let qdd = SVector::<f64, 2>::from_fn(|_, _| 5.0 * rng.symmetric());
        let (mc, fc) = compiled.mass_matrix_and_forcing_pair(t, &q, &qd, &inputs);
        let (mi, fi) = interpreted.mass_matrix_and_forcing_pair(t, &q, &qd, &inputs);
        assert_eq!(bits(mc.as_slice()), bits(mi.as_slice()), "M at {q:?}");
        assert_eq!(
            bits(fc.as_slice()),
            bits(fi.as_slice()),
            "f at {q:?} {qd:?}"
        );
        assert!(fc.iter().all(|v| v.is_finite()), "f = {fc:?} at {q:?}");
        let (ec, ei) = (
            compiled.energies(t, &q, &qd, &inputs),
            interpreted.energies(t, &q, &qd, &inputs),
        );
        assert_eq!(ec, ei);
        let n = compiled.switching_count();
        let (mut sc, mut si) = (vec![0.0; n], vec![0.0; n]);
        compiled.switching_functions(t, &q, &qd, &inputs, &mut sc);
        interpreted.switching_functions(t, &q, &qd, &inputs, &mut si);
        assert_eq!(bits(&sc), bits(&si));
        let (mut jc, mut ji) = (Jacobians::<2>::default(), Jacobians::<2>::default());
        compiled
            .jacobians(t, &q, &qd, &qdd, &inputs, &mut jc)
            .unwrap();
        interpreted
            .jacobians(t, &q, &qd, &qdd, &inputs, &mut ji)
            .unwrap();
        assert_eq!(bits(jc.forcing_q.as_slice()), bits(ji.forcing_q.as_slice()));
        assert_eq!(
            bits(jc.forcing_qd.as_slice()),
            bits(ji.forcing_qd.as_slice())
        );
    }
}
