//! The solve of `M q̈ = f` in an emitted model: `L D Lᵀ` written for the
//! model's constant `N` (the runtime's routine, which unrolls for it) with the
//! zeros of its `M` known at compile time, so that their terms are never
//! computed. The interpreter reads the same zeros from its tape.

use crate::program::{Op, Program, RoutineKind};
use lagrangian_runtime::layout::mass_entries;
use proc_macro2::{Literal, TokenStream};
use quote::quote;

/// Whether each entry `M_ij` can be nonzero (both triangles): `false` for
/// those the program computes as the constant zero. `None` without dynamics.
pub(crate) fn mass_nonzeros(program: &Program) -> Option<Vec<Vec<bool>>> {
    let routine = program.routine(RoutineKind::Dynamics)?;
    let n = program.dimension;
    let mut nonzero = vec![vec![true; n]; n];
    for ((i, j), &r) in mass_entries(n).zip(&routine.outputs) {
        if matches!(program.ops[r as usize], Op::Const(c) if c.value() == 0.0) {
            nonzero[i][j] = false;
            nonzero[j][i] = false;
        }
    }
    Some(nonzero)
}

/// The `solve_mass` method of a model whose `M` has zeros (nothing for a
/// dense `M`: the trait's default solve is the same routine without zeros).
pub(super) fn solve_mass_method(program: &Program, rt: &TokenStream) -> TokenStream {
    let Some(nonzero) = mass_nonzeros(program) else {
        return TokenStream::new();
    };
    if nonzero.iter().flatten().all(|&x| x) {
        return TokenStream::new();
    }
    let dim = Literal::usize_unsuffixed(program.dimension);
    let rows = nonzero.iter().map(|row| quote!([#(#row),*]));
    quote! {
        #[inline]
        fn solve_mass(
            &self,
            mass: &#rt::nalgebra::SMatrix<f64, #dim, #dim>,
            b: &#rt::nalgebra::SVector<f64, #dim>,
        ) -> ::core::option::Option<#rt::nalgebra::SVector<f64, #dim>> {
            /// Which entries of `M` can be nonzero (the others are zero by
            /// the equations).
            const PATTERN: #rt::linalg::LdltPattern<#dim> =
                #rt::linalg::LdltPattern::from_mass([#(#rows),*]);
            #rt::linalg::solve_with_pattern(mass, b, &PATTERN)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Compiled;

    #[test]
    fn emitted_and_interpreted_models_know_the_same_zeros_of_m() {
        let specs = concat!(env!("CARGO_MANIFEST_DIR"), "/../specs");
        let mut zeros = 0;
        for entry in std::fs::read_dir(specs).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_none_or(|e| e != "lpm") {
                continue;
            }
            let compiled = Compiled::from_source(&std::fs::read_to_string(&path).unwrap())
                .unwrap_or_else(|e| panic!("{}: {e:?}", path.display()));
            let emitted: Vec<bool> = mass_nonzeros(&compiled.program).unwrap().concat();
            let interpreted = compiled.interpreted().mass_nonzeros();
            assert_eq!(emitted, interpreted, "{}", path.display());
            zeros += emitted.iter().filter(|&&x| !x).count();
        }
        // The paper model's M_r,θ1 among them.
        assert!(zeros >= 2);
        let yaris = Compiled::from_source(include_str!("../../../specs/yaris_double_pendulum.lpm"))
            .unwrap();
        let nonzero = mass_nonzeros(&yaris.program).unwrap();
        assert!(!nonzero[0][1] && !nonzero[1][0]);
        assert_eq!(nonzero.concat().iter().filter(|&&x| !x).count(), 2);
    }
}
