use super::*;
use crate::expr::no_inputs;
use crate::rational::Rational;

fn setup() -> (Store, Vec<ExprId>) {
    let mut s = Store::new();
    let names = ["x", "y", "a", "b"];
    let ids = names
        .iter()
        .enumerate()
        .map(|(i, n)| s.symbol(n, SymbolKind::Parameter(i)).1)
        .collect();
    (s, ids)
}

#[test]
fn sums_collect_and_cancel() {
    let (mut s, v) = setup();
    let (x, y) = (v[0], v[1]);
    let a = s.add(x, y);
    let b = s.sub(a, x);
    assert_eq!(b, y);
    let two_x = s.add(x, x);
    let q = s.div(two_x, x);
    assert_eq!(s.as_num(q), Some(Rational::integer(2)));
}

#[test]
fn products_distribute_and_hash_cons() {
    let (mut s, v) = setup();
    let (x, y) = (v[0], v[1]);
    let sum = s.add(x, y);
    let sq = s.mul(sum, sum);
    let x2 = s.pow(x, Rational::integer(2));
    let y2 = s.pow(y, Rational::integer(2));
    let xy = s.mul(x, y);
    let xy2 = s.scale(xy, Rational::integer(2));
    let expected = s.sum(&[x2, xy2, y2]);
    assert_eq!(sq, expected);
    let diff = s.sub(x, y);
    let prod = s.mul(sum, diff);
    let expected = s.sub(x2, y2);
    assert_eq!(prod, expected);
}

#[test]
fn pythagorean_identity_folds() {
    let (mut s, v) = setup();
    let x = v[0];
    let sin = s.sin(x);
    let cos = s.cos(x);
    let s2 = s.mul(sin, sin);
    let c2 = s.mul(cos, cos);
    assert_eq!(s.add(s2, c2), Store::ONE);
}

#[test]
fn angle_addition_combines() {
    let (mut s, v) = setup();
    let (x, y) = (v[0], v[1]);
    let (sx, cx, sy, cy) = (s.sin(x), s.cos(x), s.sin(y), s.cos(y));
    let cc = s.mul(cx, cy);
    let ss = s.mul(sx, sy);
    let lhs = s.add(cc, ss);
    let d = s.sub(x, y);
    assert_eq!(lhs, s.cos(d));
    let sc = s.mul(sx, cy);
    let cs = s.mul(cx, sy);
    let lhs = s.sub(sc, cs);
    assert_eq!(lhs, s.sin(d));
}

#[test]
fn trig_argument_sign_is_normalized() {
    let (mut s, v) = setup();
    let (x, y) = (v[0], v[1]);
    let xy = s.sub(x, y);
    let yx = s.sub(y, x);
    assert_eq!(s.cos(xy), s.cos(yx));
    let sin_xy = s.sin(xy);
    let neg = s.neg(sin_xy);
    assert_eq!(s.sin(yx), neg);
    assert_eq!(s.sin(Store::ZERO), Store::ZERO);
    assert_eq!(s.cos(Store::ZERO), Store::ONE);
}

#[test]
fn derivatives_follow_the_usual_rules() {
    let (mut s, v) = setup();
    let (x, y) = (v[0], v[1]);
    let xs = s.as_symbol(x).unwrap();
    // d/dx (x^3 y) = 3 x^2 y
    let x3 = s.pow(x, Rational::integer(3));
    let e = s.mul(x3, y);
    let d = s.diff(e, xs);
    let x2 = s.pow(x, Rational::integer(2));
    let x2y = s.mul(x2, y);
    assert_eq!(d, s.scale(x2y, Rational::integer(3)));
    // d/dx sin(x y) = y cos(x y)
    let xy = s.mul(x, y);
    let e = s.sin(xy);
    let d = s.diff(e, xs);
    let c = s.cos(xy);
    assert_eq!(d, s.mul(y, c));
    // d/dx sqrt(x) = 1/(2 sqrt(x))
    let e = s.sqrt(x);
    let d = s.diff(e, xs);
    let inv = s.pow(x, Rational::new(-1, 2).unwrap());
    assert_eq!(d, s.scale(inv, Rational::HALF));
    // d/dx ln(x) = 1/x, d/dx exp(2x) = 2 exp(2x)
    let e = s.ln(x);
    assert_eq!(s.diff(e, xs), s.pow(x, Rational::MINUS_ONE));
    let two_x = s.scale(x, Rational::integer(2));
    let e = s.exp(two_x);
    assert_eq!(s.diff(e, xs), s.scale(e, Rational::integer(2)));
}

