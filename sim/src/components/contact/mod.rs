//! A contact that pushes only, with a force law cited by name: a linear
//! spring–dashpot, Anagnostopoulos, Hunt–Crossley, Lankarani–Nikravesh or
//! Flores et al.
//!
//! In terms of the penetration `δ` (compression positive) and its rate
//! `δ̇`, every law is a case of
//!
//! `P = k·δⁿ + c·δ̇ + k·D·δⁿ·δ̇ / v₀`
//!
//! ([`ContactForce`]): a spring `k·δⁿ`, a linear dashpot `c` and a
//! hysteresis damping whose factor `D` each law derives from the requested
//! coefficient of restitution `e`, scaled by the impact velocity `v₀` (the
//! penetration rate when the contact began). Each law is one file of this
//! folder, behind [`ContactLaw`], registered in [`LAWS`].
//!
//! The contact begins at `δ = 0` and pushes only: in contact the force is
//! `P` until `P` falls to 0 (separation, which may come before `δ` is back
//! at 0: a damper that would pull lets go); separated it is 0 until `δ`
//! reaches 0 again with `P ≥ 0` (contact, where `v₀` is taken). Both are
//! events of the integration, so the force is smooth within a step. Its
//! force, penetration and dissipated power are trajectory columns
//! (`NAME.force \[N\]`, `NAME.penetration [m]`, `NAME.power \[W\]`).
//!
//! The `NAME.power` column is the damping's power, `(c + k·D·δⁿ/v₀)·δ̇²`.
//! The energy it reports as dissipated is the work it absorbs, `∫ P·δ̇ dt`,
//! less what its spring still stores, `k·δ^(n+1)/(n+1)` in contact
//! ([`Dissipation::stored_energy`]): the damping's work, plus, for a contact
//! that lets go with `δ > 0` (the linear laws), the spring energy it holds
//! then, lost as the wall relaxes out of contact.
//!
//! Its scenario section is `type = "contact"` (`ContactSection`), with
//! `law = "hunt_crossley"` (or another law's name), `stiffness`,
//! `restitution`, `exponent` for the laws with a power of `δ`, `mass` for
//! those whose damping follows from the oscillator's, and
//! `min_impact_velocity` (default 1 mm/s), the least `v₀` — a contact that
//! begins at rest would otherwise have an unbounded hysteresis damping.

mod anagnostopoulos;
mod flores;
mod hunt_crossley;
mod lankarani_nikravesh;
mod linear;

use super::{Binder, Column, Component, Contact, Event, Port, Report, Section};
use crate::components::section::Ports;
use crate::components::{Dissipation, Events};
use crate::curve::OutOfRange;
use crate::entry::positive;
use crate::entry::{EntryError, KeyPath};
use crate::ode::Direction;
use serde::Deserialize;

/// A contact law: how its force follows from the section's entries.
pub trait ContactLaw: Sync {
    /// The law's name, as `law = "NAME"` writes it.
    fn name(&self) -> &'static str;

    /// The optional entries it reads, of `exponent` and `mass`; a section
    /// that gives another is refused.
    fn reads(&self) -> &'static [&'static str];

    /// The force for the checked `entries` of section
    /// `[components.{name}]`, or a message naming the entry at fault.
    fn force(&self, entries: &LawEntries, name: &str) -> Result<ContactForce, EntryError>;
}

/// The laws, by name: one line per law.
pub const LAWS: &[&dyn ContactLaw] = &[
    &linear::Linear,
    &anagnostopoulos::Anagnostopoulos,
    &hunt_crossley::HuntCrossley,
    &lankarani_nikravesh::LankaraniNikravesh,
    &flores::Flores,
];

/// The entries of a contact section a law reads, checked: `stiffness`
/// positive, `restitution` in [0, 1], `exponent` ≥ 1 and `mass` positive
/// when given.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LawEntries {
    /// `k` [N/mⁿ].
    pub stiffness: f64,
    /// The requested coefficient of restitution `e`.
    pub restitution: f64,
    /// `n`, if given.
    pub exponent: Option<f64>,
    /// The effective mass `m₁·m₂/(m₁ + m₂)` of the bodies in contact \[kg\],
    /// if given.
    pub mass: Option<f64>,
}

/// The exponent of the laws with a power of `δ` when the section gives
/// none: Hertz's, for spheres.
pub const HERTZ_EXPONENT: f64 = 1.5;

impl LawEntries {
    /// The exponent given, or Hertz's.
    pub fn exponent_or_hertz(&self) -> f64 {
        self.exponent.unwrap_or(HERTZ_EXPONENT)
    }

