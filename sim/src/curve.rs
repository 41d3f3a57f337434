//! Piecewise-linear curves: tabulated inputs, weld moment curves, and the
//! crush characteristics: the secant form of the paper's eqs 1–2 and
//! force–deflection curves.

mod formula;
mod pchip;

use formula::Formula;
use std::cell::Cell;
use std::fmt;
use std::sync::Arc;

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

/// The `outside` policy written as `text` in the section at `section`.
pub(crate) fn outside(section: &str, text: &str) -> Result<Outside, crate::entry::EntryError> {
    Outside::parse(text).ok_or_else(|| {
        let reason = format!("outside = `{text}`; use one of {}", Outside::NAMES);
        crate::entry::EntryError::at(section.into(), reason)
    })
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
    /// The slope between points `index` and `index + 1` (from 0) is not
    /// finite: points too close for the difference of their values.
    Slope {
        /// The first point's index, from 0.
        index: usize,
        /// The slope.
        slope: f64,
    },
    /// Not as many values as abscissae.
    LengthMismatch {
        /// The number of abscissae.
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
            CurveError::Slope { index, slope } => write!(f, "{}", slope_message(*index, *slope)),
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
            CurveError::LengthMismatch {
                breakpoints,
                values,
            } => write!(
                f,
                "{breakpoints} abscissae need as many values, found {values}"
            ),
        }
    }
}

/// `y(x)` by linear interpolation between points with increasing `x`, or
/// by a monotone cubic ([`Curve::smooth`]).
///
/// The points are shared between copies: a scenario copied for each run of
/// a sweep copies no table.
#[derive(Clone, Debug)]
pub struct Curve {
    xs: Arc<[f64]>,
    ys: Arc<[f64]>,
    /// The slope of each segment, computed once.
    slopes: Arc<[f64]>,
    /// The points where the slope changes, ends included where the policy
    /// outside changes the end segment.
    kinks: Arc<[f64]>,
    /// The tangent at each point of a curve interpolated by a monotone
    /// cubic (PCHIP); `None`: linear between the points.
    tangents: Option<Arc<[f64]>>,
    outside: Outside,
    /// Every value is `+0` and the curve is linear between its points (a
    /// table column that never acts, as the horizontal barrier forces of a
    /// full frontal): it is 0, with slope 0, wherever it has a value.
    zero: bool,
    /// The formula of each piece ([`Curve::piece`]), for [`Curve::eval_on`].
    formulas: Arc<[Formula]>,
    /// The segment of the last lookup: an integration asks for nearby `x`
    /// again and again (a time table at advancing `t`), so it is tried first.
    hint: Cell<usize>,
}

impl PartialEq for Curve {
    fn eq(&self, other: &Curve) -> bool {
        self.xs == other.xs
            && self.ys == other.ys
            && self.tangents == other.tangents
            && self.outside == other.outside
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
        if let Some((index, slope)) = overflowing_slope(&xs, &ys) {
            return Err(CurveError::Slope { index, slope });
        }
        Ok(Curve::linear(xs, ys, outside))
    }

    /// The curve through checked points, linear between them.
    fn linear(xs: Vec<f64>, ys: Vec<f64>, outside: Outside) -> Curve {
        let slopes: Vec<f64> = (xs.windows(2).zip(ys.windows(2)))
            .map(|(x, y)| (y[1] - y[0]) / (x[1] - x[0]))
            .collect();
        let last = xs.len() - 1;
        // An end is a kink where the policy outside changes the end
        // segment: `error` always (the curve ends there).
        let end = |y: f64, slope: f64| match outside {
            Outside::Extrapolate => false,
            Outside::Hold => slope != 0.0,
            Outside::Zero => slope != 0.0 || y != 0.0,
            Outside::Error => true,
        };
        let kink = |i: usize| match i {
            0 => end(ys[0], slopes[0]),
            i if i == last => end(ys[last], slopes[last - 1]),
            i => slopes[i - 1] != slopes[i],
        };
        let kinks = (0..=last).filter(|&i| kink(i)).map(|i| xs[i]).collect();
        let zero = ys.iter().all(|y| y.to_bits() == 0);
        Curve {
            xs: xs.into(),
            ys: ys.into(),
            slopes: slopes.into(),
            kinks,
            tangents: None,
            outside,
            zero,
            formulas: Arc::new([]),
            hint: Cell::new(0),
        }
        .with_formulas()
    }

