//! A chain whose positions are a recursive family (`x[i] = x[i - 1] +
//! l[i] sin θ[i]`, a loop from 2) and whose energies are sums: the pendulum
//! chain of `tests/specs/chain/pendulum_chain_10_families.lpm` (12 lines)
//! has the M and f of `specs/pendulum_chain_10.lpm` (101 lines, written by
//! `lpm chain 10`) at random states and parameters. Its parameters are
//! declared in another order (all masses, then all lengths), so the
//! canonical forms order their factors otherwise and agree to rounding,
//! not bit for bit.

use lagrangian::nalgebra::SVector;
use lagrangian::{ConstantInputs, Interpreted, LagrangianSystem};
use lagrangian_core::random::Lcg;

fn interpreted(path: &str) -> Interpreted<10> {
    let source = std::fs::read_to_string(path).unwrap();
    Interpreted::new(lagrangian_core::interpret(&source).unwrap()).unwrap()
}

/// `m[3]` as the written-out spec names it, `m3`.
fn written_out(name: &str) -> String {
    name.replace(['[', ']'], "")
}

#[test]
fn the_pendulum_chain_with_families_has_the_written_out_equations() {
    let mut families = interpreted("tests/specs/chain/pendulum_chain_10_families.lpm");
    let mut original = interpreted("specs/pendulum_chain_10.lpm");
    let names: Vec<String> = families
        .parameter_names()
        .iter()
        .map(|n| n.to_string())
        .collect();
    let mut expected: Vec<String> = original
        .parameter_names()
        .iter()
        .map(|n| n.to_string())
        .collect();
    let mut found: Vec<String> = names.iter().map(|n| written_out(n)).collect();
    expected.sort();
    found.sort();
    assert_eq!(found, expected);
    let mut rng = Lcg::new(10);
    let none = ConstantInputs(vec![]);
    let mut worst = 0.0f64;
    for _ in 0..100 {
        for name in &names {
            let value = 0.5 + rng.unit();
            families.set_parameter(name, value).unwrap();
            original.set_parameter(&written_out(name), value).unwrap();
        }
        let q = SVector::<f64, 10>::from_fn(|_, _| 2.0 * rng.symmetric());
        let qd = SVector::<f64, 10>::from_fn(|_, _| 3.0 * rng.symmetric());
        let (mf, ff) = families.mass_matrix_and_forcing_pair(0.0, &q, &qd, &none);
        let (mo, fo) = original.mass_matrix_and_forcing_pair(0.0, &q, &qd, &none);
        let scale = mo.abs().max() + fo.abs().max();
        worst = worst.max(((mf - mo).abs().max() + (ff - fo).abs().max()) / scale);
    }
    assert!(
        worst < 1e-13,
        "largest difference {worst:e} of the values' scale"
    );
}
