//! Crash-pulse metrics from a vehicle's deceleration history, simulated or
//! measured: SAE J211 CFC filtering, crush, time to zero velocity, rebound,
//! peak and equivalent-square-wave deceleration, OLC and ASI.
//!
//! Conventions: the vehicle moves forward into the barrier; velocity is
//! positive forward, acceleration is its derivative (negative while the car
//! decelerates), crush is positive in compression.

pub mod cfc;
pub mod channels;
pub mod occupant;

use crate::warning::Warning;
pub use cfc::{CfcError, cfc_filter, cfc_filter_classes};
pub use occupant::{Olc, asi, clip_3ms, integrate, olc};
use serde::Serialize;

/// Standard gravity [m/s²], the unit `g` of the metrics (one constant with
/// the `g` of a scenario's quantities).
pub use crate::quantity::STANDARD_GRAVITY;

/// How far apart, relative to the smallest, the periods of samples that
/// [`Pulse::resampled`] takes as evenly spaced may be: far below what
/// linear interpolation onto an even grid would change, far above the
/// rounding of times computed as `k·dt` (a few `1e-13` relative for
/// `k` in the thousands).
pub const EVEN_PERIODS: f64 = 1e-9;

/// A vehicle pulse sampled at a constant period.
#[derive(Clone, Debug, PartialEq)]
pub struct Pulse {
    /// Sample times \[s\], equally spaced.
    pub t: Vec<f64>,
    /// Vehicle acceleration [m/s²], forward positive.
    pub acceleration: Vec<f64>,
    /// Velocity at `t[0]` [m/s], forward positive.
    pub v0: f64,
    /// Crush \[m\] when measured or simulated; otherwise the vehicle's
    /// displacement is used (equal to the crush against a rigid barrier).
    pub crush: Option<Vec<f64>>,
}

/// The metrics of a pulse.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PulseMetrics {
    /// The velocity at the first sample, [`Pulse::v0`] [m/s].
    pub impact_velocity_mps: f64,
    /// Largest crush (the crush channel, or the displacement from the CFC 180
    /// acceleration integrated twice; the raw one where the rate cannot
    /// give CFC 180) \[m\].
    pub max_dynamic_crush_m: Option<f64>,
    /// When the largest crush is reached: the time of its sample \[s\].
    /// `None`, like the crush, when the vehicle never compresses.
    pub time_of_max_crush_s: Option<f64>,
    /// First time the velocity (CFC 180 acceleration integrated; the raw
    /// one where the rate cannot give CFC 180) reaches zero \[s\].
    pub time_to_zero_velocity_s: Option<f64>,
    /// Largest backward velocity after that [m/s].
    pub rebound_velocity_mps: Option<f64>,
    /// Largest deceleration of the unfiltered acceleration \[g\]; 0 when the
    /// vehicle never decelerates.
    pub peak_deceleration_g: f64,
    /// Largest deceleration of the CFC 60 filtered acceleration \[g\];
    /// `None` where the sample rate cannot give CFC 60 (see
    /// [`Pulse::filter_warnings`]).
    pub peak_deceleration_cfc60_g: Option<f64>,
    /// `v0² / (2 g C)`: the constant deceleration that stops the car in its
    /// maximum crush \[g\].
    pub equivalent_square_wave_g: Option<f64>,
    /// Occupant load criterion (Euro NCAP, from the CFC 180 velocity) \[g\].
    pub olc_g: Option<f64>,
    /// End of the virtual occupant's free flight (65 mm of relative
    /// travel) \[s\]; see [`Olc::t1`].
    pub olc_t1_s: Option<f64>,
    /// End of its restraint phase (300 mm of relative travel) \[s\]; see
    /// [`Olc::t2`].
    pub olc_t2_s: Option<f64>,
    /// Acceleration severity index (EN 1317-1, 50 ms averages of the CFC 180
    /// acceleration; the longitudinal component only).
    pub asi: Option<f64>,
    /// When the ASI is reached: the end of its 50 ms window \[s\].
    pub asi_time_s: Option<f64>,
}

