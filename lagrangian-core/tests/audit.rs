//! The audit of hand-derived equations: specific findings on the paper's
//! eqs 25–27 and 37–43 (each worked out by hand from the paper against the
//! correct derivation), and clean verdicts on correct hand derivations.

use lagrangian_core::Compiled;
use lagrangian_core::audit::{AuditReport, Finding, GroupVerdict, Part, Verdict, audit};
use lagrangian_core::expr::ExprId;
use lagrangian_core::rational::Rational;
use syn::{BinOp, Expr, Lit, UnOp};

/// Builds `text` (a small expression language: names, numbers, + - * /,
/// pow, sin, cos, dot(q), ddot(q), input(t)) in the compiled model's store.
fn build(c: &mut Compiled, text: &str) -> ExprId {
    let expr: Expr = syn::parse_str(text).unwrap();
    fn go(c: &mut Compiled, e: &Expr) -> ExprId {
        let s = &mut c.model.store;
        match e {
            Expr::Lit(l) => match &l.lit {
                Lit::Int(i) => s.int(i.base10_parse().unwrap()),
                Lit::Float(f) => s.num(Rational::parse_decimal(f.base10_digits()).unwrap()),
                _ => panic!(),
            },
            Expr::Paren(p) => go(c, &p.expr),
            Expr::Unary(u) if matches!(u.op, UnOp::Neg(_)) => {
                let x = go(c, &u.expr);
                c.model.store.neg(x)
            }
            Expr::Binary(b) => {
                let (x, y) = (go(c, &b.left), go(c, &b.right));
                let s = &mut c.model.store;
                match b.op {
                    BinOp::Add(_) => s.add(x, y),
                    BinOp::Sub(_) => s.sub(x, y),
                    BinOp::Mul(_) => s.mul(x, y),
                    BinOp::Div(_) => s.div(x, y),
                    _ => panic!(),
                }
            }
            Expr::Path(p) => {
                let name = p.path.get_ident().unwrap().to_string();
                let sym = s
                    .symbol_named(&name)
                    .unwrap_or_else(|| panic!("no symbol {name}"));
                s.symbol_expr(sym)
            }
            Expr::Call(call) => {
                let Expr::Path(p) = &*call.func else { panic!() };
                let name = p.path.get_ident().unwrap().to_string();
                let args: Vec<&Expr> = call.args.iter().collect();
                match name.as_str() {
                    "dot" | "ddot" => {
                        let Expr::Path(q) = args[0] else { panic!() };
                        let symbol = format!("{name}({})", q.path.get_ident().unwrap());
                        let sym = c.model.store.symbol_named(&symbol).unwrap();
                        c.model.store.symbol_expr(sym)
                    }
                    "pow" => {
                        let x = go(c, args[0]);
                        let Expr::Lit(l) = args[1] else { panic!() };
                        let Lit::Int(n) = &l.lit else { panic!() };
                        c.model
                            .store
                            .pow(x, Rational::integer(n.base10_parse().unwrap()))
                    }
                    "sin" | "cos" => {
                        let x = go(c, args[0]);
                        if name == "sin" {
                            c.model.store.sin(x)
                        } else {
                            c.model.store.cos(x)
                        }
                    }
                    input => {
                        let index = c.model.inputs.iter().position(|i| i.name == input).unwrap();
                        let values = args.iter().map(|a| go(c, a)).collect();
                        c.model.store.input_call(index, values)
                    }
                }
            }
            _ => panic!("unsupported {e:?}"),
        }
    }
    go(c, &expr)
}

fn paper() -> (Compiled, AuditReport) {
    let source = std::fs::read_to_string("../specs/yaris_double_pendulum.lpm").unwrap();
    let mut compiled = Compiled::from_source(&source).unwrap();
    let report = audit(&mut compiled).unwrap();
    (compiled, report)
}

fn group<'a>(
    c: &mut Compiled,
    report: &'a AuditReport,
    part: Part,
    q: &str,
    motion: &str,
) -> &'a lagrangian_core::audit::GroupAudit {
    let key = build(c, motion);
    report
        .audit(part, q)
        .unwrap()
        .groups
        .iter()
        .find(|g| g.motion_expr == key)
        .unwrap_or_else(|| panic!("no group {motion} in {q}"))
}

fn has(findings: &[Finding], pred: impl Fn(&Finding) -> bool) -> bool {
    findings.iter().any(pred)
}

