//! The head injury criterion (HIC): FMVSS 208 S6.2 (HIC15), and HIC36 of
//! its earlier editions and of ECE R94.

/// The HIC of a record and the interval that gives it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hic {
    /// The criterion (dimensionless: accelerations in g, times in s).
    pub value: f64,
    /// Start of the interval \[s\].
    pub t1: f64,
    /// End of the interval \[s\].
    pub t2: f64,
}

/// The longest interval of HIC15 \[s\].
pub const HIC15_WINDOW: f64 = 0.015;
/// The longest interval of HIC36 \[s\].
pub const HIC36_WINDOW: f64 = 0.036;

/// The HIC of the resultant head acceleration `a` (in g) sampled every `dt`
/// from `t0`:
/// `max over t1 < t2 ≤ t1 + window of (t2 − t1) · [∫ a dt / (t2 − t1)]^2.5`,
/// the integral that of the samples' piecewise-linear interpolant (the
/// trapezoidal rule). Every pair of samples no further apart than the window
/// is tried: the maximum need not use the whole window (a short spike's
/// does not), so no interval is skipped. A negative mean (of a component
/// rather than a resultant) is not a candidate. `None` for fewer than two
/// samples, a period that is not positive, or a non-finite sample.
pub fn hic(a: &[f64], t0: f64, dt: f64, window: f64) -> Option<Hic> {
    if a.len() < 2 || !(dt > 0.0 && dt.is_finite()) || a.iter().any(|x| !x.is_finite()) {
        return None;
    }
    let integral = cumulative_trapezoid(a, dt);
    // The widest pair, tolerant of `window / dt` rounding below an integer.
    let widest = ((window / dt) * (1.0 + 1e-9)).floor() as usize;
    let mut best = Hic {
        value: 0.0,
        t1: t0,
        t2: t0,
    };
    for i in 0..a.len() - 1 {
        for j in i + 1..=(i + widest).min(a.len() - 1) {
            let duration = (j - i) as f64 * dt;
            let mean = (integral[j] - integral[i]) / duration;
            if mean <= 0.0 {
                continue;
            }
            let value = duration * mean.powf(2.5);
            if value > best.value {
                best = Hic {
                    value,
                    t1: t0 + i as f64 * dt,
                    t2: t0 + j as f64 * dt,
                };
            }
        }
    }
    Some(best)
}

/// `∫ a dt` from the first sample to each sample, by the trapezoidal rule.
fn cumulative_trapezoid(a: &[f64], dt: f64) -> Vec<f64> {
    let mut sum = 0.0;
    let mut out = Vec::with_capacity(a.len());
    out.push(0.0);
    for pair in a.windows(2) {
        sum += 0.5 * (pair[0] + pair[1]) * dt;
        out.push(sum);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// HIC of the half-sine `A sin(πt/T)` over `w`-wide windows centred
    /// on its peak (the best for a symmetric single-peaked pulse):
    /// `w^-1.5 · ((2AT/π) sin(πw/2T))^2.5`, maximised over `w ≤ min(window,
    /// T)` by a fine search of the closed form.
    fn half_sine_hic(amplitude: f64, duration: f64, window: f64) -> f64 {
        let closed = |w: f64| {
            let integral = 2.0 * amplitude * duration / std::f64::consts::PI
                * (std::f64::consts::PI * w / (2.0 * duration)).sin();
            w.powf(-1.5) * integral.powf(2.5)
        };
        let widest = window.min(duration);
        (1..=100_000)
            .map(|k| closed(widest * k as f64 / 100_000.0))
            .fold(0.0, f64::max)
    }

    fn half_sine(amplitude: f64, duration: f64, dt: f64, pad: f64) -> Vec<f64> {
        let n = ((duration + 2.0 * pad) / dt).round() as usize;
        (0..=n)
            .map(|k| {
                let t = k as f64 * dt - pad;
                if (0.0..=duration).contains(&t) {
                    amplitude * (std::f64::consts::PI * t / duration).sin()
                } else {
                    0.0
                }
            })
            .collect()
    }

    #[test]
    fn hic_of_a_long_half_sine_uses_the_whole_window() {
        // 80 g over 40 ms: the unconstrained optimum (0.669 T = 27 ms) is
        // wider than 15 ms, so HIC15 takes 15 ms centred on the peak; HIC36
        // takes the optimum itself.
        let (a, t, dt) = (80.0, 0.040, 1e-4);
        let samples = half_sine(a, t, dt, 0.01);
        for window in [HIC15_WINDOW, HIC36_WINDOW] {
            let hic = hic(&samples, -0.01, dt, window).unwrap();
            let exact = half_sine_hic(a, t, window);
            assert!(
                (hic.value - exact).abs() < 2e-4 * exact,
                "window {window}: {} against {exact}",
                hic.value
            );
            assert!(hic.t2 - hic.t1 <= window + 1e-12);
            assert!((0.5 * (hic.t1 + hic.t2) - 0.5 * t).abs() <= dt);
        }
    }

    #[test]
    fn hic_of_a_short_spike_does_not_widen_its_interval() {
        // A 5 ms half-sine: the best interval is 0.669·5 ms, well inside
        // 15 ms; a search over full windows only would understate it.
        let (a, t, dt) = (150.0, 0.005, 1e-5);
        let samples = half_sine(a, t, dt, 0.02);
        let hic = hic(&samples, -0.02, dt, HIC15_WINDOW).unwrap();
        let exact = half_sine_hic(a, t, HIC15_WINDOW);
        assert!(
            (hic.value - exact).abs() < 1e-4 * exact,
            "{} against {exact}",
            hic.value
        );
        assert!((hic.t2 - hic.t1 - 0.6686 * t).abs() < 2e-5);
    }

    #[test]
    fn hic_of_a_square_pulse_is_its_level_to_the_power_two_and_a_half() {
        // a = 60 g for 10 ms: HIC = 0.010 · 60^2.5 (every sub-interval of
        // the plateau gives less; the ramps at the ends cost the trapezoid).
        let dt = 1e-5;
        let samples: Vec<f64> = (0..3000)
            .map(|k| {
                if (1000..=2000).contains(&k) {
                    60.0
                } else {
                    0.0
                }
            })
            .collect();
        let hic = hic(&samples, 0.0, dt, HIC15_WINDOW).unwrap();
        let exact = 0.010 * 60f64.powf(2.5);
        assert!(
            (hic.value - exact).abs() < 1e-3 * exact,
            "{} against {exact}",
            hic.value
        );
    }

    #[test]
    fn hic_refuses_what_it_cannot_rate() {
        assert_eq!(hic(&[1.0], 0.0, 1e-4, HIC15_WINDOW), None);
        assert_eq!(hic(&[1.0, f64::NAN], 0.0, 1e-4, HIC15_WINDOW), None);
        assert_eq!(hic(&[1.0, 2.0], 0.0, 0.0, HIC15_WINDOW), None);
        let zero = hic(&[0.0; 10], 0.0, 1e-4, HIC15_WINDOW).unwrap();
        assert_eq!(zero.value, 0.0);
    }
}
