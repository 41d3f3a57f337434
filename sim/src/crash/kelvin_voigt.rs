//! A Kelvin–Voigt element: a linear spring and a linear dashpot in
//! parallel, `F = k·u + c·u̇` (Voigt, W., 1892; the standard element of
//! linear viscoelasticity), in the sign of its input's arguments (`u` an
//! extension gives a tension). Unlike a contact it pulls as well as
//! pushes. Its force and the power its dashpot dissipates, `c·u̇²`, are
//! trajectory columns (`NAME.force \[N\]`, `NAME.power \[W\]`).
//!
//! Its scenario section is `type = "kelvin_voigt"` (`KelvinVoigtSection`):
//! `stiffness` `k` [N/m] and `damping` `c` [N·s/m], both ≥ 0.

use super::curve::OutOfRange;
use super::{Binder, Column, Component, Port, Section, Smoothness};
use crate::scenario::bind::{Ports, non_negative};
use serde::Deserialize;

/// `F = k·u + c·u̇`.
#[derive(Clone, Debug, PartialEq)]
pub struct KelvinVoigt {
    /// `k` [N/m].
    pub stiffness: f64,
    /// `c` [N·s/m].
    pub damping: f64,
}

/// Its columns: the force and the dissipated power.
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

impl KelvinVoigt {
    /// `F` at the arguments `(u, u̇)`.
    pub fn force(&self, args: &[f64]) -> f64 {
        self.stiffness * args[0] + self.damping * args[1]
    }

    /// `c·u̇²` \[W\].
    pub fn power(&self, args: &[f64]) -> f64 {
        self.damping * args[1] * args[1]
    }
}

impl Component for KelvinVoigt {
    fn kind(&self) -> &'static str {
        "kelvin_voigt"
    }

    fn arguments(&self) -> Option<(usize, &'static str)> {
        Some((2, "the extension and its rate"))
    }

    fn value(&self, port: Port, args: &[f64]) -> Result<f64, OutOfRange> {
        Ok(match port {
            Port::Value => self.force(args),
            Port::Stiffness => self.stiffness,
            Port::Damping => self.damping,
        })
    }

    // None: it keeps no state.
    no_events!();

    fn start(&mut self, _args: Option<&[f64]>) -> Result<(), OutOfRange> {
        Ok(())
    }

    fn columns(&self) -> &'static [Column] {
        COLUMNS
    }

    fn column_values(&self, args: &[f64], out: &mut [f64]) -> Result<(), OutOfRange> {
        out[0] = self.force(args);
        out[1] = self.power(args);
        Ok(())
    }

    fn dissipated_power(&self, args: &[f64]) -> Option<f64> {
        Some(self.power(args))
    }

    fn smoothness(&self) -> Smoothness {
        Smoothness::Smooth
    }
}

/// `[components.NAME]` with `type = "kelvin_voigt"`: `stiffness`,
/// `damping` and the inputs it supplies (force and, optionally, its
/// derivatives).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct KelvinVoigtSection {
    inputs: Ports,
    stiffness: f64,
    damping: f64,
}

impl Section for KelvinVoigtSection {
    fn build(&self, name: &str, binder: &mut Binder) -> Result<(), String> {
        let key = |entry: &str| format!("components.{name}.{entry}");
        let element = KelvinVoigt {
            stiffness: non_negative(&key("stiffness"), self.stiffness)?,
            damping: non_negative(&key("damping"), self.damping)?,
        };
        let c = binder.add(name.to_string(), Box::new(element));
        binder.bind_ports(&self.inputs, "force", c, name)
    }
}

#[cfg(test)]
mod tests {
    use crate::scenario::{ModelNames, Scenario};
    use crate::simulate::simulate;
    use lagrangian_model::Interpreted;

    /// A 1 kg mass on the element.
    const MASS: &str = "model Oscillator;\n\
        coordinates { x [m], }\n\
        parameters { m [kg] = 1.0, }\n\
        inputs { kv(x [m], v [m/s]) [N], }\n\
        kinetic = 0.5 * m * pow(dot(x), 2);\n\
        force x = -kv(x, dot(x));\n";

    const SCENARIO: &str = "[simulation]\nt_end = 1.0\nrtol = 1e-10\natol = 1e-12\n\
        [initial]\ncoordinates = { x = 0.1 }\n\
        [components.mount]\ntype = \"kelvin_voigt\"\ninputs = { force = \"kv\" }\n\
        stiffness = 100.0\ndamping = 2.0\n";

    fn names() -> (Interpreted<1>, ModelNames) {
        let model = lagrangian_core::interpret(MASS).unwrap();
        let names = ModelNames::of_interpreted(&model);
        (Interpreted::new(model).unwrap(), names)
    }

    #[test]
    fn a_mass_on_it_is_the_damped_oscillator() {
        // ω₀ = 10 rad/s, ζ = c/(2√(km)) = 0.1: from rest at x₀,
        // x = x₀·e^(−ζω₀t)·(cos ω_d t + ζω₀/ω_d · sin ω_d t).
        let (model, names) = names();
        let scenario = Scenario::parse(SCENARIO, None, &names, &[]).unwrap();
        let result = simulate(&model, &scenario).unwrap();
        let last = result.samples.last().unwrap();
        let (sigma, wd) = (1.0, (100.0f64 - 1.0).sqrt());
        let t = last.t;
        let x = 0.1 * (-sigma * t).exp() * ((wd * t).cos() + sigma / wd * (wd * t).sin());
        assert!(
            (t - 1.0).abs() < 1e-12 && (last.q[0] - x).abs() < 1e-8,
            "{} vs {x}",
            last.q[0]
        );
        let columns = &result.component_columns;
        assert_eq!(columns[0], ("mount.force".into(), Some("N".into())));
        assert_eq!(columns[1], ("mount.power".into(), Some("W".into())));
        let force = 100.0 * last.q[0] + 2.0 * last.v[0];
        assert!((last.components[0] - force).abs() < 1e-9);
        assert!((last.components[1] - 2.0 * last.v[0].powi(2)).abs() < 1e-12);
    }

    #[test]
    fn a_negative_stiffness_or_damping_is_refused() {
        let (_, names) = names();
        let refused = |text: &str| {
            Scenario::parse(text, None, &names, &[])
                .unwrap_err()
                .message
        };
        assert_eq!(
            refused(&SCENARIO.replace("stiffness = 100.0", "stiffness = -100.0")),
            "components.mount.stiffness = -100: must be a finite number ≥ 0"
        );
        assert_eq!(
            refused(&SCENARIO.replace("damping = 2.0", "damping = -2.0")),
            "components.mount.damping = -2: must be a finite number ≥ 0"
        );
    }
}