#[test]
fn every_paper_equation_disagrees() {
    let (_, report) = paper();
    assert!(report.disagrees());
    assert_eq!(report.audits.len(), 6);
    for a in &report.audits {
        assert_eq!(
            a.verdict,
            Verdict::Disagrees,
            "{} {:?}",
            a.coordinate,
            a.part
        );
        assert!(
            a.max_residual > 1e-2,
            "{}: residual {}",
            a.coordinate,
            a.max_residual
        );
    }
}

#[test]
fn eq_25_centrifugal_terms_have_wrong_signs_and_factors() {
    let (mut c, report) = paper();
    // Derived: −(m1 (l0+r) + m2 (l0+r+l1)) θ̇1². Printed: −2 m2 l1 θ̇1² − m1(l0+r)θ̇1²
    // + m2(l0+r)θ̇1² + m2 l1 θ1² θ̇1².
    let g = group(&mut c, &report, Part::Equation, "r", "pow(dot(theta1), 2)").clone();
    assert_eq!(g.verdict, GroupVerdict::Differs);
    let sign = build(&mut c, "-m2 * (l0 + r)");
    assert!(
        has(
            &g.findings,
            |f| matches!(f, Finding::Sign { expr, .. } if *expr == sign)
        ),
        "{:?}",
        g.findings
    );
    let twice = build(&mut c, "-m2 * l1");
    assert!(has(
        &g.findings,
        |f| matches!(f, Finding::Scaled { expr, ratio, .. } if *expr == twice && *ratio == Rational::integer(2))
    ));
    let extra = build(&mut c, "m2 * l1 * pow(theta1, 2)");
    assert!(has(
        &g.findings,
        |f| matches!(f, Finding::Extra { expr, .. } if *expr == extra)
    ));
}

#[test]
fn eq_25_gravity_acts_on_the_wrong_angle() {
    let (mut c, report) = paper();
    // Derived (small angles): (m1 + m2) g θ1. Printed: m1 g θ1 + m2 g θ2.
    let g = group(&mut c, &report, Part::Equation, "r", "1").clone();
    let missing = build(&mut c, "m2 * g * theta1");
    let extra = build(&mut c, "m2 * g * theta2");
    assert!(
        has(
            &g.findings,
            |f| matches!(f, Finding::Missing { expr, .. } if *expr == missing)
        ),
        "{:?}",
        g.findings
    );
    assert!(has(
        &g.findings,
        |f| matches!(f, Finding::Extra { expr, .. } if *expr == extra)
    ));
    // The mass terms of the r equation are right.
    assert_eq!(
        group(&mut c, &report, Part::Equation, "r", "ddot(r)").verdict,
        GroupVerdict::Match
    );
}

#[test]
fn eq_26_suspension_springs_have_the_wrong_sign_and_terms_the_wrong_dimension() {
    let (mut c, report) = paper();
    let g = group(&mut c, &report, Part::Equation, "theta1", "1").clone();
    let springs = build(
        &mut c,
        "k1 * pow(l0 + r - l3, 2) * theta1 + k2 * (l0 + r + l1) * ((l0 + r + l1) * theta1 + l2 * theta2)",
    );
    assert!(
        has(
            &g.findings,
            |f| matches!(f, Finding::Sign { expr, .. } if *expr == springs)
        ),
        "{:?}",
        g.findings
    );
    // Seven printed terms of eq 26 are not torques, e.g. 2 m1 (l0 + r) θ̇1
    // (kg·m/s: a factor ṙ is missing) and −m2 l1 θ̇1 r̈ (a power).
    let a = report.audit(Part::Equation, "theta1").unwrap();
    assert_eq!(a.dimension_findings.len(), 7, "{:?}", a.dimension_findings);
    let momentum = lagrangian_core::units::Dimension::parse("kg*m/s").unwrap();
    let power = lagrangian_core::units::Dimension::parse("W").unwrap();
    assert!(a.dimension_findings.iter().any(|f| f.found == momentum));
    assert!(a.dimension_findings.iter().any(|f| f.found == power));
    // The mass-matrix entry M_θ1θ1 = m1 (l0+r)² + m2 (l0+r+l1)² is printed as m1 (l0+r)² + m2 l1².
    let g = group(&mut c, &report, Part::Equation, "theta1", "ddot(theta1)").clone();
    let missing = build(&mut c, "m2 * (pow(l0 + r, 2) + 2 * (l0 + r) * l1)");
    assert!(
        has(
            &g.findings,
            |f| matches!(f, Finding::Missing { expr, .. } if *expr == missing)
        ),
        "{:?}",
        g.findings
    );
}

