//! The crush element: a spring and damper between a vehicle and a barrier
//! (or two bodies), the paper's eqs 1–2, with plastic unloading,
//! compression-only contact and a gap as options.
//!
//! In terms of the element's deflection `δ` (compression positive: the
//! crush, less the gap) and its rate `δ̇`, the compressive force is
//! `P = S(δ) + D(δ̇)`:
//!
//! * loading: `S(δ)` is the spring's loading curve, in one of two forms
//!   ([`LoadingCurve`]):
//!   - a **secant stiffness** curve `k(δ)`, `S = k(δ)·δ` (eq 1; `k` linear
//!     between breakpoints, so `S` is quadratic there): the paper's form;
//!   - a **force–deflection** curve: `S` given at breakpoints, linear
//!     between (what a test's force–deflection curve gives);
//!
//!   both odd in `δ` (`S(−δ) = −S(δ)`); `D = c(|δ̇|)·δ̇` (eq 2);
//! * plastic unloading from the peak `(δ_p, S_p)` reached: `S = S_p − k_u (δ_p − δ)`,
//!   back along that line on reloading and onto the loading curve beyond `δ_p`
//!   (permanent set `δ_p − S_p/k_u`). Elastic unloading follows the loading
//!   curve, which returns all the stored energy (the paper's model);
//! * compression only: the barrier pushes but never pulls. In contact the
//!   force is `S + D` until that would pull (`S + D < 0`: the car separates);
//!   separated it is 0 until the gap closes — the deflection reaches the
//!   spring's zero (0 on the loading curve, the permanent set after plastic
//!   unloading) — while `S + D ≥ 0`. A run that starts with a gap (or moving
//!   away) starts separated ([`CrushElement::start`]);
//! * a gap `g` (compression only): the contact opens after an offset. The
//!   deflection is the crush less the gap, `δ = crush − g`, so there is no
//!   force until the crush exceeds the gap, and the loading curve starts
//!   there.
//!
//! Each change of regime is an event of the integration, so the force is
//! smooth within a step. So is each kink of the two curves (a breakpoint
//! of `k`, `S` or `c`): with `stop_at_kinks` (the default) the element
//! holds the segment of each curve that `|δ|` and `|δ̇|` are on, continued
//! past its breakpoints, and crossing a breakpoint is an event after which
//! it holds the next one ([`super::held`]); the force is the same, only no
//! step straddles a kink. The element's force `P` and deflection `δ` are
//! trajectory columns (`NAME.force [N]`, `NAME.deflection [m]`).
//!
//! Its scenario section is `type = "crush"` (`CrushSection`): the loading
//! curve is either `stiffness_breakpoints` and `stiffness_values` (secant
//! stiffness) or `force_breakpoints` and `force_values` (force–deflection),
//! never both.

use super::held::{self, Crossed, Held};
use super::{Binder, Column, Component, Contact, Event, Port, Report, Section, Smoothness};
use crate::components::section::Ports;
use crate::components::{Dissipation, Events};
use crate::curve::outside;
use crate::curve::{Curve, ForceCurve, OutOfRange, Outside, SecantCurve, TableError};
use crate::entry::non_negative;
use crate::entry::{EntryError, KeyPath};
use crate::ode::Direction;
use serde::Deserialize;

mod energy;

/// The loading curve `S(δ)` of the crush spring, in one of its two forms.
#[derive(Clone, Debug, PartialEq)]
pub enum LoadingCurve {
    /// A secant stiffness `k(|δ|)`: `S = k(|δ|)·δ` (the paper's eq 1).
    SecantStiffness(SecantCurve),
    /// A force–deflection curve: `S` at breakpoints, linear between.
    ForceDeflection(ForceCurve),
}

impl LoadingCurve {
    /// `(S(δ), dS/dδ)`: the spring force and its tangent stiffness.
    pub fn force(&self, delta: f64) -> Result<(f64, f64), OutOfRange> {
        self.force_on(Held::NONE, delta)
    }

    /// [`LoadingCurve::force`] on the held piece of its curve in `|δ|`.
    pub fn force_on(&self, held: Held, delta: f64) -> Result<(f64, f64), OutOfRange> {
        match self {
            LoadingCurve::SecantStiffness(k) => k.force_on(held.piece(), delta),
            LoadingCurve::ForceDeflection(f) => f.force_on(held.piece(), delta),
        }
    }

    /// The curve in `|δ|` whose kinks are the form's: `k` or `S`.
    pub fn curve(&self) -> &Curve {
        match self {
            LoadingCurve::SecantStiffness(k) => k.curve(),
            LoadingCurve::ForceDeflection(f) => f.curve(),
        }
    }
}

/// How the crush spring unloads.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Unloading {
    /// Along the loading curve (the paper's elastic spring).
    Elastic,
    /// Linearly from the peak.
    Plastic {
        /// The unloading stiffness `k_u` [N/m].
        stiffness: f64,
    },
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Phase {
    Loading,
    Unloading { peak_crush: f64, peak_force: f64 },
}

/// The crush element and its state during a run.
#[derive(Clone, Debug, PartialEq)]
pub struct CrushElement {
    /// The spring's loading curve `S(δ)`.
    pub loading: LoadingCurve,
    /// The damper's `c(|δ̇|)` of eq 2.
    pub damping: SecantCurve,
    /// How the spring unloads.
    pub unloading: Unloading,
    /// `+1` if compression is a positive input argument, `−1` if negative
    /// (the paper's `r < 0`).
    pub compression_sign: f64,
    /// The barrier pushes but never pulls.
    pub contact_only: bool,
    /// The crush at which the contact opens \[m\]: the deflection is the
    /// crush less the gap. 0 unless [`CrushElement::with_gap`] sets it.
    pub gap: f64,
    /// No step straddles a kink of the loading or damping curve: the
    /// segment of each is held within a step (see the module
    /// documentation). On unless [`CrushElement::with_stop_at_kinks`]
    /// turns it off.
    pub stop_at_kinks: bool,
    /// The piece of the loading curve held (on the loading curve).
    loading_piece: Held,
    /// The piece of the damping curve held.
    damping_piece: Held,
    phase: Phase,
    in_contact: bool,
    /// When the last contact ended, while out of contact after one.
    separated_at: Option<f64>,
}

