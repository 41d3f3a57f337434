//! Piecewise-linear curves: tabulated inputs, weld moment curves, and the
//! crush characteristics of the paper's eqs 1–2.

use std::cell::Cell;
use std::fmt;

/// What a curve does outside its first and last points.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outside {
    /// Keep the end value.
    Hold,
    /// Continue the end segment's line.
    Extrapolate,
    /// Zero outside (a force that has ended).
    Zero,
    /// Evaluation outside is an error.
    Error,
}

impl Outside {
    /// The policy named `text` (one of [`Outside::NAMES`]).
    pub fn parse(text: &str) -> Option<Outside> {
        match text {
            "hold" => Some(Outside::Hold),
            "extrapolate" => Some(Outside::Extrapolate),
            "zero" => Some(Outside::Zero),
            "error" => Some(Outside::Error),
            _ => None,
        }
    }

    /// The names of the policies, for messages.
    pub const NAMES: &'static str = "hold, extrapolate, zero, error";
}

/// A problem with a curve's table.
#[derive(Clone, Debug, PartialEq)]
pub enum CurveError {
    /// Fewer than two points (this many).
    TooFewPoints(usize),
    /// A breakpoint or value is NaN or ±∞.
    NotFinite {
        /// Its index, from 0.
        index: usize,
    },
    /// An abscissa does not exceed the one before it.
    NotIncreasing {
        /// Its index, from 0.
        index: usize,
        /// The abscissa before it.
        previous: f64,
        /// The abscissa.
        value: f64,
    },
    /// A stiffness or damping coefficient is negative.
    Negative {
        /// Its index, from 0.
        index: usize,
        /// The coefficient.
        value: f64,
    },
    /// A characteristic needs one more value than breakpoints.
    LengthMismatch {
        /// The number of breakpoints.
        breakpoints: usize,
        /// The number of values.
        values: usize,
    },
}

impl fmt::Display for CurveError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CurveError::TooFewPoints(n) => write!(f, "needs at least 2 points, has {n}"),
            CurveError::NotFinite { index } => {
                write!(f, "point {} is not a finite number", index + 1)
            }
            CurveError::NotIncreasing {
                index,
                previous,
                value,
            } => write!(
                f,
                "abscissae must increase strictly: point {} ({value}) does not exceed point {} ({previous})",
                index + 1,
                index
            ),
            CurveError::Negative { index, value } => {
                write!(
                    f,
                    "value {} is negative ({value}); stiffness and damping must be ≥ 0",
                    index + 1
                )
            }
            CurveError::LengthMismatch {
                breakpoints,
                values,
            } => write!(
                f,
                "{breakpoints} breakpoints need {} values (one at 0 and one at each breakpoint), found {values}",
                breakpoints + 1
            ),
        }
    }
}

/// `y(x)` by linear interpolation between points with increasing `x`.
#[derive(Clone, Debug)]
pub struct Curve {
    xs: Vec<f64>,
    ys: Vec<f64>,
    outside: Outside,
    /// The segment of the last lookup: an integration asks for nearby `x`
    /// again and again (a time table at advancing `t`), so it is tried first.
    hint: Cell<usize>,
}

impl PartialEq for Curve {
    fn eq(&self, other: &Curve) -> bool {
        self.xs == other.xs && self.ys == other.ys && self.outside == other.outside
    }
}

/// The result of evaluating outside a curve whose policy is `Outside::Error`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OutOfRange {
    /// Where it was evaluated.
    pub x: f64,
    /// The first abscissa.
    pub min: f64,
    /// The last abscissa.
    pub max: f64,
}

impl Curve {
    /// The curve through `(xs[i], ys[i])`; `xs` must increase strictly and
    /// every number be finite.
    pub fn new(xs: Vec<f64>, ys: Vec<f64>, outside: Outside) -> Result<Curve, CurveError> {
        if xs.len() != ys.len() {
            return Err(CurveError::LengthMismatch {
                breakpoints: xs.len(),
                values: ys.len(),
            });
        }
        if xs.len() < 2 {
            return Err(CurveError::TooFewPoints(xs.len()));
        }
        if let Some(index) = xs.iter().chain(&ys).position(|v| !v.is_finite()) {
            return Err(CurveError::NotFinite {
                index: index % xs.len(),
            });
        }
        for i in 1..xs.len() {
            if xs[i] <= xs[i - 1] {
                return Err(CurveError::NotIncreasing {
                    index: i,
                    previous: xs[i - 1],
                    value: xs[i],
                });
            }
        }
        Ok(Curve {
            xs,
            ys,
            outside,
            hint: Cell::new(0),
        })
    }