    /// The mass, which law `law` of section `[components.{name}]` needs.
    pub fn needed_mass(&self, law: &str, name: &str) -> Result<f64, EntryError> {
        self.mass.ok_or_else(|| {
            EntryError::sentence(KeyPath::component(name).join("mass"), format!(
                "is missing: the {law} law's damping follows from the effective mass m₁·m₂/(m₁ + m₂) of the bodies in contact [kg]"
            ))
        })
    }

    /// `e`, which must be positive for law `law` (its damping diverges at 0).
    pub fn positive_restitution(&self, law: &str, name: &str) -> Result<f64, EntryError> {
        let e = self.restitution;
        if e > 0.0 {
            return Ok(e);
        }
        Err(EntryError::value(
            KeyPath::component(name).join("restitution"),
            format!("{e}"),
            format!(
                "the {law} law needs a coefficient of restitution in (0, 1] (its damping is unbounded at 0)"
            ),
        ))
    }
}

/// `P = k·δⁿ + c·δ̇ + k·D·δⁿ·δ̇ / v₀`, the compressive force of every law,
/// extended to `δ < 0` as an odd function of `δ` (`δⁿ` read as
/// `|δ|ⁿ·sign δ`) for the event functions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactForce {
    /// `k` [N/mⁿ].
    pub stiffness: f64,
    /// `n` (≥ 1).
    pub exponent: f64,
    /// The linear dashpot `c` [N·s/m].
    pub viscous: f64,
    /// The hysteresis damping factor `D` (dimensionless).
    pub hysteresis: f64,
}

impl ContactForce {
    /// `(P, ∂P/∂δ, ∂P/∂δ̇)` at penetration `delta`, rate `rate` and impact
    /// velocity `impact` (> 0).
    pub fn eval(&self, delta: f64, rate: f64, impact: f64) -> (f64, f64, f64) {
        let n = self.exponent;
        let power = delta.abs().powf(n).copysign(delta);
        let slope = n * delta.abs().powf(n - 1.0);
        let chi = self.stiffness * self.hysteresis / impact;
        let p = self.stiffness * power + self.viscous * rate + chi * power * rate;
        (
            p,
            (self.stiffness + chi * rate) * slope,
            self.viscous + chi * power,
        )
    }

    /// The dissipative part of `P`, `c·δ̇ + k·D·δⁿ·δ̇ / v₀`, times `δ̇`:
    /// the power its damping dissipates \[W\].
    pub fn damping_power(&self, delta: f64, rate: f64, impact: f64) -> f64 {
        let power = delta.abs().powf(self.exponent).copysign(delta);
        let chi = self.stiffness * self.hysteresis / impact;
        (self.viscous + chi * power) * rate * rate
    }
}

/// The contact and its state during a run.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactElement {
    /// The law's name, for messages.
    pub law: &'static str,
    /// Its force.
    pub force: ContactForce,
    /// `+1` if compression is a positive input argument, `−1` if negative.
    pub compression_sign: f64,
    /// The least impact velocity `v₀` [m/s].
    pub min_impact_velocity: f64,
    in_contact: bool,
    impact_velocity: f64,
    separated_at: Option<f64>,
}

/// The contact's events, in index order (see [`ContactElement::event_values`]).
const EVENTS: &[Event] = &[
    Event {
        name: "separation",
        direction: Direction::Falling,
    },
    Event {
        name: "contact",
        direction: Direction::Rising,
    },
];

/// The contact's columns: its compressive force, penetration and the
/// power its damping dissipates.
const COLUMNS: &[Column] = &[
    Column {
        quantity: "force",
        unit: "N",
    },
    Column {
        quantity: "penetration",
        unit: "m",
    },
    Column {
        quantity: "power",
        unit: "W",
    },
];

impl ContactElement {
    /// A contact with force `force` of law `law`, in contact, whose impact
    /// velocity is `min_impact_velocity` until a run starts.
    pub fn new(
        law: &'static str,
        force: ContactForce,
        compression_sign: f64,
        min_impact_velocity: f64,
    ) -> ContactElement {
        ContactElement {
            law,
            force,
            compression_sign,
            min_impact_velocity,
            in_contact: true,
            impact_velocity: min_impact_velocity,
            separated_at: None,
        }
    }

    /// Whether it is in contact.
    pub fn in_contact(&self) -> bool {
        self.in_contact
    }

    /// The impact velocity `v₀` of the current (or last) contact [m/s].
    pub fn impact_velocity(&self) -> f64 {
        self.impact_velocity
    }

    /// The penetration `δ` and its rate from the input's arguments.
    fn penetration(&self, args: &[f64]) -> (f64, f64) {
        (
            self.compression_sign * args[0],
            self.compression_sign * args[1],
        )
    }

