//! The integration methods by name: the one list that scenarios, the command
//! line and messages take their names from.

use super::tableau::{DOPRI5, RK4};
use super::tr_bdf2::{self, AccelerationJacobians};
use super::{Observer, Options, Outcome, PhaseState, SolverError, explicit};
use std::fmt;
use std::str::FromStr;

/// An integration method for a mechanical problem.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Method {
    /// Dormand–Prince 5(4): adaptive, with dense output (the default).
    Dopri5,
    /// The classical Runge–Kutta method with a fixed step.
    Rk4,
    /// TR-BDF2, L-stable and implicit, with Newton iterations on the
    /// model's Jacobians: for stiff contact or weld springs.
    TrBdf2,
}

impl Method {
    /// Every method, in the order of [`Method::NAMES`].
    pub const ALL: [Method; 3] = [Method::Dopri5, Method::Rk4, Method::TrBdf2];

    /// The name of each method of [`Method::ALL`], as scenarios and
    /// `--method` write it.
    pub const NAMES: [&'static str; 3] = {
        let mut names = [""; 3];
        let mut i = 0;
        while i < names.len() {
            names[i] = Method::ALL[i].name();
            i += 1;
        }
        names
    };

    /// Former names still read, `(name, method)`: scenarios written for an
    /// earlier version keep working. Messages and help list [`Method::NAMES`].
    pub const ALIASES: [(&'static str, Method); 1] = [("implicit", Method::TrBdf2)];

    /// The method's name.
    pub const fn name(self) -> &'static str {
        match self {
            Method::Dopri5 => "dopri5",
            Method::Rk4 => "rk4",
            Method::TrBdf2 => "tr-bdf2",
        }
    }

    /// The order of accuracy of the solution.
    pub fn order(self) -> u32 {
        match self {
            Method::Dopri5 => DOPRI5.order,
            Method::Rk4 => RK4.order,
            Method::TrBdf2 => 2,
        }
    }

    /// Whether the method controls its step size by an error estimate (a
    /// fixed-step method needs `Options::fixed_step`).
    pub fn is_adaptive(self) -> bool {
        match self {
            Method::Dopri5 => DOPRI5.error.is_some(),
            Method::Rk4 => RK4.error.is_some(),
            Method::TrBdf2 => true,
        }
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A name that is none of [`Method::NAMES`].
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown method `{0}`; use {names}", names = Method::NAMES.join(", "))]
pub struct UnknownMethod(pub String);

impl FromStr for Method {
    type Err = UnknownMethod;

    fn from_str(text: &str) -> Result<Method, UnknownMethod> {
        let names = Method::ALL.into_iter().map(|m| (m.name(), m));
        names
            .chain(Method::ALIASES)
            .find(|(name, _)| *name == text)
            .map(|(_, method)| method)
            .ok_or_else(|| UnknownMethod(text.to_string()))
    }
}

/// Integrates the mechanical problem `problem` from `(t0, y0)` to `t_end`
/// with `method`, calling `observer` with the problem and every accepted
/// step (truncated at events).
pub fn integrate<const N: usize, P: AccelerationJacobians<N>>(
    method: Method,
    problem: &mut P,
    (t0, y0): (f64, PhaseState<N>),
    t_end: f64,
    options: &Options,
    observer: Observer<'_, P, PhaseState<N>>,
) -> Result<Outcome<PhaseState<N>>, SolverError<P::Error>> {
    match method {
        Method::Dopri5 => explicit::integrate(&DOPRI5, problem, t0, y0, t_end, options, observer),
        Method::Rk4 => explicit::integrate(&RK4, problem, t0, y0, t_end, options, observer),
        Method::TrBdf2 => tr_bdf2::integrate(problem, t0, y0, t_end, options, observer),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_method_reads_back_from_its_name() {
        for method in Method::ALL {
            assert_eq!(method.name().parse::<Method>(), Ok(method));
            assert_eq!(method.to_string(), method.name());
        }
        // The former name of TR-BDF2 still reads, but is not listed.
        assert_eq!("implicit".parse::<Method>(), Ok(Method::TrBdf2));
        let error = "sdirk".parse::<Method>().unwrap_err();
        assert_eq!(
            error.to_string(),
            "unknown method `sdirk`; use dopri5, rk4, tr-bdf2"
        );
    }
}
