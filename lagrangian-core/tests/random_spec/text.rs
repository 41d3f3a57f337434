//! The spec text of a random [`Model`].

use super::{Angle, Damper, Force, Kind, Link, Model, Spring};
use std::fmt::Write;

/// Parameters collected while the expressions are written.
#[derive(Default)]
struct Parameters(Vec<(String, &'static str, f64)>);

impl Parameters {
    fn add(&mut self, name: String, unit: &'static str, value: f64) -> String {
        self.0.push((name.clone(), unit, value));
        name
    }
}

/// The parts of a spec's text, collected while the mechanics are written.
#[derive(Default)]
struct Text {
    parameters: Parameters,
    lets: String,
    kinetic: Vec<String>,
    potential: Vec<String>,
    dissipation: Vec<String>,
    /// The `force` statements, one a line.
    forces: String,
    /// Whether a force calls the input function `push`.
    uses_input: bool,
}

impl Model {
    pub fn coordinate_name(&self, i: usize) -> String {
        match self.kinds[i] {
            Kind::Angle => format!("theta{}", i + 1),
            Kind::Length => format!("r{}", i + 1),
        }
    }

    fn angle_text(&self, angle: Angle, parameter: String, p: &mut Parameters) -> String {
        match angle {
            Angle::Fixed(value) => p.add(parameter, "rad", value),
            Angle::Coordinates { a, k: 0, .. } => self.coordinate_name(a),
            Angle::Coordinates { a, k, b } => format!(
                "({} {} {}.0 * {})",
                self.coordinate_name(a),
                if k < 0 { '-' } else { '+' },
                k.abs(),
                self.coordinate_name(b)
            ),
        }
    }

    fn link_text(&self, body: usize, index: usize, link: &Link, p: &mut Parameters) -> [String; 2] {
        let tag = format!("{}_{}", body + 1, index + 1);
        let length = p.add(format!("l{tag}"), "m", link.length);
        let length = match link.stretch {
            Some(r) => format!("({length} + {})", self.coordinate_name(r)),
            None => length,
        };
        let angle = self.angle_text(link.angle, format!("alpha{tag}"), p);
        [
            format!("{length} * sin({angle})"),
            format!("{length} * cos({angle})"),
        ]
    }

    /// The spec, named `Random`.
    pub fn source(&self) -> String {
        let mut text = Text::default();
        self.positions(&mut text);
        self.masses(&mut text);
        for (s, spring) in self.springs.iter().enumerate() {
            self.spring(s + 1, spring, &mut text);
        }
        for (d, damper) in self.dampers.iter().enumerate() {
            self.damper(d + 1, damper, &mut text);
        }
        for (f, force) in self.forces.iter().enumerate() {
            self.force(f + 1, force, &mut text);
        }
        self.assemble(text)
    }

    /// `let xb`, the pivot's motion, and `let x1`, `let z1`, … the bodies'
    /// positions.
    fn positions(&self, text: &mut Text) {
        let p = &mut text.parameters;
        if let Some((amplitude, omega)) = self.base {
            let a = p.add("base_amplitude".into(), "m", amplitude);
            let w = p.add("base_omega".into(), "rad/s", omega);
            writeln!(text.lets, "let xb = {a} * sin({w} * t);").unwrap();
        }
        for (b, body) in self.bodies.iter().enumerate() {
            let (mut x, mut z) = match body.parent {
                Some(parent) => (format!("x{}", parent + 1), format!("z{}", parent + 1)),
                None if self.base.is_some() => ("xb".to_string(), String::new()),
                None => (String::new(), String::new()),
            };
            for (k, link) in body.links.iter().enumerate() {
                let [sin, cos] = self.link_text(b, k, link, p);
                x = if x.is_empty() {
                    sin
                } else {
                    format!("{x} + {sin}")
                };
                z = if z.is_empty() {
                    format!("-{cos}")
                } else {
                    format!("{z} - {cos}")
                };
            }
            writeln!(text.lets, "let x{} = {x};\nlet z{} = {z};", b + 1, b + 1).unwrap();
        }
    }

    /// The bodies' kinetic and gravitational energies, and each coordinate's
    /// own inertia.
    fn masses(&self, text: &mut Text) {
        let p = &mut text.parameters;
        let g = p.add("g".into(), "m/s^2", self.gravity);
        for (b, body) in self.bodies.iter().enumerate() {
            let m = p.add(format!("m{}", b + 1), "kg", body.mass);
            let b = b + 1;
            text.kinetic.push(format!(
                "0.5 * {m} * (pow(dot(x{b}), 2) + pow(dot(z{b}), 2))"
            ));
            text.potential.push(format!("{m} * {g} * z{b}"));
        }
        for (i, &inertia) in self.inertia.iter().enumerate() {
            let unit = if self.kinds[i] == Kind::Angle {
                "kg*m^2"
            } else {
                "kg"
            };
            let j = p.add(format!("J{}", i + 1), unit, inertia);
            text.kinetic.push(format!(
                "0.5 * {j} * pow(dot({}), 2)",
                self.coordinate_name(i)
            ));
        }
    }

    /// Spring number `s`.
    fn spring(&self, s: usize, spring: &Spring, text: &mut Text) {
        let p = &mut text.parameters;
        match *spring {
            Spring::Linear {
                coordinate,
                k,
                rest,
            } => {
                let angle = self.kinds[coordinate] == Kind::Angle;
                let k = p.add(format!("k{s}"), if angle { "N*m/rad" } else { "N/m" }, k);
                let rest = p.add(format!("q0_{s}"), if angle { "rad" } else { "m" }, rest);
                let q = self.coordinate_name(coordinate);
                text.potential
                    .push(format!("0.5 * {k} * pow({q} - {rest}, 2)"));
            }
            Spring::Quartic { coordinate, k } => {
                let angle = self.kinds[coordinate] == Kind::Angle;
                let k = p.add(format!("k{s}"), if angle { "N*m" } else { "N/m^3" }, k);
                let q = self.coordinate_name(coordinate);
                text.potential.push(format!("0.25 * {k} * pow({q}, 4)"));
            }
            Spring::Anchor {
                body,
                k,
                rest,
                x,
                z,
            } => {
                let k = p.add(format!("k{s}"), "N/m", k);
                let rest = p.add(format!("rest{s}"), "m", rest);
                let ax = p.add(format!("ax{s}"), "m", x);
                let az = p.add(format!("az{s}"), "m", z);
                let b = body + 1;
                writeln!(
                    text.lets,
                    "let d{s} = sqrt(pow(x{b} - {ax}, 2) + pow(z{b} - {az}, 2));"
                )
                .unwrap();
                text.potential
                    .push(format!("0.5 * {k} * pow(d{s} - {rest}, 2)"));
            }
        }
    }

    /// Damper number `d`.
    fn damper(&self, d: usize, damper: &Damper, text: &mut Text) {
        let p = &mut text.parameters;
        let name = format!("c{d}");
        let term = match *damper {
            Damper::Coordinate { coordinate, c } => {
                let angle = self.kinds[coordinate] == Kind::Angle;
                let c = p.add(name, if angle { "N*m*s/rad" } else { "N*s/m" }, c);
                let q = self.coordinate_name(coordinate);
                format!("0.5 * {c} * pow(dot({q}), 2)")
            }
            Damper::Body { body, c } => {
                let c = p.add(name, "N*s/m", c);
                let b = body + 1;
                format!("0.5 * {c} * (pow(dot(x{b}), 2) + pow(dot(z{b}), 2))")
            }
            Damper::Anchor { spring, c } => {
                let c = p.add(name, "N*s/m", c);
                format!("0.5 * {c} * pow(dot(d{}), 2)", spring + 1)
            }
        };
        text.dissipation.push(term);
    }

    /// Force number `f`: its `let`s and its `force` statement.
    fn force(&self, f: usize, force: &Force, text: &mut Text) {
        let p = &mut text.parameters;
        let lets = &mut text.lets;
        let at = |body: usize| format!("(x{}, z{})", body + 1, body + 1);
        let statement = match *force {
            Force::Harmonic {
                coordinate,
                amplitude,
                omega,
            } => {
                let angle = self.kinds[coordinate] == Kind::Angle;
                let a = p.add(format!("F{f}"), if angle { "N*m" } else { "N" }, amplitude);
                let w = p.add(format!("omega{f}"), "rad/s", omega);
                writeln!(lets, "let Q{f} = {a} * sin({w} * t);").unwrap();
                let q = self.coordinate_name(coordinate);
                format!("force {q} = Q{f};")
            }
            Force::Pulse { body, x, z, tau } => {
                let fx = p.add(format!("Fx{f}"), "N", x);
                let fz = p.add(format!("Fz{f}"), "N", z);
                let tau = p.add(format!("tau{f}"), "s", tau);
                writeln!(lets, "let fx{f} = {fx} * exp(-t / {tau});").unwrap();
                writeln!(lets, "let fz{f} = {fz} * exp(-t / {tau});").unwrap();
                format!("force at {} = (fx{f}, fz{f});", at(body))
            }
            Force::Drag { body, c } => {
                let c = p.add(format!("cd{f}"), "N*s/m", c);
                let b = body + 1;
                writeln!(lets, "let fx{f} = -{c} * dot(x{b});").unwrap();
                writeln!(lets, "let fz{f} = -{c} * dot(z{b});").unwrap();
                format!("force at {} = (fx{f}, fz{f});", at(body))
            }
            Force::Input { body } => {
                text.uses_input = true;
                let b = body + 1;
                writeln!(lets, "let fx{f} = -push(x{b}, dot(x{b}));").unwrap();
                writeln!(lets, "let fz{f} = -0.5 * push(z{b}, dot(z{b}));").unwrap();
                format!("force at {} = (fx{f}, fz{f});", at(body))
            }
        };
        writeln!(text.forces, "{statement}").unwrap();
    }

    /// The spec text from its parts.
    fn assemble(&self, text: Text) -> String {
        let mut coordinates = String::new();
        for (i, kind) in self.kinds.iter().enumerate() {
            let unit = if *kind == Kind::Angle { "rad" } else { "m" };
            writeln!(coordinates, "    {} [{unit}],", self.coordinate_name(i)).unwrap();
        }
        let mut out = String::from("//! A random spec (property tests).\n\nmodel Random;\n\n");
        writeln!(out, "coordinates {{\n{coordinates}}}\n\nparameters {{").unwrap();
        for (name, unit, value) in &text.parameters.0 {
            writeln!(out, "    {name} [{unit}] = {value:?},").unwrap();
        }
        out.push_str("}\n\n");
        if text.uses_input {
            out.push_str(
                "inputs {\n    push(x [m], v [m/s]) [N] {\n        d(x) = push_x(x, v),\n        \
                 d(v) = push_v(x, v),\n    },\n    push_x(x [m], v [m/s]) [N/m],\n    \
                 push_v(x [m], v [m/s]) [N*s/m],\n}\n\n",
            );
        }
        out.push_str(&text.lets);
        writeln!(out, "\nkinetic = {};", text.kinetic.join("\n    + ")).unwrap();
        writeln!(out, "potential = {};", text.potential.join("\n    + ")).unwrap();
        if !text.dissipation.is_empty() {
            let dissipation = text.dissipation.join("\n    + ");
            writeln!(out, "dissipation = {dissipation};").unwrap();
        }
        out.push_str(&text.forces);
        out.push_str("\njacobians;\n");
        out
    }
}
