//! Input beyond what the compiler represents exactly is a located error,
//! never a silently wrong model nor a panic.

use lagrangian_core::Compiled;

const HEADER: &str = "model Spring;
coordinates { x }
parameters { m = 1.0, k = 100.0 }
kinetic = 0.5 * m * pow(dot(x), 2);
";

/// Compiles `HEADER` + `body` and returns the rendered errors.
fn error_of(body: &str) -> String {
    let source = format!("{HEADER}{body}");
    match Compiled::from_source(&source) {
        Ok(_) => panic!("should not compile:\n{body}"),
        Err(e) => e.render("spring.lpm", &source),
    }
}

#[test]
fn a_literal_too_large_for_an_exact_rational_is_an_error_not_zero() {
    let huge = format!("1{}.0", "0".repeat(42));
    let text = error_of(&format!("potential = 0.5 * {huge} * k * pow(x, 2);"));
    assert!(
        text.contains(&format!("the literal `{huge}` is too large")),
        "{text}"
    );
    assert!(text.contains("spring.lpm:5:19"), "{text}");
}

#[test]
fn a_parameter_default_may_be_any_finite_f64() {
    let source = "model Spring;
coordinates { x }
parameters { m = 1.0, k = 1000000000000000000000000000000000000000000.0, c = -1e300 }
kinetic = 0.5 * m * pow(dot(x), 2);
potential = 0.5 * k * pow(x, 2) + c * x;
";
    let compiled = Compiled::from_source(source).unwrap();
    assert_eq!(compiled.default_parameters(), vec![1.0, 1e42, -1e300]);
    let text = match Compiled::from_source(&source.replace("1e300", "1e999")) {
        Ok(_) => panic!("1e999 is not finite"),
        Err(e) => e.to_string(),
    };
    assert!(text.contains("`1e999` is not a finite f64"), "{text}");
}

#[test]
fn a_power_of_a_sum_too_large_to_expand_in_an_energy_compiles_on_the_graph() {
    use lagrangian_core::program::{EvalContext, RoutineKind};
    let source = format!("{HEADER}potential = k * pow(x + m + 1, 100);");
    let compiled = Compiled::from_source(&source).unwrap();
    assert!(
        compiled.derivation.is_none(),
        "too large for the canonical form"
    );
    let ctx = EvalContext {
        t: 0.0,
        q: &[0.5],
        qd: &[2.0],
        qdd: &[0.0],
        parameters: &[1.0, 100.0],
        inputs: &|_: usize, _: &[f64]| 0.0,
    };
    let program = &compiled.program;
    let run = |kind| {
        let routine = program.routine(kind).unwrap();
        let mut out = vec![0.0; routine.outputs.len()];
        program.run(routine, &ctx, &mut program.registers(), &mut out);
        out
    };
    let (m, f) = (run(RoutineKind::Dynamics)[0], run(RoutineKind::Dynamics)[1]);
    let energies = run(RoutineKind::Energies);
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-14 * b.abs();
    assert_eq!(m, 1.0);
    // f = −dV/dx = −100 k (x + m + 1)^99, V = k (x + m + 1)^100, T = ½ m ẋ².
    assert!(close(f, -100.0 * 100.0 * 2.5f64.powi(99)), "{f}");
    assert!(close(energies[1], 100.0 * 2.5f64.powi(100)), "{energies:?}");
    assert_eq!(energies[0], 2.0);
}

#[test]
fn a_power_of_a_sum_with_a_huge_expansion_is_refused_at_the_call() {
    // A `let` is canonical (energies are not: see the next test).
    let text = error_of("let p = pow(x + m + 1, 100);\npotential = k * p;");
    assert!(
        text.contains(
            "this power raises a sum of 3 terms to the power 100, whose expansion would have more than 4096 terms"
        ),
        "{text}"
    );
    assert!(text.contains("spring.lpm:5:9"), "{text}");
    // pow(x + 1, 100000) ran for ever.
    let text = error_of("potential = k * pow(x + 1, 100000);");
    assert!(
        text.contains("this power has the exponent 100000, beyond the supported range"),
        "{text}"
    );
    // Beyond i64 the exponent was read as 0: pow(x + 1, …) was 1.
    let text = error_of("potential = k * pow(x + 1, 100000000000000000000000);");
    assert!(
        text.contains(
            "this power has the exponent 100000000000000000000000, beyond the supported range"
        ),
        "{text}"
    );
}

#[test]
fn an_exponent_beyond_the_supported_range_is_refused() {
    // 4294967298 = 2³² + 2 was truncated to u32 in the emitted program.
    let text = error_of("potential = k * pow(x, 4294967298);");
    assert!(
        text.contains("this power has the exponent 4294967298, beyond the supported range"),
        "{text}"
    );
    assert!(text.contains("spring.lpm:5:17"), "{text}");
    assert!(text.contains("at most 1024"), "{text}");
    let text = error_of("potential = k * pow(pow(x, 1000), 1000);");
    assert!(text.contains("the exponent 1000000"), "{text}");
}

