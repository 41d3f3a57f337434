//! The 3 ms clip of FMVSS 208 (S6.3, chest; also read for the head): the
//! highest level the magnitude of an acceleration stays at or above for a
//! cumulative 3 ms. One definition, the pulse's ([`crate::pulse`]), which a
//! channel's `clip3ms_g` in the summary reads too.

pub use crate::pulse::occupant::{CLIP_DURATION, clip};

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn clip_of_a_half_sine_matches_the_closed_form() {
        // A sin(πt/T) is at or above L for T − (2T/π)·asin(L/A); that is
        // 3 ms at L = A cos(π·3 ms / 2T).
        let (amplitude, duration, dt): (f64, f64, f64) = (50.0, 0.060, 1e-4);
        let n = (duration / dt).round() as usize;
        let a: Vec<f64> = (0..=n)
            .map(|k| -amplitude * (PI * k as f64 * dt / duration).sin())
            .collect();
        let exact = amplitude * (PI * CLIP_DURATION / (2.0 * duration)).cos();
        let got = clip(&a, dt, CLIP_DURATION).unwrap();
        assert!((got - exact).abs() < 1e-4, "{got} against {exact}");
    }

    #[test]
    fn clip_of_a_square_pulse_longer_than_3_ms_is_its_level() {
        let a: Vec<f64> = (0..200)
            .map(|k| if (50..100).contains(&k) { 40.0 } else { 5.0 })
            .collect();
        assert!((clip(&a, 1e-4, CLIP_DURATION).unwrap() - 40.0).abs() < 1e-9);
    }

    #[test]
    fn clip_counts_separate_exceedances_together() {
        // Two 2 ms plateaus at 30 g: 4 ms in all above 30 g, so the clip is
        // 30 g although neither lasts 3 ms.
        let a: Vec<f64> = (0..400)
            .map(|k| {
                if (100..=120).contains(&k) || (300..=320).contains(&k) {
                    30.0
                } else {
                    0.0
                }
            })
            .collect();
        assert!((clip(&a, 1e-4, CLIP_DURATION).unwrap() - 30.0).abs() < 1e-9);
    }

    #[test]
    fn clip_needs_a_record_of_3_ms() {
        assert_eq!(clip(&[1.0; 30], 1e-4, CLIP_DURATION), None);
        assert!(clip(&[1.0; 31], 1e-4, CLIP_DURATION).is_some());
        assert_eq!(clip(&[1.0, f64::NAN, 1.0, 1.0], 0.002, CLIP_DURATION), None);
    }
}