/// The element's events, in index order (see [`CrushElement::event_values`]).
const EVENTS: &[Event] = &[
    Event {
        name: "peak crush",
        direction: Direction::Falling,
    },
    Event {
        name: "reloading past the peak",
        direction: Direction::Rising,
    },
    Event {
        name: "separation",
        direction: Direction::Falling,
    },
    Event {
        name: "contact",
        direction: Direction::Rising,
    },
    SPRING_KINKS[0],
    SPRING_KINKS[1],
    DAMPER_KINKS[0],
    DAMPER_KINKS[1],
];

/// The loading curve's held segment ends: `|δ|` crosses a breakpoint.
const SPRING_KINKS: [Event; 2] = held::events(
    "crush below a breakpoint of the loading curve",
    "crush above a breakpoint of the loading curve",
);

/// The damping curve's held segment ends: `|δ̇|` crosses a breakpoint.
const DAMPER_KINKS: [Event; 2] = held::events(
    "crush rate below a breakpoint of the damping curve",
    "crush rate above a breakpoint of the damping curve",
);

/// The element's columns: its compressive force and its deflection.
const COLUMNS: &[Column] = &[
    Column {
        quantity: "force",
        unit: "N",
    },
    Column {
        quantity: "deflection",
        unit: "m",
    },
];

impl CrushElement {
    /// An element without a gap in the undeformed, loading state, in contact.
    pub fn new(
        loading: LoadingCurve,
        damping: SecantCurve,
        unloading: Unloading,
        compression_sign: f64,
        contact_only: bool,
    ) -> CrushElement {
        CrushElement {
            loading,
            damping,
            unloading,
            compression_sign,
            contact_only,
            gap: 0.0,
            stop_at_kinks: true,
            loading_piece: Held::NONE,
            damping_piece: Held::NONE,
            phase: Phase::Loading,
            in_contact: true,
            separated_at: None,
        }
    }

    /// The element with a gap of `gap` \[m\] (finite, ≥ 0; a gap only opens
    /// for a compression-only element).
    pub fn with_gap(self, gap: f64) -> CrushElement {
        CrushElement { gap, ..self }
    }

    /// The element that holds the segments of its curves within a step
    /// (`true`, the default) or steps across their kinks (`false`).
    pub fn with_stop_at_kinks(self, stop_at_kinks: bool) -> CrushElement {
        CrushElement {
            stop_at_kinks,
            ..self
        }
    }

    /// Whether the element is in contact with the barrier.
    pub fn in_contact(&self) -> bool {
        self.in_contact
    }

    /// The deflection at which the spring of the current phase is unloaded:
    /// 0 on the loading curve, the permanent set after plastic unloading.
    fn spring_zero(&self) -> f64 {
        self.permanent_set().unwrap_or(0.0)
    }

    /// `S + D`: the compressive force the barrier would exert in contact.
    fn total(&self, delta: f64, rate: f64) -> Result<f64, OutOfRange> {
        Ok(self.spring(delta)?.0 + self.damper(rate)?.0)
    }

    /// `min(δ − δ₀, S + D)`, non-negative once the gap has closed (`δ₀` the
    /// spring's zero) with the barrier pushing.
    fn closing(&self, delta: f64, rate: f64) -> Result<f64, OutOfRange> {
        Ok((delta - self.spring_zero()).min(self.total(delta, rate)?))
    }

    /// The deflection `δ` (the crush less the gap) and its rate `δ̇` from
    /// the input's arguments `(x, v)`.
    fn crush(&self, args: &[f64]) -> (f64, f64) {
        (
            self.compression_sign * args[0] - self.gap,
            self.compression_sign * args[1],
        )
    }

    /// `(S, dS/dδ)` of the current phase.
    fn spring(&self, delta: f64) -> Result<(f64, f64), OutOfRange> {
        match (self.phase, self.unloading) {
            (
                Phase::Unloading {
                    peak_crush,
                    peak_force,
                },
                Unloading::Plastic { stiffness },
            ) => Ok((peak_force - stiffness * (peak_crush - delta), stiffness)),
            _ => self.loading.force_on(self.loading_piece, delta),
        }
    }

    /// `(D, dD/dδ̇)` on the held segment of the damping curve.
    fn damper(&self, rate: f64) -> Result<(f64, f64), OutOfRange> {
        self.damping.force_on(self.damping_piece.piece(), rate)
    }

    /// Whether the spring follows the loading curve (not the plastic
    /// unloading line).
    fn on_loading_curve(&self) -> bool {
        match (self.phase, self.unloading) {
            (Phase::Unloading { .. }, Unloading::Plastic { .. }) => false,
            (Phase::Loading, _) | (_, Unloading::Elastic) => true,
        }
    }

