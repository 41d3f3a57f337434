//! Random well-formed specs for property tests, with an independent numeric
//! model of the same mechanics.
//!
//! A spec is a planar chain of point masses: each body hangs off the moving
//! pivot or an earlier body through one or two links, a link being a rod of
//! fixed length or an elastic rod of length `l + r` at an angle `θ_a + k·θ_b`
//! (or a fixed angle). Springs act on coordinates (linear, quartic) or between
//! a body and a fixed anchor (a `sqrt` distance); dampers on coordinates,
//! bodies and anchor springs; forces are harmonic generalized forces, decaying
//! point forces, point drag and an input function with declared derivatives.
//! Every coordinate carries a rotational or translational inertia, so `M` is
//! positive definite.
//!
//! [`Model::source`] writes the spec text; [`Model::kinetic`],
//! [`Model::potential`], [`Model::dissipation`] and
//! [`Model::generalized_forces`] evaluate the same mechanics directly, with
//! hand-written velocities, so the tests can check the derivation against
//! finite differences without using the compiler's calculus.

use proptest::prelude::*;

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Kind {
    Angle,
    Length,
}

/// The angle of a link from the downward vertical.
#[derive(Clone, Copy, Debug)]
pub enum Angle {
    /// A parameter.
    Fixed(f64),
    /// `θ_a + k·θ_b` (`k = 0`: `θ_a` alone).
    Coordinates { a: usize, k: i8, b: usize },
}

#[derive(Clone, Copy, Debug)]
pub struct Link {
    pub length: f64,
    /// The length coordinate that stretches the link.
    pub stretch: Option<usize>,
    pub angle: Angle,
}

#[derive(Clone, Debug)]
pub struct Body {
    pub mass: f64,
    pub parent: Option<usize>,
    pub links: Vec<Link>,
}

#[derive(Clone, Copy, Debug)]
pub enum Spring {
    /// `½k(q − q0)²`.
    Linear {
        coordinate: usize,
        k: f64,
        rest: f64,
    },
    /// `¼k q⁴`.
    Quartic { coordinate: usize, k: f64 },
    /// `½k(d − l)²`, `d` the distance from the body to `(x, z)`.
    Anchor {
        body: usize,
        k: f64,
        rest: f64,
        x: f64,
        z: f64,
    },
}

#[derive(Clone, Copy, Debug)]
pub enum Damper {
    /// `½c q̇²`.
    Coordinate { coordinate: usize, c: f64 },
    /// `½c (ẋ² + ż²)`.
    Body { body: usize, c: f64 },
    /// `½c ḋ²` for anchor spring number `spring`.
    Anchor { spring: usize, c: f64 },
}

#[derive(Clone, Copy, Debug)]
pub enum Force {
    /// `Q = F sin(ωt)` on a coordinate.
    Harmonic {
        coordinate: usize,
        amplitude: f64,
        omega: f64,
    },
    /// `(F_x, F_z) e^(−t/τ)` at a body.
    Pulse {
        body: usize,
        x: f64,
        z: f64,
        tau: f64,
    },
    /// `−c (ẋ, ż)` at a body.
    Drag { body: usize, c: f64 },
    /// `(−push(x, ẋ), −½ push(z, ż))` at a body, `push` an input function.
    Input { body: usize },
}

#[derive(Clone, Debug)]
pub struct Model {
    pub kinds: Vec<Kind>,
    pub inertia: Vec<f64>,
    /// Horizontal pivot motion `A sin(ωt)`: `(A, ω)`.
    pub base: Option<(f64, f64)>,
    pub gravity: f64,
    pub bodies: Vec<Body>,
    pub springs: Vec<Spring>,
    pub dampers: Vec<Damper>,
    pub forces: Vec<Force>,
}

/// The input function `push(x, v)` and its partial derivatives, by input
/// number (declaration order: `push`, `push_x`, `push_v`).
pub fn push(input: usize, args: &[f64]) -> f64 {
    let (x, v) = (args[0], args[1]);
    match input {
        0 => 30.0 * x + 2.0 * v + 5.0 * x.powi(3) + 4.0 * x * v,
        1 => 30.0 + 15.0 * x * x + 4.0 * v,
        2 => 2.0 + 4.0 * x,
        _ => f64::NAN,
    }
}

// ---------------------------------------------------------------- strategy

/// A value in `[lo, hi]` with two decimals, so the spec text is exact.
fn value(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    let (a, b) = ((lo * 100.0).round() as i64, (hi * 100.0).round() as i64);
    (a..=b).prop_map(|k| k as f64 / 100.0)
}

/// Indices are drawn as free bytes and resolved against what exists
/// (`pick % count`), so every combination is well formed and shrinks.
type Pick = u8;

/// A link as drawn: length, angle coordinates `a` and `b`, stretch
/// coordinate, `k`, fixed angle, elastic.
type RawLink = (f64, Pick, Pick, Pick, i8, f64, bool);
/// A body as drawn: mass, parent, links.
type RawBody = (f64, Option<Pick>, Vec<RawLink>);
/// A spring as drawn: kind, what it acts on, stiffness, rest, anchor x, z.
type RawSpring = (u8, Pick, f64, f64, f64, f64);
/// A damper as drawn: kind, what it acts on, coefficient.
type RawDamper = (u8, Pick, f64);
/// A force as drawn: kind, where it acts, three values.
type RawForce = (u8, Pick, f64, f64, f64);

fn link() -> impl Strategy<Value = RawLink> {
    (
        value(0.3, 1.5),
        any::<Pick>(),
        any::<Pick>(),
        any::<Pick>(),
        -2i8..=2,
        value(-1.0, 1.0),
        any::<bool>(),
    )
}

