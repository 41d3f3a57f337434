//! An ISO-MME test's vehicle channels as the time histories a fit reads:
//! the channels asked for by their codes, in SI units and the project's
//! signs, on one time base ([`vehicle_histories`]).
//!
//! **What a channel is.** A `--channel CODE[=QUANTITY]` names a channel of
//! the test and, optionally, the simulated quantity it is compared with:
//! `acceleration`, `velocity` or `crush` (of the scenario's crush
//! coordinate). Without one, the code's physical dimension says it: `AC`
//! an acceleration, `VE` (and `VA`, `VD`, velocities integrated from an
//! acceleration or differentiated from a displacement) a velocity, `DS`
//! (and `DV`, integrated from a velocity) the crush. The channel must be
//! on a vehicle's structure — test object `1`–`9` and a main location
//! RED B files under the vehicle (`VEHC`, `SILB`, `BPIL`, `TUNN`, …; a
//! dummy's `HEAD` in vehicle 1, `11HEAD…`, is not one) — and longitudinal
//! (direction `X`).
//!
//! **Signs.** Direction `X` is SAE J211's, forward positive; so are the
//! project's signs (`lagrangian_sim::pulse`): the vehicle's acceleration is
//! negative while it decelerates, its velocity is the impact speed at
//! first contact, and the crush grows as the car moves forward into the
//! barrier. The channels are taken with their signs as they are. A `DS` x
//! channel is the point's forward displacement since time zero: against a
//! fixed barrier, whose face does not move, that is the crush the model's
//! crush coordinate measures, and the channel `lpm simulate --iso-mme`
//! writes as `10VEHCCG0000DSXP`. (Against a moving barrier it is not the
//! crush; nothing in the test says which, and it is taken as written.)
//! Direction `1` (x with signs other than SAE J211's) is refused.
//!
//! **Units.** Each channel's `Unit` (`g`, `m/s**2`, `m/(s*s)`, `m / s2`, `km/h`,
//! `mm`, …, as [`super::unit_text`] writes them) is read by the simulation
//! library's units (`lagrangian_sim::quantity`: a bare `g` beside an
//! acceleration is standard gravity, 9.806 65 m/s²) and converted to SI; a
//! unit of another dimension than the code's is an error.
//!
//! **Time base.** The fit's simulation starts at first contact, the test's
//! time zero: samples before it (the pre-trigger) are left out, and a time
//! within 10⁻⁹ of an interval of zero is zero. Where the channels share one
//! sampling (the same interval, times of first sample a whole number of
//! intervals apart: one data acquisition system), their samples are used as
//! they are, over the interval all of them span. Where they do not, the
//! coarsest channel's times are the time base, over that interval, and the
//! others are interpolated linearly at them: each value lies between two of
//! the channel's own samples, none is extrapolated, and no channel gains
//! samples it does not have. A sample without a value (`NOVALUE`) within
//! that interval is an error naming the channel and its time.

use super::unit_text;
use crate::error::StudyError;
use lagrangian_crashdata::code::{Category, Dimension, Direction, TestObject};
use lagrangian_crashdata::isomme::{Channel as TestChannel, Test};
use lagrangian_crashdata::{ChannelCode, CodeError};
use lagrangian_sim::pulse::channels::{Channel, Quantity, TimeHistories};
use lagrangian_sim::pulse::interpolate;
use lagrangian_sim::quantity::{QuantityError, value_in};
use std::fmt;
use std::path::{Path, PathBuf};

/// How close to a time a sample is taken as at it, in sampling intervals.
const ON_TIME: f64 = 1e-9;

/// How far from a whole number of intervals apart two channels' first
/// times may be and still share a sampling, in intervals: rounding of
/// `t0 + i·dt`, far below a sample.
const ON_GRID: f64 = 1e-6;

/// The fewest times the time histories hold ([`TimeHistories`]' own).
const MIN_TIMES: usize = 3;