    /// `(P, ∂P/∂δ, ∂P/∂δ̇)` as if in contact.
    fn law_force(&self, delta: f64, rate: f64) -> (f64, f64, f64) {
        self.force.eval(delta, rate, self.impact_velocity)
    }

    /// `min(δ, P)`: non-negative once `δ` reached 0 with the law pushing.
    fn closing(&self, delta: f64, rate: f64) -> f64 {
        delta.min(self.law_force(delta, rate).0)
    }

    /// `(P, ∂P/∂δ, ∂P/∂δ̇)`: the compressive force, 0 out of contact.
    fn compressive(&self, args: &[f64]) -> (f64, f64, f64) {
        if !self.in_contact {
            return (0.0, 0.0, 0.0);
        }
        let (delta, rate) = self.penetration(args);
        self.law_force(delta, rate)
    }

    /// The power its damping dissipates at the input's arguments \[W\]: 0 out
    /// of contact.
    pub fn power(&self, args: &[f64]) -> f64 {
        if !self.in_contact {
            return 0.0;
        }
        let (delta, rate) = self.penetration(args);
        self.force.damping_power(delta, rate, self.impact_velocity)
    }

    /// Starts a contact at penetration rate `rate`: its impact velocity.
    fn touch(&mut self, rate: f64) {
        self.in_contact = true;
        self.separated_at = None;
        self.impact_velocity = rate.max(self.min_impact_velocity);
    }
}

impl Component for ContactElement {
    fn kind(&self) -> &'static str {
        "contact"
    }

    fn arguments(&self) -> Option<(usize, &'static str)> {
        Some((2, "the penetration coordinate and its rate"))
    }

    /// `±P` in the sign convention of the input's argument; its derivatives.
    fn value(&self, port: Port, args: &[f64]) -> Result<f64, OutOfRange> {
        let (p, dp, dc) = self.compressive(args);
        Ok(match port {
            Port::Value => self.compression_sign * p,
            Port::Stiffness => dp,
            Port::Damping => dc,
        })
    }

    capabilities!(events: yes, states: no, energy: yes);

    fn columns(&self) -> &'static [Column] {
        COLUMNS
    }

    /// The compressive force `P`, the penetration `δ` and the dissipated power.
    fn column_values(&self, args: &[f64], out: &mut [f64]) -> Result<(), OutOfRange> {
        out[0] = self.compressive(args).0;
        out[1] = self.penetration(args).0;
        out[2] = self.power(args);
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
}

impl Events for ContactElement {
    fn list(&self) -> &'static [Event] {
        EVENTS
    }

    /// 0. separation (in contact): `P`, falling;
    /// 1. contact (separated): `min(δ, P)`, rising.
    fn event_values(&self, args: &[f64], g: &mut [f64]) -> Result<(), OutOfRange> {
        let (delta, rate) = self.penetration(args);
        g[0] = match self.in_contact {
            true => self.law_force(delta, rate).0,
            false => 1.0,
        };
        g[1] = match self.in_contact {
            true => -1.0,
            false => self.closing(delta, rate),
        };
        Ok(())
    }

    fn on_event(&mut self, k: usize, t: f64, args: &[f64]) -> Result<String, OutOfRange> {
        let (delta, rate) = self.penetration(args);
        if k == 0 {
            self.in_contact = false;
            self.separated_at = Some(t);
            return Ok(format!(
                "separation at penetration {delta:.4e} m, leaving at {:.4} m/s",
                -rate
            ));
        }
        self.touch(rate);
        Ok(format!(
            "contact ({} law) at {:.4} m/s",
            self.law, self.impact_velocity
        ))
    }

    /// In contact when `δ ≥ 0` and the law pushes, with the impact
    /// velocity `δ̇` (at least the least); separated otherwise.
    fn start(&mut self, args: Option<&[f64]>) -> Result<(), OutOfRange> {
        let (delta, rate) = self.penetration(args.unwrap_or(&[0.0, 0.0]));
        self.touch(rate);
        self.in_contact = self.closing(delta, rate) >= 0.0;
        Ok(())
    }
}

impl Dissipation for ContactElement {
    /// The power it absorbs, `P·δ̇`; 0 out of contact.
    fn dissipated_power(&self, args: &[f64]) -> f64 {
        let (force, _, _) = self.compressive(args);
        force * self.penetration(args).1
    }

    /// Its spring's energy `k·|δ|^(n+1)/(n+1)` in contact; 0 out of it.
    fn stored_energy(&self, args: &[f64]) -> Result<f64, OutOfRange> {
        if !self.in_contact {
            return Ok(0.0);
        }
        let delta = self.penetration(args).0.abs();
        let n = self.force.exponent;
        Ok(self.force.stiffness * delta.powf(n + 1.0) / (n + 1.0))
    }
}