    /// The curve with the formulas of its pieces.
    fn with_formulas(self) -> Curve {
        let formulas = self.piece_formulas();
        Curve { formulas, ..self }
    }

    /// The same points interpolated by a monotone cubic (PCHIP): C¹, no
    /// overshoot between the points, so without kinks. Beyond the ends,
    /// `Outside::Extrapolate` continues the end tangent.
    pub fn smooth(self) -> Curve {
        let tangents = pchip::tangents(&self.xs, &self.ys).into();
        Curve {
            tangents: Some(tangents),
            zero: false,
            ..self
        }
        .with_formulas()
    }

    /// The points where the slope of a curve interpolated linearly jumps,
    /// in increasing order: the ends too, unless the policy outside
    /// continues the end segment (`extrapolate`, or `hold` of a flat one,
    /// `zero` of a flat one at 0) — always under `error`; none for a
    /// smooth one.
    pub fn kinks(&self) -> &[f64] {
        match self.tangents {
            Some(_) => &[],
            None => &self.kinks,
        }
    }

    /// Whether it is `(0, 0)` at every finite abscissa: all its values +0,
    /// interpolated linearly, with a policy outside that has a value
    /// there (not `error`). [`Curve::eval`] answers so, to the bit.
    pub fn is_zero_everywhere(&self) -> bool {
        self.zero && self.outside != Outside::Error
    }

    /// Whether it is interpolated by a monotone cubic ([`Curve::smooth`]).
    pub fn is_smooth(&self) -> bool {
        self.tangents.is_some()
    }

    /// The points where the curve is not continuously differentiable, in
    /// increasing order: its [`Curve::kinks`]; for a smooth one, its ends,
    /// unless the policy outside continues the end tangent (`extrapolate`).
    pub fn corners(&self) -> Vec<f64> {
        match (&self.tangents, self.outside) {
            (None, _) | (Some(_), Outside::Extrapolate) => self.kinks().to_vec(),
            (Some(_), Outside::Hold | Outside::Zero | Outside::Error) => {
                vec![self.xs[0], self.xs[self.xs.len() - 1]]
            }
        }
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
        self.eval_as(x, x)
    }

    /// The piece of the curve that `x` lies in: the pieces lie between
    /// consecutive [`Curve::kinks`], piece 0 below the first, piece
    /// `kinks().len()` above the last; a point on a kink is in the piece
    /// above it. A smooth curve is one piece.
    pub fn piece(&self, x: f64) -> usize {
        self.kinks().partition_point(|&kink| kink <= x)
    }

    /// The ends of piece `piece` ([`Curve::piece`]): the kinks below and
    /// above it, −∞ or +∞ where it has none.
    pub fn piece_ends(&self, piece: usize) -> (f64, f64) {
        let kinks = self.kinks();
        let below = piece.checked_sub(1).and_then(|k| kinks.get(k));
        let above = kinks.get(piece);
        (
            below.copied().unwrap_or(f64::NEG_INFINITY),
            above.copied().unwrap_or(f64::INFINITY),
        )
    }

    /// `(y, dy/dx)` at `x` of the formula of piece `piece` ([`Curve::piece`])
    /// continued past its ends, so that it is smooth in `x`; the curve
    /// itself ([`Curve::eval`]) for `None`. Within the piece both agree.
    pub fn eval_on(&self, piece: Option<usize>, x: f64) -> Result<(f64, f64), OutOfRange> {
        match piece.and_then(|piece| self.formulas.get(piece)) {
            Some(formula) => formula.eval(self, x),
            None => self.eval(x),
        }
    }

