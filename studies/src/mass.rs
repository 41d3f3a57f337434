//! Which parameter settings make a mass matrix not positive definite.
//!
//! The test is direct: `M` is evaluated at the same state with each set
//! parameter back at its default; a parameter whose default alone makes
//! `M` positive definite again is named (else the set parameters together,
//! when their defaults do).

use lagrangian_runtime::nalgebra::DMatrix;
use lagrangian_runtime::{ConstantInputs, InterpretedModel};

/// A state: time, coordinates, velocities.
pub type State<'a> = (f64, &'a [f64], &'a [f64]);

/// Whether `model`'s `M` at `state` is positive definite (it has a
/// Cholesky factor). `M` comes from the kinetic energy, so the inputs play
/// no part: they are given as zeros.
pub fn positive_definite(model: &InterpretedModel, (t, q, qd): State) -> bool {
    let n = model.dimension();
    let (mut mass, mut forcing) = (vec![0.0; n * n], vec![0.0; n]);
    let zeros = ConstantInputs(vec![0.0; model.input_names().len()]);
    if model
        .evaluate_dynamics(t, q, qd, &zeros, &mut mass, &mut forcing)
        .is_err()
        || mass.iter().any(|m| !m.is_finite())
    {
        return false;
    }
    DMatrix::from_row_slice(n, n, &mass).cholesky().is_some()
}

/// Why `model`'s `M` (not positive definite at `state`) is so, by the
/// parameters set away from their `defaults` (`set`: their indices), or
/// `None` when their defaults do not make it positive definite either.
pub fn blame(
    model: &InterpretedModel,
    defaults: &[f64],
    set: &[usize],
    state: State,
) -> Option<String> {
    let names = model.parameter_names();
    let with_defaults = |indices: &[usize]| {
        let mut copy = model.clone();
        for &i in indices {
            copy.set_parameter(&names[i], defaults[i]).ok()?;
        }
        Some(positive_definite(&copy, state))
    };
    let setting = |&i: &usize| format!("`{} = {}`", names[i], model.parameters()[i]);
    let culprits: Vec<usize> = (set.iter().copied())
        .filter(|&i| with_defaults(&[i]) == Some(true))
        .collect();
    if let Some(&first) = culprits.first() {
        let listed: Vec<String> = culprits.iter().map(setting).collect();
        let defaults: Vec<String> = (culprits.iter())
            .map(|&i| format!("{} = {}", names[i], defaults[i]))
            .collect();
        return Some(format!(
            "made so by {} (with {} it is positive definite at this state); check the sign of `{}`",
            listed.join(", "),
            defaults.join(" or "),
            names[first]
        ));
    }
    (!set.is_empty() && with_defaults(set) == Some(true)).then(|| {
        let listed: Vec<String> = set.iter().map(setting).collect();
        format!(
            "made so by {} together (with all of them at their defaults it is positive definite at this state)",
            listed.join(", ")
        )
    })
}
