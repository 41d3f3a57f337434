//! Coulomb friction with an event-switched stick: the body sticks while
//! the force applied along the surface stays within the static limit, and
//! slides against the kinetic friction otherwise (Coulomb, C. A., 1785;
//! the switching of Karnopp, D., 1985, "Computer simulation of stick-slip
//! friction in mechanical dynamic systems", Journal of Dynamic Systems,
//! Measurement, and Control 107: 100–103, with events in place of his
//! velocity band).
//!
//! Its input takes the sliding velocity `v` and the force `F_a` applied
//! along it (everything but this friction), and gives the friction force
//! in the sign of `v` (the model subtracts it):
//!
//! * sticking: `F = F_a`, so the body stays at rest, until `|F_a|` reaches
//!   `μ_s·N` (event: breakaway, sliding the way `F_a` pushes);
//! * sliding in direction `s = ±1`: `F = s·μ_k·N` until `v` is back at 0
//!   (event: it sticks there if `|F_a| ≤ μ_s·N`, else slides the other way).
//!
//! Its force and the power it dissipates, `F·v`, are trajectory columns
//! (`NAME.force \[N\]`, `NAME.power \[W\]`).
//!
//! Its scenario section is `type = "stick_slip"` (`StickSlipSection`):
//! `coefficient` `μ_k`, `static_coefficient` `μ_s ≥ μ_k` (default `μ_k`)
//! and `normal_force` `N` \[N\].

use super::curve::OutOfRange;
use super::{Binder, Column, Component, Event, Port, Section};
use crate::ode::Direction;
use crate::scenario::bind::{Ports, non_negative};
use serde::Deserialize;

/// The friction and its state during a run.
#[derive(Clone, Debug, PartialEq)]
pub struct StickSlip {
    /// `μ_k`.
    pub kinetic: f64,
    /// `μ_s ≥ μ_k`.
    pub stiction: f64,
    /// `N` \[N\].
    pub normal_force: f64,
    /// `None`: sticking; `Some(s)`: sliding in direction `s = ±1`.
    sliding: Option<f64>,
}

/// Its events: breakaway while sticking, stop while sliding.
const EVENTS: &[Event] = &[
    Event {
        name: "breakaway",
        direction: Direction::Rising,
    },
    Event {
        name: "stop",
        direction: Direction::Falling,
    },
];

/// Its columns: the friction force and the dissipated power.
const COLUMNS: &[Column] = &[
    Column {
        quantity: "force",
        unit: "N",
    },
    Column {
        quantity: "power",
        unit: "W",
    },
];

impl StickSlip {
    /// A friction of coefficients `kinetic` ≤ `stiction` under
    /// `normal_force`, sticking.
    pub fn new(kinetic: f64, stiction: f64, normal_force: f64) -> StickSlip {
        StickSlip {
            kinetic,
            stiction,
            normal_force,
            sliding: None,
        }
    }

    /// `None` while sticking, else the direction of sliding.
    pub fn sliding(&self) -> Option<f64> {
        self.sliding
    }

    /// `(F, ∂F/∂v, ∂F/∂F_a)` at the arguments `(v, F_a)`.
    pub fn force(&self, args: &[f64]) -> (f64, f64, f64) {
        match self.sliding {
            None => (args[1], 0.0, 1.0),
            Some(s) => (s * self.kinetic * self.normal_force, 0.0, 0.0),
        }
    }

    /// Whether a body at rest under `applied` sticks; else the direction it
    /// slides.
    fn regime_at_rest(&self, applied: f64) -> Option<f64> {
        match applied.abs() <= self.stiction * self.normal_force {
            true => None,
            false => Some(applied.signum()),
        }
    }
}

impl Component for StickSlip {
    fn kind(&self) -> &'static str {
        "stick_slip"
    }

    fn arguments(&self) -> Option<(usize, &'static str)> {
        Some((
            2,
            "the sliding velocity and the force applied along it, friction aside",
        ))
    }

    fn value(&self, port: Port, args: &[f64]) -> Result<f64, OutOfRange> {
        let (f, dv, da) = self.force(args);
        Ok(match port {
            Port::Value => f,
            Port::Stiffness => dv,
            Port::Damping => da,
        })
    }

    fn events(&self) -> &'static [Event] {
        EVENTS
    }

    /// 0. breakaway (sticking): `|F_a| − μ_s·N`, rising;
    /// 1. stop (sliding in direction `s`): `s·v`, falling.
    fn event_values(&self, args: &[f64], g: &mut [f64]) -> Result<(), OutOfRange> {
        let limit = self.stiction * self.normal_force;
        g[0] = match self.sliding {
            None => args[1].abs() - limit,
            Some(_) => -1.0,
        };
        g[1] = match self.sliding {
            None => 1.0,
            Some(s) => s * args[0],
        };
        Ok(())
    }

    fn on_event(&mut self, k: usize, _t: f64, args: &[f64]) -> Result<String, OutOfRange> {
        let applied = args[1];
        self.sliding = match k {
            0 => Some(applied.signum()),
            _ => self.regime_at_rest(applied),
        };
        Ok(match self.sliding {
            None => format!("sticks under {applied:.4} N"),
            Some(s) => format!("slides towards {s:+} under {applied:.4} N"),
        })
    }

    /// Sliding the way it moves, or at rest as the applied force decides.
    fn start(&mut self, args: Option<&[f64]>) -> Result<(), OutOfRange> {
        let (v, applied) = args.map_or((0.0, 0.0), |a| (a[0], a[1]));
        self.sliding = match v == 0.0 {
            true => self.regime_at_rest(applied),
            false => Some(v.signum()),
        };
        Ok(())
    }

    fn columns(&self) -> &'static [Column] {
        COLUMNS
    }

    fn column_values(&self, args: &[f64], out: &mut [f64]) -> Result<(), OutOfRange> {
        out[0] = self.force(args).0;
        out[1] = out[0] * args[0];
        Ok(())
    }

    /// `F·v`: 0 while sticking.
    fn dissipated_power(&self, args: &[f64]) -> Option<f64> {
        Some(self.force(args).0 * args[0])
    }
}