    /// Event function `k` at `(δ, δ̇)` (see [`CrushElement::event_values`]).
    fn event_at(&self, k: usize, (delta, rate): (f64, f64)) -> Result<f64, OutOfRange> {
        let plastic = matches!(self.unloading, Unloading::Plastic { .. });
        let (touching, separated) = (self.in_contact, !self.in_contact);
        Ok(match k {
            0 => match self.phase {
                Phase::Loading if plastic => rate,
                _ => 1.0,
            },
            1 => match self.phase {
                Phase::Unloading { peak_crush, .. } => delta - peak_crush,
                Phase::Loading => -1.0,
            },
            2 if self.contact_only && touching => self.total(delta, rate)?,
            2 => 1.0,
            3 if self.contact_only && separated => self.closing(delta, rate)?,
            3 => -1.0,
            4 | 5 => self.spring_kink_values(delta)[k - 4],
            k => (self.damping_piece).event_values(self.damping.curve(), rate.abs(), 0.0)[k - 6],
        })
    }

    /// The event functions of the ends of the loading curve's held segment
    /// (events 4 and 5), on the loading curve.
    fn spring_kink_values(&self, delta: f64) -> [f64; 2] {
        let spring = match self.on_loading_curve() {
            true => self.loading_piece,
            false => Held::NONE,
        };
        spring.event_values(self.loading.curve(), delta.abs(), 0.0)
    }

    /// Applies kink event `k` (4–7) at `(δ, δ̇)`: the next segment of the
    /// curve crossed.
    fn cross_kink(&mut self, k: usize, delta: f64, rate: f64) -> String {
        let crossed = match k % 2 {
            0 => Crossed::Below,
            _ => Crossed::Above,
        };
        match k {
            4 | 5 => (self.loading_piece).cross(self.loading.curve(), crossed, delta.abs()),
            _ => (self.damping_piece).cross(self.damping.curve(), crossed, rate.abs()),
        }
        // Not a change of regime: the event log leaves it out.
        String::new()
    }

    /// Holds the segments that `(δ, δ̇)` are on, when stopping at kinks.
    fn hold_segments(&mut self, delta: f64, rate: f64) {
        let hold = self.stop_at_kinks;
        self.loading_piece = Held::at(self.loading.curve(), delta.abs(), hold);
        self.damping_piece = Held::at(self.damping.curve(), rate.abs(), hold);
    }

    /// `(P, ∂P/∂δ, ∂P/∂δ̇)`: the compressive force and its derivatives.
    fn compressive(&self, args: &[f64]) -> Result<(f64, f64, f64), OutOfRange> {
        let (delta, rate) = self.crush(args);
        let (s, ds) = self.spring(delta)?;
        let (d, dd) = self.damper(rate)?;
        if self.contact_only && !self.in_contact {
            return Ok((0.0, 0.0, 0.0));
        }
        Ok((s + d, ds, dd))
    }

    /// The input's value `F = ±P` in the sign convention of its argument
    /// (for `compression_sign = −1`, `F(x, v) = k(|x|)x + c(|v|)v` as in eqs 1–2).
    pub fn force(&self, args: &[f64]) -> Result<f64, OutOfRange> {
        Ok(self.compression_sign * self.compressive(args)?.0)
    }

    /// `∂F/∂x` (the tangent stiffness).
    pub fn force_stiffness(&self, args: &[f64]) -> Result<f64, OutOfRange> {
        Ok(self.compressive(args)?.1)
    }

    /// `∂F/∂v` (the tangent damping).
    pub fn force_damping(&self, args: &[f64]) -> Result<f64, OutOfRange> {
        Ok(self.compressive(args)?.2)
    }

    /// The permanent deflection after plastic unloading from the peak, if
    /// any (the permanent crush less the gap).
    pub fn permanent_set(&self) -> Option<f64> {
        match (self.phase, self.unloading) {
            (
                Phase::Unloading {
                    peak_crush,
                    peak_force,
                },
                Unloading::Plastic { stiffness },
            ) => Some(peak_crush - peak_force / stiffness),
            _ => None,
        }
    }
}

impl Component for CrushElement {
    fn kind(&self) -> &'static str {
        "crush"
    }

    fn arguments(&self) -> Option<(usize, &'static str)> {
        Some((2, "the crush coordinate and its rate"))
    }

    fn value(&self, port: Port, args: &[f64]) -> Result<f64, OutOfRange> {
        match port {
            Port::Value => self.force(args),
            Port::Stiffness => self.force_stiffness(args),
            Port::Damping => self.force_damping(args),
        }
    }

    capabilities!(events: yes, states: no, energy: yes);

    fn columns(&self) -> &'static [Column] {
        COLUMNS
    }

    /// The compressive force `P` and the deflection `δ`.
    fn column_values(&self, args: &[f64], out: &mut [f64]) -> Result<(), OutOfRange> {
        out[0] = self.compressive(args)?.0;
        out[1] = self.crush(args).0;
        Ok(())
    }

    /// Its force and deflection for the force–crush plot, and its contact.
    fn report(&self) -> Report {
        let contact = match (self.in_contact, self.separated_at) {
            (true, _) => Contact::Touching,
            (false, Some(t)) => Contact::EndedAt(t),
            (false, None) => Contact::Never,
        };
        Report {
            force_deflection: Some((0, 1)),
            contact: Some(contact),
            ..Report::default()
        }
    }

    /// Smooth when it holds the segments of its curves (`stop_at_kinks`):
    /// its changes of regime and the kinks of its curves are then events.
    fn smoothness(&self) -> Smoothness {
        match self.stop_at_kinks {
            true => Smoothness::Smooth,
            false => Smoothness::Unknown,
        }
    }
}

