//! SAE J211-1 channel frequency class (CFC) filtering.
//!
//! A two-pole Butterworth low-pass run forward and then backward over the
//! signal (zero phase, four poles overall), with the coefficients of J211-1
//! Appendix C for sample period `T`:
//!
//! ```text
//! ω_d = 2π · CFC · 2.0775,   ω_a = tan(ω_d T / 2),   s = 1 + √2 ω_a + ω_a²
//! a0 = ω_a² / s,   a1 = 2 a0,   a2 = a0
//! b1 = −2 (ω_a² − 1) / s,   b2 = (−1 + √2 ω_a − ω_a²) / s
//! y[n] = a0 x[n] + a1 x[n−1] + a2 x[n−2] + b1 y[n−1] + b2 y[n−2]
//! ```
//!
//! The CFC number is not the −3 dB frequency: that lies near 5/3 · CFC.

use crate::warning::Warning;
use std::f64::consts::SQRT_2;

/// The standard channel classes of J211-1.
pub const STANDARD_CLASSES: [f64; 4] = [60.0, 180.0, 600.0, 1000.0];

/// The class J211-1 recommends for what a channel measures (its table of
/// filter classes by measurement), by the name a scenario's
/// `metrics.classes` gives it.
pub const CLASS_BY_MEASUREMENT: [(&str, f64); 12] = [
    ("head", 1000.0),
    ("neck_force", 1000.0),
    ("neck_moment", 600.0),
    ("chest", 180.0),
    ("chest_deflection", 180.0),
    ("pelvis", 1000.0),
    ("femur", 600.0),
    ("tibia", 600.0),
    ("structure", 60.0),
    ("integration", 180.0),
    ("sled", 60.0),
    ("belt", 60.0),
];

/// The class of an acceleration channel that names none: CFC 180, J211-1's
/// for a thorax (chest) acceleration and for a structure's acceleration to
/// be integrated, and the one the 3 ms clip of FMVSS 208 reads.
pub const DEFAULT_CLASS: f64 = 180.0;

/// Length of the padding at each end before filtering \[s\]. J211 asks for at
/// least 10 ms of pre-test data; the padding stands in for it, and is made
/// long enough that the start-up transient of the slowest class (CFC 60:
/// poles with real part −554 s⁻¹) has decayed by e^−27 when the signal begins.
const PADDING: f64 = 0.050;

/// Why a signal cannot be filtered.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CfcError {
    /// The sample period is not a positive finite number.
    #[error("sample period {0} s is not a positive number")]
    SamplePeriod(f64),
    /// The class is not positive, or too high for the sample rate: the
    /// design frequency 2.0775·CFC must stay below the Nyquist frequency.
    #[error(
        "CFC {cfc} cannot be applied to a signal sampled at {sample_rate:.0} Hz \
         (needs 0 < 2.0775·CFC < half the sample rate; J211 recommends a sample \
         rate of at least 10 × CFC)"
    )]
    Class {
        /// The channel frequency class asked for (60, 180, …).
        cfc: f64,
        /// The signal's sample rate, `1 / period` \[Hz\].
        sample_rate: f64,
    },
}

/// The factor from the class to the design frequency of J211-1 Appendix C:
/// `f_d = 2.0775 · CFC`.
const DESIGN_FACTOR: f64 = 2.0775;

/// The design angular frequency `ω_d = 2π · 2.0775 · CFC` [rad/s].
fn design_frequency(cfc: f64) -> f64 {
    2.0 * std::f64::consts::PI * cfc * DESIGN_FACTOR
}

/// Whether class `cfc` can be applied to a signal sampled every `dt`
/// seconds: the one rule of this module (and of every metric that filters),
/// the design frequency `2.0775·CFC` below half the sample rate, so that
/// `tan(ω_d T / 2)` is finite and positive.
pub fn applies(cfc: f64, dt: f64) -> bool {
    dt > 0.0 && dt.is_finite() && cfc > 0.0 && design_frequency(cfc) * dt < std::f64::consts::PI
}

/// The sample rate [Hz] that class `cfc` needs to exceed: twice its design
/// frequency, `2 · 2.0775 · CFC` (748 Hz for CFC 180, 249 Hz for CFC 60).
pub fn min_sample_rate(cfc: f64) -> f64 {
    2.0 * DESIGN_FACTOR * cfc
}