    /// `(y, dy/dx)` at `x` of the formula (the segment, or the policy
    /// outside) that holds at `at`.
    fn eval_as(&self, x: f64, at: f64) -> Result<(f64, f64), OutOfRange> {
        let (first, last) = (self.xs[0], self.xs[self.xs.len() - 1]);
        let inside = at >= first && at <= last;
        // What the formulas below give a zero curve at a finite `x`, where
        // it has a value: `0 + 0·(x − x_i)`, `0` held, or `0` outside.
        if self.zero && x.is_finite() && (inside || self.outside != Outside::Error) {
            return Ok((0.0, 0.0));
        }
        if !inside {
            match self.outside {
                Outside::Hold => {
                    let y = if at < first {
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
        let i = self.segment(at);
        match &self.tangents {
            None => {
                let slope = self.slopes[i];
                Ok((self.ys[i] + slope * (x - self.xs[i]), slope))
            }
            Some(d) if !inside => {
                let end = if at < first { 0 } else { self.xs.len() - 1 };
                Ok((self.ys[end] + d[end] * (x - self.xs[end]), d[end]))
            }
            Some(d) => {
                let (xs, ys) = ((self.xs[i], self.xs[i + 1]), (self.ys[i], self.ys[i + 1]));
                Ok(pchip::hermite(x, xs, ys, (d[i], d[i + 1])))
            }
        }
    }
}

/// What is wrong with the table of a crush characteristic, in terms of its
/// two lists as written: the breakpoints and the values.
#[derive(Clone, Debug, PartialEq)]
pub enum TableError {
    /// There are no breakpoints.
    NoBreakpoints,
    /// A breakpoint that is not a finite number above the one before (above
    /// 0 for the first): breakpoints increase strictly from 0.
    Breakpoint {
        /// Its index, from 0.
        index: usize,
        /// The breakpoint.
        value: f64,
        /// The breakpoint before it (0 for the first).
        previous: f64,
    },
    /// A value that is negative or not a finite number.
    Value {
        /// Its index, from 0.
        index: usize,
        /// The value.
        value: f64,
    },
    /// The slope between points `index` and `index + 1` of the curve (from
    /// 0, the curve's first point at 0) is not finite.
    Slope {
        /// The first point's index, from 0.
        index: usize,
        /// The slope.
        slope: f64,
    },
    /// The number of values does not fit the number of breakpoints.
    Count {
        /// The number of breakpoints.
        breakpoints: usize,
        /// The number of values.
        values: usize,
        /// The number of values the breakpoints need.
        expected: usize,
    },
}

impl TableError {
    /// Whether the problem is in the values (else in the breakpoints).
    pub fn in_values(&self) -> bool {
        matches!(
            self,
            TableError::Value { .. } | TableError::Count { .. } | TableError::Slope { .. }
        )
    }
}

impl fmt::Display for TableError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TableError::NoBreakpoints => write!(f, "needs at least one breakpoint"),
            TableError::Breakpoint {
                index: 0, value, ..
            } => write!(
                f,
                "breakpoint 1 ({value}) must be a positive, finite number (the curve starts at 0)"
            ),
            TableError::Breakpoint {
                index,
                value,
                previous,
            } => write!(
                f,
                "breakpoint {} ({value}) must be finite and exceed breakpoint {index} ({previous}): breakpoints increase strictly",
                index + 1
            ),
            TableError::Value { index, value } => write!(
                f,
                "value {} ({value}) must be a finite number ≥ 0",
                index + 1
            ),
            TableError::Slope { index, slope } => write!(f, "{}", slope_message(*index, *slope)),
            TableError::Count {
                breakpoints,
                values,
                expected,
            } => {
                let plural = |n: usize| if n == 1 { "" } else { "s" };
                write!(
                    f,
                    "{breakpoints} breakpoint{} need{} {expected} value{}, found {values}",
                    plural(*breakpoints),
                    if *breakpoints == 1 { "s" } else { "" },
                    plural(*expected),
                )
            }
        }
    }
}

/// The curve through `(0, first)` and `(breakpoints[i], values[i + skip])`
/// after checking the table: `expected` values, breakpoints finite,
/// positive and strictly increasing, values finite and non-negative.
fn checked_table(
    breakpoints: &[f64],
    values: &[f64],
    expected: usize,
    first: Option<f64>,
    outside: Outside,
) -> Result<Curve, TableError> {
    if breakpoints.is_empty() {
        return Err(TableError::NoBreakpoints);
    }
    if values.len() != expected {
        return Err(TableError::Count {
            breakpoints: breakpoints.len(),
            values: values.len(),
            expected,
        });
    }
    let mut previous = 0.0;
    for (index, &value) in breakpoints.iter().enumerate() {
        if !(value.is_finite() && value > previous) {
            return Err(TableError::Breakpoint {
                index,
                value,
                previous,
            });
        }
        previous = value;
    }
    if let Some((index, &value)) =
        (values.iter().enumerate()).find(|(_, v)| !(**v >= 0.0 && v.is_finite()))
    {
        return Err(TableError::Value { index, value });
    }
    let xs: Vec<f64> = std::iter::once(0.0)
        .chain(breakpoints.iter().copied())
        .collect();
    let ys: Vec<f64> = first.into_iter().chain(values.iter().copied()).collect();
    if let Some((index, slope)) = overflowing_slope(&xs, &ys) {
        return Err(TableError::Slope { index, slope });
    }
    Ok(Curve::linear(xs, ys, outside))
}

/// The first segment of the points `(xs, ys)` (finite, `xs` increasing)
/// whose slope is not finite, with it: points too close for their values,
/// whose tangent stiffness a run would meet as ±∞.
fn overflowing_slope(xs: &[f64], ys: &[f64]) -> Option<(usize, f64)> {
    (xs.windows(2).zip(ys.windows(2)))
        .map(|(x, y)| (y[1] - y[0]) / (x[1] - x[0]))
        .enumerate()
        .find(|(_, slope)| !slope.is_finite())
}

/// The message of a slope that is not finite between points `index` and
/// `index + 1` (from 0).
fn slope_message(index: usize, slope: f64) -> String {
    format!(
        "the slope between points {} and {} is {slope}: the points are too close for the difference of their values (a tangent that is not finite)",
        index + 1,
        index + 2
    )
}

/// A coefficient curve in the secant form of the paper's eqs 1–2: the
/// force is `F(x) = k(|x|)·x`, the coefficient `k` (a secant stiffness, or
/// a damping coefficient) is `k_1` at 0, `k_{i+1}` at breakpoint `x_i` (the
/// last breakpoint is the maximum dynamic crush `C`, or `v_0` for the
/// damper), linear in between. The force is quadratic between breakpoints.
#[derive(Clone, Debug, PartialEq)]
pub struct SecantCurve {
    curve: Curve,
}

impl SecantCurve {
    /// `breakpoints = [x1, …, x5, C]` (positive, increasing) and
    /// `values = [k1, …, k7]` (non-negative): one value more than
    /// breakpoints.
    pub fn new(
        breakpoints: &[f64],
        values: &[f64],
        outside: Outside,
    ) -> Result<SecantCurve, TableError> {
        let expected = breakpoints.len() + 1;
        let curve = checked_table(breakpoints, values, expected, None, outside)?;
        Ok(SecantCurve { curve })
    }

