//! Occupant and vehicle injury criteria, each with its standard's filter
//! class and definition: HIC15 and HIC36, the head and chest 3 ms clips,
//! chest deflection and the viscous criterion, Nij and the upper neck loads,
//! femur force ([`occupant`]); the vehicle's OLC, ASI and ESW come from the
//! pulse ([`crate::pulse`]) and THIV/PHD from [`roadside`].
//!
//! [`Criterion`] is the one list of the criteria: its key in JSON, its unit,
//! its standard and its filter class; [`limits`] rates a value against
//! FMVSS 208 and Euro NCAP. The functions of each criterion take samples in
//! SI units (accelerations in g where the criterion is defined in g), evenly
//! spaced, already filtered; [`occupant::rate`] picks the channels, filters
//! them as the standard asks and calls them.

mod clip;
pub mod codes;
mod dummy;
mod hic;
pub mod limits;
mod neck;
pub mod occupant;
pub mod roadside;
mod viscous;

pub use clip::{CLIP_DURATION, clip};
pub use dummy::{DUMMIES, Dummy, NijIntercepts};
pub use hic::{HIC15_WINDOW, HIC36_WINDOW, Hic, hic};
pub use neck::{Nij, NijMode, nij, occipital_moment};
pub use occupant::{Body, Criteria, Measure, Measured, Rated, rate};
pub use viscous::{Viscous, viscous_criterion};

/// A criterion: what `summary.json`, `lpm metrics --format json` and the
/// report call it, its unit and where it is defined.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Criterion {
    /// HIC over at most 15 ms.
    Hic15,
    /// HIC over at most 36 ms.
    Hic36,
    /// The head's resultant 3 ms clip.
    Head3ms,
    /// The chest's resultant 3 ms clip.
    Chest3ms,
    /// The largest chest compression.
    ChestDeflection,
    /// The viscous criterion's peak.
    Vc,
    /// The neck injury criterion's peak.
    Nij,
    /// The largest upper neck tension.
    NeckTension,
    /// The largest upper neck compression.
    NeckCompression,
    /// The largest upper neck shear, either way.
    NeckShear,
    /// The largest flexion moment at the occipital condyle.
    NeckFlexion,
    /// The largest extension moment at the occipital condyle.
    NeckExtension,
    /// The largest femur axial compression, of either femur.
    FemurMax,
    /// The vehicle's occupant load criterion.
    Olc,
    /// The vehicle's acceleration severity index.
    Asi,
    /// The vehicle's equivalent square wave.
    Esw,
    /// The theoretical head impact velocity (longitudinal).
    Thiv,
    /// The post-impact head deceleration (longitudinal).
    Phd,
}

impl Criterion {
    /// Every criterion, in the order the outputs list them.
    pub const ALL: [Criterion; 18] = [
        Criterion::Hic15,
        Criterion::Hic36,
        Criterion::Head3ms,
        Criterion::Chest3ms,
        Criterion::ChestDeflection,
        Criterion::Vc,
        Criterion::Nij,
        Criterion::NeckTension,
        Criterion::NeckCompression,
        Criterion::NeckShear,
        Criterion::NeckFlexion,
        Criterion::NeckExtension,
        Criterion::FemurMax,
        Criterion::Olc,
        Criterion::Asi,
        Criterion::Esw,
        Criterion::Thiv,
        Criterion::Phd,
    ];

