//! Reusable parts expand into exactly the written-out model: the train of
//! `tests/specs/parts/train_parts.lpm`, built from the standard library
//! (`mass`, `spring_damper`, `crush_to_wall`, `belted_occupant`), derives
//! the M, f, Q, Jacobians, energies and outputs of `train_written.lpm`,
//! term for term, once its names are spelled as generated code spells
//! them; and every misuse is an error at its span.

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
    let jacobians = derivation.jacobians.as_ref().expect("jacobians");
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

/// A name as the written-out spec spells it: `car[1].m` is `car_1_m`.
fn spelled(text: &str) -> String {
    text.replace("].", "_")
        .replace('[', "_")
        .replace(']', "")
        .replace('.', "_")
}

fn names(c: &Compiled) -> Vec<String> {
    let m = &c.model;
    (m.coordinates.iter().map(|c| c.name.clone()))
        .chain(m.parameters.iter().map(|p| p.name.clone()))
        .chain(m.inputs.iter().map(|i| i.name.clone()))
        .chain(m.outputs.iter().map(|o| o.name.clone()))
        .collect()
}

#[test]
fn a_train_built_from_parts_derives_the_written_out_equations() {
    let mut parts = Compiled::from_source(&read("tests/specs/parts/train_parts.lpm")).unwrap();
    let mut written = Compiled::from_source(&read("tests/specs/parts/train_written.lpm")).unwrap();
    let part_names = names(&parts);
    assert_eq!(
        part_names[..6],
        ["x[1]", "x[2]", "x[3]", "driver.x", "car[1].m", "car[2].m"]
    );
    assert!(part_names.contains(&"front.crush_dv".to_string()));
    assert!(part_names.contains(&"coupler[2].force".to_string()));
    let spelled_names: Vec<String> = part_names.iter().map(|n| spelled(n)).collect();
    assert_eq!(spelled_names, names(&written));
    let ours: Vec<String> = equations(&mut parts).iter().map(|e| spelled(e)).collect();
    let theirs = equations(&mut written);
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
    assert_eq!(defaults(&parts), defaults(&written));
}

const SPEC: &str = "
model Parts;
coordinates { x[2] [m], theta [rad] }
parameters { J [kg*m^2] = 1.0 }
kinetic = 0.5 * J * pow(dot(theta), 2);
part link(a [m], b [m]) {
    parameters { k [N/m] = 1.0 }
    potential = 0.5 * k * pow(b - a, 2);
    output stretch [m] = b - a + LINK_BODY;
}
part car[1] = mass(x[1]);
part car[2] = mass(x[2]);
BAD
";

/// Every error of the spec with `bad` in place of `BAD` and `body` in
/// place of `LINK_BODY`: message, line, column, and the note's line.
fn errors(bad: &str, body: &str) -> Vec<(String, usize, usize, Option<usize>)> {
    let source = SPEC.replace("BAD", bad).replace("LINK_BODY", body);
    let errors = Compiled::from_source(&source).err().expect("an error");
    (errors.diagnostics.iter())
        .map(|d| {
            let start = d.span.start.start();
            let note = d.note.as_ref().map(|n| n.1.start.start().line);
            (d.message.clone(), start.line, start.column, note)
        })
        .collect()
}

fn first(bad: &str) -> (String, usize, usize) {
    let (message, line, column, _) = errors(bad, "0.0").remove(0);
    (message, line, column)
}

#[test]
fn a_spec_s_own_part_and_the_library_s_compose() {
    let source = SPEC
        .replace("BAD", "part l = link(x[1], x[2]) { k = 3.0 };")
        .replace("LINK_BODY", "0.0");
    let compiled = Compiled::from_source(&source).unwrap();
    let parameters: Vec<(String, f64)> = (compiled.model.parameters.iter())
        .map(|p| (p.name.clone(), p.default))
        .collect();
    let expected = [
        ("J", 1.0),
        ("car[1].m", 1.0),
        ("car[2].m", 1.0),
        ("l.k", 3.0),
    ];
    assert_eq!(parameters, expected.map(|(n, v)| (n.to_string(), v)));
    assert_eq!(compiled.model.outputs[0].name, "l.stretch");
}