/// The coefficients `[a0, a1, a2, b1, b2]` of one pass.
pub fn coefficients(cfc: f64, dt: f64) -> Result<[f64; 5], CfcError> {
    if !(dt > 0.0 && dt.is_finite()) {
        return Err(CfcError::SamplePeriod(dt));
    }
    if !applies(cfc, dt) {
        return Err(CfcError::Class {
            cfc,
            sample_rate: 1.0 / dt,
        });
    }
    let wd = design_frequency(cfc);
    let wa = (wd * dt / 2.0).tan();
    let s = 1.0 + SQRT_2 * wa + wa * wa;
    let a0 = wa * wa / s;
    Ok([
        a0,
        2.0 * a0,
        a0,
        -2.0 * (wa * wa - 1.0) / s,
        (-1.0 + SQRT_2 * wa - wa * wa) / s,
    ])
}

/// `signal`, sampled every `dt` seconds, filtered to channel class `cfc`.
///
/// Both ends are padded by odd reflection (`2 x[0] − x[k]`, 50 ms or as much
/// of the signal as there is), so that the filter starts and ends settled on
/// the signal's level and slope instead of on zero.
pub fn cfc_filter(signal: &[f64], dt: f64, cfc: f64) -> Result<Vec<f64>, CfcError> {
    let [filtered] = cfc_filter_classes(signal, dt, [cfc])?;
    Ok(filtered)
}

/// [`cfc_filter`] of `signal` to each of `classes`, bit for bit, with the
/// filters run side by side: a pass is a chain of dependent multiply-adds,
/// and the chains of different classes overlap in the processor.
pub fn cfc_filter_classes<const M: usize>(
    signal: &[f64],
    dt: f64,
    classes: [f64; M],
) -> Result<[Vec<f64>; M], CfcError> {
    let mut coefficients = [[0.0; 5]; M];
    for (c, cfc) in coefficients.iter_mut().zip(classes) {
        *c = self::coefficients(cfc, dt)?;
    }
    let n = signal.len();
    if n < 2 {
        return Ok(classes.map(|_| signal.to_vec()));
    }
    let pad = ((PADDING / dt).ceil() as usize).min(n - 1);
    let (first, last) = (signal[0], signal[n - 1]);
    let lead = (1..=pad).rev().map(|k| 2.0 * first - signal[k]);
    let tail = (1..=pad).map(|k| 2.0 * last - signal[n - 1 - k]);
    // Forward over the padded signal; the leading padding's outputs only
    // settle the filters (the backward passes drop them), the rest are kept.
    let at_rest = lead.clone().next().unwrap_or(first);
    let mut forward = coefficients.map(|c| Pass::at_rest(c, at_rest));
    for x in lead {
        forward.iter_mut().for_each(|pass| _ = pass.step(x));
    }
    let mut ys: [Vec<f64>; M] = std::array::from_fn(|_| vec![0.0; n + pad]);
    for (k, x) in signal.iter().copied().chain(tail).enumerate() {
        for (pass, y) in forward.iter_mut().zip(ys.iter_mut()) {
            y[k] = pass.step(x);
        }
    }
    // Backward from the end of the trailing padding.
    let mut backward: [Pass; M] =
        std::array::from_fn(|m| Pass::at_rest(coefficients[m], ys[m][n + pad - 1]));
    for k in (0..n + pad).rev() {
        for (pass, y) in backward.iter_mut().zip(ys.iter_mut()) {
            y[k] = pass.step(y[k]);
        }
    }
    for y in &mut ys {
        y.truncate(n);
    }
    Ok(ys)
}

/// One pass of the filter: its coefficients and its last two inputs and
/// outputs.
struct Pass {
    coefficients: [f64; 5],
    x1: f64,
    x2: f64,
    y1: f64,
    y2: f64,
}

impl Pass {
    /// A pass at rest on `x` (y = x for a constant input).
    fn at_rest(coefficients: [f64; 5], x: f64) -> Pass {
        Pass {
            coefficients,
            x1: x,
            x2: x,
            y1: x,
            y2: x,
        }
    }

    /// The output for the next input `x`.
    #[inline]
    fn step(&mut self, x: f64) -> f64 {
        let [a0, a1, a2, b1, b2] = self.coefficients;
        let y = a0 * x + a1 * self.x1 + a2 * self.x2 + b1 * self.y1 + b2 * self.y2;
        (self.x2, self.x1) = (self.x1, x);
        (self.y2, self.y1) = (self.y1, y);
        y
    }
}