#[test]
fn constants_outside_a_function_domain_are_reported_at_compile_time() {
    // These compiled and failed only at run time ("M or f is not finite").
    let text = error_of("potential = k * x * sqrt(-1);");
    assert!(
        text.contains(
            "`sqrt` of the constant -1: the square root of a negative number is not real"
        ),
        "{text}"
    );
    assert!(text.contains("spring.lpm:5:21"), "{text}");
    let text = error_of("potential = k * x * ln(1 - 1);");
    assert!(
        text.contains("`ln` of the constant 0: the logarithm is defined for positive numbers only"),
        "{text}"
    );
    let text = error_of("potential = k * x * (-2.0).powf(0.5);");
    assert!(
        text.contains("the negative constant -2 to the power 1/2 is not a real number"),
        "{text}"
    );
    // Exact roots of negative constants are fine, and so is 0⁰ = 1.
    let source = format!("{HEADER}potential = k * x * pow(-8, 1/3) * pow(0, 0);");
    Compiled::from_source(&source).unwrap();
}

/// A spec whose potential is `k * x * (…)` with `inner` in the brackets.
fn with_potential_factor(inner: &str) -> String {
    format!("{HEADER}potential = k * x * ({inner});\n")
}

#[test]
fn a_sum_of_twenty_thousand_terms_compiles() {
    // Lowering recursed once per term and overflowed the stack (an abort).
    let source = with_potential_factor(&vec!["x"; 20_000].join(" + "));
    let compiled = Compiled::from_source(&source).unwrap();
    let v = compiled.derivation.as_ref().expect("canonical").potential;
    assert_eq!(compiled.model.store.to_text(v), "20000*x^2*k");
}

#[test]
fn the_longest_accepted_spec_still_compiles() {
    // Just below MAX_TOKENS: the deepest recursion the limit allows.
    let terms = lagrangian_core::depth::MAX_TOKENS / 2 - 100;
    let source = with_potential_factor(&vec!["x"; terms].join(" + "));
    Compiled::from_source(&source).unwrap();
    let source = with_potential_factor(&vec!["x"; terms + 200].join(" + "));
    let text = match Compiled::from_source(&source) {
        Ok(_) => panic!("more than MAX_TOKENS"),
        Err(e) => e.render("spring.lpm", &source),
    };
    assert!(text.contains("the spec is too long"), "{text}");
}

#[test]
fn deep_nesting_and_long_operator_runs_are_located_errors_not_aborts() {
    let deep = format!("{}x{}", "(".repeat(1000), ")".repeat(1000));
    let text = error_of(&format!("potential = k * x * {deep};"));
    assert!(
        text.contains("brackets nested more than 256 deep"),
        "{text}"
    );
    // The 257th bracket: column 21 + 256.
    assert!(text.contains("spring.lpm:5:277"), "{text}");
    let signs = format!("{}x", "-".repeat(20_000));
    let text = error_of(&format!("potential = k * x * {signs};"));
    assert!(text.contains("more than 256 operators in a row"), "{text}");
}

#[test]
fn deep_input_in_the_macro_is_a_compile_error() {
    let deep: proc_macro2::TokenStream = format!(
        "model Deep; coordinates {{ x }} parameters {{ m = 1.0 }} kinetic = m * pow(dot(x), 2) * {}1{};",
        "(".repeat(1000),
        ")".repeat(1000)
    )
    .parse()
    .unwrap();
    let out = lagrangian_core::expand::expand(deep).to_string();
    assert!(out.contains("compile_error"), "{out}");
    assert!(out.contains("brackets nested more than 256 deep"), "{out}");
    // Far beyond the limit, too deep even to read the model's outline for
    // its stand-in: the error alone, and no overflow of the stack.
    let deeper: proc_macro2::TokenStream = format!(
        "model Deep; coordinates {{ x }} kinetic = pow(dot(x), 2) * {}1{};",
        "(".repeat(100_000),
        ")".repeat(100_000)
    )
    .parse()
    .unwrap();
    let out = lagrangian_core::expand::expand(deeper).to_string();
    assert!(out.contains("brackets nested more than 256 deep"));
    assert!(!out.contains("struct Deep"), "no stand-in past the limits");
}

#[test]
fn a_double_star_power_is_explained_like_the_caret() {
    let text = error_of("potential = 0.5 * k * x ** 2;");
    assert!(
        text.contains("`**` is not a power in Rust syntax"),
        "{text}"
    );
    assert!(text.contains("write the power as `pow(x, 2)`"), "{text}");
    assert!(text.contains("spring.lpm:5:26"), "{text}");
}