#[test]
fn eq_27_gravity_matches_only_for_small_angles() {
    let (mut c, report) = paper();
    // Derived m2 g l2 cos θ2 + …; printed m2 g l2 + …: equal with cos θ2 ≈ 1.
    assert_eq!(
        group(&mut c, &report, Part::Equation, "theta2", "1").verdict,
        GroupVerdict::SmallAngle
    );
    assert_eq!(
        group(&mut c, &report, Part::Equation, "theta2", "ddot(theta2)").verdict,
        GroupVerdict::Match
    );
    let a = report.audit(Part::Equation, "theta2").unwrap();
    assert_eq!(a.dimension_findings.len(), 1, "m2 r θ̇2 l2 is not a torque");
}

#[test]
fn eqs_41_to_43_repeat_the_barrier_forces_instead_of_damping() {
    let (mut c, report) = paper();
    for input in [
        "barrier_x1(t)",
        "barrier_z1(t)",
        "barrier_x2(t)",
        "barrier_z2(t)",
    ] {
        let g = group(&mut c, &report, Part::GeneralizedForce, "r", input).clone();
        assert!(
            has(
                &g.findings,
                |f| matches!(f, Finding::Scaled { ratio, .. } if *ratio == Rational::integer(2))
            ),
            "{input}: {:?}",
            g.findings
        );
    }
    // The damping force on r, −(c_comp + (c1 + c2) θ1²) ṙ, is absent by hand.
    let g = group(&mut c, &report, Part::GeneralizedForce, "r", "dot(r)").clone();
    assert_eq!(g.verdict, GroupVerdict::MissingByHand);
    let damping = build(&mut c, "-(c_comp + (c1 + c2) * pow(theta1, 2))");
    assert_eq!(g.derived_expr, damping);
    assert_eq!(
        group(
            &mut c,
            &report,
            Part::GeneralizedForce,
            "theta2",
            "dot(theta2)"
        )
        .verdict,
        GroupVerdict::MissingByHand
    );
}

const DOUBLE_PENDULUM: &str = "
model P;
coordinates { a [rad], b [rad] }
parameters { m1 [kg] = 1.0, m2 [kg] = 2.0, l1 [m] = 1.0, l2 [m] = 0.5, g [m/s^2] = 9.81 }
kinetic = 0.5 * m1 * pow(l1 * dot(a), 2)
        + 0.5 * m2 * (pow(l1 * dot(a), 2) + pow(l2 * dot(b), 2) + 2.0 * l1 * l2 * dot(a) * dot(b) * cos(a - b));
potential = -(m1 + m2) * g * l1 * cos(a) - m2 * g * l2 * cos(b);
";

fn audit_of(hand: &str) -> AuditReport {
    let mut c =
        Compiled::from_source(&format!("{DOUBLE_PENDULUM}\nhand_derived {{ {hand} }}")).unwrap();
    audit(&mut c).unwrap()
}

#[test]
fn a_correct_hand_derivation_agrees_exactly() {
    let report = audit_of(
        "a = (m1 + m2) * pow(l1, 2) * ddot(a) + m2 * l1 * l2 * ddot(b) * cos(a - b)
             + m2 * l1 * l2 * pow(dot(b), 2) * sin(a - b) + (m1 + m2) * g * l1 * sin(a);
         b = m2 * pow(l2, 2) * ddot(b) + m2 * l1 * l2 * ddot(a) * cos(a - b)
             - m2 * l1 * l2 * pow(dot(a), 2) * sin(a - b) + m2 * g * l2 * sin(b);",
    );
    assert!(!report.disagrees());
    for a in &report.audits {
        assert_eq!(a.verdict, Verdict::Exact);
        assert!(a.max_residual < 1e-14);
    }
}

#[test]
fn a_linearized_hand_derivation_agrees_for_small_angles() {
    // The textbook linearization: cos(a − b) ≈ 1, sin(a − b) ≈ a − b, sin a ≈ a.
    let report = audit_of(
        "a = (m1 + m2) * pow(l1, 2) * ddot(a) + m2 * l1 * l2 * ddot(b)
             + m2 * l1 * l2 * pow(dot(b), 2) * (a - b) + (m1 + m2) * g * l1 * a;
         b = m2 * pow(l2, 2) * ddot(b) + m2 * l1 * l2 * ddot(a)
             - m2 * l1 * l2 * pow(dot(a), 2) * (a - b) + m2 * g * l2 * b;",
    );
    assert!(!report.disagrees());
    assert!(
        report
            .audits
            .iter()
            .all(|a| a.verdict == Verdict::SmallAngle)
    );
}