    /// A constant coefficient (a linear spring or damper).
    pub fn constant(value: f64) -> SecantCurve {
        SecantCurve {
            curve: Curve::linear(vec![0.0, 1.0], vec![value, value], Outside::Hold),
        }
    }

    /// `(k(|x|), dk/d|x|)`.
    pub fn coefficient(&self, x: f64) -> Result<(f64, f64), OutOfRange> {
        self.curve.eval(x.abs())
    }

    /// The force `F(x) = k(|x|)·x` of eq 1 and its derivative
    /// `dF/dx = k(|x|) + |x|·k'(|x|)`.
    pub fn force(&self, x: f64) -> Result<(f64, f64), OutOfRange> {
        self.force_on(None, x)
    }

    /// [`SecantCurve::force`] with `k` on piece `piece` of its curve in
    /// `|x|` ([`Curve::eval_on`]).
    pub fn force_on(&self, piece: Option<usize>, x: f64) -> Result<(f64, f64), OutOfRange> {
        let (k, slope) = self.curve.eval_on(piece, x.abs())?;
        Ok((k * x, k + x.abs() * slope))
    }

    /// The curve `k(|x|)`, through `(0, k_1)`.
    pub fn curve(&self) -> &Curve {
        &self.curve
    }

    /// The last breakpoint (the maximum dynamic crush `C` or velocity `v_0`).
    pub fn range(&self) -> f64 {
        self.curve.xs[self.curve.xs.len() - 1]
    }
}

/// A force–deflection curve, as a test measures it: the force `F_i` at
/// breakpoint `x_i`, 0 at 0, linear in between, so that its slope (the
/// tangent stiffness) is the slope of the segment. Odd in `x`, like the
/// secant form: `F(−x) = −F(x)`.
#[derive(Clone, Debug, PartialEq)]
pub struct ForceCurve {
    curve: Curve,
}

impl ForceCurve {
    /// `breakpoints = [x1, …, xn]` (positive, increasing) and
    /// `forces = [F1, …, Fn]` (non-negative): one force per breakpoint.
    pub fn new(
        breakpoints: &[f64],
        forces: &[f64],
        outside: Outside,
    ) -> Result<ForceCurve, TableError> {
        let expected = breakpoints.len();
        let curve = checked_table(breakpoints, forces, expected, Some(0.0), outside)?;
        Ok(ForceCurve { curve })
    }

