//! Indexed families (`x[7]`, `for`, `sum`, `x[i + 1]`) expand into exactly
//! the written-out model: the Pioneer chain written with families
//! (`tests/specs/pioneer_families.lpm`, its tangents left to the
//! components: `d(x), d(v)`) derives the M, f, Q, Jacobians,
//! energies and outputs of `specs/pioneer_wagon.lpm`, term for term, once
//! its element names are read as the written-out spec spells them; and
//! every misuse is an error at its span.

use lagrangian_core::Compiled;
use lagrangian_core::derive::Derivation;

const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/..");

fn read(path: &str) -> String {
    std::fs::read_to_string(format!("{ROOT}/{path}")).unwrap()
}

/// Every derived expression of `compiled`, as text.
fn equations(compiled: &mut Compiled) -> Vec<String> {
    let derivation: Derivation = compiled.canonical().unwrap().clone();
    let store = &compiled.model.store;
    let jacobians = derivation
        .jacobians
        .as_ref()
        .expect("both ask for jacobians");
    (derivation.mass_matrix.iter())
        .chain(&derivation.forcing)
        .chain(&derivation.generalized_forces)
        .chain(&jacobians.forcing_q)
        .chain(&jacobians.forcing_qd)
        .chain(&jacobians.mass_times_acceleration_q)
        .chain([
            &derivation.kinetic,
            &derivation.potential,
            &derivation.external_power,
        ])
        .chain(&derivation.outputs)
        .map(|&e| store.display(e).to_string())
        .collect()
}

/// `text` with the families' elements spelled as the written-out spec
/// names them: `x[3]` is `x3`, and the tangents the components supply,
/// `spring[3]_dx` and `spring[3]_dv`, are its `spring3_stiffness` and
/// `spring3_damping`.
fn written_out(text: &str) -> String {
    let text = text.replace("_dx", "_stiffness").replace("_dv", "_damping");
    let mut out = String::new();
    let mut rest = text.as_str();
    while let Some(open) = rest.find('[') {
        let close = open + rest[open..].find(']').unwrap();
        let (before, index) = (&rest[..open], &rest[open + 1..close]);
        let start = before
            .rfind(|c: char| !(c.is_alphanumeric() || c == '_'))
            .map_or(0, |k| k + 1);
        let name = &before[start..];
        out.push_str(&before[..start]);
        out.push_str(&format!("{name}{index}"));
        rest = &rest[close + 1..];
    }
    out.push_str(rest);
    out
}

#[test]
fn the_pioneer_chain_with_families_derives_the_written_out_equations() {
    let mut families = Compiled::from_source(&read("tests/specs/pioneer_families.lpm")).unwrap();
    let mut original = Compiled::from_source(&read("specs/pioneer_wagon.lpm")).unwrap();
    let names = |c: &Compiled| {
        let m = &c.model;
        (m.coordinates.iter().map(|c| c.name.clone()))
            .chain(m.parameters.iter().map(|p| p.name.clone()))
            .chain(m.inputs.iter().map(|i| i.name.clone()))
            .collect::<Vec<_>>()
    };
    let family_names = names(&families);
    assert_eq!(
        &family_names[..8],
        [
            "x[1]", "x[2]", "x[3]", "x[4]", "x[5]", "x[6]", "x[7]", "m[1]"
        ]
    );
    assert!(family_names.contains(&"spring[6]_dv".to_string()));
    let mut expected = names(&original);
    let mut found: Vec<String> = family_names.iter().map(|n| written_out(n)).collect();
    expected.sort();
    found.sort();
    assert_eq!(found, expected);
    let ours: Vec<String> = equations(&mut families)
        .iter()
        .map(|e| written_out(e))
        .collect();
    let theirs = equations(&mut original);
    assert_eq!(ours.len(), theirs.len());
    for (k, (a, b)) in ours.iter().zip(&theirs).enumerate() {
        assert_eq!(a, b, "expression {k}");
    }
    let defaults = |c: &Compiled| {
        c.model
            .parameters
            .iter()
            .map(|p| p.default)
            .collect::<Vec<_>>()
    };
    assert_eq!(defaults(&families), defaults(&original));
}

