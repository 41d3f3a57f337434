//! The theoretical head impact velocity (THIV) and post-impact head
//! deceleration (PHD) of EN 1317-1:2010, longitudinal only: a lumped model
//! moving along x has no lateral motion or yaw, so the theoretical head
//! reaches the front surface (0.6 m ahead) and never a side.

use crate::pulse::{STANDARD_GRAVITY, integrate};

/// The free travel of the theoretical head to the front surface \[m\].
pub const THIV_FORWARD_TRAVEL: f64 = 0.6;
/// The averaging window of PHD \[s\].
pub const PHD_WINDOW: f64 = 0.010;

/// THIV and PHD of a vehicle pulse.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeadImpact {
    /// The head's velocity relative to the vehicle when it has travelled
    /// [`THIV_FORWARD_TRAVEL`] \[m/s\].
    pub thiv: f64,
    /// When that is \[s\].
    pub flight_time: f64,
    /// The largest 10 ms average of the vehicle's deceleration after it \[g\];
    /// `None` when the record ends within 10 ms of the flight time.
    pub phd: Option<f64>,
}

/// THIV and PHD of the vehicle's velocity `v` and acceleration `a`
/// (forward positive, CFC 180) sampled at `t`: the head keeps `v(t0)`, its
/// travel relative to the vehicle is `v0 (t − t0) − (s(t) − s(t0))`.
/// `None` when the head never travels 0.6 m within the record.
pub fn head_impact(t: &[f64], v: &[f64], a: &[f64]) -> Option<HeadImpact> {
    if t.len() < 2 || v.len() != t.len() || a.len() != t.len() {
        return None;
    }
    let s = integrate(t, v, 0.0);
    let (t0, v0) = (t[0], v[0]);
    let travel = |k: usize| v0 * (t[k] - t0) - s[k];
    let k = (1..t.len()).find(|&k| travel(k) >= THIV_FORWARD_TRAVEL)?;
    let f = (THIV_FORWARD_TRAVEL - travel(k - 1)) / (travel(k) - travel(k - 1));
    let flight_time = t[k - 1] + f * (t[k] - t[k - 1]);
    let vehicle = v[k - 1] + f * (v[k] - v[k - 1]);
    let phd = average_peak(&t[k..], &a[k..], PHD_WINDOW).map(|p| p / STANDARD_GRAVITY);
    Some(HeadImpact {
        thiv: v0 - vehicle,
        flight_time,
        phd,
    })
}

/// The largest magnitude of the `window`-long moving average of `a` over
/// the samples at `t` (trapezoidal).
fn average_peak(t: &[f64], a: &[f64], window: f64) -> Option<f64> {
    let integral = integrate(t, a, 0.0);
    let mut best: Option<f64> = None;
    let mut i = 0;
    for j in 0..t.len() {
        while t[j] - t[i] > window * (1.0 + 1e-9) {
            i += 1;
        }
        if t[j] - t[i] < window * (1.0 - 1e-9) {
            continue;
        }
        let mean = ((integral[j] - integral[i]) / (t[j] - t[i])).abs();
        best = Some(best.map_or(mean, |b: f64| b.max(mean)));
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thiv_of_a_constant_deceleration_matches_the_closed_form() {
        // a = −10 g from v0 = 20 m/s: the head travels ½ a t² = 0.6 m at
        // t = √(1.2 / a), hitting at a·t; PHD is the 10 g itself.
        let decel = 10.0 * STANDARD_GRAVITY;
        let dt = 1e-5;
        let t: Vec<f64> = (0..=20_000).map(|k| k as f64 * dt).collect();
        let v: Vec<f64> = t.iter().map(|t| 20.0 - decel * t).collect();
        let a = vec![-decel; t.len()];
        let hit = head_impact(&t, &v, &a).unwrap();
        let flight = (2.0 * THIV_FORWARD_TRAVEL / decel).sqrt();
        assert!((hit.flight_time - flight).abs() < 1e-6);
        assert!((hit.thiv - decel * flight).abs() < 1e-4);
        assert!((hit.phd.unwrap() - 10.0).abs() < 1e-9);
    }

    #[test]
    fn no_thiv_when_the_head_stops_short_of_the_surface() {
        let t: Vec<f64> = (0..100).map(|k| k as f64 * 1e-3).collect();
        let v = vec![10.0; 100];
        assert_eq!(head_impact(&t, &v, &[0.0; 100]), None);
    }
}