#[test]
fn a_let_used_before_its_definition_says_where_it_is() {
    let text = error_of("let v = 2.0 * w;\nlet w = x;\npotential = 0.5 * k * pow(v, 2);");
    assert!(
        text.contains("error: `w` is defined below, by a later `let`"),
        "{text}"
    );
    assert!(text.contains("spring.lpm:5:15"), "{text}");
    assert!(
        text.contains("note: defined here\n --> spring.lpm:6:5"),
        "{text}"
    );
    assert!(text.contains("move `let w` up"), "{text}");
}

/// Each kind of hostile length is refused before `syn` parses it, at the
/// token, in far less than a second (a 100 000-digit integer took syn over
/// 20 s; a 50 000-character misspelt name, the suggestion search as long).
#[test]
fn a_huge_number_or_name_is_a_located_error_at_once() {
    for (token, message) in [
        (
            format!("1{}", "0".repeat(99_999)),
            "a number of 100000 characters: numbers are at most 256",
        ),
        (
            format!("{}.5", "9".repeat(99_998)),
            "a number of 100000 characters: numbers are at most 256",
        ),
        (
            "k".repeat(50_000),
            "a name of 50000 characters: names are at most 256",
        ),
    ] {
        let start = std::time::Instant::now();
        let text = error_of(&format!("potential = 0.5 * {token} * k * pow(x, 2);"));
        let seconds = start.elapsed().as_secs_f64();
        assert!(
            text.starts_with(&format!("error: {message}\n --> spring.lpm:5:19\n")),
            "{}",
            &text[..200]
        );
        assert!(
            text.len() < 1000,
            "the snippet shows a window of the line: {} bytes",
            text.len()
        );
        assert!(seconds < 2.0, "{seconds} s");
    }
}

/// A misspelt name as long as names may be still gets its suggestion, in
/// bounded time.
#[test]
fn a_long_misspelt_name_is_suggested_its_declaration() {
    let name = "k".repeat(256);
    let typo = format!("{}j", "k".repeat(255));
    let source = format!(
        "model Spring;
coordinates {{ x }}
parameters {{ m = 1.0, {name} = 100.0 }}
kinetic = 0.5 * m * pow(dot(x), 2);
potential = 0.5 * {typo} * pow(x, 2);
"
    );
    let text = match Compiled::from_source(&source) {
        Ok(_) => panic!("compiled"),
        Err(e) => e.render("spring.lpm", &source),
    };
    assert!(text.contains(&format!("did you mean `{name}`?")), "{text}");
}

/// An input's argument that calls another input, directly or through a
/// `let` (friction under a contact's normal force): it compiles, and the
/// input-argument routine hands the outer input the inner one's value.
#[test]
fn an_input_called_in_an_inputs_arguments_gets_the_inner_value() {
    let header = "model Rubbing;
coordinates { x [m], y [m] }
parameters { m [kg] = 1.0, w [N] = 10.0 }
inputs { press(d [m], v [m/s]) [N], rub(v [m/s], n [N]) [N] }
kinetic = 0.5 * m * (pow(dot(x), 2) + pow(dot(y), 2));
force y = press(y, dot(y));
";
    // press(d, v) = 1000 d + 10 v; rub(v, n) = v n.
    let inputs = |index: usize, args: &[f64]| match index {
        0 => 1000.0 * args[0] + 10.0 * args[1],
        _ => args[0] * args[1],
    };
    let (q, qd) = ([0.0, 0.002], [3.0, -0.1]);
    let press = 1000.0 * 0.002 + 10.0 * -0.1;
    for (body, rub_normal) in [
        ("force x = -rub(dot(x), press(y, dot(y)));", press),
        (
            "let n = press(y, dot(y));\nforce x = -rub(dot(x), 2.0 * n);",
            2.0 * press,
        ),
    ] {
        let source = format!("{header}{body}\n");
        let model = Compiled::from_source(&source).unwrap().interpreted();
        // One call of each input, by input index: press(y, ẏ), rub(ẋ, n).
        assert_eq!(model.input_sites(), &[(0, 2), (1, 2)], "{body}");
        let mut arguments = [0.0; 4];
        (model.evaluate_input_arguments(0.0, &q, &qd, &inputs, &mut arguments)).unwrap();
        assert_eq!(arguments, [0.002, -0.1, 3.0, rub_normal], "{body}");
        let (mut mass, mut forcing) = ([0.0; 4], [0.0; 2]);
        (model.evaluate_dynamics(0.0, &q, &qd, &inputs, &mut mass, &mut forcing)).unwrap();
        assert_eq!(forcing, [-3.0 * rub_normal, press], "{body}");
    }
}