impl Events for CrushElement {
    fn list(&self) -> &'static [Event] {
        EVENTS
    }

    /// The event functions; one that does not apply in the current regime is
    /// held at a constant of the sign that cannot trigger it.
    ///
    /// 0. peak crush (plastic unloading, loading): `δ̇`, falling;
    /// 1. reloading past the peak (unloading): `δ − δ_peak`, rising;
    /// 2. separation (contact only, in contact): `S + D`, falling;
    /// 3. contact (contact only, separated): `min(δ − δ₀, S + D)`, rising —
    ///    the gap closes at the spring's zero `δ₀` with the barrier pushing;
    /// 4. kink below (stopping at kinks, on the loading curve): `|δ|` less
    ///    the breakpoint below the held segment, falling;
    /// 5. kink above (likewise): `|δ|` less the breakpoint above it, rising;
    /// 6. 7. the same of `|δ̇|` and the damping curve (stopping at kinks).
    fn event_values(&self, args: &[f64], g: &mut [f64]) -> Result<(), OutOfRange> {
        let state = self.crush(args);
        let each = |k| self.event_at(k, state);
        let values = [each(0)?, each(1)?, each(2)?, each(3)?];
        g[..4].copy_from_slice(&values);
        g[4..8].copy_from_slice(&[each(4)?, each(5)?, each(6)?, each(7)?]);
        Ok(())
    }

    /// The one asked for of [`CrushElement::event_values`].
    fn event_value(&self, k: usize, args: &[f64], _: &mut [f64]) -> Result<f64, OutOfRange> {
        self.event_at(k, self.crush(args))
    }

    /// Applies event `k`; the description gives the crush (the deflection
    /// plus the gap), and is empty for a kink (events 4–7), which changes
    /// no regime.
    fn on_event(&mut self, k: usize, t: f64, args: &[f64]) -> Result<String, OutOfRange> {
        let (delta, rate) = self.crush(args);
        let crush = delta + self.gap;
        Ok(match k {
            0 => {
                let peak_force = self.spring(delta)?.0;
                self.phase = Phase::Unloading {
                    peak_crush: delta,
                    peak_force,
                };
                format!(
                    "peak crush {crush:.4} m at {:.1} kN; unloading",
                    peak_force / 1e3
                )
            }
            1 => {
                self.phase = Phase::Loading;
                format!("crush {crush:.4} m passes the previous peak; loading")
            }
            2 => {
                self.in_contact = false;
                self.separated_at = Some(t);
                format!("separation at crush {crush:.4} m")
            }
            3 => {
                self.in_contact = true;
                self.separated_at = None;
                format!("contact at crush {crush:.4} m")
            }
            k => self.cross_kink(k, delta, rate),
        })
    }

    /// Back to the undeformed, loading state, in contact or not as the
    /// state the run starts in, with input arguments `args`, says: in contact
    /// when the gap is closed and the barrier would push (see
    /// [`CrushElement::event_values`]). Without arguments (its force is not
    /// called by the dynamics, so it has no events) it starts at rest.
    fn start(&mut self, args: Option<&[f64]>) -> Result<(), OutOfRange> {
        let args = args.unwrap_or(&[0.0, 0.0]);
        self.phase = Phase::Loading;
        self.in_contact = true;
        self.separated_at = None;
        let (delta, rate) = self.crush(args);
        self.hold_segments(delta, rate);
        if self.contact_only {
            self.in_contact = self.closing(delta, rate)? >= 0.0;
        }
        Ok(())
    }
}

impl Dissipation for CrushElement {
    /// The power the element absorbs, `P·δ̇`, of which
    /// [`Dissipation::stored_energy`] says what it stores (`energy` module);
    /// NaN where a curve cannot be evaluated (the force then reports it).
    fn dissipated_power(&self, args: &[f64]) -> f64 {
        self.absorbed_power(args).unwrap_or(f64::NAN)
    }

    /// In contact, the energy of the unloading line (plastic unloading) or
    /// `∫₀^δ S dx` (elastic, or under tension); 0 separated.
    fn stored_energy(&self, args: &[f64]) -> Result<f64, OutOfRange> {
        self.stored(args)
    }
}

/// `[components.NAME]` with `type = "crush"`: the element's loading curve
/// (one of two forms), damper, gap, unloading and contact, and the inputs
/// it supplies (force and, optionally, its tangent stiffness and damping).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct CrushSection {
    inputs: Ports,
    compression: String,
    stiffness_breakpoints: Option<Vec<f64>>,
    stiffness_values: Option<Vec<f64>>,
    force_breakpoints: Option<Vec<f64>>,
    force_values: Option<Vec<f64>>,
    damping_breakpoints: Vec<f64>,
    damping_values: Vec<f64>,
    #[serde(default)]
    gap: f64,
    #[serde(default = "elastic")]
    unloading: String,
    unloading_stiffness: Option<f64>,
    #[serde(default = "yes")]
    contact_only: bool,
    #[serde(default = "hold")]
    outside: String,
    #[serde(default = "yes")]
    stop_at_kinks: bool,
}

impl super::SectionUnits for CrushSection {
    const UNITS: &'static [(&'static str, super::Measure)] = {
        use super::Measure::One;
        &[
            ("stiffness_breakpoints", One("m")),
            ("stiffness_values", One("N/m")),
            ("force_breakpoints", One("m")),
            ("force_values", One("N")),
            ("damping_breakpoints", One("m/s")),
            ("damping_values", One("N*s/m")),
            ("gap", One("m")),
            ("unloading_stiffness", One("N/m")),
        ]
    };
}

fn elastic() -> String {
    "elastic".into()
}
fn yes() -> bool {
    true
}
fn hold() -> String {
    "hold".into()
}

impl Section for CrushSection {
    fn build(&self, name: &str, binder: &mut Binder) -> Result<(), EntryError> {
        let element = self.element(name)?;
        let c = binder.add(name.to_string(), Box::new(element));
        binder.bind_ports(&self.inputs, "force", c, name)
    }
}

