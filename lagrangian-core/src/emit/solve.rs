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
    if is_narrow(&nonzero) {
        return quote! {
            #[inline]
            fn solve_mass(
                &self,
                mass: &#rt::nalgebra::SMatrix<f64, #dim, #dim>,
                b: &#rt::nalgebra::SVector<f64, #dim>,
            ) -> ::core::option::Option<#rt::nalgebra::SVector<f64, #dim>> {
                /// Which entries of `M` can be nonzero (the others are zero by
                /// the equations), and their envelope, a band.
                const ENVELOPE: #rt::linalg::Envelope<#dim> = #rt::linalg::Envelope::of(
                    #rt::linalg::LdltPattern::from_mass([#(#rows),*]),
                );
                #rt::linalg::solve_in_envelope(mass, b, &ENVELOPE)
            }
        };
    }
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

/// Whether the envelope of `M`'s zeros (which its factor's fill-in never
/// leaves) is narrow enough for the runtime's envelope solve, as
/// `Envelope::is_narrow` decides for the interpreter.
fn is_narrow(nonzero: &[Vec<bool>]) -> bool {
    let n = nonzero.len();
    let size: usize = (0..n)
        .map(|i| i - (0..i).find(|&j| nonzero[i][j]).unwrap_or(i))
        .sum();
    n >= 16 && 4 * size < n * (n - 1)
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

    #[test]
    fn a_chain_s_band_is_solved_in_its_envelope_a_small_model_s_is_not() {
        let read = |path: &str| {
            let file = format!("{}/../{path}", env!("CARGO_MANIFEST_DIR"));
            Compiled::from_source(&std::fs::read_to_string(file).unwrap()).unwrap()
        };
        let rt = quote!(::lagrangian_runtime);
        let chain = read("tests/specs/chain/chain_50.lpm");
        let nonzero = mass_nonzeros(&chain.program).unwrap();
        assert!(is_narrow(&nonzero));
        let method = solve_mass_method(&chain.program, &rt).to_string();
        assert!(method.contains("solve_in_envelope"), "{method}");
        let pioneer = read("specs/pioneer_wagon.lpm");
        assert!(!is_narrow(&mass_nonzeros(&pioneer.program).unwrap()));
        let method = solve_mass_method(&pioneer.program, &rt).to_string();
        assert!(method.contains("solve_with_pattern"), "{method}");
        // A dense M of 16 is not narrow; a band of half-width 4 of 16 is.
        let band = |w: usize| -> Vec<Vec<bool>> {
            (0..16usize)
                .map(|i| (0..16).map(|j| i.abs_diff(j) <= w).collect())
                .collect()
        };
        assert!(is_narrow(&band(4)) && !is_narrow(&band(15)));
    }
}