#[test]
fn every_misuse_of_a_part_is_an_error_at_its_span() {
    assert_eq!(
        first("part l = link(x[1]);"),
        (
            "part `link` has 2 ports (a [m], b [m]), but 1 is given".into(),
            13,
            13
        )
    );
    assert_eq!(
        first("part l = linkage(x[1], x[2]);"),
        ("no part `linkage` is defined".into(), 13, 9)
    );
    assert_eq!(
        first("part l = link(x[1], theta);"),
        (
            "port `b` of part `link` is in [m], but `theta` is in [rad]".into(),
            13,
            20
        )
    );
    assert_eq!(
        first("part l = link(x[1], x[2]) { c = 1.0 };"),
        ("part `link` has no parameter `c`".into(), 13, 28)
    );
    assert_eq!(
        first("part l = link(x[1], x[3]);"),
        (
            "`x[3]` is outside `x`, whose elements are 1..=2".into(),
            13,
            22
        )
    );
    assert_eq!(
        first("part w = crush_to_wall(x[1] - x[2]);"),
        (
            "port `x` takes a coordinate here: the part applies `force x = …;` to it".into(),
            13,
            23
        )
    );
    assert_eq!(
        first("for i in 1..=2 { part p(a [m]) { } }"),
        ("part `p` is defined inside a loop".into(), 13, 22)
    );
    assert_eq!(
        first("part ring(a [m]) { part inner = ring(a); } part l = ring(x[1]);"),
        ("part `ring` contains itself: ring → ring".into(), 13, 32)
    );
    assert_eq!(
        first("part j(a [m]) { jacobians; } part l = j(x[1]);"),
        (
            "`jacobians;` belongs to the model, not to a part (`l`, an instance of `j`)".into(),
            13,
            16
        )
    );
    assert_eq!(
        first("part car[2] = mass(x[1]);"),
        ("`car[2]` names two instances".into(), 13, 5)
    );
    assert_eq!(
        first("parameters { car_1_m [kg] = 1.0 }"),
        (
            "`car_1_m` and `car[1].m` are both `car_1_m` in generated code".into(),
            13,
            13
        )
    );
}

#[test]
fn a_problem_inside_a_part_names_the_instance_too() {
    let found = errors("part l = link(x[1], x[2]);", "y");
    assert_eq!(
        found[0],
        ("unknown name `y`".to_string(), 9, 33, Some(13)),
        "{found:?}"
    );
}

/// `text` with one piece replaced, removed or doubled by a snippet that
/// misuses parts.
fn mutated(text: &str, rng: &mut lagrangian_core::random::Lcg) -> String {
    const SNIPPETS: [&str; 12] = [
        "part ",
        "part p = mass(x[1]);",
        "part q(a [m]) { part r = q(a); }",
        "(x[1], x[2])",
        "(0.0)",
        "{ m = 1.0 }",
        "{ k = }",
        "car[1].m",
        "mass",
        "stop(",
        ")",
        "force a = 0.0;",
    ];
    let pieces: Vec<&str> = text.split_inclusive([' ', '(', ')', '\n']).collect();
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
fn mutated_part_specs_give_a_model_or_located_errors_never_a_panic() {
    let originals = [
        read("tests/specs/parts/train_parts.lpm"),
        read("tests/specs/parts/bottoming.lpm"),
        SPEC.replace("BAD", "part l = link(x[1], x[2]) { k = 2.0 };")
            .replace("LINK_BODY", "0.0"),
    ];
    let mut rng = lagrangian_core::random::Lcg::new(38);
    let (mut compiled, mut refused) = (0, 0);
    let runs: usize = std::env::var("PARTS_MUTATIONS").map_or(600, |n| n.parse().unwrap());
    for k in 0..runs {
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
fn parts_nested_past_the_limit_are_refused_not_expanded() {
    let mut source = String::from("model Nest;\ncoordinates { x [m] }\n");
    source.push_str("part p0(a [m]) { part m = mass(a); }\n");
    for k in 1..=8 {
        let inner: String = (0..10)
            .map(|j| format!("part i{j} = p{}(a); ", k - 1))
            .collect();
        source.push_str(&format!("part p{k}(a [m]) {{ {inner}}}\n"));
    }
    source.push_str("part top = p8(x);\n");
    let start = std::time::Instant::now();
    let errors = Compiled::from_source(&source).err().expect("refused");
    assert_eq!(
        errors.diagnostics[0].message,
        "the parts of this spec expand past 100000 instances"
    );
    assert!(start.elapsed().as_secs() < 60, "{:?}", start.elapsed());
}