prop_compose! {
    fn body()(mass in value(0.5, 3.0), parent in prop::option::of(any::<Pick>()),
              links in prop::collection::vec(link(), 1..=2)) -> RawBody {
        (mass, parent, links)
    }
}

fn spring() -> impl Strategy<Value = RawSpring> {
    (
        0u8..3,
        any::<Pick>(),
        value(5.0, 200.0),
        value(-0.2, 0.2),
        value(-2.0, 2.0),
        value(14.0, 16.0),
    )
}

fn damper() -> impl Strategy<Value = RawDamper> {
    (0u8..3, any::<Pick>(), value(0.1, 5.0))
}

fn force() -> impl Strategy<Value = RawForce> {
    (
        0u8..4,
        any::<Pick>(),
        value(-20.0, 20.0),
        value(-20.0, 20.0),
        value(0.2, 5.0),
    )
}

/// Random models with one to three coordinates and one to three bodies.
pub fn model() -> impl Strategy<Value = Model> {
    (
        prop::collection::vec(any::<bool>(), 1..=3),
        prop::collection::vec(value(0.05, 1.0), 3),
        prop::option::of((value(0.05, 0.3), value(1.0, 6.0))),
        prop::collection::vec(body(), 1..=3),
        prop::collection::vec(spring(), 0..=3),
        prop::collection::vec(damper(), 0..=2),
        prop::collection::vec(force(), 0..=2),
    )
        .prop_map(
            |(angles, inertia, base, bodies, springs, dampers, forces)| {
                let kinds: Vec<Kind> = angles
                    .iter()
                    .map(|&a| if a { Kind::Angle } else { Kind::Length })
                    .collect();
                let n = kinds.len();
                let bodies = resolve_bodies(&kinds, bodies);
                let body_count = bodies.len();
                let springs = resolve_springs(n, body_count, springs);
                let dampers = resolve_dampers(n, body_count, &springs, dampers);
                Model {
                    inertia: inertia[..n].to_vec(),
                    kinds,
                    base,
                    gravity: 9.81,
                    bodies,
                    springs,
                    dampers,
                    forces: resolve_forces(n, body_count, forces),
                }
            },
        )
}

/// `set[pick % len]`.
fn pick(set: &[usize], p: Pick) -> usize {
    set[p as usize % set.len()]
}

/// The bodies, each hanging off an earlier one or the pivot; links turn on
/// angle coordinates (fixed angles without any) and stretch with length
/// coordinates.
fn resolve_bodies(kinds: &[Kind], bodies: Vec<RawBody>) -> Vec<Body> {
    let of_kind = |kind| -> Vec<usize> { (0..kinds.len()).filter(|&i| kinds[i] == kind).collect() };
    let (angle_coordinates, length_coordinates) = (of_kind(Kind::Angle), of_kind(Kind::Length));
    let link = |(length, a, b, s, k, fixed, elastic): RawLink| Link {
        length,
        stretch: (elastic && !length_coordinates.is_empty()).then(|| pick(&length_coordinates, s)),
        angle: if angle_coordinates.is_empty() {
            Angle::Fixed(fixed)
        } else {
            Angle::Coordinates {
                a: pick(&angle_coordinates, a),
                k,
                b: pick(&angle_coordinates, b),
            }
        },
    };
    bodies
        .into_iter()
        .enumerate()
        .map(|(i, (mass, parent, links))| Body {
            mass,
            parent: parent.filter(|_| i > 0).map(|p| p as usize % i),
            links: links.into_iter().map(link).collect(),
        })
        .collect()
}

/// The springs, on `n` coordinates and `body_count` bodies.
fn resolve_springs(n: usize, body_count: usize, springs: Vec<RawSpring>) -> Vec<Spring> {
    springs
        .into_iter()
        .map(|(kind, p, k, rest, x, z)| match kind {
            0 => Spring::Linear {
                coordinate: p as usize % n,
                k,
                rest,
            },
            1 => Spring::Quartic {
                coordinate: p as usize % n,
                k,
            },
            _ => Spring::Anchor {
                body: p as usize % body_count,
                k,
                rest: z - 1.0,
                x,
                z,
            },
        })
        .collect()
}

/// The dampers; one drawn on an anchor spring acts on a coordinate when
/// there is no anchor spring.
fn resolve_dampers(
    n: usize,
    body_count: usize,
    springs: &[Spring],
    dampers: Vec<RawDamper>,
) -> Vec<Damper> {
    let anchors: Vec<usize> = (0..springs.len())
        .filter(|&s| matches!(springs[s], Spring::Anchor { .. }))
        .collect();
    dampers
        .into_iter()
        .map(|(kind, p, c)| match kind {
            0 => Damper::Coordinate {
                coordinate: p as usize % n,
                c,
            },
            1 => Damper::Body {
                body: p as usize % body_count,
                c,
            },
            _ if anchors.is_empty() => Damper::Coordinate {
                coordinate: p as usize % n,
                c,
            },
            _ => Damper::Anchor {
                spring: pick(&anchors, p),
                c,
            },
        })
        .collect()
}

/// The forces, on `n` coordinates and `body_count` bodies.
fn resolve_forces(n: usize, body_count: usize, forces: Vec<RawForce>) -> Vec<Force> {
    forces
        .into_iter()
        .map(|(kind, p, a, b, c)| match kind {
            0 => Force::Harmonic {
                coordinate: p as usize % n,
                amplitude: a,
                omega: c,
            },
            1 => Force::Pulse {
                body: p as usize % body_count,
                x: a,
                z: b,
                tau: c,
            },
            2 => Force::Drag {
                body: p as usize % body_count,
                c,
            },
            _ => Force::Input {
                body: p as usize % body_count,
            },
        })
        .collect()
}

mod numeric;
mod text;
