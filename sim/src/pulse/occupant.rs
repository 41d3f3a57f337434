//! Occupant-related criteria of a vehicle pulse: the occupant load criterion
//! (OLC, Euro NCAP) and the acceleration severity index (ASI, EN 1317-1).

/// The running integral `x0 + ∫ x dt` by the trapezoidal rule (exact for the
/// piecewise-linear interpolant of the samples).
pub fn integrate(t: &[f64], x: &[f64], x0: f64) -> Vec<f64> {
    let t = &t[..x.len()];
    let mut out = Vec::with_capacity(x.len());
    let mut sum = x0;
    if !x.is_empty() {
        out.push(sum);
    }
    for (t, x) in t.windows(2).zip(x.windows(2)) {
        sum += 0.5 * (x[1] + x[0]) * (t[1] - t[0]);
        out.push(sum);
    }
    out
}

/// The occupant load criterion and its two times.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Olc {
    /// The virtual occupant's constant deceleration in the restraint phase [m/s²].
    pub deceleration: f64,
    /// End of free flight: the occupant has moved 65 mm relative to the vehicle \[s\].
    pub t1: f64,
    /// End of the restraint phase: relative travel 300 mm, velocities equal \[s\].
    pub t2: f64,
}

/// Free-flight travel of the virtual occupant before the restraint acts \[m\].
pub const OLC_FREE_FLIGHT: f64 = 0.065;
/// Total relative travel of the virtual occupant \[m\].
pub const OLC_TOTAL_TRAVEL: f64 = 0.300;

/// The OLC of the vehicle velocity `v(t)` (forward positive; Euro NCAP
/// integrates the CFC 180 acceleration to get it).
///
/// The occupant keeps `v0 = v(t0)` until its travel relative to the vehicle,
/// `d(t) = v0 (t − t0) − (s(t) − s(t0))`, reaches 65 mm at `t1`. It then
/// decelerates uniformly at `OLC` so that at `t2` its velocity equals the
/// vehicle's and `d(t2)` = 300 mm. With `OLC = (v0 − v(t2)) / (t2 − t1)` the
/// second condition reads
/// `½ (v0 + v(t2)) (t2 − t1) − (s(t2) − s(t1)) = 235 mm`, solved for `t2`.
/// `None` when the pulse ends before either travel is reached.
pub fn olc(t: &[f64], v: &[f64]) -> Option<Olc> {
    if t.len() < 2 || t.len() != v.len() {
        return None;
    }
    let s = integrate(t, v, 0.0);
    let (t0, v0) = (t[0], v[0]);
    let d = |k: usize| v0 * (t[k] - t0) - s[k];
    let (k1, f1) = first_crossing(t.len(), d, OLC_FREE_FLIGHT)?;
    let t1 = lerp(t[k1 - 1], t[k1], f1);
    let s1 = lerp(s[k1 - 1], s[k1], f1);
    let rest = OLC_TOTAL_TRAVEL - OLC_FREE_FLIGHT;
    let g = |k: usize| {
        if t[k] <= t1 {
            -rest
        } else {
            0.5 * (v0 + v[k]) * (t[k] - t1) - (s[k] - s1) - rest
        }
    };
    let (k2, f2) = first_crossing(t.len(), g, 0.0)?;
    let t2 = lerp(t[k2 - 1], t[k2], f2);
    let v2 = lerp(v[k2 - 1], v[k2], f2);
    Some(Olc {
        deceleration: (v0 - v2) / (t2 - t1),
        t1,
        t2,
    })
}

/// The first `k < n` with `x(k − 1) < level ≤ x(k)`, and the fraction of
/// the way from `k − 1` to `k` at which the linear interpolant reaches
/// `level`; `x(k)` is evaluated only up to the crossing.
fn first_crossing(n: usize, x: impl Fn(usize) -> f64, level: f64) -> Option<(usize, f64)> {
    if n < 2 {
        return None;
    }
    let mut before = x(0);
    for k in 1..n {
        let at = x(k);
        if before < level && at >= level {
            return Some((k, (level - before) / (at - before)));
        }
        before = at;
    }
    None
}

fn lerp(a: f64, b: f64, f: f64) -> f64 {
    a + f * (b - a)
}

/// Averaging window of the ASI \[s\].
pub const ASI_WINDOW: f64 = 0.050;