/// A channel of a test asked for: `CODE[=QUANTITY]`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ChannelRequest {
    /// The channel's code.
    pub code: ChannelCode,
    /// The simulated quantity it is compared with; `None`: the one its
    /// code's dimension says.
    pub quantity: Option<Quantity>,
}

impl ChannelRequest {
    /// Reads `CODE` or `CODE=QUANTITY` (`acceleration`, `velocity`,
    /// `crush`).
    pub fn parse(text: &str) -> Result<ChannelRequest, TestDataError> {
        let (code, quantity) = match text.split_once('=') {
            Some((code, quantity)) => (code.trim(), Some(quantity.trim())),
            None => (text.trim(), None),
        };
        let code = ChannelCode::parse(code).map_err(|error| TestDataError::BadCode {
            text: text.to_string(),
            error,
        })?;
        let quantity = quantity
            .map(|name| {
                quantity_named(name).ok_or_else(|| TestDataError::UnknownQuantity {
                    text: text.to_string(),
                    name: name.to_string(),
                })
            })
            .transpose()?;
        Ok(ChannelRequest { code, quantity })
    }
}

impl fmt::Display for ChannelRequest {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.quantity {
            Some(q) => write!(f, "{}={}", self.code, q.name()),
            None => write!(f, "{}", self.code),
        }
    }
}

/// The quantities a channel can be compared with.
const QUANTITIES: [Quantity; 3] = [Quantity::Acceleration, Quantity::Velocity, Quantity::Crush];

/// The quantity called `name` ([`Quantity::name`]).
fn quantity_named(name: &str) -> Option<Quantity> {
    QUANTITIES.into_iter().find(|q| q.name() == name)
}