    /// The abscissae.
    pub fn xs(&self) -> &[f64] {
        &self.xs
    }

    /// The values.
    pub fn ys(&self) -> &[f64] {
        &self.ys
    }

    /// The segment `[x_i, x_{i+1}]` that `x` falls in (the end segments beyond).
    fn segment(&self, x: f64) -> usize {
        let last = self.xs.len() - 2;
        let within = |i: usize| (i == 0 || self.xs[i] <= x) && (i == last || x < self.xs[i + 1]);
        let hint = self.hint.get();
        for i in [hint, hint + 1] {
            if i <= last && within(i) {
                self.hint.set(i);
                return i;
            }
        }
        let i = match self.xs.partition_point(|&p| p <= x) {
            0 => 0,
            i => (i - 1).min(last),
        };
        self.hint.set(i);
        i
    }

    /// `(y(x), dy/dx)`.
    pub fn eval(&self, x: f64) -> Result<(f64, f64), OutOfRange> {
        let (first, last) = (self.xs[0], self.xs[self.xs.len() - 1]);
        let inside = x >= first && x <= last;
        if !inside {
            match self.outside {
                Outside::Hold => {
                    let y = if x < first {
                        self.ys[0]
                    } else {
                        self.ys[self.ys.len() - 1]
                    };
                    return Ok((y, 0.0));
                }
                Outside::Zero => return Ok((0.0, 0.0)),
                Outside::Error => {
                    return Err(OutOfRange {
                        x,
                        min: first,
                        max: last,
                    });
                }
                Outside::Extrapolate => {}
            }
        }
        let i = self.segment(x);
        let slope = (self.ys[i + 1] - self.ys[i]) / (self.xs[i + 1] - self.xs[i]);
        Ok((self.ys[i] + slope * (x - self.xs[i]), slope))
    }
}

/// A coefficient curve of the paper's eqs 1–2: `k(|x̂|)` is `k_1` at 0, `k_{i+1}`
/// at breakpoint `x_i` (the last breakpoint is the maximum dynamic crush `C`,
/// or `v_0` for the damper), linear in between.
#[derive(Clone, Debug, PartialEq)]
pub struct Characteristic {
    curve: Curve,
}

impl Characteristic {
    /// `breakpoints = [x1, …, x5, C]` (positive, increasing) and
    /// `values = [k1, …, k7]` (non-negative).
    pub fn new(
        breakpoints: &[f64],
        values: &[f64],
        outside: Outside,
    ) -> Result<Characteristic, CurveError> {
        if values.len() != breakpoints.len() + 1 {
            return Err(CurveError::LengthMismatch {
                breakpoints: breakpoints.len(),
                values: values.len(),
            });
        }
        if let Some((index, &value)) = values.iter().enumerate().find(|(_, v)| **v < 0.0) {
            return Err(CurveError::Negative { index, value });
        }
        if let Some(&first) = breakpoints.first()
            && first <= 0.0
        {
            return Err(CurveError::NotIncreasing {
                index: 1,
                previous: 0.0,
                value: first,
            });
        }
        let xs = std::iter::once(0.0)
            .chain(breakpoints.iter().copied())
            .collect();
        Ok(Characteristic {
            curve: Curve::new(xs, values.to_vec(), outside)?,
        })
    }

    /// A constant coefficient (a linear spring or damper).
    pub fn constant(value: f64) -> Characteristic {
        Characteristic {
            curve: Curve {
                xs: vec![0.0, 1.0],
                ys: vec![value, value],
                outside: Outside::Hold,
                hint: Cell::new(0),
            },
        }
    }

    /// `(k(|x|), dk/d|x|)`.
    pub fn coefficient(&self, x: f64) -> Result<(f64, f64), OutOfRange> {
        self.curve.eval(x.abs())
    }

    /// The force `F(x) = k(|x|)·x` of eq 1 and its derivative
    /// `dF/dx = k(|x|) + |x|·k'(|x|)`.
    pub fn force(&self, x: f64) -> Result<(f64, f64), OutOfRange> {
        let (k, slope) = self.coefficient(x)?;
        Ok((k * x, k + x.abs() * slope))
    }