/// Why a pulse has no metrics.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum PulseError {
    /// Fewer than 3 samples (the number it has).
    #[error("a pulse needs at least 3 samples, has {0}")]
    TooShort(usize),
    /// Time does not increase at sample `index`.
    #[error("time does not increase at sample {index}")]
    NotIncreasing {
        /// The first sample, from 0, whose time is not after the one before.
        index: usize,
    },
    /// The period varies by more than 1e-6 relative (resample first).
    #[error(
        "samples are not equally spaced: period {period:e} s at sample {index}, {first:e} s at the start"
    )]
    Unequal {
        /// The first sample, from 1, that ends a period unlike the first.
        index: usize,
        /// The period ending at that sample \[s\].
        period: f64,
        /// The first period, `t[1] − t[0]` \[s\].
        first: f64,
    },
    /// A channel has not one value per sample time.
    #[error("{what} has {len} values for {samples} sample times")]
    Length {
        /// Which channel: `acceleration` or `crush`.
        what: &'static str,
        /// The number of its values.
        len: usize,
        /// The number of sample times.
        samples: usize,
    },
    /// A NaN or ±∞ among the samples.
    #[error("{what} at sample {index} is not a finite number")]
    NotFinite {
        /// Which channel: `time`, `acceleration` or `crush`.
        what: &'static str,
        /// The first sample, from 0, that is not finite.
        index: usize,
    },
}

impl Pulse {
    /// A pulse from samples at any increasing times, resampled by linear
    /// interpolation onto the grid of the smallest period that occurs;
    /// samples already evenly spaced (every period within
    /// [`EVEN_PERIODS`] of the smallest: `k·dt` in floating point) are
    /// taken as they are.
    pub fn resampled(
        t: &[f64],
        acceleration: &[f64],
        v0: f64,
        crush: Option<&[f64]>,
    ) -> Result<Pulse, PulseError> {
        check_times(t)?;
        check_lengths(
            t.len(),
            [("acceleration", Some(acceleration)), ("crush", crush)],
        )?;
        let period = grid_period(t);
        let longest = period * (1.0 + EVEN_PERIODS);
        if t.windows(2).all(|w| w[1] - w[0] <= longest) {
            return Ok(Pulse {
                t: t.to_vec(),
                acceleration: acceleration.to_vec(),
                v0,
                crush: crush.map(<[f64]>::to_vec),
            });
        }
        let count = ((t[t.len() - 1] - t[0]) / period * (1.0 + 1e-12)).floor() as usize + 1;
        let grid: Vec<f64> = (0..count).map(|k| t[0] + k as f64 * period).collect();
        let (acceleration, crush) = match crush {
            Some(crush) => {
                let [a, c] = interpolate_all(t, [acceleration, crush], &grid);
                (a, Some(c))
            }
            None => (interpolate(t, acceleration, &grid), None),
        };
        Ok(Pulse {
            acceleration,
            crush,
            t: grid,
            v0,
        })
    }

    fn check(&self) -> Result<f64, PulseError> {
        check_times(&self.t)?;
        let first = self.t[1] - self.t[0];
        for k in 1..self.t.len() {
            let period = self.t[k] - self.t[k - 1];
            if (period - first).abs() > 1e-6 * first {
                return Err(PulseError::Unequal {
                    index: k,
                    period,
                    first,
                });
            }
        }
        let channels = [
            ("acceleration", Some(&self.acceleration[..])),
            ("crush", self.crush.as_deref()),
        ];
        check_lengths(self.t.len(), channels)?;
        for (what, values) in channels {
            if let Some(index) = values.and_then(|v| v.iter().position(|x| !x.is_finite())) {
                return Err(PulseError::NotFinite { what, index });
            }
        }
        Ok((self.t[self.t.len() - 1] - self.t[0]) / (self.t.len() - 1) as f64)
    }