/// Why a test gives no time histories: each error names the test, the
/// channel (and where it matters its time or unit).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum TestDataError {
    /// A `--channel` whose code is not a channel code.
    #[error("--channel {text}: {error}")]
    BadCode {
        /// The text given.
        text: String,
        /// Why its code is not one.
        error: CodeError,
    },
    /// A `--channel` naming a quantity the fit does not simulate.
    #[error(
        "--channel {text}: `{name}` is not a simulated quantity; expected acceleration, velocity or crush"
    )]
    UnknownQuantity {
        /// The text given.
        text: String,
        /// The quantity's name as given.
        name: String,
    },
    /// No channel asked for.
    #[error(
        "{}: name the test's channels to use with --channel CODE[=acceleration|velocity|crush] (its vehicle x channels: {})",
        .test.display(),
        list(.available)
    )]
    NoChannel {
        /// The test.
        test: PathBuf,
        /// Its channels a fit can use.
        available: Vec<String>,
    },
    /// A code the test has no channel of.
    #[error(
        "{}: no channel {code} (channels: {}){}",
        .test.display(),
        list(.available),
        .suggestion.as_ref().map_or(String::new(), |s| format!("; did you mean {s}?"))
    )]
    UnknownCode {
        /// The test.
        test: PathBuf,
        /// The code asked for.
        code: ChannelCode,
        /// The codes it has.
        available: Vec<String>,
        /// The closest of them, when one is close.
        suggestion: Option<String>,
    },
    /// A channel that is not on a vehicle's structure.
    #[error(
        "channel {code} is on {object}, not a vehicle's structure (test object 1-9, a vehicle location such as VEHC): the fit compares the vehicle's crush motion"
    )]
    NotVehicle {
        /// The channel.
        code: ChannelCode,
        /// What it is on, in words.
        object: String,
    },
    /// A channel that is not longitudinal with SAE J211's signs.
    #[error(
        "channel {code} is {direction}, not x (direction X, forward positive): the crush coordinate is longitudinal"
    )]
    NotLongitudinal {
        /// The channel.
        code: ChannelCode,
        /// Its direction, in words.
        direction: &'static str,
    },
    /// A channel whose dimension is none of the simulated quantities', or
    /// not the one asked for.
    #[error("channel {code} is {found} ({dimension}); {needs}")]
    Dimension {
        /// The channel.
        code: ChannelCode,
        /// Its dimension's two characters.
        dimension: String,
        /// What that dimension measures, in words.
        found: &'static str,
        /// What it would need to be.
        needs: String,
    },
    /// Two channels compared with the same quantity.
    #[error("channels {first} and {second} are both compared with the {}: keep one", .quantity.name())]
    Duplicate {
        /// The first.
        first: ChannelCode,
        /// The second.
        second: ChannelCode,
        /// The quantity both are compared with.
        quantity: Quantity,
    },
    /// A channel without a unit.
    #[error("{}: channel {code} gives no Unit; it needs one of {}", .test.display(), .quantity.si_unit())]
    NoUnit {
        /// The test.
        test: PathBuf,
        /// The channel.
        code: ChannelCode,
        /// The quantity it is compared with.
        quantity: Quantity,
    },
    /// A channel whose unit is not one of its quantity's.
    #[error("{}: channel {code}, Unit {unit}: {error}", .test.display())]
    Unit {
        /// The test.
        test: PathBuf,
        /// The channel.
        code: ChannelCode,
        /// The unit as written.
        unit: String,
        /// Why it does not convert.
        error: Box<QuantityError>,
    },
    /// Channels that share no time from 0 on.
    #[error(
        "{}: the channels share no time from first contact (t = 0) on: {}",
        .test.display(),
        .spans.iter().map(|(code, a, b)| format!("{code} {a} s to {b} s")).collect::<Vec<_>>().join(", ")
    )]
    NoCommonTime {
        /// The test.
        test: PathBuf,
        /// Each channel's first and last time \[s\] (the first from 0).
        spans: Vec<(ChannelCode, f64, f64)>,
    },
    /// Channels that share too few times from 0 on.
    #[error(
        "{}: the channels share {times} time{} from first contact (t = 0) on; at least {MIN_TIMES} are needed",
        .test.display(),
        if *.times == 1 { "" } else { "s" }
    )]
    TooFewTimes {
        /// The test.
        test: PathBuf,
        /// The times they share.
        times: usize,
    },
    /// A sample without a value where the fit needs one.
    #[error(
        "{}: channel {code} has no value (NOVALUE) at t = {time} s, which the fit uses",
        .test.display()
    )]
    NoValue {
        /// The test.
        test: PathBuf,
        /// The channel.
        code: ChannelCode,
        /// The time \[s\].
        time: f64,
    },
}

/// Items of a list, comma-separated (`none` for none).
fn list(items: &[String]) -> String {
    match items.is_empty() {
        true => "none".to_string(),
        false => items.join(", "),
    }
}

/// A `--channel` that does not fit the test is a bad request; a test whose
/// channels cannot be used (their units, times, values) a data file's
/// error.
impl From<TestDataError> for StudyError {
    fn from(e: TestDataError) -> StudyError {
        match e {
            TestDataError::BadCode { .. }
            | TestDataError::UnknownQuantity { .. }
            | TestDataError::NoChannel { .. }
            | TestDataError::UnknownCode { .. }
            | TestDataError::NotVehicle { .. }
            | TestDataError::NotLongitudinal { .. }
            | TestDataError::Dimension { .. }
            | TestDataError::Duplicate { .. } => StudyError::usage(e.to_string()),
            TestDataError::NoUnit { .. }
            | TestDataError::Unit { .. }
            | TestDataError::NoCommonTime { .. }
            | TestDataError::TooFewTimes { .. }
            | TestDataError::NoValue { .. } => StudyError::data_file(e.to_string()),
        }
    }
}

