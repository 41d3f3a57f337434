//! `lpm chain N`: the spec of an N-link pendulum chain.

use crate::failure::{Failure, Outcome};

/// Options of `lpm chain`.
#[derive(clap::Args)]
pub struct Args {
    /// Number of links.
    links: usize,
}

/// Runs `lpm chain`.
pub fn run(args: Args) -> Result<Outcome, Failure> {
    if args.links == 0 {
        return Err(Failure::usage("a chain needs at least one link"));
    }
    Ok(Outcome::success(lagrangian_core::examples::pendulum_chain(
        args.links,
    )))
}
