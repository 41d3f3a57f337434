//! The grade of an overall rating: ISO/TS 18571's four classes.

use std::fmt;

/// The overall rating above which a comparison is excellent: 0.94.
pub const EXCELLENT_ABOVE: f64 = 0.94;
/// The overall rating above which a comparison is good: 0.80.
pub const GOOD_ABOVE: f64 = 0.8;
/// The overall rating above which a comparison is fair: 0.58.
pub const FAIR_ABOVE: f64 = 0.58;

/// The class of an overall rating `R` (ISO/TS 18571:2014): excellent
/// `R > 0.94`, good `0.80 < R ≤ 0.94`, fair `0.58 < R ≤ 0.80`, poor
/// `R ≤ 0.58`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Grade {
    /// `R ≤ 0.58`.
    Poor,
    /// `0.58 < R ≤ 0.80`.
    Fair,
    /// `0.80 < R ≤ 0.94`.
    Good,
    /// `R > 0.94`.
    Excellent,
}

impl Grade {
    /// The grade of overall rating `overall`.
    pub fn of(overall: f64) -> Grade {
        if overall > EXCELLENT_ABOVE {
            Grade::Excellent
        } else if overall > GOOD_ABOVE {
            Grade::Good
        } else if overall > FAIR_ABOVE {
            Grade::Fair
        } else {
            Grade::Poor
        }
    }

    /// The grade in lower case (`excellent`), as JSON writes it.
    pub fn name(self) -> &'static str {
        match self {
            Grade::Excellent => "excellent",
            Grade::Good => "good",
            Grade::Fair => "fair",
            Grade::Poor => "poor",
        }
    }
}

impl fmt::Display for Grade {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_threshold_belongs_to_the_class_below() {
        let cases = [
            (1.0, Grade::Excellent),
            (0.9400001, Grade::Excellent),
            (0.94, Grade::Good),
            (0.8000001, Grade::Good),
            (0.8, Grade::Fair),
            (0.5800001, Grade::Fair),
            (0.58, Grade::Poor),
            (0.0, Grade::Poor),
        ];
        for (overall, grade) in cases {
            assert_eq!(Grade::of(overall), grade, "{overall}");
        }
        assert_eq!(Grade::Good.to_string(), "good");
    }
}