/// The acceleration severity index of EN 1317-1 and when it is reached (the
/// end of the averaging window).
///
/// `ASI(t) = √((āx/â_x)² + (āy/â_y)² + (āz/â_z)²)` with ā the 50 ms moving
/// averages of the components and the limits `â = 12 g, 9 g, 10 g`; pass the
/// components a model has, each with its limit. The moving average is exact
/// for the piecewise-linear interpolant of the samples. `None` when the
/// record is shorter than the window.
pub fn asi(t: &[f64], components: &[(&[f64], f64)]) -> Option<(f64, f64)> {
    let n = t.len();
    if n < 2 || t[n - 1] - t[0] < ASI_WINDOW * (1.0 - 1e-12) {
        return None;
    }
    let integrals: Vec<Vec<f64>> = components
        .iter()
        .map(|(a, _)| integrate(t, a, 0.0))
        .collect();
    let mut best: Option<(f64, f64)> = None;
    let mut k = 0; // the interval [t[k], t[k + 1]] holding the window's start
    for j in 0..n {
        let start = t[j] - ASI_WINDOW;
        if start < t[0] - 1e-12 * ASI_WINDOW {
            continue;
        }
        while k + 1 < n && t[k + 1] <= start {
            k += 1;
        }
        let mut sum = 0.0;
        for ((a, limit), integral) in components.iter().zip(&integrals) {
            let at_start = if k + 1 < n {
                let (h, u) = (t[k + 1] - t[k], (start - t[k]).max(0.0));
                integral[k] + a[k] * u + 0.5 * (a[k + 1] - a[k]) / h * u * u
            } else {
                integral[k]
            };
            let mean = (integral[j] - at_start) / ASI_WINDOW;
            sum += (mean / limit).powi(2);
        }
        let value = sum.sqrt();
        if best.is_none_or(|(b, _)| value > b) {
            best = Some((value, t[j]));
        }
    }
    best
}

/// The cumulative duration of the 3 ms clip \[s\].
pub const CLIP_DURATION: f64 = 0.003;

/// The 3 ms clip of FMVSS 208 (S6.3) of an acceleration sampled every
/// `dt`: [`clip`] over [`CLIP_DURATION`].
pub fn clip_3ms(acceleration: &[f64], dt: f64) -> Option<f64> {
    clip(acceleration, dt, CLIP_DURATION)
}

/// The highest level `L` at which the magnitude of `a`, sampled every `dt`
/// and read as the piecewise-linear interpolant of its samples, spends a
/// cumulative `duration` or more at or above `L` (each crossing between two
/// samples counts its fraction of the interval; the exceedances add up, as
/// FMVSS 208 counts them). The duration above a level falls as the level
/// rises, so `L` is found by bisection between 0 and the peak to the
/// resolution of `f64`. `None` for a record shorter than `duration`, a
/// period that is not positive, or a non-finite sample.
pub fn clip(a: &[f64], dt: f64, duration: f64) -> Option<f64> {
    let record = dt * a.len().saturating_sub(1) as f64;
    if !(dt > 0.0 && dt.is_finite()) || record < duration || a.iter().any(|x| !x.is_finite()) {
        return None;
    }
    let magnitude: Vec<f64> = a.iter().map(|x| x.abs()).collect();
    let (mut low, mut high) = (0.0, magnitude.iter().copied().fold(0.0, f64::max));
    for _ in 0..200 {
        let level = 0.5 * (low + high);
        if level <= low || level >= high {
            break;
        }
        if time_at_or_above(&magnitude, dt, level) >= duration {
            low = level;
        } else {
            high = level;
        }
    }
    Some(low)
}

/// How long the interpolant of `x` is at or above `level`.
fn time_at_or_above(x: &[f64], dt: f64, level: f64) -> f64 {
    let mut total = 0.0;
    for pair in x.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        total += match (a >= level, b >= level) {
            (true, true) => dt,
            (false, false) => 0.0,
            // The fraction of the interval on the side above the level.
            (true, false) => dt * (a - level) / (a - b),
            (false, true) => dt * (b - level) / (b - a),
        };
    }
    total
}

#[cfg(test)]
mod tests {
    use super::*;

    const G: f64 = 9.80665;

    fn grid(t_end: f64, dt: f64) -> Vec<f64> {
        (0..=(t_end / dt).round() as usize)
            .map(|k| k as f64 * dt)
            .collect()
    }

