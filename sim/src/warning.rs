//! Warnings: what a run (or a measured pulse) does not stop at, but whose
//! numbers a user should not trust without a look — a vehicle moving away
//! from the barrier, a crush channel that never compresses, an acceleration
//! column that looks flipped, an energy balance that does not close.
//!
//! [`Warning`] is the one list of kinds: each variant has its snake-case
//! [`Warning::kind`] (the `kind` of `summary.json`'s `warnings`) and its
//! [`Warning::message`], naming what looked wrong and the value. The checks
//! are small functions over a channel's samples — time, value (crush,
//! compression positive) and rate — so that they apply to any channel.

use serde::Serialize;

/// The largest relative energy balance error of a run that is trusted
/// without a warning.
pub const ENERGY_BALANCE_LIMIT: f64 = 1e-3;

/// Something that looked wrong, with the values that showed it.
#[derive(Clone, Debug, PartialEq)]
pub enum Warning {
    /// The crush channel's rate at the start is negative: the vehicle
    /// moves away from the barrier instead of into it.
    MovingAway {
        /// The channel, as messages name it (e.g. "crush channel `-r`").
        channel: String,
        /// Its initial rate, compression positive [m/s].
        rate: f64,
    },
    /// The crush channel never exceeds its initial value during the run.
    NeverCompresses {
        /// The channel, as messages name it.
        channel: String,
        /// Its value at the start \[m\].
        initial: f64,
        /// Its largest value \[m\].
        max: f64,
    },
    /// An acceleration column whose integral speeds the vehicle up in the
    /// direction it moves at impact: a deceleration given as an
    /// acceleration, or the reverse.
    FlippedAcceleration {
        /// The column's header.
        column: String,
        /// Its integral over the record [m/s].
        velocity_change: f64,
        /// The impact velocity [m/s].
        v0: f64,
    },
    /// The run's relative energy balance error exceeds
    /// [`ENERGY_BALANCE_LIMIT`]: the tolerances are too loose to trust it.
    EnergyBalance {
        /// The error, relative to the initial energy.
        error: f64,
    },
    /// The crush channel still compresses at the end of the run: its
    /// largest crush is not the maximum of the pulse.
    StillCrushing {
        /// The channel, as messages name it.
        channel: String,
        /// The end of the run \[s\].
        t_end: f64,
        /// The crush there \[m\].
        crush: f64,
        /// Its rate there, compression positive [m/s].
        rate: f64,
    },
    /// The crush channel does not start at 0: its crush figures are
    /// measured from the channel's zero, not from the start of the run.
    CrushOffset {
        /// The channel, as messages name it.
        channel: String,
        /// Its value at the start \[m\].
        initial: f64,
    },
    /// A quantity of the run that is not a number (NaN or ±∞) at some
    /// time: an output, or a term of the energy balance.
    NonFinite {
        /// What it is, as messages name it (e.g. "output `th`").
        what: String,
        /// The first time it is not finite \[s\].
        t: f64,
        /// Its value there.
        value: f64,
    },
    /// A criterion whose channels are there but which cannot be rated.
    NotRated {
        /// The criterion's key (`"vc_mps"`).
        criterion: &'static str,
        /// Why.
        reason: String,
    },
    /// A filter class that the samples' rate cannot give (SAE J211-1: the
    /// design frequency 2.0775·CFC below half the sample rate), and what
    /// the metrics do without it.
    FilterClass {
        /// The class (60, 180, 600, 1000).
        cfc: f64,
        /// The period of the samples \[s\].
        period: f64,
        /// The sample rate the class needs \[Hz\] (`pulse::cfc::min_sample_rate`).
        min_rate: f64,
        /// What goes without it, e.g. "the CFC 60 peak deceleration is not
        /// computed".
        consequence: String,
    },
}