    /// The CFC 60 and CFC 180 accelerations, each where the sample
    /// period `dt` allows its class, and the velocity: of the CFC 180
    /// acceleration (as J211 integrates), of the raw one where CFC 180
    /// does not apply.
    fn filtered(&self, dt: f64) -> Filtered {
        let raw = &self.acceleration;
        let (cfc60, cfc180) = match cfc_filter_classes(raw, dt, [60.0, 180.0]) {
            Ok([cfc60, cfc180]) => (Some(cfc60), Some(cfc180)),
            Err(_) => (cfc_filter(raw, dt, 60.0).ok(), None),
        };
        let velocity = integrate(&self.t, cfc180.as_deref().unwrap_or(raw), self.v0);
        Filtered {
            cfc60,
            cfc180,
            velocity,
        }
    }

    /// The metrics of the pulse's filtered acceleration alone, as
    /// [`Pulse::metrics`] has them, without those of its crush and its
    /// raw acceleration.
    pub fn filtered_metrics(&self) -> Result<FilteredMetrics, PulseError> {
        let dt = self.check()?;
        Ok(FilteredMetrics::of(
            &self.t,
            &self.acceleration,
            &self.filtered(dt),
        ))
    }

    /// The filter classes the metrics take that the pulse's sample rate
    /// cannot give, each with what the metrics do without it (empty when
    /// the rate gives both CFC 60 and CFC 180, or the pulse has too few
    /// samples to have a rate).
    pub fn filter_warnings(&self) -> Vec<Warning> {
        if self.t.len() < 2 {
            return Vec::new();
        }
        let needs = [
            (60.0, "the CFC 60 peak deceleration is not computed".into()),
            (
                180.0,
                "the velocity (time to zero velocity, rebound, OLC) and the ASI are those of the \
                 unfiltered acceleration"
                    .into(),
            ),
        ];
        cfc::filter_classes(grid_period(&self.t), &needs)
    }

    /// The metrics of the pulse.
    pub fn metrics(&self) -> Result<PulseMetrics, PulseError> {
        let dt = self.check()?;
        let g = STANDARD_GRAVITY;
        let t = &self.t;
        let filtered = self.filtered(dt);
        let velocity = &filtered.velocity;
        let integrated;
        let crush = match &self.crush {
            Some(c) => c,
            None => {
                integrated = integrate(t, velocity, 0.0);
                &integrated
            }
        };
        let (peak_index, max_crush) =
            crush
                .iter()
                .copied()
                .enumerate()
                .fold(
                    (0, f64::NEG_INFINITY),
                    |b, (k, c)| if c > b.1 { (k, c) } else { b },
                );
        let zero = (1..t.len())
            .find(|&k| velocity[k - 1] > 0.0 && velocity[k] <= 0.0)
            .map(|k| {
                let f = velocity[k - 1] / (velocity[k - 1] - velocity[k]);
                (k, t[k - 1] + f * (t[k] - t[k - 1]))
            });
        let rebound = zero.map(|(k, _)| velocity[k..].iter().fold(0.0f64, |m, &v| m.max(-v)));
        let FilteredMetrics {
            peak_deceleration_cfc60_g,
            olc,
            asi,
        } = FilteredMetrics::of(t, &self.acceleration, &filtered);
        let crushed = max_crush > 0.0;
        Ok(PulseMetrics {
            impact_velocity_mps: self.v0,
            max_dynamic_crush_m: crushed.then_some(max_crush),
            time_of_max_crush_s: crushed.then_some(t[peak_index]),
            time_to_zero_velocity_s: zero.map(|(_, t)| t),
            rebound_velocity_mps: rebound,
            peak_deceleration_g: peak_deceleration(&self.acceleration),
            peak_deceleration_cfc60_g,
            equivalent_square_wave_g: crushed.then(|| self.v0 * self.v0 / (2.0 * g * max_crush)),
            olc_g: olc.map(|o| o.deceleration / g),
            olc_t1_s: olc.map(|o| o.t1),
            olc_t2_s: olc.map(|o| o.t2),
            asi: asi.map(|(a, _)| a),
            asi_time_s: asi.map(|(_, t)| t),
        })
    }
}

