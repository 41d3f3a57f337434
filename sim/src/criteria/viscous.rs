//! The viscous criterion VC (Lau and Viano; ECE R94 Annex 4 and Euro NCAP
//! TB 021, computed as SAE J1727 prescribes).

/// The peak of VC and when it is reached.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Viscous {
    /// max of `VC(t)` \[m/s\].
    pub value: f64,
    /// Its time \[s\].
    pub time: f64,
}

/// `VC(t) = scale · V(t) · C(t)` of a chest deflection `d` \[m\]
/// (compression positive or negative: its sign is the channel's
/// convention, and the magnitude of VC is rated) sampled every `dt` from
/// `t0`, with `C = d / depth` and `V = ḋ` by the central difference of
/// J1727, `(8 (d[i+1] − d[i−1]) − (d[i+2] − d[i−2])) / 12 dt`. Its peak
/// magnitude; `None` for fewer than five samples, a bad period or a
/// non-finite sample. Filter the deflection (CFC 180) first.
pub fn viscous_criterion(d: &[f64], t0: f64, dt: f64, scale: f64, depth: f64) -> Option<Viscous> {
    if d.len() < 5 || !(dt > 0.0 && dt.is_finite()) || d.iter().any(|x| !x.is_finite()) {
        return None;
    }
    let mut best = Viscous {
        value: 0.0,
        time: t0,
    };
    for i in 2..d.len() - 2 {
        let rate = (8.0 * (d[i + 1] - d[i - 1]) - (d[i + 2] - d[i - 2])) / (12.0 * dt);
        let vc = (scale * rate * d[i] / depth).abs();
        if vc > best.value {
            best = Viscous {
                value: vc,
                time: t0 + i as f64 * dt,
            };
        }
    }
    Some(best)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vc_of_a_sinusoidal_deflection_matches_the_closed_form() {
        // d = D sin ωt: V·C = D² ω sin 2ωt / (2 depth), peak D² ω / (2 depth)
        // at ωt = π/4.
        let (amplitude, omega, dt) = (0.040, 2.0 * std::f64::consts::PI * 10.0, 1e-4);
        let d: Vec<f64> = (0..=250)
            .map(|k| -amplitude * (omega * k as f64 * dt).sin())
            .collect();
        let vc = viscous_criterion(&d, 0.0, dt, 1.3, 0.229).unwrap();
        let exact = 1.3 * amplitude * amplitude * omega / (2.0 * 0.229);
        assert!(
            (vc.value - exact).abs() < 1e-6 * exact,
            "{} against {exact}",
            vc.value
        );
        let peak_time = std::f64::consts::FRAC_PI_4 / omega;
        assert!((vc.time - peak_time).abs() <= dt);
    }

    #[test]
    fn vc_needs_five_samples() {
        assert_eq!(viscous_criterion(&[0.0; 4], 0.0, 1e-4, 1.3, 0.229), None);
    }
}