#[test]
fn a_planted_sign_error_is_found() {
    let report = audit_of(
        "a = (m1 + m2) * pow(l1, 2) * ddot(a) + m2 * l1 * l2 * ddot(b) * cos(a - b)
             - m2 * l1 * l2 * pow(dot(b), 2) * sin(a - b) + (m1 + m2) * g * l1 * sin(a);",
    );
    assert!(report.disagrees());
    let a = report.audit(Part::Equation, "a").unwrap();
    let wrong: Vec<_> = a
        .groups
        .iter()
        .filter(|g| g.verdict == GroupVerdict::Differs)
        .collect();
    assert_eq!(wrong.len(), 1);
    assert_eq!(wrong[0].motion, "dot(b)^2");
    assert!(
        matches!(wrong[0].findings.as_slice(), [Finding::Sign { .. }]),
        "{:?}",
        wrong[0].findings
    );
}

#[test]
fn hand_sections_are_checked() {
    let bad = |hand: &str| {
        let source = format!("{DOUBLE_PENDULUM}\nhand_derived {{ {hand} }}");
        Compiled::from_source(&source)
            .err()
            .map(|e| e.render("p.lpm", &source))
            .unwrap_or_default()
    };
    assert!(bad("c = 1.0;").contains("`c` is not a generalized coordinate"));
    assert!(bad("convention = newton;").contains("unknown convention `newton`"));
    assert!(bad("symbols { g = 1.0 }").contains("`g` is already a name of the spec"));
    assert!(bad("assume { h = 0.0 }").contains("neither an input function nor a parameter"));
    let outside = Compiled::from_source(&format!("{DOUBLE_PENDULUM}\nforce a = ddot(a);"))
        .err()
        .unwrap()
        .to_string();
    assert!(
        outside.contains("`ddot` is only available in `hand_derived`"),
        "{outside}"
    );
}

#[test]
fn an_equal_hand_derivation_in_a_non_canonical_form_agrees_numerically() {
    // (1 + cos b)/(1 + cos b) and (2 + cos a)/(2 + cos a) times a sum do not
    // simplify in the canonical form; the hand equations are still right.
    let report = audit_of(
        "a = (m1 + m2) * pow(l1, 2) * ddot(a) + m2 * l1 * l2 * ddot(b) * cos(a - b)
             + m2 * l1 * l2 * pow(dot(b), 2) * sin(a - b) * (1 + cos(b)) / (1 + cos(b))
             + (m1 + m2) * g * l1 * sin(a);
         b = m2 * pow(l2, 2) * ddot(b) + m2 * l1 * l2 * ddot(a) * cos(a - b)
             - m2 * l1 * l2 * pow(dot(a), 2) * sin(a - b) * (2 + cos(a)) / (2 + cos(a))
             + m2 * g * l2 * sin(b);",
    );
    assert!(!report.disagrees());
    for a in &report.audits {
        assert_eq!(a.verdict, Verdict::Numerical, "{}", a.coordinate);
        assert!(a.max_residual < 1e-14);
    }
    let a = report.audit(Part::Equation, "a").unwrap();
    let g = a.groups.iter().find(|g| g.motion == "dot(b)^2").unwrap();
    assert_eq!(g.verdict, GroupVerdict::NumericalMatch);
    let text = lagrangian_core::audit::markdown(&report, "p.lpm");
    assert!(
        text.contains("**agrees**, established numerically"),
        "{text}"
    );
    assert!(text.contains("match (numerically)"), "{text}");
}

#[test]
fn a_small_numerical_difference_is_not_agreement() {
    // 1.000001 · g: relatively 1e-6, far above round-off.
    let report = audit_of(
        "a = (m1 + m2) * pow(l1, 2) * ddot(a) + m2 * l1 * l2 * ddot(b) * cos(a - b)
             + m2 * l1 * l2 * pow(dot(b), 2) * sin(a - b) + (m1 + m2) * 1.000001 * g * l1 * sin(a);",
    );
    assert_eq!(
        report.audit(Part::Equation, "a").unwrap().verdict,
        Verdict::Disagrees
    );
}