/// The filter classes of `needs` (`(class, what goes without it)` pairs)
/// that samples every `period` seconds cannot give: one warning a class, in
/// the order of their first need, with what goes without it joined.
pub fn filter_classes(period: f64, needs: &[(f64, String)]) -> Vec<Warning> {
    let mut missing: Vec<(f64, Vec<&str>)> = Vec::new();
    for (cfc, what) in needs {
        if applies(*cfc, period) {
            continue;
        }
        match missing.iter_mut().find(|(c, _)| c == cfc) {
            Some((_, whats)) => whats.push(what),
            None => missing.push((*cfc, vec![what])),
        }
    }
    (missing.into_iter())
        .map(|(cfc, whats)| Warning::FilterClass {
            cfc,
            period,
            min_rate: min_sample_rate(cfc),
            consequence: whats.join("; "),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Gain (dB) of the filter on a sine of `f` Hz sampled at `rate`: the
    /// amplitude in the middle half of a long record, by projection on the
    /// sine and cosine of the input frequency.
    fn measured_gain_db(cfc: f64, f: f64, rate: f64) -> f64 {
        let dt = 1.0 / rate;
        let periods = (20.0f64).max(f * 0.5);
        let n = (periods / f / dt).ceil() as usize;
        let w = 2.0 * std::f64::consts::PI * f;
        let x: Vec<f64> = (0..n).map(|k| (w * k as f64 * dt).sin()).collect();
        let y = cfc_filter(&x, dt, cfc).unwrap();
        let (lo, hi) = (n / 4, 3 * n / 4);
        let (mut s, mut c) = (0.0, 0.0);
        for (k, y) in y.iter().enumerate().take(hi).skip(lo) {
            s += y * (w * k as f64 * dt).sin();
            c += y * (w * k as f64 * dt).cos();
        }
        let m = (hi - lo) as f64;
        let amplitude = 2.0 * (s * s + c * c).sqrt() / m;
        20.0 * amplitude.log10()
    }

    /// The response corridor of SAE J211-1 (1995) Figure 1 / ISO 6487 for a
    /// channel of class CFC: F_H = CFC, F_N = 5/3·CFC. Limits in dB:
    /// 0.1 Hz…F_H: ±0.5; at F_H: +0.5/−1; at F_N: +0.5/−4 (straight lines on
    /// a log-frequency axis between F_H and F_N); beyond F_N the upper limit
    /// falls at 9 dB/octave (to a floor of −30 dB) and the lower at 24 dB/octave.
    fn corridor(cfc: f64, f: f64) -> (f64, f64) {
        let (fh, fnn) = (cfc, cfc * 5.0 / 3.0);
        if f <= fh {
            (0.5, -0.5)
        } else if f <= fnn {
            let s = (f / fh).log2() / (fnn / fh).log2();
            (0.5, -1.0 + s * (-4.0 + 1.0))
        } else {
            let octaves = (f / fnn).log2();
            ((0.5 - 9.0 * octaves).max(-30.0), -4.0 - 24.0 * octaves)
        }
    }

    #[test]
    fn the_magnitude_response_lies_in_the_j211_corridor() {
        for cfc in STANDARD_CLASSES {
            // J211 asks for a sample rate of at least 10 × F_H... and the
            // bilinear transform bends the response near Nyquist, so check
            // up to 2·F_N with a rate of 20 × F_N (≥ 10 kHz).
            let rate = (20.0 * cfc * 5.0 / 3.0).max(10_000.0);
            let fnn = cfc * 5.0 / 3.0;
            for f in [
                0.1,
                1.0,
                0.1 * cfc,
                0.5 * cfc,
                cfc,
                1.3 * cfc,
                fnn,
                1.5 * fnn,
                2.0 * fnn,
            ] {
                if f < 1.0 && cfc > 60.0 {
                    continue; // the 0.1 Hz point is the same for every class
                }
                let gain = measured_gain_db(cfc, f, rate);
                let (upper, lower) = corridor(cfc, f);
                assert!(
                    gain <= upper + 1e-9 && gain >= lower - 1e-9,
                    "CFC {cfc} at {f} Hz: {gain:.3} dB outside [{lower:.2}, {upper:.2}] dB"
                );
            }
        }
    }

    #[test]
    fn the_minus_3_db_point_is_near_five_thirds_of_the_class() {
        // Analog four-pole response |H| = 1 / (1 + (f / 2.0775 CFC)^4): −3 dB
        // at f = 2.0775 · CFC · (√2 − 1)^(1/4) = 1.6681 · CFC.
        let f3 = 2.0775 * (SQRT_2 - 1.0).powf(0.25) * 60.0;
        let gain = measured_gain_db(60.0, f3, 10_000.0);
        assert!((gain + 3.0103).abs() < 0.02, "{gain}");
    }

    #[test]
    fn constants_and_ramps_pass_unchanged() {
        let dt = 1e-4;
        let ramp: Vec<f64> = (0..2000).map(|k| 3.0 + 50.0 * k as f64 * dt).collect();
        let y = cfc_filter(&ramp, dt, 60.0).unwrap();
        let worst = ramp
            .iter()
            .zip(&y)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(worst < 1e-8, "{worst}");
    }

    #[test]
    fn a_class_too_high_for_the_sample_rate_is_refused() {
        let e = cfc_filter(&[0.0; 10], 1e-3, 1000.0).unwrap_err();
        assert_eq!(
            e,
            CfcError::Class {
                cfc: 1000.0,
                sample_rate: 1000.0
            }
        );
        assert!(matches!(
            cfc_filter(&[0.0; 10], 0.0, 60.0),
            Err(CfcError::SamplePeriod(_))
        ));
    }

    /// The rule is the design frequency 2.0775·CFC below half the rate: at
    /// 1.5 ms (667 Hz) CFC 60 applies (needs 249.3 Hz), CFC 180 does not
    /// (747.9 Hz); just either side of 747.9 Hz, it does and does not.
    #[test]
    fn each_class_applies_above_twice_its_design_frequency() {
        assert!(applies(60.0, 1.5e-3) && !applies(180.0, 1.5e-3));
        assert!((min_sample_rate(180.0) - 747.9).abs() < 1e-9);
        assert!((min_sample_rate(60.0) - 249.3).abs() < 1e-9);
        assert!(applies(180.0, 1.0 / 748.0) && !applies(180.0, 1.0 / 747.8));
        assert!(applies(1000.0, 1e-4) && !applies(1000.0, 1.0 / 4150.0));
        for dt in [0.0, -1e-3, f64::NAN, f64::INFINITY] {
            assert!(!applies(60.0, dt), "{dt}");
        }
        assert_eq!(
            cfc_filter(&[0.0; 10], 1.5e-3, 180.0).is_ok(),
            applies(180.0, 1.5e-3)
        );
    }

    /// The filter as J211 draws it: pad, filter, reverse, filter, reverse,
    /// cut the padding off.
    fn reference(signal: &[f64], dt: f64, cfc: f64) -> Vec<f64> {
        let [a0, a1, a2, b1, b2] = coefficients(cfc, dt).unwrap();
        let n = signal.len();
        let pad = ((PADDING / dt).ceil() as usize).min(n - 1);
        let mut x: Vec<f64> = (1..=pad)
            .rev()
            .map(|k| 2.0 * signal[0] - signal[k])
            .collect();
        x.extend_from_slice(signal);
        x.extend((1..=pad).map(|k| 2.0 * signal[n - 1] - signal[n - 1 - k]));
        for _ in 0..2 {
            let (mut x1, mut x2, mut y1, mut y2) = (x[0], x[0], x[0], x[0]);
            for v in x.iter_mut() {
                let y = a0 * *v + a1 * x1 + a2 * x2 + b1 * y1 + b2 * y2;
                (x2, x1, y2, y1, *v) = (x1, *v, y1, y, y);
            }
            x.reverse();
        }
        x[pad..pad + n].to_vec()
    }

    #[test]
    fn the_filter_is_the_reference_pass_by_pass_bit_for_bit() {
        let dt = 1e-4;
        for n in [2, 3, 40, 1501] {
            let x: Vec<f64> = (0..n)
                .map(|k| {
                    let t = k as f64 * dt;
                    -200.0 * (60.0 * t).sin() + 30.0 * (1700.0 * t).cos() + 5.0 * t
                })
                .collect();
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            let side_by_side = cfc_filter_classes(&x, dt, [60.0, 180.0]).unwrap();
            for (cfc, together) in [60.0, 180.0].into_iter().zip(side_by_side) {
                let got = cfc_filter(&x, dt, cfc).unwrap();
                let expected = reference(&x, dt, cfc);
                assert_eq!(bits(&got), bits(&expected), "n = {n}, CFC {cfc}");
                assert_eq!(
                    bits(&together),
                    bits(&expected),
                    "n = {n}, CFC {cfc} beside another"
                );
            }
        }
    }

    /// One warning a class, in the order of the first need, joining what
    /// goes without it; classes the rate gives are not there.
    #[test]
    fn filter_classes_the_rate_cannot_give_warn_once_each() {
        let needs = [
            (60.0, "a".to_string()),
            (180.0, "b".to_string()),
            (1000.0, "c".to_string()),
            (180.0, "d".to_string()),
        ];
        // 1 kHz: CFC 60 and 180 apply (249.3 and 747.9 Hz), 1000 does not.
        let [w] = &filter_classes(1e-3, &needs)[..] else {
            panic!("{:?}", filter_classes(1e-3, &needs))
        };
        assert_eq!(w.kind(), "filter_class");
        assert_eq!(
            w.message(),
            "CFC 1000 needs a sample rate above 4155 Hz (SAE J211-1: 2.0775·CFC below half the \
             sample rate); samples every 1 ms give 1000 Hz: c"
        );
        let slow = filter_classes(1.5e-3, &needs);
        assert_eq!(slow.len(), 2);
        assert!(
            slow[0].message().ends_with("give 667 Hz: b; d"),
            "{}",
            slow[0]
        );
        assert_eq!(filter_classes(1e-4, &needs), []);
    }
}