#[test]
fn powers_of_products_and_roots() {
    let (mut s, v) = setup();
    let x = v[0];
    let r = s.sqrt(x);
    assert_eq!(s.mul(r, r), x);
    let x2 = s.mul(x, x);
    let r2 = s.sqrt(x2);
    assert_ne!(r2, x, "sqrt(x^2) is |x|, not x");
    let four = s.int(4);
    assert_eq!(s.sqrt(four), s.int(2));
    let two = s.int(2);
    let r2 = s.sqrt(two);
    assert_eq!(s.mul(r2, r2), two);
}

#[test]
fn evaluation_matches_direct_arithmetic() {
    let (mut s, v) = setup();
    let (x, y) = (v[0], v[1]);
    let sum = s.add(x, y);
    let c = s.cos(sum);
    let q = s.div(c, y);
    let e = s.mul(q, sum);
    let mut ev = Evaluator::new(&s, vec![0.3, 1.7, 0.0, 0.0], &no_inputs);
    let expected = (0.3f64 + 1.7).cos() / 1.7 * (0.3 + 1.7);
    assert!((ev.eval(e) - expected).abs() < 1e-14);
}

#[test]
fn overflow_is_recorded_not_silent() {
    let (mut s, v) = setup();
    let big = s.num(Rational::new(i128::MAX / 3, 1).unwrap());
    let e = s.mul(big, v[0]);
    let _ = s.scale(e, Rational::integer(1000));
    assert_eq!(s.take_errors(), vec![EngineError::Overflow]);
}

#[test]
fn dependency_queries_see_through_every_node_kind() {
    let (mut s, v) = setup();
    let (x, y, a) = (v[0], v[1], v[2]);
    let (xs, ys, as_, bs) = (
        s.as_symbol(x).unwrap(),
        s.as_symbol(y).unwrap(),
        s.as_symbol(a).unwrap(),
        s.as_symbol(v[3]).unwrap(),
    );
    let input = s.declare_input("f", &["u".to_string()]);
    // f(x) · sin(y)^(1/2) + a: an input call, a function, a product and a sum.
    let call = s.input_call(input, vec![x]);
    let sin = s.sin(y);
    let root = s.sqrt(sin);
    let product = s.mul(call, root);
    let e = s.add(product, a);
    for sym in [xs, ys, as_] {
        assert!(s.depends_on(e, sym));
    }
    assert!(!s.depends_on(e, bs));
    assert_eq!(s.free_symbols(e), vec![xs, ys, as_]);
    // e, the product f(x)·sin(y)^(1/2), f(x), x, sin(y), y, a.
    assert_eq!(s.dag_size(&[e]), 7);
    let mut children = Vec::new();
    s.node(e).for_each_child(|c| children.push(c));
    assert_eq!(children.len(), 2);
}

#[test]
fn high_powers_of_a_sine_stay_small() {
    let (mut s, v) = setup();
    let sin = s.sin(v[0]);
    // sin⁴⁰ x = Σ_k c_k cos(2k x), k = 0…20: 21 terms. Without merging like
    // terms between multiplications the expansion held 2⁴⁰ products.
    let p = s.pow(sin, Rational::integer(40));
    assert!(s.terms(p).len() <= 21, "{} terms", s.terms(p).len());
    assert!(s.take_errors().is_empty());
    let x = 0.7f64;
    let mut ev = Evaluator::new(&s, vec![x, 0.0, 0.0, 0.0], &no_inputs);
    assert!((ev.eval(p) - x.sin().powi(40)).abs() < 1e-15);
}