/// `[components.NAME]` with `type = "contact"`: the law and its entries,
/// the sign of compression and the inputs it supplies (force and,
/// optionally, its tangent stiffness and damping).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ContactSection {
    inputs: Ports,
    law: String,
    compression: String,
    stiffness: f64,
    restitution: f64,
    exponent: Option<f64>,
    mass: Option<f64>,
    #[serde(default = "one_millimetre_per_second")]
    min_impact_velocity: f64,
}

impl super::SectionUnits for ContactSection {
    const UNITS: &'static [(&'static str, super::Measure)] = {
        use super::Measure::One;
        &[("mass", One("kg")), ("min_impact_velocity", One("m/s"))]
    };
}

fn one_millimetre_per_second() -> f64 {
    1e-3
}

impl Section for ContactSection {
    fn build(&self, name: &str, binder: &mut Binder) -> Result<(), EntryError> {
        let element = self.element(name)?;
        let c = binder.add(name.to_string(), Box::new(element));
        binder.bind_ports(&self.inputs, "force", c, name)
    }
}

impl ContactSection {
    /// The contact `[components.{name}]` describes.
    fn element(&self, name: &str) -> Result<ContactElement, EntryError> {
        let key = |entry: &str| format!("components.{name}.{entry}");
        let law = law(&self.law, &key("law"))?;
        self.refuse_unread(law, name)?;
        let entries = LawEntries {
            stiffness: positive(key("stiffness"), self.stiffness)?,
            restitution: restitution(&key("restitution"), self.restitution)?,
            exponent: self
                .exponent
                .map(|n| exponent(&key("exponent"), n))
                .transpose()?,
            mass: self.mass.map(|m| positive(key("mass"), m)).transpose()?,
        };
        let v_min = positive(key("min_impact_velocity"), self.min_impact_velocity)?;
        let force = law.force(&entries, name)?;
        let sign = compression_sign(&key("compression"), &self.compression)?;
        Ok(ContactElement::new(law.name(), force, sign, v_min))
    }

    /// An error for an optional entry given that `law` does not read.
    fn refuse_unread(&self, law: &dyn ContactLaw, name: &str) -> Result<(), EntryError> {
        let given = [("exponent", self.exponent), ("mass", self.mass)];
        for (entry, value) in given {
            if let Some(value) = value
                && !law.reads().contains(&entry)
            {
                return Err(EntryError::value(
                    KeyPath::component(name).join(entry),
                    format!("{value}"),
                    format!("the {} law takes no {entry}", law.name()),
                ));
            }
        }
        Ok(())
    }
}

/// The law named `text` at `key`, or an error listing the laws.
fn law(text: &str, key: &str) -> Result<&'static dyn ContactLaw, EntryError> {
    if let Some(law) = LAWS.iter().find(|law| law.name() == text) {
        return Ok(*law);
    }
    let names: Vec<&str> = LAWS.iter().map(|law| law.name()).collect();
    let hint = lagrangian_runtime::names::closest(text, names.iter().copied())
        .map(|n| format!(" (did you mean `{n}`?)"))
        .unwrap_or_default();
    Err(EntryError::text(
        key.into(),
        text,
        format!("not a contact law{hint}; use one of {}", names.join(", ")),
    ))
}

/// `e` if it is in [0, 1]; else an error naming `key`.
fn restitution(key: &str, e: f64) -> Result<f64, EntryError> {
    if (0.0..=1.0).contains(&e) {
        return Ok(e);
    }
    Err(EntryError::value(
        key.into(),
        format!("{e}"),
        "a coefficient of restitution is in [0, 1] (1: elastic, 0: no rebound)",
    ))
}

/// `n` if it is finite and at least 1; else an error naming `key`.
fn exponent(key: &str, n: f64) -> Result<f64, EntryError> {
    if n.is_finite() && n >= 1.0 {
        return Ok(n);
    }
    Err(EntryError::value(
        key.into(),
        format!("{n}"),
        "the exponent must be a finite number ≥ 1 (1: linear, 1.5: Hertz)",
    ))
}

/// `+1` for `positive`, `−1` for `negative`.
fn compression_sign(key: &str, text: &str) -> Result<f64, EntryError> {
    match text {
        "positive" => Ok(1.0),
        "negative" => Ok(-1.0),
        other => Err(EntryError::sentence(
            key.into(),
            format!(
                "= `{other}`; use positive or negative (the sign of the input's first argument under compression)"
            ),
        )),
    }
}