/// The channels `asked` of `test` (read from `file`, as messages name it)
/// as time histories: in SI units and the project's signs, on one time
/// base from first contact (see the module). Sorted by quantity, as
/// [`TimeHistories`] are; each channel's header is `CODE [unit]`.
pub fn vehicle_histories(
    test: &Test,
    file: &Path,
    asked: &[ChannelRequest],
) -> Result<TimeHistories, TestDataError> {
    if asked.is_empty() {
        return Err(TestDataError::NoChannel {
            test: file.to_path_buf(),
            available: usable_codes(test),
        });
    }
    let mut chosen: Vec<(Quantity, &TestChannel)> = Vec::new();
    for request in asked {
        let channel = find(test, file, &request.code)?;
        let quantity = quantity_of(request)?;
        if let Some((_, first)) = chosen.iter().find(|(q, _)| *q == quantity) {
            return Err(TestDataError::Duplicate {
                first: first.code,
                second: channel.code,
                quantity,
            });
        }
        chosen.push((quantity, channel));
    }
    chosen.sort_by_key(|(q, _)| *q);
    let converted = (chosen.iter())
        .map(|&(quantity, channel)| in_si(channel, quantity, file))
        .collect::<Result<Vec<_>, _>>()?;
    on_one_time_base(&converted, file)
}

/// The codes of `test`'s channels a fit can use as they are (a vehicle's,
/// longitudinal, of a dimension with a default quantity).
fn usable_codes(test: &Test) -> Vec<String> {
    let usable = |code: &ChannelCode| {
        let request = ChannelRequest {
            code: *code,
            quantity: None,
        };
        quantity_of(&request).is_ok()
    };
    (test.channels.iter())
        .filter(|c| usable(&c.code))
        .map(|c| c.code.to_string())
        .collect()
}

/// The channel `code` of `test`, or the error naming the closest code.
fn find<'a>(
    test: &'a Test,
    file: &Path,
    code: &ChannelCode,
) -> Result<&'a TestChannel, TestDataError> {
    test.channel(code).ok_or_else(|| {
        let available: Vec<String> = test.channels.iter().map(|c| c.code.to_string()).collect();
        let names = available.iter().map(String::as_str);
        let suggestion = lagrangian_runtime::names::closest(code.as_str(), names);
        TestDataError::UnknownCode {
            test: file.to_path_buf(),
            code: *code,
            suggestion: suggestion.map(str::to_string),
            available,
        }
    })
}

/// The simulated quantity `request`'s channel is compared with, checked
/// against its code: a vehicle's, direction X, a dimension of that
/// quantity.
fn quantity_of(request: &ChannelRequest) -> Result<Quantity, TestDataError> {
    let code = request.code;
    if let Some(object) = not_on_the_structure(&code) {
        return Err(TestDataError::NotVehicle { code, object });
    }
    if code.direction() != Direction::X {
        let direction = direction_name(code.direction());
        return Err(TestDataError::NotLongitudinal { code, direction });
    }
    let dimension = code.dimension();
    let (found, of_dimension) = dimension_quantity(dimension);
    let error = |needs: String| TestDataError::Dimension {
        code,
        dimension: dimension.code(),
        found,
        needs,
    };
    match (of_dimension, request.quantity) {
        (Some(q), None) => Ok(q),
        (Some(q), Some(asked)) if q == asked => Ok(q),
        (_, Some(asked)) => Err(error(format!(
            "the {} needs {}",
            asked.name(),
            dimensions_of(asked)
        ))),
        (None, None) => Err(error(
            "a fit compares an acceleration (AC), a velocity (VE, VA, VD) or a displacement (DS, DV)"
                .to_string(),
        )),
    }
}