/// `[components.NAME]` with `type = "stick_slip"`: `coefficient`,
/// `static_coefficient` (default `coefficient`), `normal_force` and the
/// inputs it supplies.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct StickSlipSection {
    inputs: Ports,
    coefficient: f64,
    static_coefficient: Option<f64>,
    normal_force: f64,
}

impl Section for StickSlipSection {
    fn build(&self, name: &str, binder: &mut Binder) -> Result<(), String> {
        let key = |entry: &str| format!("components.{name}.{entry}");
        let kinetic = non_negative(&key("coefficient"), self.coefficient)?;
        let stiction = self.static_coefficient.unwrap_or(kinetic);
        let stiction = non_negative(&key("static_coefficient"), stiction)?;
        if stiction < kinetic {
            return Err(format!(
                "components.{name}.static_coefficient = {stiction}: the static coefficient μ_s must be at least the kinetic one (coefficient = {kinetic})"
            ));
        }
        let normal = non_negative(&key("normal_force"), self.normal_force)?;
        let c = binder.add(
            name.to_string(),
            Box::new(StickSlip::new(kinetic, stiction, normal)),
        );
        binder.bind_ports(&self.inputs, "force", c, name)
    }
}

#[cfg(test)]
mod tests {
    use crate::scenario::{ModelNames, Scenario};
    use crate::simulate::simulate;
    use lagrangian_model::Interpreted;

    /// A 1 kg block pulled by `10·t` N against its friction.
    const BLOCK: &str = "model Pulled;\n\
        coordinates { x [m], }\n\
        parameters { m [kg] = 1.0, pull [N/s] = 10.0, }\n\
        inputs { friction(v [m/s], f [N]) [N], }\n\
        kinetic = 0.5 * m * pow(dot(x), 2);\n\
        force x = pull * t - friction(dot(x), pull * t);\n";

    /// μ_s = 0.5, μ_k = 0.3 under its weight.
    const SCENARIO: &str = "[simulation]\nt_end = 0.8\nrtol = 1e-10\natol = 1e-12\n\
        [components.floor]\ntype = \"stick_slip\"\ninputs = { force = \"friction\" }\n\
        coefficient = 0.3\nstatic_coefficient = 0.5\nnormal_force = 9.81\n";

    fn block() -> (Interpreted<1>, ModelNames) {
        let model = lagrangian_core::interpret(BLOCK).unwrap();
        let names = ModelNames::of_interpreted(&model);
        (Interpreted::new(model).unwrap(), names)
    }

    #[test]
    fn a_pulled_block_sticks_until_the_static_limit_then_slides() {
        // Still until 10·t₁ = μ_s·N (t₁ = 0.4905 s); then
        // v = 5(t² − t₁²) − μ_k·N·(t − t₁), x its integral.
        let (model, names) = block();
        let scenario = Scenario::parse(SCENARIO, None, &names, &[]).unwrap();
        let result = simulate(&model, &scenario).unwrap();
        let t1 = 0.5 * 9.81 / 10.0;
        let [breakaway] = result.events.as_slice() else {
            panic!("{:?}", result.events)
        };
        assert!((breakaway.t - t1).abs() < 1e-9, "{}", breakaway.t);
        for s in &result.samples {
            let (x, v) = match s.t <= t1 {
                true => (0.0, 0.0),
                false => {
                    let dt = s.t - t1;
                    let v = 5.0 * (s.t * s.t - t1 * t1) - 2.943 * dt;
                    let x = 5.0 * (s.t.powi(3) - t1.powi(3)) / 3.0
                        - 5.0 * t1 * t1 * dt
                        - 1.4715 * dt * dt;
                    (x, v)
                }
            };
            assert!(
                (s.q[0] - x).abs() < 1e-8 && (s.v[0] - v).abs() < 1e-8,
                "{}",
                s.t
            );
        }
    }

    #[test]
    fn a_sliding_block_stops_and_stays() {
        // Unpulled from 2 m/s: stops at v₀/(μ_k·g) = 0.6796 s after
        // v₀²/(2μ_k·g), and sticks there.
        let (model, names) = block();
        let text =
            format!("{SCENARIO}[parameters]\npull = 0.0\n[initial]\nvelocities = {{ x = 2.0 }}\n");
        let scenario = Scenario::parse(&text, None, &names, &[]).unwrap();
        let result = simulate(&model, &scenario).unwrap();
        let [stop] = result.events.as_slice() else {
            panic!("{:?}", result.events)
        };
        assert!((stop.t - 2.0 / 2.943).abs() < 1e-9, "{}", stop.t);
        assert_eq!(stop.description, "sticks under 0.0000 N");
        let last = result.samples.last().unwrap();
        assert!(
            (last.q[0] - 4.0 / (2.0 * 2.943)).abs() < 1e-9,
            "{}",
            last.q[0]
        );
        assert!(last.v[0].abs() < 1e-9);
    }

    #[test]
    fn a_static_coefficient_below_the_kinetic_is_refused() {
        let (_, names) = block();
        let text = SCENARIO.replace("static_coefficient = 0.5", "static_coefficient = 0.2");
        assert_eq!(
            Scenario::parse(&text, None, &names, &[])
                .unwrap_err()
                .message,
            "components.floor.static_coefficient = 0.2: the static coefficient μ_s must be at least the kinetic one (coefficient = 0.3)"
        );
    }
}