/// The filtered signals of a pulse, each where its class applies, and the
/// velocity.
struct Filtered {
    cfc60: Option<Vec<f64>>,
    cfc180: Option<Vec<f64>>,
    velocity: Vec<f64>,
}

/// The metrics of a pulse's filtered acceleration (the part of
/// [`PulseMetrics`] that its crush does not enter).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FilteredMetrics {
    /// Largest deceleration of the CFC 60 filtered acceleration \[g\];
    /// `None` where the sample rate cannot give CFC 60.
    pub peak_deceleration_cfc60_g: Option<f64>,
    /// The occupant load criterion of the CFC 180 velocity (of the raw
    /// one where the sample rate cannot give CFC 180).
    pub olc: Option<Olc>,
    /// The acceleration severity index of the CFC 180 acceleration (of the
    /// raw one where the rate cannot give CFC 180; its 50 ms average is a
    /// low-pass of its own) and when it is reached \[s\].
    pub asi: Option<(f64, f64)>,
}

impl FilteredMetrics {
    fn of(t: &[f64], raw: &[f64], f: &Filtered) -> FilteredMetrics {
        let for_asi = f.cfc180.as_deref().unwrap_or(raw);
        FilteredMetrics {
            peak_deceleration_cfc60_g: f.cfc60.as_deref().map(peak_deceleration),
            olc: olc(t, &f.velocity),
            asi: asi(t, &[(for_asi, 12.0 * STANDARD_GRAVITY)]),
        }
    }
}

/// The period of the grid [`Pulse::resampled`] puts samples at times `t`
/// on: the smallest that occurs \[s\] (∞ for fewer than 2 samples).
pub fn grid_period(t: &[f64]) -> f64 {
    (t.windows(2))
        .map(|w| w[1] - w[0])
        .fold(f64::INFINITY, f64::min)
}

/// The largest deceleration of `a` \[g\]; 0 when it never decelerates.
fn peak_deceleration(a: &[f64]) -> f64 {
    a.iter().fold(0.0f64, |m, &x| m.max(-x)) / STANDARD_GRAVITY
}

fn check_times(t: &[f64]) -> Result<(), PulseError> {
    if t.len() < 3 {
        return Err(PulseError::TooShort(t.len()));
    }
    if let Some(index) = t.iter().position(|x| !x.is_finite()) {
        return Err(PulseError::NotFinite {
            what: "time",
            index,
        });
    }
    match (1..t.len()).find(|&k| t[k] <= t[k - 1]) {
        Some(index) => Err(PulseError::NotIncreasing { index }),
        None => Ok(()),
    }
}