impl Warning {
    /// The kind in snake case, as `summary.json` writes it.
    pub fn kind(&self) -> &'static str {
        match self {
            Warning::MovingAway { .. } => "moving_away",
            Warning::NeverCompresses { .. } => "never_compresses",
            Warning::FlippedAcceleration { .. } => "flipped_acceleration",
            Warning::EnergyBalance { .. } => "energy_balance",
            Warning::FilterClass { .. } => "filter_class",
            Warning::StillCrushing { .. } => "still_crushing",
            Warning::CrushOffset { .. } => "crush_offset",
            Warning::NonFinite { .. } => "non_finite",
            Warning::NotRated { .. } => "criterion_not_rated",
        }
    }

    /// What looked wrong, with the value.
    pub fn message(&self) -> String {
        match self {
            Warning::MovingAway { channel, rate } => format!(
                "the impact velocity points away from the barrier: the {channel} starts at rate \
                 {rate:.4} m/s (compression positive), so the vehicle moves away; check the sign \
                 of the initial velocity"
            ),
            Warning::NeverCompresses {
                channel,
                initial,
                max,
            } => format!(
                // `+ 0.0`: −0 shows as 0.
                "the {channel} never compresses: its largest value {:.4e} m is not above its \
                 initial {:.4e} m",
                max + 0.0,
                initial + 0.0
            ),
            Warning::FlippedAcceleration {
                column,
                velocity_change,
                v0,
            } => format!(
                "the acceleration column `{column}` looks flipped: its integral changes the \
                 velocity by {velocity_change:+.3} m/s, speeding the vehicle up into the barrier \
                 from the impact velocity {v0:.3} m/s (a deceleration column is headed \
                 `decel`/`deceleration`)"
            ),
            Warning::EnergyBalance { error } => format!(
                "energy balance error {error:.1e} (relative) exceeds {ENERGY_BALANCE_LIMIT:.0e}: \
                 the results are not accurate; tighten simulation.rtol and simulation.atol"
            ),
            Warning::StillCrushing {
                channel,
                t_end,
                crush,
                rate,
            } => format!(
                "the {channel} is still compressing at t_end = {:.1} ms (crush {crush:.4} m, rate \
                 {rate:.3} m/s): the max dynamic crush is not the maximum, and the pulse's metrics \
                 are of its first {:.1} ms only; raise simulation.t_end",
                t_end * 1e3,
                t_end * 1e3
            ),
            Warning::CrushOffset { channel, initial } => format!(
                "the {channel} starts at {initial:.4e} m, not 0: the max dynamic crush and the \
                 equivalent square wave are measured from its zero, not from the start of the run \
                 (a gap before contact starts below 0; a crush above 0 was there before the impact)"
            ),
            Warning::NonFinite { what, t, value } => format!(
                "{what} is {value} at t = {t:.6} s, the first sample where it is not a number; \
                 check its expression's domain and the parameters"
            ),
            Warning::FilterClass {
                cfc,
                period,
                min_rate,
                consequence,
            } => format!(
                "CFC {cfc} needs a sample rate above {:.0} Hz (SAE J211-1: 2.0775·CFC below half \
                 the sample rate); samples every {} ms give {:.0} Hz: {consequence}",
                min_rate,
                round_ms(*period),
                1.0 / period
            ),
            Warning::NotRated { criterion, reason } => {
                format!("criterion `{criterion}` is not rated: {reason}")
            }
        }
    }
}

/// `period` in ms, to 4 decimals without trailing zeros (1.5, 0.1,
/// 4.1667).
fn round_ms(period: f64) -> String {
    let text = format!("{:.4}", period * 1e3);
    let text = text.trim_end_matches('0').trim_end_matches('.');
    text.to_string()
}

impl std::fmt::Display for Warning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message())
    }
}

/// `{ "kind": …, "message": … }`.
impl Serialize for Warning {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        let mut s = serializer.serialize_struct("Warning", 2)?;
        s.serialize_field("kind", self.kind())?;
        s.serialize_field("message", &self.message())?;
        s.end()
    }
}

/// `value` (a struct or map) as pretty-printed JSON, its own keys first,
/// then `"warnings": [{ "kind": …, "message": … }, …]` (`[]` when there
/// are none), ending in a newline.
pub fn json_with_warnings<T: Serialize>(value: &T, warnings: &[Warning]) -> String {
    #[derive(Serialize)]
    struct WithWarnings<'a, T> {
        #[serde(flatten)]
        value: &'a T,
        warnings: &'a [Warning],
    }
    let file = WithWarnings { value, warnings };
    serde_json::to_string_pretty(&file).unwrap_or_else(|_| "{}".to_string()) + "\n"
}