    /// The last breakpoint (the maximum dynamic crush `C` or velocity `v_0`).
    pub fn range(&self) -> f64 {
        self.curve.xs[self.curve.xs.len() - 1]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_segment_hint_never_changes_the_segment() {
        let xs: Vec<f64> = vec![0.0, 0.5, 1.0, 2.5, 3.0, 7.0];
        let curve = Curve::new(xs.clone(), vec![0.0; 6], Outside::Extrapolate).unwrap();
        let reference = |x: f64| match xs.partition_point(|&p| p <= x) {
            0 => 0,
            i => (i - 1).min(xs.len() - 2),
        };
        // Sweeps forward and backward, jumps, exact breakpoints, beyond both ends, NaN.
        let mut probes: Vec<f64> = (0..200).map(|k| -1.0 + 0.05 * k as f64).collect();
        probes.extend((0..200).rev().map(|k| -1.0 + 0.05 * k as f64));
        probes.extend(xs.iter().copied());
        probes.extend([8.0, -3.0, 2.5, 0.0, 7.0, 6.99, f64::NAN, 1.0, 0.5]);
        for x in probes {
            assert_eq!(curve.segment(x), reference(x), "x = {x}");
        }
    }

    #[test]
    fn eq_1_interpolates_between_breakpoints() {
        // k(x): 10 at 0, 20 at 1, 40 at 2 (C).
        let k = Characteristic::new(&[1.0, 2.0], &[10.0, 20.0, 40.0], Outside::Hold).unwrap();
        assert_eq!(k.coefficient(0.5).unwrap(), (15.0, 10.0));
        assert_eq!(k.coefficient(-1.5).unwrap(), (30.0, 20.0));
        // F = k(|x|) x: odd; dF/dx = k + |x| k'.
        assert_eq!(k.force(1.5).unwrap(), (45.0, 30.0 + 1.5 * 20.0));
        assert_eq!(k.force(-1.5).unwrap().0, -45.0);
        // Beyond C the coefficient holds.
        assert_eq!(k.coefficient(3.0).unwrap(), (40.0, 0.0));
        let strict = Characteristic::new(&[1.0, 2.0], &[10.0, 20.0, 40.0], Outside::Error).unwrap();
        assert_eq!(
            strict.coefficient(2.5),
            Err(OutOfRange {
                x: 2.5,
                min: 0.0,
                max: 2.0
            })
        );
    }

    #[test]
    fn bad_tables_are_rejected_with_the_offending_entry() {
        assert_eq!(
            Characteristic::new(&[1.0, 1.0], &[1.0, 2.0, 3.0], Outside::Hold),
            Err(CurveError::NotIncreasing {
                index: 2,
                previous: 1.0,
                value: 1.0
            })
        );
        assert_eq!(
            Characteristic::new(&[1.0], &[1.0, -2.0], Outside::Hold),
            Err(CurveError::Negative {
                index: 1,
                value: -2.0
            })
        );
        assert_eq!(
            Characteristic::new(&[1.0, 2.0], &[1.0, 2.0], Outside::Hold),
            Err(CurveError::LengthMismatch {
                breakpoints: 2,
                values: 2
            })
        );
        assert!(Characteristic::new(&[-1.0], &[1.0, 2.0], Outside::Hold).is_err());
        assert_eq!(
            Curve::new(vec![0.0], vec![1.0], Outside::Hold),
            Err(CurveError::TooFewPoints(1))
        );
        assert_eq!(
            Curve::new(vec![0.0, f64::NAN], vec![1.0, 2.0], Outside::Hold),
            Err(CurveError::NotFinite { index: 1 })
        );
    }

    #[test]
    fn outside_policies() {
        let c = |o| Curve::new(vec![0.0, 1.0], vec![2.0, 4.0], o).unwrap();
        assert_eq!(c(Outside::Hold).eval(-1.0).unwrap(), (2.0, 0.0));
        assert_eq!(c(Outside::Zero).eval(2.0).unwrap(), (0.0, 0.0));
        assert_eq!(c(Outside::Extrapolate).eval(2.0).unwrap(), (6.0, 2.0));
        assert!(c(Outside::Error).eval(1.5).is_err());
    }
}