    /// Its key in JSON, with the unit of its value in the name.
    pub fn key(self) -> &'static str {
        match self {
            Criterion::Hic15 => "hic15",
            Criterion::Hic36 => "hic36",
            Criterion::Head3ms => "head_3ms_g",
            Criterion::Chest3ms => "chest_3ms_g",
            Criterion::ChestDeflection => "chest_deflection_mm",
            Criterion::Vc => "vc_mps",
            Criterion::Nij => "nij",
            Criterion::NeckTension => "neck_tension_kn",
            Criterion::NeckCompression => "neck_compression_kn",
            Criterion::NeckShear => "neck_shear_kn",
            Criterion::NeckFlexion => "neck_flexion_nm",
            Criterion::NeckExtension => "neck_extension_nm",
            Criterion::FemurMax => "femur_max_kn",
            Criterion::Olc => "olc_g",
            Criterion::Asi => "asi",
            Criterion::Esw => "esw_g",
            Criterion::Thiv => "thiv_kmh",
            Criterion::Phd => "phd_g",
        }
    }

    /// Its name in text and the report.
    pub fn label(self) -> &'static str {
        match self {
            Criterion::Hic15 => "HIC15",
            Criterion::Hic36 => "HIC36",
            Criterion::Head3ms => "head 3 ms clip",
            Criterion::Chest3ms => "chest 3 ms clip",
            Criterion::ChestDeflection => "chest deflection",
            Criterion::Vc => "VC",
            Criterion::Nij => "Nij",
            Criterion::NeckTension => "neck tension",
            Criterion::NeckCompression => "neck compression",
            Criterion::NeckShear => "neck shear",
            Criterion::NeckFlexion => "neck flexion",
            Criterion::NeckExtension => "neck extension",
            Criterion::FemurMax => "femur compression",
            Criterion::Olc => "OLC",
            Criterion::Asi => "ASI",
            Criterion::Esw => "ESW",
            Criterion::Thiv => "THIV",
            Criterion::Phd => "PHD",
        }
    }

    /// The unit of its value (`""` for a pure number).
    pub fn unit(self) -> &'static str {
        match self {
            Criterion::Hic15 | Criterion::Hic36 | Criterion::Nij | Criterion::Asi => "",
            Criterion::Head3ms
            | Criterion::Chest3ms
            | Criterion::Olc
            | Criterion::Esw
            | Criterion::Phd => "g",
            Criterion::ChestDeflection => "mm",
            Criterion::Vc => "m/s",
            Criterion::NeckTension
            | Criterion::NeckCompression
            | Criterion::NeckShear
            | Criterion::FemurMax => "kN",
            Criterion::Thiv => "km/h",
            Criterion::NeckFlexion | Criterion::NeckExtension => "N·m",
        }
    }

    /// The SAE J211-1 class its channels are filtered at (`None` for ESW,
    /// which reads the crush).
    pub fn filter_class(self) -> Option<f64> {
        match self {
            Criterion::Hic15 | Criterion::Hic36 | Criterion::Head3ms => Some(1000.0),
            Criterion::Nij
            | Criterion::NeckTension
            | Criterion::NeckCompression
            | Criterion::NeckShear
            | Criterion::NeckFlexion
            | Criterion::NeckExtension
            | Criterion::FemurMax => Some(600.0),
            Criterion::Chest3ms
            | Criterion::ChestDeflection
            | Criterion::Vc
            | Criterion::Olc
            | Criterion::Asi
            | Criterion::Thiv
            | Criterion::Phd => Some(180.0),
            Criterion::Esw => None,
        }
    }

    /// The criterion whose JSON key is `key`.
    pub fn of_key(key: &str) -> Option<Criterion> {
        Criterion::ALL.into_iter().find(|c| c.key() == key)
    }

    /// Where it is defined.
    pub fn standard(self) -> &'static str {
        match self {
            Criterion::Hic15 => "FMVSS 208 S6.2 (49 CFR 571.208)",
            Criterion::Hic36 => "FMVSS 208 (1998 edition), ECE R94",
            Criterion::Head3ms => "Euro NCAP frontal protocol (cumulative, as FMVSS 208 S6.3)",
            Criterion::Chest3ms => "FMVSS 208 S6.3",
            Criterion::ChestDeflection => "FMVSS 208 S6.4, ECE R94",
            Criterion::Vc => "ECE R94 Annex 4, SAE J1727",
            Criterion::Nij => "FMVSS 208 S6.6",
            Criterion::NeckTension | Criterion::NeckCompression => "FMVSS 208 S6.6(b)",
            Criterion::NeckShear => "Euro NCAP frontal protocol, ECE R94",
            Criterion::NeckFlexion | Criterion::NeckExtension => {
                "Euro NCAP frontal protocol (moment at the occipital condyle)"
            }
            Criterion::FemurMax => "FMVSS 208 S6.5",
            Criterion::Olc => "Euro NCAP (Kübler et al.)",
            Criterion::Asi | Criterion::Thiv | Criterion::Phd => "EN 1317-1:2010",
            Criterion::Esw => "v0² / (2 g C)",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_book_documents_every_criterion_and_every_limit() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../docs/book/reference/criteria.md"
        );
        let book = std::fs::read_to_string(path).unwrap();
        for c in Criterion::ALL {
            assert!(
                book.contains(&format!("`{}`", c.key())),
                "{} is not in {path}",
                c.key()
            );
        }
        let limits_table = &book[book.find("## Limits").unwrap()..];
        for protocol in limits::Protocol::ALL {
            for dummy in DUMMIES {
                for limit in limits::limits(protocol, dummy) {
                    let label = limit.criterion.label();
                    let row = (limits_table.lines())
                        .find(|l| l.starts_with(&format!("| {label} |")))
                        .unwrap_or_else(|| panic!("no row for {label} in the limits table"));
                    let shown = match limit.higher {
                        Some(higher) => format!("{higher}–{}", limit.lower),
                        None => format!("{}", limit.lower),
                    };
                    assert!(row.contains(&shown), "{label}: {shown} is not in `{row}`");
                }
            }
        }
    }
}