    /// Bisection on a closed-form function, independent of the sampled code.
    fn bisect(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
        for _ in 0..200 {
            let m = 0.5 * (a + b);
            if (f(a) < 0.0) == (f(m) < 0.0) {
                a = m;
            } else {
                b = m;
            }
        }
        0.5 * (a + b)
    }

    #[test]
    fn olc_of_a_constant_deceleration_matches_the_hand_calculation() {
        // v = v0 − A t, s = v0 t − ½ A t². Free flight: d = ½ A t1² = 65 mm.
        // Restraint: ½ (2 v0 − A t2)(t2 − t1) − (v0 (t2 − t1) − ½ A (t2² − t1²))
        //          = ½ A t1 (t2 − t1) = 235 mm, so t2 = t1 + 0.47 / (A t1),
        // and OLC = A t2 / (t2 − t1).
        let (v0, a) = (15.5556, 20.0 * G);
        let t1 = (2.0 * OLC_FREE_FLIGHT / a).sqrt();
        let t2 = t1 + 2.0 * (OLC_TOTAL_TRAVEL - OLC_FREE_FLIGHT) / (a * t1);
        let expected = a * t2 / (t2 - t1);
        let t = grid(0.2, 1e-4);
        let v: Vec<f64> = t.iter().map(|t| v0 - a * t).collect();
        let got = olc(&t, &v).unwrap();
        assert!((got.t1 - t1).abs() < 1e-6, "{} vs {t1}", got.t1);
        assert!((got.t2 - t2).abs() < 1e-6, "{} vs {t2}", got.t2);
        assert!(
            (got.deceleration / expected - 1.0).abs() < 1e-5,
            "{} vs {expected}",
            got.deceleration
        );
        // 20 g gives 25.5 g (t1 = 25.7 ms, t2 = 118.8 ms).
        assert!((expected / G - 25.53).abs() < 0.01, "{}", expected / G);
    }

    #[test]
    fn olc_of_a_half_sine_matches_the_closed_form() {
        // a(t) = −A sin(πt/T) on [0, T], zero after:
        // v = v0 − (A T/π)(1 − cos(πt/T)), s = v0 t − (A T/π)(t − (T/π) sin(πt/T)).
        let (v0, a, tp) = (15.5556, 30.0 * G, 0.080);
        let w = std::f64::consts::PI / tp;
        let vel = |t: f64| {
            let t = t.min(tp);
            v0 - a / w * (1.0 - (w * t).cos())
        };
        let pos = |t: f64| {
            let tt = t.min(tp);
            let s_tp = v0 * tt - a / w * (tt - (w * tt).sin() / w);
            s_tp + vel(tp) * (t - tt)
        };
        let d = |t: f64| v0 * t - pos(t);
        let t1 = bisect(|t| d(t) - OLC_FREE_FLIGHT, 0.0, 0.2);
        let g = |t2: f64| {
            0.5 * (v0 + vel(t2)) * (t2 - t1)
                - (pos(t2) - pos(t1))
                - (OLC_TOTAL_TRAVEL - OLC_FREE_FLIGHT)
        };
        let t2 = bisect(g, t1 + 1e-9, 0.3);
        let expected = (v0 - vel(t2)) / (t2 - t1);
        let t = grid(0.3, 1e-4);
        let v: Vec<f64> = t.iter().map(|&t| vel(t)).collect();
        let got = olc(&t, &v).unwrap();
        assert!((got.t1 - t1).abs() < 2e-6, "{} vs {t1}", got.t1);
        assert!((got.t2 - t2).abs() < 2e-6, "{} vs {t2}", got.t2);
        assert!(
            (got.deceleration / expected - 1.0).abs() < 1e-5,
            "{} vs {expected}",
            got.deceleration
        );
    }

    #[test]
    fn olc_needs_the_occupant_to_travel() {
        let t = grid(0.1, 1e-3);
        let v = vec![10.0; t.len()];
        assert_eq!(olc(&t, &v), None);
    }

    #[test]
    fn asi_of_a_constant_pulse_is_its_level_over_twelve_g() {
        let t = grid(0.2, 1e-4);
        let a: Vec<f64> = t
            .iter()
            .map(|&t| {
                if (0.02..=0.12).contains(&t) {
                    -15.0 * G
                } else {
                    0.0
                }
            })
            .collect();
        let (value, at) = asi(&t, &[(&a, 12.0 * G)]).unwrap();
        assert!((value - 15.0 / 12.0).abs() < 1e-9, "{value}");
        assert!((0.07..=0.12).contains(&at), "{at}");
    }