/// The keys of the loading curve's secant stiffness form.
const SECANT: [&str; 2] = ["stiffness_breakpoints", "stiffness_values"];
/// The keys of the loading curve's force–deflection form.
const FORCE: [&str; 2] = ["force_breakpoints", "force_values"];

impl CrushSection {
    /// The element `[components.{name}]` describes.
    fn element(&self, name: &str) -> Result<CrushElement, EntryError> {
        let policy = outside(&format!("components.{name}"), &self.outside)?;
        let damping = SecantCurve::new(&self.damping_breakpoints, &self.damping_values, policy)
            .map_err(|e| table_error(name, ["damping_breakpoints", "damping_values"], &e))?;
        let loading = self.loading(name, policy)?;
        let unloading = self.unloading(name)?;
        check_unloading(name, &loading, unloading)?;
        let element = CrushElement::new(
            loading,
            damping,
            unloading,
            self.compression_sign(name)?,
            self.contact_only,
        );
        let element = element.with_stop_at_kinks(self.stop_at_kinks);
        Ok(element.with_gap(self.gap(name)?))
    }

    /// The loading curve, from the one form the section gives.
    fn loading(&self, name: &str, policy: Outside) -> Result<LoadingCurve, EntryError> {
        let secant = [&self.stiffness_breakpoints, &self.stiffness_values];
        let force = [&self.force_breakpoints, &self.force_values];
        let given = |lists: [&Option<Vec<f64>>; 2]| lists.iter().any(|l| l.is_some());
        match (given(secant), given(force)) {
            (true, true) => Err(EntryError::at(
                KeyPath::component(name),
                format!(
                    "{} (a secant stiffness curve) and {} (a force–deflection curve) are two forms of the spring's loading curve; give one of them",
                    SECANT.join(", "),
                    FORCE.join(", ")
                ),
            )),
            (false, false) => Err(EntryError::at(
                KeyPath::component(name),
                format!(
                    "the spring's loading curve is missing: give {} (a force–deflection curve) or {} (a secant stiffness curve, F = k(δ)·δ)",
                    FORCE.join(" and "),
                    SECANT.join(" and ")
                ),
            )),
            (true, false) => {
                let (b, v) = both(name, SECANT, secant)?;
                let curve = SecantCurve::new(b, v, policy);
                curve
                    .map(LoadingCurve::SecantStiffness)
                    .map_err(|e| table_error(name, SECANT, &e))
            }
            (false, true) => {
                let (b, v) = both(name, FORCE, force)?;
                let curve = ForceCurve::new(b, v, policy);
                curve
                    .map(LoadingCurve::ForceDeflection)
                    .map_err(|e| table_error(name, FORCE, &e))
            }
        }
    }

    /// The gap: finite, ≥ 0, and only for a compression-only element.
    fn gap(&self, name: &str) -> Result<f64, EntryError> {
        let gap = non_negative(format!("components.{name}.gap"), self.gap)?;
        if gap > 0.0 && !self.contact_only {
            return Err(EntryError::sentence(
                KeyPath::component(name).join("gap"),
                format!(
                    "= {gap} needs contact_only = true: an element that pulls has no gap to open"
                ),
            ));
        }
        Ok(gap)
    }

    fn unloading(&self, name: &str) -> Result<Unloading, EntryError> {
        match (self.unloading.as_str(), self.unloading_stiffness) {
            ("elastic", _) => Ok(Unloading::Elastic),
            ("plastic", Some(k)) if k > 0.0 && k.is_finite() => {
                Ok(Unloading::Plastic { stiffness: k })
            }
            ("plastic", _) => Err(EntryError::at(
                KeyPath::component(name),
                "plastic unloading needs a positive unloading_stiffness [N/m]",
            )),
            (other, _) => Err(EntryError::at(
                KeyPath::component(name),
                format!("unloading = `{other}`; use elastic or plastic"),
            )),
        }
    }

    fn compression_sign(&self, name: &str) -> Result<f64, EntryError> {
        match self.compression.as_str() {
            "positive" => Ok(1.0),
            "negative" => Ok(-1.0),
            other => Err(EntryError::at(
                KeyPath::component(name),
                format!(
                    "compression = `{other}`; use positive or negative (the sign of the input's first argument under compression)"
                ),
            )),
        }
    }
}

/// Plastic unloading at least as stiff as the loading curve's tangent
/// wherever the spring pushes: loading dissipates `S·δ̇·(1 − S′/k_u)`
/// ([`energy`]), so where `S′ > k_u` the unloading line would give back
/// more than loading stored and the dissipated energy would fall, below
/// zero in the end.
fn check_unloading(
    name: &str,
    loading: &LoadingCurve,
    unloading: Unloading,
) -> Result<(), EntryError> {
    let Unloading::Plastic { stiffness } = unloading else {
        return Ok(());
    };
    let Some((delta, tangent)) = stiffest(loading) else {
        return Ok(());
    };
    if tangent <= stiffness {
        return Ok(());
    }
    Err(EntryError::at(
        KeyPath::component(name),
        format!(
            "unloading_stiffness = {stiffness:e} N/m is softer than the loading \
         curve, whose tangent stiffness is {tangent:.4e} N/m at a deflection of {delta:.4} m: \
         unloading from there would return more energy than loading stored (a negative \
         dissipated energy); plastic unloading needs an unloading_stiffness of at least \
         {tangent:.4e} N/m"
        ),
    ))
}