/// One sample of a channel: time \[s\], value and rate (for a crush
/// channel: crush, compression positive, and its rate).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChannelPoint {
    /// Time \[s\].
    pub t: f64,
    /// The channel's value.
    pub value: f64,
    /// Its rate of change.
    pub rate: f64,
}

/// A crush channel whose first sample moves away from the barrier.
pub fn moving_away(channel: &str, first: ChannelPoint) -> Option<Warning> {
    (first.rate < 0.0).then(|| Warning::MovingAway {
        channel: channel.to_string(),
        rate: first.rate,
    })
}

/// A crush channel that never rises above its first sample (`max`: its
/// largest value over the run).
pub fn never_compresses(channel: &str, first: ChannelPoint, max: f64) -> Option<Warning> {
    (max <= first.value).then(|| Warning::NeverCompresses {
        channel: channel.to_string(),
        initial: first.value,
        max,
    })
}

/// An acceleration record (`t`, `acceleration`, forward positive) whose
/// integral moves the velocity away from zero in the direction of `v0` by
/// more than a twentieth of `v0`: the vehicle would speed up into the
/// barrier. No warning without an impact velocity (`v0 = 0`).
pub fn flipped_acceleration(
    column: &str,
    t: &[f64],
    acceleration: &[f64],
    v0: f64,
) -> Option<Warning> {
    let velocity_change: f64 = t
        .windows(2)
        .zip(acceleration.windows(2))
        .map(|(t, a)| 0.5 * (a[0] + a[1]) * (t[1] - t[0]))
        .sum();
    let speeds_up = velocity_change * v0.signum() > 0.05 * v0.abs();
    (v0 != 0.0 && speeds_up).then(|| Warning::FlippedAcceleration {
        column: column.to_string(),
        velocity_change,
        v0,
    })
}

/// Crush at the start of a crush channel below which it counts as 0 \[m\]:
/// a micrometre, far above the rounding of an equilibrium solve.
pub const CRUSH_AT_START: f64 = 1e-6;

/// The crush rate at the end of a run, relative to the impact velocity,
/// above which the crush is still under way (a car resting against the
/// barrier creeps at far less).
pub const STILL_CRUSHING: f64 = 1e-3;

/// Whether a crush channel compressing at `rate` at the end of a run that
/// started at `v0` (its rate at the start) is still under way: faster than
/// [`STILL_CRUSHING`] of `|v0|`.
pub fn is_still_crushing(rate: f64, v0: f64) -> bool {
    rate > STILL_CRUSHING * v0.abs()
}

/// A crush channel that is still compressing at its last sample (see
/// [`is_still_crushing`]; `v0`: its rate at the start).
pub fn still_crushing(channel: &str, last: ChannelPoint, v0: f64) -> Option<Warning> {
    is_still_crushing(last.rate, v0).then(|| Warning::StillCrushing {
        channel: channel.to_string(),
        t_end: last.t,
        crush: last.value,
        rate: last.rate,
    })
}

/// A crush channel whose first sample is farther than [`CRUSH_AT_START`]
/// from 0.
pub fn crush_offset(channel: &str, first: ChannelPoint) -> Option<Warning> {
    (first.value.abs() > CRUSH_AT_START).then(|| Warning::CrushOffset {
        channel: channel.to_string(),
        initial: first.value,
    })
}

