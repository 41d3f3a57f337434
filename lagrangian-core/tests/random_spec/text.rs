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
        let mut p = Parameters::default();
        let mut lets = String::new();
        let mut coordinates = String::new();
        for (i, kind) in self.kinds.iter().enumerate() {
            let unit = if *kind == Kind::Angle { "rad" } else { "m" };
            writeln!(coordinates, "    {} [{unit}],", self.coordinate_name(i)).unwrap();
        }
        if let Some((amplitude, omega)) = self.base {
            let a = p.add("base_amplitude".into(), "m", amplitude);
            let w = p.add("base_omega".into(), "rad/s", omega);
            writeln!(lets, "let xb = {a} * sin({w} * t);").unwrap();
        }
        for (b, body) in self.bodies.iter().enumerate() {
            let (mut x, mut z) = match body.parent {
                Some(parent) => (format!("x{}", parent + 1), format!("z{}", parent + 1)),
                None if self.base.is_some() => ("xb".to_string(), String::new()),
                None => (String::new(), String::new()),
            };
            for (k, link) in body.links.iter().enumerate() {
                let [sin, cos] = self.link_text(b, k, link, &mut p);
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
            writeln!(lets, "let x{} = {x};\nlet z{} = {z};", b + 1, b + 1).unwrap();
        }

        let g = p.add("g".into(), "m/s^2", self.gravity);
        let mut kinetic = Vec::new();
        let mut potential = Vec::new();
        for (b, body) in self.bodies.iter().enumerate() {
            let m = p.add(format!("m{}", b + 1), "kg", body.mass);
            let b = b + 1;
            kinetic.push(format!(
                "0.5 * {m} * (pow(dot(x{b}), 2) + pow(dot(z{b}), 2))"
            ));
            potential.push(format!("{m} * {g} * z{b}"));
        }
        for (i, &inertia) in self.inertia.iter().enumerate() {
            let unit = if self.kinds[i] == Kind::Angle {
                "kg*m^2"
            } else {
                "kg"
            };
            let j = p.add(format!("J{}", i + 1), unit, inertia);
            kinetic.push(format!(
                "0.5 * {j} * pow(dot({}), 2)",
                self.coordinate_name(i)
            ));
        }
        for (s, spring) in self.springs.iter().enumerate() {
            let s = s + 1;
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
                    potential.push(format!("0.5 * {k} * pow({q} - {rest}, 2)"));
                }
                Spring::Quartic { coordinate, k } => {
                    let angle = self.kinds[coordinate] == Kind::Angle;
                    let k = p.add(format!("k{s}"), if angle { "N*m" } else { "N/m^3" }, k);
                    let q = self.coordinate_name(coordinate);
                    potential.push(format!("0.25 * {k} * pow({q}, 4)"));
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
                        lets,
                        "let d{s} = sqrt(pow(x{b} - {ax}, 2) + pow(z{b} - {az}, 2));"
                    )
                    .unwrap();
                    potential.push(format!("0.5 * {k} * pow(d{s} - {rest}, 2)"));
                }
            }
        }
        let mut dissipation = Vec::new();
        for (d, damper) in self.dampers.iter().enumerate() {
            let name = format!("c{}", d + 1);
            match *damper {
                Damper::Coordinate { coordinate, c } => {
                    let angle = self.kinds[coordinate] == Kind::Angle;
                    let c = p.add(name, if angle { "N*m*s/rad" } else { "N*s/m" }, c);
                    let q = self.coordinate_name(coordinate);
                    dissipation.push(format!("0.5 * {c} * pow(dot({q}), 2)"));
                }
                Damper::Body { body, c } => {
                    let c = p.add(name, "N*s/m", c);
                    let b = body + 1;
                    dissipation.push(format!(
                        "0.5 * {c} * (pow(dot(x{b}), 2) + pow(dot(z{b}), 2))"
                    ));
                }
                Damper::Anchor { spring, c } => {
                    let c = p.add(name, "N*s/m", c);
                    dissipation.push(format!("0.5 * {c} * pow(dot(d{}), 2)", spring + 1));
                }
            }
        }
        let mut forces = String::new();
        let mut uses_input = false;
        for (f, force) in self.forces.iter().enumerate() {
            let f = f + 1;
            let at = |body: usize| format!("(x{}, z{})", body + 1, body + 1);
            match *force {
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
                    writeln!(forces, "force {q} = Q{f};").unwrap();
                }
                Force::Pulse { body, x, z, tau } => {
                    let fx = p.add(format!("Fx{f}"), "N", x);
                    let fz = p.add(format!("Fz{f}"), "N", z);
                    let tau = p.add(format!("tau{f}"), "s", tau);
                    writeln!(lets, "let fx{f} = {fx} * exp(-t / {tau});").unwrap();
                    writeln!(lets, "let fz{f} = {fz} * exp(-t / {tau});").unwrap();
                    writeln!(forces, "force at {} = (fx{f}, fz{f});", at(body)).unwrap();
                }
                Force::Drag { body, c } => {
                    let c = p.add(format!("cd{f}"), "N*s/m", c);
                    let b = body + 1;
                    writeln!(lets, "let fx{f} = -{c} * dot(x{b});").unwrap();
                    writeln!(lets, "let fz{f} = -{c} * dot(z{b});").unwrap();
                    writeln!(forces, "force at {} = (fx{f}, fz{f});", at(body)).unwrap();
                }
                Force::Input { body } => {
                    uses_input = true;
                    let b = body + 1;
                    writeln!(lets, "let fx{f} = -push(x{b}, dot(x{b}));").unwrap();
                    writeln!(lets, "let fz{f} = -0.5 * push(z{b}, dot(z{b}));").unwrap();
                    writeln!(forces, "force at {} = (fx{f}, fz{f});", at(body)).unwrap();
                }
            }
        }

        let mut out = String::from("//! A random spec (property tests).\n\nmodel Random;\n\n");
        writeln!(out, "coordinates {{\n{coordinates}}}\n\nparameters {{").unwrap();
        for (name, unit, value) in &p.0 {
            writeln!(out, "    {name} [{unit}] = {value:?},").unwrap();
        }
        out.push_str("}\n\n");
        if uses_input {
            out.push_str(
                "inputs {\n    push(x [m], v [m/s]) [N] {\n        d(x) = push_x(x, v),\n        \
                 d(v) = push_v(x, v),\n    },\n    push_x(x [m], v [m/s]) [N/m],\n    \
                 push_v(x [m], v [m/s]) [N*s/m],\n}\n\n",
            );
        }
        out.push_str(&lets);
        writeln!(out, "\nkinetic = {};", kinetic.join("\n    + ")).unwrap();
        writeln!(out, "potential = {};", potential.join("\n    + ")).unwrap();
        if !dissipation.is_empty() {
            writeln!(out, "dissipation = {};", dissipation.join("\n    + ")).unwrap();
        }
        out.push_str(&forces);
        out.push_str("\njacobians;\n");
        out
    }
}
