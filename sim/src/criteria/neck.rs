//! Neck criteria of FMVSS 208: Nij (S6.6) and the peak axial and shear
//! forces and moments of the upper neck load cell.

use super::dummy::NijIntercepts;

/// Which of the four combinations of Nij rates highest.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NijMode {
    /// Tension and flexion (`Ntf`).
    TensionFlexion,
    /// Tension and extension (`Nte`).
    TensionExtension,
    /// Compression and flexion (`Ncf`).
    CompressionFlexion,
    /// Compression and extension (`Nce`).
    CompressionExtension,
}

impl NijMode {
    /// The name FMVSS 208 gives it (`"Ntf"`, …).
    pub fn name(self) -> &'static str {
        match self {
            NijMode::TensionFlexion => "Ntf",
            NijMode::TensionExtension => "Nte",
            NijMode::CompressionFlexion => "Ncf",
            NijMode::CompressionExtension => "Nce",
        }
    }
}

/// The peak of Nij.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Nij {
    /// max over time of `|Fz|/Fzc + |My|/Myc` \[-\].
    pub value: f64,
    /// The combination it is reached in.
    pub mode: NijMode,
    /// Its time \[s\].
    pub time: f64,
}

/// The occipital condyle moment `M_oc = M_y − D · F_x` from the upper neck
/// load cell's moment `my` \[N·m\] and shear `fx` \[N\], `D` the dummy's
/// offset (`Dummy::neck_offset`).
pub fn occipital_moment(my: &[f64], fx: &[f64], offset: f64) -> Vec<f64> {
    my.iter().zip(fx).map(|(m, f)| m - offset * f).collect()
}

/// Nij of the axial force `fz` \[N\] (tension positive) and the occipital
/// moment `moc` \[N·m\] (flexion positive), sampled together every `dt` from
/// `t0`: at each sample the combination the signs select, each load over its
/// intercept. `None` for no samples, records of different lengths or a
/// non-finite sample. Filter both at CFC 600 first (S6.6(a)).
pub fn nij(fz: &[f64], moc: &[f64], t0: f64, dt: f64, intercepts: &NijIntercepts) -> Option<Nij> {
    if fz.is_empty() || fz.len() != moc.len() || fz.iter().chain(moc).any(|x| !x.is_finite()) {
        return None;
    }
    let mut best: Option<Nij> = None;
    for (k, (&f, &m)) in fz.iter().zip(moc).enumerate() {
        let (force, mode_tension) = if f >= 0.0 {
            (f / intercepts.tension, true)
        } else {
            (-f / intercepts.compression, false)
        };
        let (moment, flexion) = if m >= 0.0 {
            (m / intercepts.flexion, true)
        } else {
            (-m / intercepts.extension, false)
        };
        let mode = match (mode_tension, flexion) {
            (true, true) => NijMode::TensionFlexion,
            (true, false) => NijMode::TensionExtension,
            (false, true) => NijMode::CompressionFlexion,
            (false, false) => NijMode::CompressionExtension,
        };
        let value = force + moment;
        if best.is_none_or(|b| value > b.value) {
            best = Some(Nij {
                value,
                mode,
                time: t0 + k as f64 * dt,
            });
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::criteria::Dummy;

    #[test]
    fn nij_is_one_at_each_intercept_alone() {
        let i = Dummy::Hybrid3Male50.nij_intercepts().unwrap();
        for (fz, m, mode) in [
            (i.tension, 0.0, NijMode::TensionFlexion),
            (-i.compression, 0.0, NijMode::CompressionFlexion),
            (0.0, i.flexion, NijMode::TensionFlexion),
            (0.0, -i.extension, NijMode::TensionExtension),
        ] {
            let n = nij(&[0.0, fz, 0.0], &[0.0, m, 0.0], 0.0, 1e-4, &i).unwrap();
            assert!((n.value - 1.0).abs() < 1e-12);
            assert_eq!((n.mode, n.time), (mode, 1e-4));
        }
    }

    #[test]
    fn nij_adds_the_two_ratios_of_one_combination() {
        // Half the tension intercept with half the extension intercept:
        // Nte = 0.5 + 0.5.
        let i = Dummy::Hybrid3Female5.nij_intercepts().unwrap();
        let n = nij(&[0.5 * 4287.0], &[-0.5 * 67.0], 0.0, 1e-4, &i).unwrap();
        assert!((n.value - 1.0).abs() < 1e-12);
        assert_eq!(n.mode.name(), "Nte");
    }

    #[test]
    fn occipital_moment_subtracts_the_shear_lever() {
        // 1000 N of shear at 17.78 mm: 17.78 N·m less flexion.
        let moc = occipital_moment(&[50.0], &[1000.0], 0.01778);
        assert!((moc[0] - (50.0 - 17.78)).abs() < 1e-12);
    }
}