#[test]
fn powers_of_sums_expand_within_a_limit() {
    let (mut s, v) = setup();
    let sum = s.add(v[0], Store::ONE);
    let p = s.pow(sum, Rational::integer(64));
    assert_eq!(s.terms(p).len(), 65);
    assert!(s.take_errors().is_empty());
    // (x + y + 1)^100 has C(102, 2) = 5151 terms: refused before expanding.
    let xy1 = s.sum(&[v[0], v[1], Store::ONE]);
    let _ = s.pow(xy1, Rational::integer(100));
    assert_eq!(
        s.take_errors(),
        vec![EngineError::ExpansionTooLarge {
            exponent: Rational::integer(100),
            sum_terms: 3
        }]
    );
    // (x + 1)^100000 ran for ever; its exponent is now out of range.
    let _ = s.pow(sum, Rational::integer(100_000));
    assert_eq!(
        s.take_errors(),
        vec![EngineError::ExponentTooLarge(Rational::integer(100_000))]
    );
    // An exponent beyond i64 was read as 0, and the power became 1.
    let beyond_i64 = Rational::new(i128::from(i64::MAX) * 4, 1).unwrap();
    let p = s.pow(sum, beyond_i64);
    assert_ne!(p, Store::ONE);
    assert_eq!(
        s.take_errors(),
        vec![EngineError::ExponentTooLarge(beyond_i64)]
    );
}

#[test]
fn exponents_beyond_the_limit_are_reported() {
    let (mut s, v) = setup();
    let x = v[0];
    let big = Rational::integer(4_294_967_298);
    let _ = s.pow(x, big);
    assert_eq!(s.take_errors(), vec![EngineError::ExponentTooLarge(big)]);
    // Each power is allowed, their product is not.
    let p = s.pow(x, Rational::integer(1000));
    let _ = s.pow(p, Rational::integer(1000));
    assert_eq!(
        s.take_errors(),
        vec![EngineError::ExponentTooLarge(Rational::integer(1_000_000))]
    );
    let sin = s.sin(x);
    let _ = s.pow(sin, Rational::integer(5000));
    assert_eq!(
        s.take_errors(),
        vec![EngineError::ExponentTooLarge(Rational::integer(5000))]
    );
    let _ = s.pow(x, Rational::new(1, 4096).unwrap());
    assert_eq!(s.take_errors().len(), 1);
}

#[test]
fn zero_to_the_zero_is_one_as_for_f64() {
    let (mut s, v) = setup();
    assert_eq!(s.pow(Store::ZERO, Rational::ZERO), Store::ONE);
    assert!(s.take_errors().is_empty(), "0⁰ was a 'division by zero'");
    // x⁰ is 1 for every x, so it evaluates to 1 at x = 0, as `powi` does.
    let x0 = s.pow(v[0], Rational::ZERO);
    assert_eq!(x0, Store::ONE);
    let mut ev = Evaluator::new(&s, vec![0.0; 4], &no_inputs);
    assert_eq!(ev.eval(x0), 1.0);
}