const CHAIN: &str = "
model Chain;
coordinates { x[3] [m] }
parameters { m[3] [kg] = [1.0, 2.0, 3.0], k[i in 1..=2] [N/m] = 10.0 * i }
for i in 1..=2 { let c[i] = x[i + 1] - x[i]; }
kinetic = sum(i in 1..=3, 0.5 * m[i] * pow(dot(x[i]), 2));
potential = sum(i in 1..=2, 0.5 * k[i] * pow(c[i], 2));
BAD
";

/// The first error of the chain with `bad` in place of `BAD`, with its
/// line and column.
fn error(bad: &str) -> (String, usize, usize) {
    let source = CHAIN.replace("BAD", bad);
    let errors = Compiled::from_source(&source).err().expect("an error");
    let d = &errors.diagnostics[0];
    let start = d.span.start.start();
    (d.message.clone(), start.line, start.column)
}

#[test]
fn a_family_s_elements_and_defaults_are_written_out() {
    let compiled = Compiled::from_source(&CHAIN.replace("BAD", "")).unwrap();
    let defaults: Vec<(String, f64)> = compiled
        .model
        .parameters
        .iter()
        .map(|p| (p.name.clone(), p.default))
        .collect();
    let expected = [
        ("m[1]", 1.0),
        ("m[2]", 2.0),
        ("m[3]", 3.0),
        ("k[1]", 10.0),
        ("k[2]", 20.0),
    ];
    assert_eq!(defaults, expected.map(|(n, v)| (n.to_string(), v)));
    let definitions: Vec<&str> = compiled
        .model
        .definitions
        .iter()
        .map(|(n, _)| n.as_str())
        .collect();
    assert_eq!(definitions, ["c[1]", "c[2]"]);
}

#[test]
fn every_misuse_of_a_family_is_an_error_at_its_span() {
    assert_eq!(
        error("output o [m] = x[4];"),
        (
            "`x[4]` is outside `x`, whose elements are 1..=3".into(),
            8,
            17
        )
    );
    assert_eq!(
        error("output o [m] = x;"),
        (
            "`x` is a family of coordinates (`x[1]` … `x[3]`): name one element, `x[i]`".into(),
            8,
            15
        )
    );
    assert_eq!(
        error("output o [m] = x[1.5];"),
        (
            "an index is an integer expression of integers and loop indices (`i + 1`)".into(),
            8,
            17
        )
    );
    let (message, line, _) = error("for i in 1..3 { output o[i] [m] = x[i]; }");
    assert_eq!(
        (message.as_str(), line),
        ("a range here includes both ends: write `a..=b`", 8)
    );
    let (message, ..) = error("output o [m] = c[3];");
    assert_eq!(message, "unknown name `c[3]`");
    let (message, ..) = error("for x in 1..=2 { output o[x] [m] = 0.0; }");
    assert_eq!(message, "the loop index `x` hides a name the spec declares");
    let source = CHAIN
        .replace("[1.0, 2.0, 3.0]", "[1.0, 2.0]")
        .replace("BAD", "");
    let errors = Compiled::from_source(&source).err().unwrap();
    assert_eq!(
        errors.diagnostics[0].message,
        "`m` has 3 elements but 2 values"
    );
}

#[test]
fn a_loop_too_large_is_refused_not_run() {
    let (message, ..) = error("for i in 1..=2000000 { output o[i] [m] = x[1]; }");
    assert!(message.contains("expand past 1000000 terms"), "{message}");
    let (message, ..) = error("output o [m] = sum(i in 1..=5000000, x[1]);");
    assert!(message.contains("expand past 1000000 terms"), "{message}");
}

#[test]
fn an_element_spelled_as_a_declared_name_in_generated_code_is_an_error() {
    let source = CHAIN.replace(
        "k[i in 1..=2] [N/m] = 10.0 * i",
        "k[i in 1..=2] [N/m] = 10.0 * i, m_2 [kg] = 1.0",
    );
    let errors = Compiled::from_source(&source.replace("BAD", ""))
        .err()
        .unwrap();
    assert_eq!(
        errors.diagnostics[0].message,
        "`m[2]` is `m_2` in generated code, which the spec declares too"
    );
}