/// A relative energy balance error above [`ENERGY_BALANCE_LIMIT`] (or not
/// a number).
pub fn energy_balance(error: f64) -> Option<Warning> {
    (error.is_nan() || error > ENERGY_BALANCE_LIMIT).then_some(Warning::EnergyBalance { error })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(value: f64, rate: f64) -> ChannelPoint {
        ChannelPoint {
            t: 0.0,
            value,
            rate,
        }
    }

    #[test]
    fn a_channel_moving_away_is_named_with_its_rate() {
        assert_eq!(moving_away("crush coordinate `x`", point(0.0, 15.6)), None);
        let w = moving_away("crush coordinate `x`", point(0.0, -15.6)).unwrap();
        assert_eq!(w.kind(), "moving_away");
        assert!(
            w.message().starts_with(
                "the impact velocity points away from the barrier: the crush coordinate `x` \
                 starts at rate -15.6000 m/s"
            ),
            "{w}"
        );
    }

    #[test]
    fn a_channel_that_never_rises_above_its_start_never_compresses() {
        assert_eq!(never_compresses("c", point(0.0, 1.0), 0.3), None);
        let w = never_compresses("crush coordinate `x`", point(0.01, 1.0), 0.01).unwrap();
        assert_eq!(w.kind(), "never_compresses");
        assert_eq!(
            w.message(),
            "the crush coordinate `x` never compresses: its largest value 1.0000e-2 m is not \
             above its initial 1.0000e-2 m"
        );
    }

    #[test]
    fn an_acceleration_that_speeds_the_vehicle_up_looks_flipped() {
        let t = [0.0, 0.05, 0.1];
        // A constant 150 m/s² over 0.1 s: +15 m/s.
        let pushing = [150.0; 3];
        let w = flipped_acceleration("a [m/s^2]", &t, &pushing, 15.0).unwrap();
        assert_eq!(w.kind(), "flipped_acceleration");
        assert!(
            w.message().contains("changes the velocity by +15.000 m/s"),
            "{w}"
        );
        let braking = [-150.0; 3];
        assert_eq!(flipped_acceleration("a", &t, &braking, 15.0), None);
        // Moving backwards into a barrier behind: braking is positive.
        assert_eq!(flipped_acceleration("a", &t, &pushing, -15.0), None);
        assert!(flipped_acceleration("a", &t, &braking, -15.0).is_some());
        // Noise of a few percent of v0 is no warning; nothing without v0.
        assert_eq!(flipped_acceleration("a", &t, &[5.0; 3], 15.0), None);
        assert_eq!(flipped_acceleration("a", &t, &pushing, 0.0), None);
    }

    #[test]
    fn an_energy_balance_above_the_limit_warns() {
        assert_eq!(energy_balance(3.4e-10), None);
        assert_eq!(energy_balance(1e-3), None);
        let w = energy_balance(14.0).unwrap();
        assert_eq!(w.kind(), "energy_balance");
        assert_eq!(
            w.message(),
            "energy balance error 1.4e1 (relative) exceeds 1e-3: the results are not accurate; \
             tighten simulation.rtol and simulation.atol"
        );
        assert!(energy_balance(f64::NAN).is_some());
        let json = serde_json::to_string(&w).unwrap();
        assert!(json.starts_with(r#"{"kind":"energy_balance","message":"energy balance"#));
    }
    #[test]
    fn a_crush_channel_still_compressing_at_the_end_or_not_at_0_warns() {
        let end = ChannelPoint {
            t: 0.03,
            value: 0.3792,
            rate: 9.071,
        };
        let w = still_crushing("crush channel `-r`", end, 15.5556).unwrap();
        assert_eq!(w.kind(), "still_crushing");
        assert!(
            w.message().starts_with(
                "the crush channel `-r` is still compressing at t_end = 30.0 ms (crush 0.3792 m, \
                 rate 9.071 m/s): the max dynamic crush is not the maximum"
            ),
            "{w}"
        );
        let rebounding = ChannelPoint { rate: -1.8, ..end };
        assert_eq!(still_crushing("c", rebounding, 15.5556), None);
        // Creeping at 1 mm/s after a 15.6 m/s impact: at rest, not crushing.
        let creeping = ChannelPoint { rate: 1e-3, ..end };
        assert_eq!(still_crushing("c", creeping, 15.5556), None);
        assert!(still_crushing("c", creeping, 0.0).is_some());
        assert_eq!(crush_offset("c", point(1e-7, 15.0)), None);
        let w = crush_offset("crush channel `-r`", point(0.01, 15.0)).unwrap();
        assert_eq!(w.kind(), "crush_offset");
        assert!(
            w.message()
                .starts_with("the crush channel `-r` starts at 1.0000e-2 m, not 0"),
            "{w}"
        );
        assert!(crush_offset("c", point(-0.05, 15.0)).is_some());
    }

    #[test]
    fn a_value_that_is_not_a_number_is_named_with_its_first_time() {
        let w = Warning::NonFinite {
            what: "output `phase`".into(),
            t: 0.0,
            value: f64::NAN,
        };
        assert_eq!(w.kind(), "non_finite");
        assert!(
            w.message()
                .starts_with("output `phase` is NaN at t = 0.000000 s"),
            "{w}"
        );
    }
}