#[test]
fn negative_trig_powers_cancel_with_positive_ones() {
    let (mut s, v) = setup();
    let x = v[0];
    let (sin, cos) = (s.sin(x), s.cos(x));
    // sin²x / sin x: sin²x arrives as ½ − ½cos 2x; it was ½(sin⁻¹x − sin⁻¹x·cos 2x).
    let sin2 = s.pow(sin, Rational::integer(2));
    assert_eq!(s.div(sin2, sin), sin);
    // tan x · cos²x − sin x cos x = 0.
    let tan = s.tan(x);
    let cos2 = s.pow(cos, Rational::integer(2));
    let lhs = s.mul(tan, cos2);
    let sc = s.mul(sin, cos);
    assert_eq!(s.sub(lhs, sc), Store::ZERO);
    // cos²x / sin x = 1/sin x − sin x, however it is built.
    let a = s.div(cos2, sin);
    let inv = s.pow(sin, Rational::MINUS_ONE);
    let b = s.sub(inv, sin);
    assert_eq!(a, b);
    // cos 3x / cos x = 4cos²x − 3 = 2cos 2x − 1, and (1/sin x)·sin 3x = 3 − 4sin²x.
    let three_x = s.scale(x, Rational::integer(3));
    let cos3 = s.cos(three_x);
    let q = s.div(cos3, cos);
    let two_x = s.scale(x, Rational::integer(2));
    let cos2x = s.cos(two_x);
    let expected = s.scale(cos2x, Rational::integer(2));
    let expected = s.sub(expected, Store::ONE);
    assert_eq!(q, expected);
    // x / sin²x and x / (sin x cos x)³: the linearized denominators are
    // recognized, so the quotient has sin⁻²x, not (½ − ½cos 2x)⁻¹.
    let q = s.div(x, sin2);
    let inv2 = s.pow(sin, Rational::integer(-2));
    assert_eq!(q, s.mul(x, inv2));
    assert_eq!(s.mul(q, sin2), x);
    // (sin x cos x)³ = ⅛ sin³2x, linearized as 3/32 sin 2x − 1/32 sin 6x.
    let sc3 = s.pow(sc, Rational::integer(3));
    let q = s.div(Store::ONE, sc3);
    let two_x = s.scale(x, Rational::integer(2));
    let sin2x = s.sin(two_x);
    let sin2x_3 = s.pow(sin2x, Rational::integer(-3));
    assert_eq!(q, s.scale(sin2x_3, Rational::integer(8)));
    let one_plus_cos = s.add(Store::ONE, cos);
    let q = s.div(x, one_plus_cos);
    assert_eq!(
        s.factors(s.terms(q)[0].0).len(),
        2,
        "x · (1 + cos x)⁻¹ stays"
    );
    // sin x / cos x + cos x / sin x = 1/(sin x cos x).
    let t = s.div(sin, cos);
    let ct = s.div(cos, sin);
    let sum = s.add(t, ct);
    let inv_s = s.pow(sin, Rational::MINUS_ONE);
    let inv_c = s.pow(cos, Rational::MINUS_ONE);
    assert_eq!(sum, s.mul(inv_s, inv_c));
    assert!(s.take_errors().is_empty());
}

#[test]
fn negative_trig_powers_keep_their_value() {
    let (mut s, v) = setup();
    let (x, y) = (v[0], v[1]);
    let (sx, cx) = (s.sin(x), s.cos(x));
    let xy = s.sub(x, y);
    let sxy = s.sin(xy);
    // (sin³x + cos 3x · sin(x − y)) / (sin x · cos²x) · (cos x + sin 2x)²
    let three_x = s.scale(x, Rational::integer(3));
    let cos3 = s.cos(three_x);
    let s3 = s.pow(sx, Rational::integer(3));
    let mixed = s.mul(cos3, sxy);
    let num = s.add(s3, mixed);
    let c2 = s.pow(cx, Rational::integer(2));
    let den = s.mul(sx, c2);
    let q = s.div(num, den);
    let two_x = s.scale(x, Rational::integer(2));
    let s2x = s.sin(two_x);
    let f = s.add(cx, s2x);
    let f2 = s.pow(f, Rational::integer(2));
    let e = s.mul(q, f2);
    assert!(s.take_errors().is_empty());
    for (a, b) in [(0.3, -1.1), (1.2, 0.4), (-2.5, 2.0)] {
        let mut ev = Evaluator::new(&s, vec![a, b, 0.0, 0.0], &no_inputs);
        let f = a.cos() + (2.0 * a).sin();
        let expected = (a.sin().powi(3) + (3.0 * a).cos() * (a - b).sin())
            / (a.sin() * a.cos().powi(2))
            * f
            * f;
        let got = ev.eval(e);
        assert!(
            (got - expected).abs() < 1e-12 * expected.abs().max(1.0),
            "{got} vs {expected}"
        );
    }
}