/// Each channel given has one value per sample time.
fn check_lengths(
    samples: usize,
    channels: [(&'static str, Option<&[f64]>); 2],
) -> Result<(), PulseError> {
    for (what, values) in channels {
        if let Some(len) = values.map(<[f64]>::len).filter(|&len| len != samples) {
            return Err(PulseError::Length { what, len, samples });
        }
    }
    Ok(())
}

/// `y(x)` at `at` by linear interpolation (`x` increasing, `at` inside).
pub fn interpolate(x: &[f64], y: &[f64], at: &[f64]) -> Vec<f64> {
    let [y] = interpolate_all(x, [y], at);
    y
}

/// [`interpolate`] of several `ys` on the same `x`, finding each point's
/// interval and fraction once.
fn interpolate_all<const M: usize>(x: &[f64], ys: [&[f64]; M], at: &[f64]) -> [Vec<f64>; M] {
    let mut out = ys.map(|_| vec![0.0; at.len()]);
    let mut k = 0;
    for (j, &a) in at.iter().enumerate() {
        while k + 2 < x.len() && x[k + 1] < a {
            k += 1;
        }
        let f = ((a - x[k]) / (x[k + 1] - x[k])).clamp(0.0, 1.0);
        for (out, y) in out.iter_mut().zip(ys) {
            out[j] = y[k] + f * (y[k + 1] - y[k]);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    const G: f64 = STANDARD_GRAVITY;

    /// A 20 g square pulse from 56 km/h: stops in t = v0 / a after
    /// crushing v0² / (2 a); the equivalent square wave is the pulse itself.
    #[test]
    fn a_square_pulse_has_its_textbook_crush_and_stopping_time() {
        let (v0, a) = (15.5556, 20.0 * G);
        let stop = v0 / a;
        let t: Vec<f64> = (0..=1500).map(|k| k as f64 * 1e-4).collect();
        let acc: Vec<f64> = t.iter().map(|&t| if t < stop { -a } else { 0.0 }).collect();
        let pulse = Pulse {
            t,
            acceleration: acc,
            v0,
            crush: None,
        };
        let m = pulse.metrics().unwrap();
        let crush = v0 * v0 / (2.0 * a);
        // The CFC 180 filter rounds the corners of the pulse (a few 0.1 ms),
        // which barely moves the integrals.
        assert!(
            (m.max_dynamic_crush_m.unwrap() / crush - 1.0).abs() < 1e-3,
            "{m:?}"
        );
        assert!(
            (m.time_to_zero_velocity_s.unwrap() - stop).abs() < 5e-4,
            "{m:?}"
        );
        assert!(
            (m.equivalent_square_wave_g.unwrap() - 20.0).abs() < 0.02,
            "{m:?}"
        );
        assert!((m.peak_deceleration_g - 20.0).abs() < 1e-9);
        // CFC 60 overshoots a step by a few per cent (Butterworth) at most.
        assert!(
            (m.peak_deceleration_cfc60_g.unwrap() / 20.0 - 1.0).abs() < 0.05,
            "{m:?}"
        );
        // The filtered step rings below zero after the stop: a little
        // apparent rebound (0.014 m/s) that the raw pulse does not have.
        assert!(m.rebound_velocity_mps.unwrap() < 0.02, "{m:?}");
        // ASI averages the CFC 180 signal, whose overshoot at the corners
        // adds ≈ 0.06 %.
        assert!((m.asi.unwrap() / (20.0 / 12.0) - 1.0).abs() < 2e-3, "{m:?}");
        assert_eq!(pulse.filter_warnings(), []);
    }

    /// A 20 g square pulse from 56 km/h, 100 ms long, sampled every 1.5 ms
    /// (667 Hz, too slow for CFC 180, which needs 747.9 Hz) and every 5 ms
    /// (200 Hz, too slow for CFC 60 too): every metric that needs no
    /// filter is there, against the closed forms of the pulse — stop at
    /// v0/a, crush v0²/(2a), ESW 20 g, ASI 20/12 (the 50 ms average of a
    /// constant 20 g) — and each class that is missing has its warning.
    #[test]
    fn a_slow_sample_rate_keeps_every_metric_that_needs_no_filter() {
        let (v0, a) = (15.5556, 20.0 * G);
        let stop = v0 / a;
        for (dt, missing) in [(1.5e-3f64, &[180.0][..]), (5e-3, &[60.0, 180.0][..])] {
            let t: Vec<f64> = (0..=(0.15 / dt).round() as usize)
                .map(|k| k as f64 * dt)
                .collect();
            // Decelerating until 0.1 s, past the stop: the velocity
            // crosses zero at v0/a, where the crush peaks.
            let acc: Vec<f64> = t.iter().map(|&t| if t < 0.1 { -a } else { 0.0 }).collect();
            let pulse = Pulse {
                t,
                acceleration: acc,
                v0,
                crush: None,
            };
            let m = pulse.metrics().unwrap();
            let (crush, zero) = (
                m.max_dynamic_crush_m.unwrap(),
                m.time_to_zero_velocity_s.unwrap(),
            );
            assert!((zero - stop).abs() < dt, "{dt}: {m:?}");
            assert!(
                (crush / (v0 * v0 / (2.0 * a)) - 1.0).abs() < 0.02,
                "{dt}: {m:?}"
            );
            let esw = m.equivalent_square_wave_g.unwrap();
            assert!((esw - 20.0).abs() < 0.4, "{dt}: {m:?}");
            assert!(
                (m.asi.unwrap() / (20.0 / 12.0) - 1.0).abs() < 0.02,
                "{dt}: {m:?}"
            );
            assert!(m.olc_g.is_some(), "{dt}: {m:?}");
            assert_eq!(m.peak_deceleration_cfc60_g.is_some(), dt < 4e-3, "{m:?}");
            let warnings = pulse.filter_warnings();
            let classes: Vec<f64> = (warnings.iter())
                .map(|w| match w {
                    Warning::FilterClass { cfc, .. } => *cfc,
                    _ => panic!("{w}"),
                })
                .collect();
            assert_eq!(classes, missing);
        }
        let pulse = Pulse {
            t: (0..100).map(|k| k as f64 * 1.5e-3).collect(),
            acceleration: vec![0.0; 100],
            v0,
            crush: None,
        };
        let [w] = &pulse.filter_warnings()[..] else {
            panic!()
        };
        assert_eq!(w.kind(), "filter_class");
        assert!(
            w.message().starts_with(
                "CFC 180 needs a sample rate above 748 Hz (SAE J211-1: 2.0775·CFC below half the \
                 sample rate); samples every 1.5 ms give 667 Hz: the velocity"
            ),
            "{w}"
        );
    }

    #[test]
    fn unequal_and_unsorted_times_are_refused_and_resampling_fixes_the_first() {
        let t = [0.0, 1e-3, 2e-3, 3.5e-3];
        let a = [0.0, -1.0, -2.0, -3.0];
        let pulse = Pulse {
            t: t.to_vec(),
            acceleration: a.to_vec(),
            v0: 1.0,
            crush: None,
        };
        assert!(matches!(
            pulse.metrics(),
            Err(PulseError::Unequal { index: 3, .. })
        ));
        let r = Pulse::resampled(&t, &a, 1.0, None).unwrap();
        assert_eq!(r.t.len(), 4);
        assert!(
            (r.acceleration[3] + 2.0 + 2.0 / 3.0).abs() < 1e-12,
            "{:?}",
            r.acceleration
        );
        assert_eq!(
            Pulse::resampled(&[0.0, 2e-3, 1e-3], &a[..3], 1.0, None),
            Err(PulseError::NotIncreasing { index: 2 })
        );
    }

    /// Times `k·dt` in floating point differ from an even grid in their
    /// last bits: the samples stay as they are, not interpolated onto the
    /// grid of the smallest period (which would move every value a little).
    #[test]
    fn samples_at_multiples_of_the_period_are_taken_as_they_are() {
        let t: Vec<f64> = (0..=1500).map(|k| k as f64 * 1e-4).collect();
        let periods = t.windows(2).map(|w| w[1] - w[0]);
        let (shortest, longest) = periods.fold((f64::INFINITY, 0.0f64), |(lo, hi), p| {
            (lo.min(p), hi.max(p))
        });
        assert!(shortest < longest, "the grid is not even in floating point");
        let a: Vec<f64> = t.iter().map(|t| (t * 90.0).sin()).collect();
        let c: Vec<f64> = t.iter().map(|t| t * t).collect();
        let pulse = Pulse::resampled(&t, &a, 2.0, Some(&c)).unwrap();
        assert_eq!((pulse.t, pulse.acceleration), (t.clone(), a.clone()));
        assert_eq!(pulse.crush, Some(c));
        // A sample between them (an event's) makes them uneven: resampled.
        let mut uneven = t.clone();
        uneven.insert(3, 2.5e-4);
        let mut a_uneven = a.clone();
        a_uneven.insert(3, 7.0);
        let resampled = Pulse::resampled(&uneven, &a_uneven, 2.0, None).unwrap();
        assert_eq!(
            resampled.t.len(),
            (1.5e-1 / 0.5e-4 * (1.0 + 1e-12)) as usize + 1
        );
    }

    #[test]
    fn interpolating_two_columns_at_once_is_interpolating_each() {
        let x = [0.0, 1e-3, 1.7e-3, 3.5e-3, 4e-3];
        let a = [0.0, -1.0, -2.5, -3.0, 7.0];
        let c = [0.0, 0.1, 0.2, 0.35, 0.3];
        let at: Vec<f64> = (0..=9).map(|k| k as f64 * 4.5e-4).collect();
        let [ia, ic] = interpolate_all(&x, [&a, &c], &at);
        assert_eq!(ia, interpolate(&x, &a, &at));
        assert_eq!(ic, interpolate(&x, &c, &at));
        // Linear between the samples: 0.1 + (0.2 − 0.1)·(1.35 − 1)/0.7 at 1.35 ms.
        assert!((ic[3] - 0.15).abs() < 1e-12, "{}", ic[3]);
    }

    /// The filtered metrics alone are those of the whole set, with or
    /// without a crush channel.
    #[test]
    fn the_filtered_metrics_are_those_of_the_full_metrics() {
        let t: Vec<f64> = (0..=1500).map(|k| k as f64 * 1e-4).collect();
        let acc: Vec<f64> = (t.iter())
            .map(|&t| -30.0 * G * (std::f64::consts::PI * t / 0.08).sin().max(0.0))
            .collect();
        let crush: Vec<f64> = t.iter().map(|&t| 15.0 * t - 90.0 * t * t).collect();
        for crush in [None, Some(crush)] {
            let pulse = Pulse {
                t: t.clone(),
                acceleration: acc.clone(),
                v0: 15.5556,
                crush,
            };
            let all = pulse.metrics().unwrap();
            let f = pulse.filtered_metrics().unwrap();
            assert_eq!(f.peak_deceleration_cfc60_g, all.peak_deceleration_cfc60_g);
            assert_eq!(f.olc.map(|o| o.deceleration / G), all.olc_g);
            assert_eq!(f.olc.map(|o| (o.t1, o.t2)), all.olc_t1_s.zip(all.olc_t2_s));
            assert_eq!(f.asi, all.asi.zip(all.asi_time_s));
            assert!(f.olc.is_some() && f.asi.is_some(), "{f:?}");
        }
        let bad = Pulse {
            t: t.clone(),
            acceleration: acc.clone(),
            v0: 15.5556,
            crush: Some(vec![f64::NAN; t.len()]),
        };
        let refused = Err(PulseError::NotFinite {
            what: "crush",
            index: 0,
        });
        assert_eq!(bad.filtered_metrics(), refused);
    }

    /// A channel without one value per sample time is refused, by the
    /// checks of a pulse and by its resampling (even or not), instead of
    /// read out of its bounds.
    #[test]
    fn a_channel_of_another_length_than_the_times_is_refused() {
        let even = [0.0, 1e-3, 2e-3, 3e-3];
        let uneven = [0.0, 1e-3, 1.5e-3, 3e-3];
        let short = [-1.0, -2.0, -3.0];
        for t in [even, uneven] {
            assert_eq!(
                Pulse::resampled(&t, &short, 1.0, None),
                Err(PulseError::Length {
                    what: "acceleration",
                    len: 3,
                    samples: 4
                })
            );
            let crush = [0.0; 5];
            let refused = Pulse::resampled(&t, &[0.0; 4], 1.0, Some(&crush));
            let expected = PulseError::Length {
                what: "crush",
                len: 5,
                samples: 4,
            };
            assert_eq!(refused, Err(expected.clone()));
            assert_eq!(
                expected.to_string(),
                "crush has 5 values for 4 sample times"
            );
        }
        let pulse = Pulse {
            t: even.to_vec(),
            acceleration: short.to_vec(),
            v0: 1.0,
            crush: None,
        };
        let refused = PulseError::Length {
            what: "acceleration",
            len: 3,
            samples: 4,
        };
        assert_eq!(pulse.metrics(), Err(refused.clone()));
        assert_eq!(pulse.filtered_metrics(), Err(refused));
    }
}
