//! The anthropomorphic test devices the criteria know, with the constants
//! each criterion takes for them: the ISO-MME code of the dummy (fine
//! location 3 of a channel code), the viscous criterion's scale and
//! deformation constants, and the neck's Nij intercepts and load-cell
//! offset.

use std::fmt;

/// A crash test dummy.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Dummy {
    /// Hybrid III 50th percentile male (`H3`).
    Hybrid3Male50,
    /// Hybrid III 5th percentile female (`HF`).
    Hybrid3Female5,
    /// Hybrid III 95th percentile male (`HM`).
    Hybrid3Male95,
}

/// The distance from the upper neck load cell's axis to the occipital
/// condyle of the Hybrid III family \[m\] (0.7 in: SAE J1733), the same for
/// the 5th, 50th and 95th, so also used where no dummy is named.
pub const NECK_OFFSET: f64 = 0.01778;

/// Every dummy, in the order of the tables below.
pub const DUMMIES: [Dummy; 3] = [
    Dummy::Hybrid3Male50,
    Dummy::Hybrid3Female5,
    Dummy::Hybrid3Male95,
];

/// The intercepts of Nij (FMVSS 208 S6.6, in-position): the axial force and
/// the flexion/extension moment at the occipital condyle that each alone make
/// Nij = 1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NijIntercepts {
    /// Tension \[N\].
    pub tension: f64,
    /// Compression \[N\], a magnitude.
    pub compression: f64,
    /// Flexion \[N·m\].
    pub flexion: f64,
    /// Extension \[N·m\], a magnitude.
    pub extension: f64,
}

impl Dummy {
    /// The dummy's code in fine location 3 of an ISO-MME channel code.
    pub fn iso_code(self) -> &'static str {
        match self {
            Dummy::Hybrid3Male50 => "H3",
            Dummy::Hybrid3Female5 => "HF",
            Dummy::Hybrid3Male95 => "HM",
        }
    }

    /// The dummy of an ISO-MME code (`"H3"`), or of the names a scenario
    /// may give it (`"hybrid3_50m"`, `"hybrid3_05f"`, `"hybrid3_95m"`).
    pub fn parse(name: &str) -> Option<Dummy> {
        DUMMIES
            .into_iter()
            .find(|d| d.iso_code() == name || d.name() == name)
    }

    /// The dummy's name in scenarios and reports.
    pub fn name(self) -> &'static str {
        match self {
            Dummy::Hybrid3Male50 => "hybrid3_50m",
            Dummy::Hybrid3Female5 => "hybrid3_05f",
            Dummy::Hybrid3Male95 => "hybrid3_95m",
        }
    }

    /// The viscous criterion's scale factor and chest deformation constant
    /// (the half-depth the deflection is divided by) \[m\], as Euro NCAP
    /// TB 021 gives them for the Hybrid III family: 1.3 and 229 mm (50th),
    /// 187 mm (5th), 254 mm (95th).
    pub fn viscous_constants(self) -> (f64, f64) {
        match self {
            Dummy::Hybrid3Male50 => (1.3, 0.229),
            Dummy::Hybrid3Female5 => (1.3, 0.187),
            Dummy::Hybrid3Male95 => (1.3, 0.254),
        }
    }

    /// The in-position Nij intercepts of FMVSS 208 (49 CFR 571.208 S6.6(a)
    /// for the 50th male, S15.3.6 for the 5th female); none for the 95th
    /// male, which the standard does not rate.
    pub fn nij_intercepts(self) -> Option<NijIntercepts> {
        match self {
            Dummy::Hybrid3Male50 => Some(NijIntercepts {
                tension: 6806.0,
                compression: 6160.0,
                flexion: 310.0,
                extension: 135.0,
            }),
            Dummy::Hybrid3Female5 => Some(NijIntercepts {
                tension: 4287.0,
                compression: 3880.0,
                flexion: 155.0,
                extension: 67.0,
            }),
            Dummy::Hybrid3Male95 => None,
        }
    }

    /// The distance from the upper neck load cell's axis to the occipital
    /// condyle \[m\], with which `M_oc = M_y − D·F_x`: [`NECK_OFFSET`] for
    /// every dummy here.
    pub fn neck_offset(self) -> f64 {
        NECK_OFFSET
    }
}

impl fmt::Display for Dummy {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}
