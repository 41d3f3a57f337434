//! Butcher tableaux of the explicit Runge–Kutta methods, as data: one
//! implementation ([`super::explicit`]) runs any of them.
//!
//! Coefficients are written as the fractions of their sources and stored
//! with zeros, so that a stage skips the terms a method does not have.

/// An explicit Runge–Kutta method: `k_i = F(t + c_i h, y + h Σ_{j<i} a_ij k_j)`,
/// `y1 = y + h Σ b_i k_i`, with an optional embedded error estimate and a
/// continuous extension.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tableau {
    /// The method's name, for messages.
    pub name: &'static str,
    /// The order of `y1`.
    pub order: u32,
    /// The nodes `c_i`.
    pub c: &'static [f64],
    /// The stage coefficients `a_ij`, row `i` holding `j < i`.
    pub a: &'static [&'static [f64]],
    /// The weights `b_i` of the solution.
    pub b: &'static [f64],
    /// `b_i − b̂_i`: the weights of the local error estimate (the solution
    /// minus the embedded one, on the stages including the last, which is
    /// `F(t + h, y1)` for an FSAL method); `None` for a fixed-step method.
    pub error: Option<&'static [f64]>,
    /// The last stage is evaluated at `y1` itself ("first same as last"):
    /// its `a` row equals `b` and it is `F(t + h, y1)`, the next step's first.
    pub fsal: bool,
    /// The continuous extension of a step.
    pub dense: DenseOutput,
}

/// How an explicit method interpolates within a step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DenseOutput {
    /// Cubic Hermite on the step's ends and their derivatives.
    Hermite,
    /// Dormand–Prince's 4th-order extension (Hairer's `contd5`):
    /// `y(t0 + θh) = r0 + θ(r1 + (1−θ)(r2 + θ(r3 + (1−θ) r4)))` with
    /// `r4 = h Σ d_i k_i`.
    DormandPrince {
        /// The weights `d_i` of `r4`, per stage.
        d: &'static [f64],
    },
}

impl Tableau {
    /// The number of stages.
    pub fn stages(&self) -> usize {
        self.c.len()
    }
}

/// Dormand–Prince 5(4) (Hairer, Nørsett & Wanner, *Solving ODEs I*, §II.5;
/// Hairer's `dopri5.f`): FSAL, 4th-order embedded estimate, dense output.
pub const DOPRI5: Tableau = Tableau {
    name: "dopri5",
    order: 5,
    c: &[0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0],
    a: &[
        &[],
        &[1.0 / 5.0],
        &[3.0 / 40.0, 9.0 / 40.0],
        &[44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0],
        &[
            19372.0 / 6561.0,
            -25360.0 / 2187.0,
            64448.0 / 6561.0,
            -212.0 / 729.0,
        ],
        &[
            9017.0 / 3168.0,
            -355.0 / 33.0,
            46732.0 / 5247.0,
            49.0 / 176.0,
            -5103.0 / 18656.0,
        ],
        &[
            35.0 / 384.0,
            0.0,
            500.0 / 1113.0,
            125.0 / 192.0,
            -2187.0 / 6784.0,
            11.0 / 84.0,
        ],
    ],
    b: &[
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
        0.0,
    ],
    error: Some(&[
        71.0 / 57600.0,
        0.0,
        -71.0 / 16695.0,
        71.0 / 1920.0,
        -17253.0 / 339200.0,
        22.0 / 525.0,
        -1.0 / 40.0,
    ]),
    fsal: true,
    dense: DenseOutput::DormandPrince {
        d: &[
            -12715105075.0 / 11282082432.0,
            0.0,
            87487479700.0 / 32700410799.0,
            -10690763975.0 / 1880347072.0,
            701980252875.0 / 199316789632.0,
            -1453857185.0 / 822651844.0,
            69997945.0 / 29380423.0,
        ],
    },
};

/// The classical 4th-order Runge–Kutta method, fixed step, with cubic
/// Hermite dense output.
pub const RK4: Tableau = Tableau {
    name: "rk4",
    order: 4,
    c: &[0.0, 0.5, 0.5, 1.0],
    a: &[&[], &[0.5], &[0.0, 0.5], &[0.0, 0.0, 1.0]],
    b: &[1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0],
    error: None,
    fsal: false,
    dense: DenseOutput::Hermite,
};

#[cfg(test)]
mod tests {
    use super::*;

    /// The order conditions up to order 4 (and row sums `Σ_j a_ij = c_i`),
    /// exact to rounding, for every tableau.
    #[test]
    fn tableaux_satisfy_their_order_conditions() {
        for tableau in [DOPRI5, RK4] {
            let (a, b, c) = (tableau.a, tableau.b, tableau.c);
            let s = tableau.stages();
            assert_eq!((a.len(), b.len()), (s, s), "{}", tableau.name);
            for i in 0..s {
                let sum: f64 = a[i].iter().sum();
                assert!((sum - c[i]).abs() < 1e-15, "{} row {i}", tableau.name);
            }
            let sum = |f: &dyn Fn(usize) -> f64| (0..s).map(|i| b[i] * f(i)).sum::<f64>();
            let ac = |i: usize| (0..i).map(|j| a[i][j] * c[j]).sum::<f64>();
            let conditions = [
                (sum(&|_| 1.0), 1.0),
                (sum(&|i| c[i]), 0.5),
                (sum(&|i| c[i] * c[i]), 1.0 / 3.0),
                (sum(&ac), 1.0 / 6.0),
                (sum(&|i| c[i].powi(3)), 0.25),
                (sum(&|i| c[i] * ac(i)), 0.125),
            ];
            for (k, (value, exact)) in conditions.into_iter().enumerate() {
                assert!(
                    (value - exact).abs() < 1e-15,
                    "{} condition {k}: {value} vs {exact}",
                    tableau.name
                );
            }
            if let Some(e) = tableau.error {
                // The embedded solution is consistent too: Σ (b − b̂) = 0.
                assert!(e.iter().sum::<f64>().abs() < 1e-15, "{}", tableau.name);
            }
            if tableau.fsal {
                assert_eq!(a[s - 1], &b[..s - 1], "{}", tableau.name);
            }
        }
    }
}
