//! The limits criteria are judged against: FMVSS 208 (pass or fail) and
//! Euro NCAP's frontal full-width test (a sliding scale of 0–4 points between
//! its higher and lower performance limits).

use super::{Criterion, Dummy};

/// A rating protocol.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Protocol {
    /// FMVSS 208 (49 CFR 571.208), the injury criteria of S6 and S15.
    Fmvss208,
    /// Euro NCAP Assessment Protocol – Adult Occupant Protection v9.3
    /// (2023), full-width rigid barrier test at 50 km/h (Hybrid III 5th
    /// female).
    EuroNcapFullWidth,
}

impl Protocol {
    /// Every protocol.
    pub const ALL: [Protocol; 2] = [Protocol::Fmvss208, Protocol::EuroNcapFullWidth];

    /// Its name in the report.
    pub fn name(self) -> &'static str {
        match self {
            Protocol::Fmvss208 => "FMVSS 208",
            Protocol::EuroNcapFullWidth => "Euro NCAP AOP v9.3, full width",
        }
    }
}

/// One criterion's limits in a protocol, in the criterion's unit, rated on
/// magnitudes (a compression of 40 mm against a limit of 63 mm).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limit {
    /// The protocol.
    pub protocol: Protocol,
    /// The criterion.
    pub criterion: Criterion,
    /// Euro NCAP's higher performance limit (full points at or below it);
    /// `None` for a pass/fail limit.
    pub higher: Option<f64>,
    /// The pass limit (FMVSS 208) or the lower performance limit (Euro
    /// NCAP: no points at or above it).
    pub lower: f64,
}

/// How a value fares against a limit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Verdict {
    /// At or below a pass/fail limit.
    Pass,
    /// Above it.
    Fail,
    /// Euro NCAP points, 0 to 4, linear between the two limits.
    Points(f64),
}

impl Limit {
    /// The verdict on `value`.
    pub fn judge(&self, value: f64) -> Verdict {
        let value = value.abs();
        match self.higher {
            None if value <= self.lower => Verdict::Pass,
            None => Verdict::Fail,
            Some(higher) => {
                let share = (self.lower - value) / (self.lower - higher);
                Verdict::Points(4.0 * share.clamp(0.0, 1.0))
            }
        }
    }
}

/// The limits of `protocol` for `dummy` (none where the protocol does not
/// rate that dummy). Values as the protocols state them, tabulated from the
/// regulation and the protocol and cross-checked with pyisomme's FMVSS 208
/// and Euro NCAP 50 km/h report definitions.
pub fn limits(protocol: Protocol, dummy: Dummy) -> Vec<Limit> {
    let pass = |criterion, lower| Limit {
        protocol,
        criterion,
        higher: None,
        lower,
    };
    let sliding = |criterion, higher, lower| Limit {
        protocol,
        criterion,
        higher: Some(higher),
        lower,
    };
    use Criterion as C;
    match (protocol, dummy) {
        (Protocol::Fmvss208, Dummy::Hybrid3Male50) => vec![
            pass(C::Hic15, 700.0),
            pass(C::Chest3ms, 60.0),
            pass(C::ChestDeflection, 63.0),
            pass(C::Nij, 1.0),
            pass(C::NeckTension, 4.17),
            pass(C::NeckCompression, 4.0),
            pass(C::FemurMax, 10.008),
        ],
        (Protocol::Fmvss208, Dummy::Hybrid3Female5) => vec![
            pass(C::Hic15, 700.0),
            pass(C::Chest3ms, 60.0),
            pass(C::ChestDeflection, 52.0),
            pass(C::Nij, 1.0),
            pass(C::NeckTension, 2.62),
            pass(C::NeckCompression, 2.52),
            pass(C::FemurMax, 6.805),
        ],
        (Protocol::EuroNcapFullWidth, Dummy::Hybrid3Female5) => vec![
            sliding(C::Hic15, 500.0, 700.0),
            sliding(C::Head3ms, 72.0, 80.0),
            sliding(C::NeckTension, 1.7, 2.62),
            sliding(C::NeckShear, 1.2, 1.95),
            sliding(C::NeckExtension, 36.0, 49.0),
            sliding(C::ChestDeflection, 18.0, 34.0),
            sliding(C::Vc, 0.5, 1.0),
            sliding(C::FemurMax, 2.6, 6.2),
        ],
        _ => Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pass_limit_passes_at_the_limit_and_fails_above() {
        let limit = limits(Protocol::Fmvss208, Dummy::Hybrid3Male50)[0];
        assert_eq!(limit.criterion, Criterion::Hic15);
        assert_eq!(limit.judge(700.0), Verdict::Pass);
        assert_eq!(limit.judge(700.1), Verdict::Fail);
    }

    #[test]
    fn euro_ncap_points_slide_between_the_two_limits() {
        let hic = limits(Protocol::EuroNcapFullWidth, Dummy::Hybrid3Female5)[0];
        assert_eq!(hic.judge(450.0), Verdict::Points(4.0));
        assert_eq!(hic.judge(600.0), Verdict::Points(2.0));
        assert_eq!(hic.judge(750.0), Verdict::Points(0.0));
        // A compression signed negative is rated on its magnitude.
        let chest = (limits(Protocol::EuroNcapFullWidth, Dummy::Hybrid3Female5).into_iter())
            .find(|l| l.criterion == Criterion::ChestDeflection)
            .unwrap();
        assert_eq!(chest.judge(-26.0), Verdict::Points(2.0));
    }

    #[test]
    fn a_protocol_rates_only_its_dummies() {
        assert!(limits(Protocol::EuroNcapFullWidth, Dummy::Hybrid3Male50).is_empty());
        assert!(limits(Protocol::Fmvss208, Dummy::Hybrid3Male95).is_empty());
    }
}
