//! The display factoring of equation documents never changes a value.

use lagrangian_core::Compiled;
use lagrangian_core::expr::pretty::{Tree, pretty, rebuild};

#[test]
fn every_displayed_equation_rebuilds_to_the_derived_one() {
    let mut sources: Vec<String> = std::fs::read_dir("../specs")
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "lpm"))
        .map(|p| std::fs::read_to_string(p).unwrap())
        .collect();
    sources.push(lagrangian_core::examples::pendulum_chain(4));
    let mut checked = 0;
    for source in sources {
        let mut c = Compiled::from_source(&source).unwrap();
        let d = c.canonical().unwrap().clone();
        let mut all = d.mass_matrix.clone();
        all.extend(&d.forcing);
        all.extend(&d.generalized_forces);
        all.extend([d.kinetic, d.potential, d.dissipation]);
        for e in all {
            let tree = pretty(&mut c.model.store, e);
            assert_eq!(
                rebuild(&mut c.model.store, &tree),
                e,
                "{}: {tree:?}",
                c.model.name
            );
            checked += 1;
        }
    }
    assert!(checked > 100);
}

#[test]
fn the_paper_inertia_is_a_sum_of_squares() {
    let source = std::fs::read_to_string("../specs/yaris_double_pendulum.lpm").unwrap();
    let mut c = Compiled::from_source(&source).unwrap();
    let m11 = c.canonical().unwrap().mass(1, 1);
    let tree = pretty(&mut c.model.store, m11);
    // m2 (r + l0 + l1)² + m1 (r + l0)² + I1: three terms, two of them squares.
    let Tree::Add(parts) = &tree else {
        panic!("{tree:?}")
    };
    assert_eq!(parts.len(), 3, "{tree:?}");
    let squares = parts
        .iter()
        .filter(|(_, t)| matches!(t, Tree::Mul(items) if items.iter().any(|i| matches!(i, Tree::Pow(_, e) if e.to_i64() == Some(2)))))
        .count();
    assert_eq!(squares, 2, "{tree:?}");
}