    /// The force `F(x) = sign(x)·F(|x|)` and its derivative `dF/dx = F'(|x|)`.
    pub fn force(&self, x: f64) -> Result<(f64, f64), OutOfRange> {
        self.force_on(None, x)
    }

    /// [`ForceCurve::force`] on piece `piece` of its curve in `|x|`
    /// ([`Curve::eval_on`]).
    pub fn force_on(&self, piece: Option<usize>, x: f64) -> Result<(f64, f64), OutOfRange> {
        let (f, slope) = self.curve.eval_on(piece, x.abs())?;
        Ok((if x < 0.0 { -f } else { f }, slope))
    }

    /// The curve `F(|x|)`, through `(0, 0)`.
    pub fn curve(&self) -> &Curve {
        &self.curve
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

    /// A result with its numbers as bits, so that `0` and `−0` differ and
    /// NaN equals NaN.
    fn bits(result: Result<(f64, f64), OutOfRange>) -> Result<(u64, u64), String> {
        result
            .map(|(y, slope)| (y.to_bits(), slope.to_bits()))
            .map_err(|e| format!("{e:?}"))
    }

    #[test]
    fn a_zero_curve_answers_bit_for_bit_as_its_formulas_do() {
        let xs: Vec<f64> = vec![0.0, 0.5, 1.0, 2.5, 3.0];
        // Forward and backward in small steps (as event location goes back
        // within a step), the points themselves, beyond both ends, and
        // numbers that are no positions.
        let mut probes: Vec<f64> = (0..90).map(|k| -0.7 + 0.05 * k as f64).collect();
        probes.extend((0..90).rev().map(|k| -0.7 + 0.05 * k as f64));
        probes.extend(xs.iter().copied());
        probes.extend([
            -0.0,
            1e300,
            -1e300,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ]);
        for outside in [
            Outside::Hold,
            Outside::Extrapolate,
            Outside::Zero,
            Outside::Error,
        ] {
            let zero = Curve::new(xs.clone(), vec![0.0; xs.len()], outside).unwrap();
            assert!(zero.zero, "{outside:?}");
            let formulas = Curve {
                zero: false,
                ..zero.clone()
            };
            for &x in &probes {
                assert_eq!(
                    bits(zero.eval(x)),
                    bits(formulas.eval(x)),
                    "{outside:?} {x}"
                );
                for piece in 0..=zero.kinks().len() {
                    let (held, general) = (
                        zero.eval_on(Some(piece), x),
                        formulas.eval_on(Some(piece), x),
                    );
                    assert_eq!(bits(held), bits(general), "{outside:?} {x} piece {piece}");
                }
            }
        }
        // Values of −0 (held as −0 before the first point), or a monotone
        // cubic, take the formulas.
        let negative = Curve::new(xs.clone(), vec![-0.0; xs.len()], Outside::Hold).unwrap();
        assert!(!negative.zero);
        assert_eq!(bits(negative.eval(-1.0)), Ok(((-0.0f64).to_bits(), 0)));
        let smooth = Curve::new(xs.clone(), vec![0.0; xs.len()], Outside::Hold).unwrap();
        assert!(!smooth.smooth().zero);
    }

    /// What `eval_on` evaluated at each call before the formulas of the
    /// pieces were chosen once: the curve's formula at a point inside the
    /// piece (its middle, or a unit or the kink's magnitude beyond a kink
    /// at an end), or the curve itself for a piece without ends.
    fn eval_on_by_search(curve: &Curve, piece: usize, x: f64) -> Result<(f64, f64), OutOfRange> {
        let at = match curve.piece_ends(piece) {
            (below, above) if below.is_finite() && above.is_finite() => 0.5 * (below + above),
            (below, _) if below.is_finite() => below + below.abs().max(1.0),
            (_, above) if above.is_finite() => above - above.abs().max(1.0),
            _ => x,
        };
        curve.eval_as(x, at)
    }

    #[test]
    fn a_held_piece_answers_bit_for_bit_as_the_search_for_its_formula() {
        // Slopes 1, 1, 0, −2, 0 (kinks at 2, 3, 4; a piece of two segments
        // below 2), ends per policy; and a curve of one piece per segment.
        let xs = vec![0.0, 1.0, 2.0, 3.0, 4.0, 5.0];
        let bent = |outside| Curve::new(xs.clone(), vec![0.5, 1.5, 2.5, 2.5, 0.5, 0.5], outside);
        let steep = |outside| Curve::new(vec![-1.0, 0.25, 3.0], vec![4.0, -2.0, 7.0], outside);
        let mut probes: Vec<f64> = (0..140).map(|k| -1.5 + 0.05 * k as f64).collect();
        probes.extend((0..140).rev().map(|k| -1.5 + 0.05 * k as f64));
        probes.extend(xs.iter().copied());
        probes.extend([
            -0.0,
            -7.0,
            9.0,
            1e300,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ]);
        let policies = [
            Outside::Hold,
            Outside::Extrapolate,
            Outside::Zero,
            Outside::Error,
        ];
        for outside in policies {
            let bent = bent(outside).unwrap();
            let steep = steep(outside).unwrap();
            let zero = Curve::new(xs.clone(), vec![0.0; 6], outside).unwrap();
            let constant = SecantCurve::constant(3.0).curve;
            for curve in [bent.clone(), bent.smooth(), steep, zero, constant] {
                // One piece beyond the last: the curve itself.
                for piece in 0..=curve.kinks().len() + 1 {
                    for &x in &probes {
                        let held = curve.eval_on(Some(piece), x);
                        let searched = eval_on_by_search(&curve, piece, x);
                        assert_eq!(bits(held), bits(searched), "{curve:?} piece {piece} at {x}");
                    }
                }
            }
        }
    }

    #[test]
    fn eq_1_interpolates_between_breakpoints() {
        // k(x): 10 at 0, 20 at 1, 40 at 2 (C).
        let k = SecantCurve::new(&[1.0, 2.0], &[10.0, 20.0, 40.0], Outside::Hold).unwrap();
        assert_eq!(k.coefficient(0.5).unwrap(), (15.0, 10.0));
        assert_eq!(k.coefficient(-1.5).unwrap(), (30.0, 20.0));
        // F = k(|x|) x: odd; dF/dx = k + |x| k'.
        assert_eq!(k.force(1.5).unwrap(), (45.0, 30.0 + 1.5 * 20.0));
        assert_eq!(k.force(-1.5).unwrap().0, -45.0);
        // Beyond C the coefficient holds.
        assert_eq!(k.coefficient(3.0).unwrap(), (40.0, 0.0));
        let strict = SecantCurve::new(&[1.0, 2.0], &[10.0, 20.0, 40.0], Outside::Error).unwrap();
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
    fn a_force_deflection_curve_is_linear_between_its_points() {
        // The points (0, 0), (0.1 m, 170 kN), (0.5 m, 180 kN) of a test.
        let f = ForceCurve::new(&[0.1, 0.5], &[170e3, 180e3], Outside::Hold).unwrap();
        // At 0.3 m, halfway along the second segment: 170 + 10/2 kN; the
        // tangent stiffness is that segment's slope, 10 kN / 0.4 m.
        let (force, slope) = f.force(0.3).unwrap();
        assert!((force - 175e3).abs() < 1e-9, "{force}");
        assert!((slope - 25e3).abs() < 1e-9, "{slope}");
        // On the first segment: 1.7 MN/m from the origin.
        let (force, slope) = f.force(0.05).unwrap();
        assert!((force - 85e3).abs() < 1e-9 && (slope - 1.7e6).abs() < 1e-6);
        // Odd, like the secant form; beyond the last point the force holds.
        assert_eq!(f.force(-0.3).unwrap().0, -f.force(0.3).unwrap().0);
        assert_eq!(f.force(0.0).unwrap().0, 0.0);
        assert_eq!(f.force(0.7).unwrap(), (180e3, 0.0));
        // The secant form through the same forces at the breakpoints (k =
        // F/x: 1.7 MN/m at 0 and 0.1 m, 0.36 MN/m at 0.5 m) is quadratic
        // between them: k(0.3) = (1.7 + 0.36)/2 MN/m, F = 0.3·1.03 MN = 309 kN.
        let k = SecantCurve::new(&[0.1, 0.5], &[1.7e6, 1.7e6, 0.36e6], Outside::Hold).unwrap();
        assert!((k.force(0.5).unwrap().0 - 180e3).abs() < 1e-6);
        assert!((k.force(0.3).unwrap().0 - 309e3).abs() < 1e-6);
    }

    #[test]
    fn bad_tables_are_rejected_with_the_offending_entry() {
        assert_eq!(
            SecantCurve::new(&[1.0, 1.0], &[1.0, 2.0, 3.0], Outside::Hold),
            Err(TableError::Breakpoint {
                index: 1,
                previous: 1.0,
                value: 1.0
            })
        );
        assert_eq!(
            SecantCurve::new(&[1.0], &[1.0, -2.0], Outside::Hold),
            Err(TableError::Value {
                index: 1,
                value: -2.0
            })
        );
        assert_eq!(
            SecantCurve::new(&[1.0, 2.0], &[1.0, 2.0], Outside::Hold),
            Err(TableError::Count {
                breakpoints: 2,
                values: 2,
                expected: 3
            })
        );
        assert!(SecantCurve::new(&[-1.0], &[1.0, 2.0], Outside::Hold).is_err());
        // A force–deflection curve: one force per breakpoint, from above 0.
        assert_eq!(
            ForceCurve::new(&[0.0, 0.1], &[0.0, 1.0], Outside::Hold),
            Err(TableError::Breakpoint {
                index: 0,
                previous: 0.0,
                value: 0.0
            })
        );
        assert_eq!(
            ForceCurve::new(&[0.1, 0.5], &[0.0, 1.0, 2.0], Outside::Hold),
            Err(TableError::Count {
                breakpoints: 2,
                values: 3,
                expected: 2
            })
        );
        assert!(matches!(
            ForceCurve::new(&[0.1, f64::NAN], &[1.0, 2.0], Outside::Hold),
            Err(TableError::Breakpoint { index: 1, previous, value }) if previous == 0.1 && value.is_nan()
        ));
        assert_eq!(
            ForceCurve::new(&[0.1], &[f64::INFINITY], Outside::Hold),
            Err(TableError::Value {
                index: 0,
                value: f64::INFINITY
            })
        );
        assert_eq!(
            ForceCurve::new(&[], &[], Outside::Hold),
            Err(TableError::NoBreakpoints)
        );
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
    fn a_smooth_curve_is_c1_through_its_points_and_linear_beyond() {
        let xs = vec![0.0, 1.0, 2.0, 4.0];
        let ys = vec![0.0, 1.0, 4.0, 5.0];
        let linear = Curve::new(xs.clone(), ys.clone(), Outside::Extrapolate).unwrap();
        let smooth = linear.clone().smooth();
        assert!(smooth.is_smooth() && !linear.is_smooth() && smooth != linear);
        // The linear one's slope changes at every inner point; the ends
        // are extrapolated.
        assert_eq!(linear.kinks(), [1.0, 2.0]);
        assert!(smooth.kinks().is_empty());
        let tangents = pchip::tangents(&xs, &ys);
        for (k, &x) in xs.iter().enumerate() {
            // Through the points, with the same slope on either side.
            let (y, _) = smooth.eval(x).unwrap();
            assert!((y - ys[k]).abs() < 1e-12, "{x}: {y}");
            for side in [x - 1e-9, x + 1e-9] {
                let (_, slope) = smooth.eval(side).unwrap();
                assert!((slope - tangents[k]).abs() < 1e-6, "{side}: {slope}");
            }
        }
        // Monotone data, monotone curve.
        let values: Vec<f64> = (0..=400)
            .map(|k| smooth.eval(0.01 * k as f64).unwrap().0)
            .collect();
        assert!(values.windows(2).all(|w| w[1] >= w[0]));
        // Beyond the ends: the end tangent's line.
        let (y, slope) = smooth.eval(5.0).unwrap();
        assert_eq!((y, slope), (5.0 + tangents[3], tangents[3]));
    }

    #[test]
    fn kinks_are_where_the_slope_changes() {
        let curve = |outside| {
            let xs = vec![0.0, 1.0, 2.0, 3.0, 4.0];
            Curve::new(xs, vec![0.0, 1.0, 2.0, 2.0, 0.0], outside).unwrap()
        };
        assert_eq!(curve(Outside::Zero).kinks(), [0.0, 2.0, 3.0, 4.0]);
        assert_eq!(curve(Outside::Extrapolate).kinks(), [2.0, 3.0]);
        // Flat ends held are no kinks; flat at 0 neither is zero outside.
        let flat = |outside| {
            let xs = vec![0.0, 1.0, 2.0, 3.0];
            Curve::new(xs, vec![1.0, 1.0, 0.0, 0.0], outside).unwrap()
        };
        assert_eq!(flat(Outside::Hold).kinks(), [1.0, 2.0]);
        assert_eq!(flat(Outside::Zero).kinks(), [0.0, 1.0, 2.0]);
        assert_eq!(flat(Outside::Error).kinks(), [0.0, 1.0, 2.0, 3.0]);
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