/// The deflection and the tangent stiffness `S′` of the loading curve's
/// stiffest point where it pushes (`S > 0`), the first of equals: sampled
/// at the start of each of its segments, 15 points within and just
/// before its end, and half its last breakpoint beyond it; `None` if it
/// pushes nowhere.
fn stiffest(loading: &LoadingCurve) -> Option<(f64, f64)> {
    let xs = loading.curve().xs();
    let last = xs[xs.len() - 1];
    let within = xs.windows(2).flat_map(|w| {
        let (a, h) = (w[0], w[1] - w[0]);
        (0..=16).map(move |j| a + h * (j as f64 / 16.0).min(1.0 - 1e-9))
    });
    let points = within.chain([1.5 * last]);
    points
        .filter_map(|delta| {
            let (force, tangent) = loading.force(delta).ok()?;
            (force > 0.0 && tangent.is_finite()).then_some((delta, tangent))
        })
        .fold(None, |best: Option<(f64, f64)>, p| match best {
            Some(b) if b.1 >= p.1 => Some(b),
            _ => Some(p),
        })
}

/// The breakpoints and values of a table whose keys are `keys`, both given.
fn both<'a>(
    name: &str,
    keys: [&str; 2],
    lists: [&'a Option<Vec<f64>>; 2],
) -> Result<(&'a [f64], &'a [f64]), EntryError> {
    let at = |k: usize| KeyPath::component(name).join(keys[k]);
    match lists {
        [Some(b), Some(v)] => Ok((b, v)),
        [Some(_), None] => Err(EntryError::sentence(
            at(1),
            format!("is missing: {} needs its values", keys[0]),
        )),
        [None, _] => Err(EntryError::sentence(
            at(0),
            format!("is missing: {} needs its breakpoints", keys[1]),
        )),
    }
}