/// What a dimension measures, in words, and the simulated quantity of it.
fn dimension_quantity(dimension: Dimension) -> (&'static str, Option<Quantity>) {
    match dimension {
        Dimension::Acceleration => ("an acceleration", Some(Quantity::Acceleration)),
        Dimension::Velocity => ("a velocity", Some(Quantity::Velocity)),
        Dimension::VelocityFromAcceleration => (
            "a velocity integrated from an acceleration",
            Some(Quantity::Velocity),
        ),
        Dimension::VelocityFromDisplacement => (
            "a velocity differentiated from a displacement",
            Some(Quantity::Velocity),
        ),
        Dimension::Displacement => ("a displacement", Some(Quantity::Crush)),
        Dimension::DisplacementFromVelocity => (
            "a displacement integrated from a velocity",
            Some(Quantity::Crush),
        ),
        Dimension::Distance => ("a distance between two points", None),
        Dimension::Force => ("a force", None),
        Dimension::Moment => ("a moment", None),
        Dimension::Angle => ("an angle", None),
        Dimension::AngularVelocity => ("an angular velocity", None),
        Dimension::AngularAcceleration => ("an angular acceleration", None),
        _ => ("of another dimension", None),
    }
}

/// The dimensions a quantity's channel may have, in words.
fn dimensions_of(quantity: Quantity) -> &'static str {
    match quantity {
        Quantity::Acceleration => "an acceleration channel (AC)",
        Quantity::Velocity => "a velocity channel (VE, VA or VD)",
        Quantity::Crush => "a displacement channel (DS or DV)",
    }
}

/// What `code` is on, in words, unless it is a vehicle's structure.
fn not_on_the_structure(code: &ChannelCode) -> Option<String> {
    let location = code.main_location();
    match (code.test_object(), code.main_location_name()) {
        (TestObject::Vehicle(_), Some((_, Category::Vehicle))) => None,
        (TestObject::Vehicle(_), Some((name, category))) => {
            Some(format!("{} ({location}, {name})", category_name(category)))
        }
        (TestObject::Vehicle(_), None) => {
            Some(format!("a main location RED B does not list ({location})"))
        }
        (other, _) => Some(object_name(other).to_string()),
    }
}

/// A category of main locations in words.
fn category_name(category: Category) -> &'static str {
    match category {
        Category::Human => "a human body",
        Category::Dummy => "a dummy",
        Category::Vehicle => "a vehicle",
        Category::Calculation => "a calculated criterion",
        Category::Other => "a barrier, sled, impactor or signal",
    }
}

/// A test object in words.
fn object_name(object: TestObject) -> &'static str {
    match object {
        TestObject::Vehicle(_) => "a vehicle",
        TestObject::Undefined => "an undefined test object (0)",
        TestObject::FixedBarrier => "a fixed barrier (B)",
        TestObject::Component => "a component (C)",
        TestObject::Dummy => "a dummy (D)",
        TestObject::LinearImpactor => "a linear impactor (H)",
        TestObject::MobileBarrier => "a mobile barrier (M)",
        TestObject::Pendulum => "a pendulum (P)",
        TestObject::Sled => "a sled (S)",
        TestObject::TestRig => "a test rig (T)",
    }
}

/// A direction in words.
fn direction_name(direction: Direction) -> &'static str {
    match direction {
        Direction::Undefined => "of no direction (0)",
        Direction::Resultant => "a resultant (R)",
        Direction::X => "x (X)",
        Direction::Y => "lateral (Y)",
        Direction::Z => "vertical (Z)",
        Direction::XOtherSigns => "x with signs other than SAE J211's (1)",
        Direction::YOtherSigns => "lateral with signs other than SAE J211's (2)",
        Direction::ZOtherSigns => "vertical with signs other than SAE J211's (3)",
    }
}

/// A channel in SI units from time zero on: its quantity, header, times
/// and values.
struct Converted {
    quantity: Quantity,
    code: ChannelCode,
    header: String,
    dt: f64,
    t: Vec<f64>,
    values: Vec<f64>,
}