#[test]
fn a_family_of_more_coordinates_than_a_derivation_can_take_is_refused() {
    let source = CHAIN
        .replace("x[3] [m]", "x[3] [m], y[998] [m]")
        .replace("BAD", "");
    let errors = Compiled::from_source(&source).err().unwrap();
    assert_eq!(
        errors.diagnostics[0].message,
        "1001 coordinates: families may declare at most 1000"
    );
}

#[test]
fn a_problem_in_a_loop_s_body_is_reported_once() {
    let errors = Compiled::from_source(
        &CHAIN.replace("BAD", "for i in 1..=2 { output o[i] [m] = x[i + 5]; }"),
    )
    .err()
    .unwrap();
    assert_eq!(errors.diagnostics.len(), 1, "{:?}", errors.diagnostics);
    assert_eq!(
        errors.diagnostics[0].message,
        "`x[6]` is outside `x`, whose elements are 1..=3"
    );
}

/// Replaces, deletes or duplicates one of `text`'s tokens (split at spaces
/// and brackets), or swaps in a construct of the families' syntax.
fn mutated(text: &str, rng: &mut lagrangian_core::random::Lcg) -> String {
    const SNIPPETS: [&str; 12] = [
        "[0]",
        "[i]",
        "[i + 1]",
        "1..7",
        "1..=0",
        "sum(i in 1..=3, x)",
        "x[",
        "]",
        "for i in 1..=2 {",
        "}",
        "[-1]",
        "d(x)",
    ];
    let pieces: Vec<&str> = text.split_inclusive([' ', '[', ']', '\n']).collect();
    let k = (rng.unit() * pieces.len() as f64) as usize % pieces.len();
    let snippet = SNIPPETS[(rng.unit() * SNIPPETS.len() as f64) as usize % SNIPPETS.len()];
    let mut out: Vec<&str> = pieces.clone();
    match (rng.unit() * 3.0) as usize {
        0 => out[k] = snippet,
        1 => {
            out.remove(k);
        }
        _ => out.insert(k, snippet),
    }
    out.concat()
}

#[test]
fn mutated_family_specs_give_a_model_or_located_errors_never_a_panic() {
    let originals = [
        read("tests/specs/pioneer_families.lpm"),
        read("tests/specs/chain/chain_50.lpm"),
        CHAIN.replace("BAD", "for i in 1..=3 { output o[i] [m] = x[i]; }"),
    ];
    let mut rng = lagrangian_core::random::Lcg::new(37);
    let (mut compiled, mut refused) = (0, 0);
    for k in 0..600 {
        let text = mutated(&originals[k % 3], &mut rng);
        let outcome = std::panic::catch_unwind(|| lagrangian_core::Model::from_source(&text));
        match outcome.unwrap_or_else(|_| panic!("panicked on:\n{text}")) {
            Ok(_) => compiled += 1,
            Err(errors) => {
                assert!(
                    !errors.diagnostics.is_empty(),
                    "an error without a diagnostic:\n{text}"
                );
                refused += 1;
            }
        }
    }
    assert!(
        compiled > 10 && refused > 100,
        "{compiled} compiled, {refused} refused"
    );
}

#[test]
fn a_lowering_problem_a_loop_repeats_is_reported_once() {
    let body = "for i in 1..=2 { let a[i] = b[i]; let b[i] = x[i]; }";
    let errors = Compiled::from_source(&CHAIN.replace("BAD", body))
        .err()
        .unwrap();
    let messages: Vec<&str> = errors
        .diagnostics
        .iter()
        .map(|d| d.message.as_str())
        .collect();
    assert_eq!(
        messages,
        [
            "`b[1]` is defined below, by a later `let`",
            "`b[2]` is defined below, by a later `let`"
        ]
    );
}

#[test]
fn a_family_s_values_are_counted_by_its_range_however_it_is_written() {
    let source = CHAIN
        .replace(
            "m[3] [kg] = [1.0, 2.0, 3.0]",
            "m[i in 1..=1 + 2] [kg] = [1.0, 2.0, 3.0]",
        )
        .replace("BAD", "");
    let compiled = Compiled::from_source(&source).unwrap();
    let masses: Vec<f64> = compiled.model.parameters[..3]
        .iter()
        .map(|p| p.default)
        .collect();
    assert_eq!(masses, [1.0, 2.0, 3.0]);
}