    #[test]
    fn asi_of_a_half_sine_matches_the_closed_form() {
        // The 50 ms mean of A sin(πt/T) is largest centred on T/2:
        // (A / δ) ∫ sin = A (2T / (π δ)) sin(π δ / (2T)).
        let (a, tp) = (25.0 * G, 0.080);
        let expected = a
            * (2.0 * tp / (std::f64::consts::PI * ASI_WINDOW))
            * (std::f64::consts::PI * ASI_WINDOW / (2.0 * tp)).sin()
            / (12.0 * G);
        let t = grid(0.2, 1e-4);
        let acc: Vec<f64> = t
            .iter()
            .map(|&t| {
                if t <= tp {
                    a * (std::f64::consts::PI * t / tp).sin()
                } else {
                    0.0
                }
            })
            .collect();
        let (value, at) = asi(&t, &[(&acc, 12.0 * G)]).unwrap();
        // The samples' linear interpolant integrates the sine to h²ω²/12 ≈ 1.3e-6.
        assert!(
            (value / expected - 1.0).abs() < 5e-6,
            "{value} vs {expected}"
        );
        assert!((at - (tp + ASI_WINDOW) / 2.0).abs() < 2e-4, "{at}");
    }

    #[test]
    fn asi_combines_components_with_their_limits() {
        let t = grid(0.1, 1e-3);
        let ax = vec![6.0 * G; t.len()];
        let az = vec![5.0 * G; t.len()];
        let (value, _) = asi(&t, &[(&ax, 12.0 * G), (&az, 10.0 * G)]).unwrap();
        assert!((value - 0.5f64.hypot(0.5)).abs() < 1e-12);
        assert_eq!(asi(&t[..10], &[(&ax[..10], 12.0 * G)]), None);
    }

    #[test]
    fn the_3ms_clip_of_a_half_sine_is_where_it_spends_3ms_above() {
        // |a| = A sin(πt/T) is at or above L for T − (2T/π)·asin(L/A), which
        // is 3 ms at L = A·cos(π·3 ms / (2T)).
        let (amplitude, duration, dt) = (400.0, 0.02, 1e-5);
        let t = grid(0.03, dt);
        let a: Vec<f64> = t
            .iter()
            .map(|&t| {
                if t < duration {
                    -amplitude * (std::f64::consts::PI * t / duration).sin()
                } else {
                    0.0
                }
            })
            .collect();
        let expected = amplitude * (std::f64::consts::PI * 0.003 / (2.0 * duration)).cos();
        let clip = clip_3ms(&a, dt).unwrap();
        assert!((clip - expected).abs() < 1e-3, "{clip} vs {expected}");
        assert_eq!(clip_3ms(&a[..200], dt), None);
    }

    #[test]
    fn a_crossing_is_the_first_rise_through_the_level() {
        let x = [0.0, 1.0, 1.0, 0.5, 2.0, 3.0, f64::NAN, 4.0];
        let at = |k: usize| x[k];
        assert_eq!(first_crossing(x.len(), at, 1.0), Some((1, 1.0)));
        assert_eq!(first_crossing(x.len(), at, 1.5), Some((4, 1.0 / 1.5)));
        assert_eq!(first_crossing(x.len(), at, 3.5), None);
        assert_eq!(first_crossing(1, at, -1.0), None);
    }

    #[test]
    fn the_running_integral_is_the_trapezoids_summed_in_order() {
        let t = [0.0, 0.1, 0.25, 0.3, 0.7];
        let x = [1.0, -2.0, 0.5, 3.0, 1e-3];
        let mut expected = vec![2.0];
        for k in 1..x.len() {
            let trapezoid = 0.5 * (x[k] + x[k - 1]) * (t[k] - t[k - 1]);
            expected.push(expected[k - 1] + trapezoid);
        }
        assert_eq!(integrate(&t, &x, 2.0), expected);
        assert_eq!(integrate(&t, &x[..1], 2.0), [2.0]);
        assert!(integrate(&t, &[], 2.0).is_empty());
        // 2 + ∫ of the linear interpolant over [0, 0.1]: 2 + 0.1·(1 − 2)/2.
        assert!((expected[1] - 1.95).abs() < 1e-15);
    }
}