/// A table's problem, at the key of the list it is in.
fn table_error(name: &str, keys: [&str; 2], e: &TableError) -> EntryError {
    let key = keys[usize::from(e.in_values())];
    EntryError::at(KeyPath::component(name).join(key), e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn element(unloading: Unloading) -> CrushElement {
        let k = SecantCurve::new(&[0.1, 0.5], &[1.0e6, 2.0e6, 1.0e6], Outside::Hold).unwrap();
        let loading = LoadingCurve::SecantStiffness(k);
        CrushElement::new(loading, SecantCurve::constant(1.0e3), unloading, -1.0, true)
    }

    /// A force–deflection curve of slopes 1e6 then 3e6 N/m (1e5 N at
    /// 0.1 m, 4e5 N at 0.2 m): plastic unloading at 2e6 N/m would give
    /// back S²/(2 k_u) = 4e4 J from 0.2 m, where loading stored
    /// 5e3 + 2.5e4 = 3e4 J; at 3e6 N/m it gives 2.67e4 J.
    #[test]
    fn plastic_unloading_softer_than_the_loading_curve_is_refused() {
        let curve = ForceCurve::new(&[0.1, 0.2], &[1.0e5, 4.0e5], Outside::Hold).unwrap();
        let loading = LoadingCurve::ForceDeflection(curve);
        let (stored, returned) = (
            0.5 * 1e5 * 0.1 + 0.5 * (1e5 + 4e5) * 0.1,
            4e5f64.powi(2) / 4e6,
        );
        assert!(returned > stored, "{returned} vs {stored}");
        let soft = Unloading::Plastic { stiffness: 2.0e6 };
        let e = check_unloading("front", &loading, soft)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with(
                "components.front: unloading_stiffness = 2e6 N/m is softer than the loading curve, \
                 whose tangent stiffness is 3.0000e6 N/m at a deflection of 0.1"
            ),
            "{e}"
        );
        for fine in [Unloading::Plastic { stiffness: 3.0e6 }, Unloading::Elastic] {
            assert_eq!(check_unloading("front", &loading, fine), Ok(()));
        }
        // The paper's secant curve (k falling from 2.4e6 N/m) and its 3e7 N/m.
        let k = SecantCurve::new(
            &[0.05, 0.10, 0.25, 0.45, 0.60, 0.80],
            &[2.4e6, 2.4e6, 2.1e6, 0.94e6, 0.567e6, 0.50e6, 0.5625e6],
            Outside::Hold,
        )
        .unwrap();
        let paper = LoadingCurve::SecantStiffness(k);
        let (_, tangent) = stiffest(&paper).unwrap();
        assert!((tangent - 2.4e6).abs() < 1.0, "{tangent}");
        assert_eq!(
            check_unloading("front_end", &paper, Unloading::Plastic { stiffness: 3.0e7 }),
            Ok(())
        );
    }

    #[test]
    fn loading_follows_eqs_1_and_2_with_the_paper_sign() {
        let e = element(Unloading::Elastic);
        // r = −0.1 (0.1 m of crush), ṙ = −2: F = k(0.1)·r + c·ṙ.
        let f = e.force(&[-0.1, -2.0]).unwrap();
        assert!((f - (2.0e6 * -0.1 + 1.0e3 * -2.0)).abs() < 1e-6, "{f}");
        assert_eq!(e.force_damping(&[-0.1, -2.0]).unwrap(), 1.0e3);
    }

    #[test]
    fn plastic_unloading_leaves_a_permanent_set_and_separates() {
        let mut e = element(Unloading::Plastic { stiffness: 1.0e8 });
        let mut g = [0.0; 8];
        // At the peak the crush rate passes zero: event 0.
        e.event_values(&[-0.3, 0.0], &mut g).unwrap();
        assert_eq!(g[0], 0.0);
        let note = e.on_event(0, 0.0, &[-0.3, 0.0]).unwrap();
        assert!(note.contains("peak crush 0.3000 m"), "{note}");
        let peak_force = 1.5e6 * 0.3; // k(0.3) = 1.5e6 N/m
        let set = e.permanent_set().unwrap();
        assert!((set - (0.3 - peak_force / 1.0e8)).abs() < 1e-12);
        // Unloading is steep: 1 mm back leaves S = 450 kN − 100 kN.
        let f = e.force(&[-0.299, 0.0]).unwrap();
        assert!((f + (peak_force - 1.0e8 * 0.001)).abs() < 1e-6, "{f}");
        // Below the permanent set, S + D < 0: the separation event function is negative.
        e.event_values(&[-(set - 1e-4), 1.0], &mut g).unwrap();
        assert!(g[2] < 0.0);
        e.on_event(2, 0.0, &[-(set - 1e-4), 1.0]).unwrap();
        assert_eq!(e.force(&[-(set - 1e-4), 1.0]).unwrap(), 0.0);
    }

    #[test]
    fn a_run_that_starts_with_a_gap_starts_separated_until_the_gap_closes() {
        // compression_sign = −1: crush δ = −r; r = 0.05 is a gap of 5 cm.
        let mut e = element(Unloading::Elastic);
        e.start(Some(&[0.05, -15.0])).unwrap();
        assert!(!e.in_contact());
        assert_eq!(e.force(&[0.05, -15.0]).unwrap(), 0.0);
        // The contact function is the gap (δ − 0) until it closes, although
        // the damper alone would push already (S + D > 0 at 1 mm).
        let mut g = [0.0; 8];
        e.event_values(&[0.001, -15.0], &mut g).unwrap();
        assert_eq!((g[2], g[3]), (1.0, -0.001));
        e.event_values(&[-0.001, -15.0], &mut g).unwrap();
        assert!(g[3] > 0.0);
        // Touching the barrier and closing in, or resting against it: in contact.
        e.start(Some(&[0.0, -15.0])).unwrap();
        assert!(e.in_contact());
        e.start(Some(&[0.0, 0.0])).unwrap();
        assert!(e.in_contact());
        // Pressed in but moving away so fast that S + D < 0: separated.
        e.start(Some(&[-0.001, 100.0])).unwrap();
        assert!(!e.in_contact());
    }

    /// The test curve (0, 0), (0.1 m, 170 kN), (0.5 m, 180 kN), no damping,
    /// compression positive, with a gap.
    fn tested(gap: f64, unloading: Unloading) -> CrushElement {
        let f = ForceCurve::new(&[0.1, 0.5], &[170e3, 180e3], Outside::Hold).unwrap();
        let loading = LoadingCurve::ForceDeflection(f);
        CrushElement::new(loading, SecantCurve::constant(0.0), unloading, 1.0, true).with_gap(gap)
    }

    #[test]
    fn a_force_deflection_curve_gives_its_force_and_its_segment_slope() {
        let e = tested(0.0, Unloading::Elastic);
        // 0.3 m: halfway between 170 and 180 kN; slope 10 kN / 0.4 m.
        assert!((e.force(&[0.3, 0.0]).unwrap() - 175e3).abs() < 1e-9);
        assert!((e.force_stiffness(&[0.3, 0.0]).unwrap() - 25e3).abs() < 1e-9);
        assert!((e.force_stiffness(&[0.05, 0.0]).unwrap() - 1.7e6).abs() < 1e-6);
        let mut columns = [0.0; 2];
        e.column_values(&[0.3, 0.0], &mut columns).unwrap();
        assert!((columns[0] - 175e3).abs() < 1e-9 && columns[1] == 0.3);
        assert_eq!(e.report().force_deflection, Some((0, 1)));
        // Compression negative (the paper's r < 0): the input's force is
        // −P, its derivative the same slope; the columns stay compression
        // positive.
        let negative = CrushElement {
            compression_sign: -1.0,
            ..e
        };
        assert!((negative.force(&[-0.3, 0.0]).unwrap() + 175e3).abs() < 1e-9);
        assert!((negative.force_stiffness(&[-0.3, 0.0]).unwrap() - 25e3).abs() < 1e-9);
        negative.column_values(&[-0.3, 0.0], &mut columns).unwrap();
        assert!((columns[0] - 175e3).abs() < 1e-9 && columns[1] == 0.3);
    }

    #[test]
    fn a_gap_delays_the_contact_and_the_curve_starts_there() {
        let mut e = tested(0.05, Unloading::Plastic { stiffness: 1.0e7 });
        // 2 cm of crush, closing: the gap is still open, no force.
        e.start(Some(&[0.02, 10.0])).unwrap();
        assert!(!e.in_contact());
        assert_eq!(e.force(&[0.02, 10.0]).unwrap(), 0.0);
        let mut columns = [0.0; 2];
        e.column_values(&[0.02, 10.0], &mut columns).unwrap();
        assert_eq!(columns, [0.0, 0.02 - 0.05]);
        // The contact function changes sign where the crush passes the gap.
        let mut g = [0.0; 8];
        e.event_values(&[0.049, 10.0], &mut g).unwrap();
        assert!(g[3] < 0.0);
        e.event_values(&[0.051, 10.0], &mut g).unwrap();
        assert!((g[3] - 0.001).abs() < 1e-12, "{g:?}");
        e.on_event(3, 0.0, &[0.05, 10.0]).unwrap();
        // The deflection passes the breakpoint at 0.1 m (0.15 m of crush):
        // the kink event, which the integration locates, moves the held
        // segment on.
        e.event_values(&[0.149, 1.0], &mut g).unwrap();
        assert!(g[5] < 0.0);
        e.event_values(&[0.151, 1.0], &mut g).unwrap();
        assert!((g[5] - 0.001).abs() < 1e-12, "{g:?}");
        assert_eq!(e.on_event(5, 0.0, &[0.15, 1.0]).unwrap(), "");
        // 0.35 m of crush is 0.3 m of deflection: 175 kN.
        assert!((e.force(&[0.35, 1.0]).unwrap() - 175e3).abs() < 1e-9);
        // Peak there: the permanent deflection is 0.3 − 175 kN / 10 MN/m.
        let note = e.on_event(0, 0.0, &[0.35, 0.0]).unwrap();
        assert_eq!(note, "peak crush 0.3500 m at 175.0 kN; unloading");
        assert!((e.permanent_set().unwrap() - 0.2825).abs() < 1e-12);
    }

    #[test]
    fn each_event_function_alone_is_the_one_of_all() {
        let mut plastic = element(Unloading::Plastic { stiffness: 1.0e8 });
        let mut gapped = tested(0.05, Unloading::Plastic { stiffness: 1.0e7 });
        gapped.start(Some(&[0.02, 10.0])).unwrap();
        let crushes = [-0.6, -0.3, -0.12, -0.05, 0.0, 0.02, 0.07, 0.2, 0.45];
        let rates = [-16.0, -2.0, 0.0, 0.5, 3.0, 12.0];
        let check = |e: &CrushElement| {
            for x in crushes {
                for v in rates {
                    crate::components::assert_event_value_is_event_values(e, &[x, v]);
                }
            }
        };
        // Loading, in contact, then unloading from a peak, then separated.
        check(&plastic);
        plastic.on_event(0, 0.0, &[-0.3, 0.0]).unwrap();
        check(&plastic);
        plastic.on_event(2, 0.0, &[-0.29, 1.0]).unwrap();
        check(&plastic);
        // A gap still open, then closed past a kink of the curve.
        check(&gapped);
        gapped.on_event(3, 0.0, &[0.05, 10.0]).unwrap();
        gapped.on_event(5, 0.0, &[0.15, 1.0]).unwrap();
        check(&gapped);
        check(&element(Unloading::Elastic).with_stop_at_kinks(false));
    }

    /// The section's element, or its message.
    fn section(text: &str) -> Result<CrushElement, String> {
        let head = "inputs = { force = \"crush\" }\ncompression = \"positive\"\ndamping_breakpoints = [1.0]\ndamping_values = [0.0, 0.0]\n";
        let section: CrushSection = toml::from_str(&format!("{head}{text}")).unwrap();
        section.element("fe").map_err(|e| e.to_string())
    }

    #[test]
    fn the_section_takes_one_form_of_the_loading_curve() {
        let force = "force_breakpoints = [0.1, 0.5]\nforce_values = [170e3, 180e3]\n";
        let secant = "stiffness_breakpoints = [0.1]\nstiffness_values = [1e6, 2e6]\n";
        let e = section(force).unwrap();
        assert!((e.force(&[0.3, 0.0]).unwrap() - 175e3).abs() < 1e-9);
        assert_eq!(e.gap, 0.0);
        let e = section(secant).unwrap();
        assert!((e.force(&[0.05, 0.0]).unwrap() - 1.5e6 * 0.05).abs() < 1e-9);
        assert_eq!(
            section(&format!("{force}{secant}")).unwrap_err(),
            "components.fe: stiffness_breakpoints, stiffness_values (a secant stiffness curve) and force_breakpoints, force_values (a force–deflection curve) are two forms of the spring's loading curve; give one of them"
        );
        assert_eq!(
            section(&format!("{force}stiffness_values = [1.0]\n")).unwrap_err(),
            section(&format!("{force}{secant}")).unwrap_err()
        );
        assert!(section("").unwrap_err().starts_with(
            "components.fe: the spring's loading curve is missing: give force_breakpoints and force_values"
        ));
        assert_eq!(
            section("force_breakpoints = [0.1]\n").unwrap_err(),
            "components.fe.force_values is missing: force_breakpoints needs its values"
        );
    }

    #[test]
    fn bad_tables_and_gaps_are_reported_at_their_key() {
        let cases = [
            (
                "force_breakpoints = [0.1, 0.1]\nforce_values = [1.0, 2.0]\n",
                "components.fe.force_breakpoints: breakpoint 2 (0.1) must be finite and exceed breakpoint 1 (0.1): breakpoints increase strictly",
            ),
            (
                "force_breakpoints = [0.0, 0.1]\nforce_values = [0.0, 2.0]\n",
                "components.fe.force_breakpoints: breakpoint 1 (0) must be a positive, finite number (the curve starts at 0)",
            ),
            (
                "force_breakpoints = [0.1]\nforce_values = [1.0, 2.0]\n",
                "components.fe.force_values: 1 breakpoint needs 1 value, found 2",
            ),
            (
                "stiffness_breakpoints = [0.1]\nstiffness_values = [1.0, -2.0]\n",
                "components.fe.stiffness_values: value 2 (-2) must be a finite number ≥ 0",
            ),
            (
                "force_breakpoints = [0.1]\nforce_values = [1.0]\ngap = -0.01\n",
                "components.fe.gap = -0.01: must be a finite number ≥ 0",
            ),
            (
                "force_breakpoints = [0.1]\nforce_values = [1.0]\ngap = nan\n",
                "components.fe.gap = NaN: must be a finite number ≥ 0",
            ),
            (
                "force_breakpoints = [0.1]\nforce_values = [1.0]\ngap = 0.02\ncontact_only = false\n",
                "components.fe.gap = 0.02 needs contact_only = true: an element that pulls has no gap to open",
            ),
        ];
        for (text, message) in cases {
            assert_eq!(section(text).unwrap_err(), message, "{text}");
        }
        let e = section("force_breakpoints = [0.1]\nforce_values = [1.0]\ngap = 0.02\n").unwrap();
        assert_eq!(e.gap, 0.02);
    }
}