/// `channel` in the SI unit of `quantity`, its samples from time zero on.
fn in_si(
    channel: &TestChannel,
    quantity: Quantity,
    file: &Path,
) -> Result<Converted, TestDataError> {
    let unit = channel.unit.trim();
    if unit.is_empty() {
        return Err(TestDataError::NoUnit {
            test: file.to_path_buf(),
            code: channel.code,
            quantity,
        });
    }
    let factor =
        value_in(&format!("1 {}", unit_text(unit)), quantity.si_unit()).map_err(|error| {
            TestDataError::Unit {
                test: file.to_path_buf(),
                code: channel.code,
                unit: unit.to_string(),
                error: Box::new(error),
            }
        })?;
    let (mut t, mut values) = (Vec::new(), Vec::new());
    for (i, value) in channel.values.iter().enumerate() {
        let time = channel.time(i);
        let time = if time.abs() <= ON_TIME * channel.dt {
            0.0
        } else {
            time
        };
        if time >= 0.0 {
            t.push(time);
            values.push(value * factor);
        }
    }
    Ok(Converted {
        quantity,
        code: channel.code,
        header: format!("{} [{unit}]", channel.code),
        dt: channel.dt,
        t,
        values,
    })
}

/// The channels on one time base (see the module): their shared samples,
/// or the coarsest one's times with the others interpolated.
fn on_one_time_base(channels: &[Converted], file: &Path) -> Result<TimeHistories, TestDataError> {
    let (start, end) = common_span(channels, file)?;
    let base = (channels.iter())
        .max_by(|a, b| a.dt.total_cmp(&b.dt))
        .unwrap_or(&channels[0]);
    let within = |t: f64| t >= start - ON_TIME * base.dt && t <= end + ON_TIME * base.dt;
    let t: Vec<f64> = base.t.iter().copied().filter(|&t| within(t)).collect();
    if t.len() < MIN_TIMES {
        let times = t.len();
        return Err(TestDataError::TooFewTimes {
            test: file.to_path_buf(),
            times,
        });
    }
    let mut out = Vec::with_capacity(channels.len());
    for c in channels {
        let shared: Vec<f64> = match shares_sampling(c, base) {
            true => (c.t.iter().zip(&c.values))
                .filter(|(t, _)| within(**t))
                .map(|(_, v)| *v)
                .collect(),
            false => Vec::new(),
        };
        let values = match shared.len() == t.len() {
            true => shared,
            false => interpolate(&c.t, &c.values, &t),
        };
        if let Some(k) = values.iter().position(|v: &f64| !v.is_finite()) {
            return Err(TestDataError::NoValue {
                test: file.to_path_buf(),
                code: c.code,
                time: t[k],
            });
        }
        out.push(Channel {
            quantity: c.quantity,
            header: c.header.clone(),
            values,
        });
    }
    Ok(TimeHistories { t, channels: out })
}

/// The interval every channel spans from time zero on.
fn common_span(channels: &[Converted], file: &Path) -> Result<(f64, f64), TestDataError> {
    let first = |c: &Converted| c.t.first().copied().unwrap_or(f64::INFINITY);
    let last = |c: &Converted| c.t.last().copied().unwrap_or(f64::NEG_INFINITY);
    let start = channels.iter().map(first).fold(0.0, f64::max);
    let end = channels.iter().map(last).fold(f64::INFINITY, f64::min);
    if start < end {
        return Ok((start, end));
    }
    Err(TestDataError::NoCommonTime {
        test: file.to_path_buf(),
        spans: (channels.iter())
            .map(|c| (c.code, first(c).max(0.0), last(c)))
            .collect(),
    })
}

/// Whether `a` is sampled at `b`'s times: the same interval, and first
/// times a whole number of intervals apart (within [`ON_TIME`]).
fn shares_sampling(a: &Converted, b: &Converted) -> bool {
    let (Some(&ta), Some(&tb)) = (a.t.first(), b.t.first()) else {
        return false;
    };
    let steps = (ta - tb) / b.dt;
    (a.dt - b.dt).abs() <= ON_TIME * b.dt && (steps - steps.round()).abs() <= ON_GRID
}

#[cfg(test)]
mod tests;
