//! Identifiers in generated code: the user's names where they are free,
//! suffixed with `_` where they would collide.

use crate::program::Op;
use crate::spec::Model;
use proc_macro2::{Ident, Span, TokenStream};
use quote::quote;
use rustc_hash::FxHashSet;

/// Names of the generated methods' parameters, which locals must not shadow.
const TAKEN: &[&str] = &[
    "t", "q", "qd", "qdd", "inputs", "mass", "forcing", "out", "self", "Self", "I", "f64", "value",
    "name",
];

pub(crate) struct Names {
    /// Struct fields, one per parameter (the parameter's own name).
    pub fields: Vec<Ident>,
    /// `INPUT_<NAME>` constants, one per input function.
    pub input_consts: Vec<Ident>,
    coordinates: Vec<Ident>,
    velocities: Vec<Ident>,
    accelerations: Vec<Ident>,
    parameters: Vec<Ident>,
    temporary_prefix: String,
}

/// An identifier for `name`, raw when it is written `r#…`.
pub(crate) fn ident(name: &str) -> Ident {
    match name.strip_prefix("r#") {
        Some(raw) => Ident::new_raw(raw, Span::call_site()),
        None => Ident::new(name, Span::call_site()),
    }
}

impl Names {
    pub fn new(model: &Model) -> Names {
        let mut taken: FxHashSet<String> = TAKEN.iter().map(|s| s.to_string()).collect();
        let mut fresh = |base: String| {
            let mut name = base;
            while !taken.insert(name.clone()) {
                name.push('_');
            }
            ident(&name)
        };
        let coordinates: Vec<Ident> = model
            .coordinates
            .iter()
            .map(|c| fresh(c.name.clone()))
            .collect();
        let parameters: Vec<Ident> = model
            .parameters
            .iter()
            .map(|p| fresh(p.name.clone()))
            .collect();
        let velocities: Vec<Ident> = model
            .coordinates
            .iter()
            .map(|c| fresh(format!("{}_dot", c.name)))
            .collect();
        let accelerations: Vec<Ident> = model
            .coordinates
            .iter()
            .map(|c| fresh(format!("{}_ddot", c.name)))
            .collect();
        let mut consts = FxHashSet::default();
        let input_consts = model
            .inputs
            .iter()
            .enumerate()
            .map(|(k, i)| {
                let mut name = format!("INPUT_{}", i.name.trim_start_matches("r#").to_uppercase());
                if !consts.insert(name.clone()) {
                    name = format!("{name}_{k}");
                    consts.insert(name.clone());
                }
                ident(&name)
            })
            .collect();
        let all: Vec<String> = coordinates
            .iter()
            .chain(&parameters)
            .chain(&velocities)
            .chain(&accelerations)
            .map(|i| i.to_string())
            .collect();
        let temporary_prefix = ["x", "tmp", "v", "w", "e", "x_"]
            .into_iter()
            .find(|p| {
                !all.iter().any(|n| {
                    n.strip_prefix(p).is_some_and(|rest| {
                        !rest.is_empty() && rest.chars().all(|c| c.is_ascii_digit())
                    })
                })
            })
            .unwrap_or("__x")
            .to_string();
        Names {
            fields: model.parameters.iter().map(|p| ident(&p.name)).collect(),
            input_consts,
            coordinates,
            velocities,
            accelerations,
            parameters,
            temporary_prefix,
        }
    }

    /// The local for a load and the expression it is loaded from.
    pub fn load(&self, op: &Op) -> (Ident, TokenStream) {
        let index = |i: &u32| proc_macro2::Literal::usize_unsuffixed(*i as usize);
        match op {
            Op::Coordinate(i) => {
                let k = index(i);
                (self.coordinates[*i as usize].clone(), quote!(q[#k]))
            }
            Op::Velocity(i) => {
                let k = index(i);
                (self.velocities[*i as usize].clone(), quote!(qd[#k]))
            }
            Op::Acceleration(i) => {
                let k = index(i);
                (self.accelerations[*i as usize].clone(), quote!(qdd[#k]))
            }
            Op::Parameter(i) => {
                let field = &self.fields[*i as usize];
                (self.parameters[*i as usize].clone(), quote!(self.#field))
            }
            _ => (ident("__unused"), quote!(f64::NAN)),
        }
    }

    pub fn temporary(&self, k: usize) -> Ident {
        ident(&format!("{}{k}", self.temporary_prefix))
    }
}
