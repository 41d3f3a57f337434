//! Direct evaluation of a random [`Model`]'s mechanics: positions with
//! hand-written velocities, energies, dissipation and generalized forces.

use super::{Angle, Damper, Force, Model, Spring, push};

/// Position `(x, z)` and velocity `(ẋ, ż)` of a body.
#[derive(Clone, Copy, Debug, Default)]
pub struct Motion {
    pub x: f64,
    pub z: f64,
    pub xd: f64,
    pub zd: f64,
}

impl Model {
    /// Every body's position and velocity at `(q, q̇, t)`.
    pub fn motions(&self, q: &[f64], qd: &[f64], t: f64) -> Vec<Motion> {
        let mut motions: Vec<Motion> = Vec::with_capacity(self.bodies.len());
        for body in &self.bodies {
            let mut m = match body.parent {
                Some(p) => motions[p],
                None => match self.base {
                    Some((a, w)) => Motion {
                        x: a * (w * t).sin(),
                        xd: a * w * (w * t).cos(),
                        ..Motion::default()
                    },
                    None => Motion::default(),
                },
            };
            for link in &body.links {
                let (length, length_rate) = match link.stretch {
                    Some(r) => (link.length + q[r], qd[r]),
                    None => (link.length, 0.0),
                };
                let (phi, phi_rate) = match link.angle {
                    Angle::Fixed(alpha) => (alpha, 0.0),
                    Angle::Coordinates { a, k, b } => {
                        let k = f64::from(k);
                        (q[a] + k * q[b], qd[a] + k * qd[b])
                    }
                };
                let (s, c) = phi.sin_cos();
                m.x += length * s;
                m.z -= length * c;
                m.xd += length_rate * s + length * c * phi_rate;
                m.zd += -length_rate * c + length * s * phi_rate;
            }
            motions.push(m);
        }
        motions
    }

    pub fn kinetic(&self, q: &[f64], qd: &[f64], t: f64) -> f64 {
        let bodies: f64 = self
            .bodies
            .iter()
            .zip(self.motions(q, qd, t))
            .map(|(b, m)| 0.5 * b.mass * (m.xd * m.xd + m.zd * m.zd))
            .sum();
        let inertia: f64 = self
            .inertia
            .iter()
            .zip(qd)
            .map(|(j, v)| 0.5 * j * v * v)
            .sum();
        bodies + inertia
    }

    /// Distance from a body to an anchor and its rate.
    fn anchor_distance(m: &Motion, x: f64, z: f64) -> (f64, f64) {
        let d = (m.x - x).hypot(m.z - z);
        (d, ((m.x - x) * m.xd + (m.z - z) * m.zd) / d)
    }

    pub fn potential(&self, q: &[f64], t: f64) -> f64 {
        let motions = self.motions(q, &vec![0.0; q.len()], t);
        let gravity: f64 = self
            .bodies
            .iter()
            .zip(&motions)
            .map(|(b, m)| b.mass * self.gravity * m.z)
            .sum();
        let springs: f64 = self
            .springs
            .iter()
            .map(|spring| match *spring {
                Spring::Linear {
                    coordinate,
                    k,
                    rest,
                } => 0.5 * k * (q[coordinate] - rest).powi(2),
                Spring::Quartic { coordinate, k } => 0.25 * k * q[coordinate].powi(4),
                Spring::Anchor {
                    body,
                    k,
                    rest,
                    x,
                    z,
                } => {
                    let (d, _) = Self::anchor_distance(&motions[body], x, z);
                    0.5 * k * (d - rest).powi(2)
                }
            })
            .sum();
        gravity + springs
    }

    pub fn dissipation(&self, q: &[f64], qd: &[f64], t: f64) -> f64 {
        let motions = self.motions(q, qd, t);
        self.dampers
            .iter()
            .map(|damper| match *damper {
                Damper::Coordinate { coordinate, c } => 0.5 * c * qd[coordinate].powi(2),
                Damper::Body { body, c } => {
                    let m = &motions[body];
                    0.5 * c * (m.xd * m.xd + m.zd * m.zd)
                }
                Damper::Anchor { spring, c } => {
                    let Spring::Anchor { body, x, z, .. } = self.springs[spring] else {
                        unreachable!("anchor dampers refer to anchor springs")
                    };
                    let (_, rate) = Self::anchor_distance(&motions[body], x, z);
                    0.5 * c * rate * rate
                }
            })
            .sum()
    }

    /// `Q_i = Σ F·∂p/∂q_i + Q_i^direct`. Positions are linear in `q̇`, so
    /// `∂p/∂q_i` is the velocity for `q̇ = e_i` minus the velocity for `q̇ = 0`.
    pub fn generalized_forces(&self, q: &[f64], qd: &[f64], t: f64) -> Vec<f64> {
        let n = q.len();
        let motions = self.motions(q, qd, t);
        let at_rest = self.motions(q, &vec![0.0; n], t);
        let unit: Vec<Vec<Motion>> = (0..n)
            .map(|i| {
                let mut e = vec![0.0; n];
                e[i] = 1.0;
                self.motions(q, &e, t)
            })
            .collect();
        let mut forces = vec![0.0; n];
        for force in &self.forces {
            let (body, fx, fz) = match *force {
                Force::Harmonic {
                    coordinate,
                    amplitude,
                    omega,
                } => {
                    forces[coordinate] += amplitude * (omega * t).sin();
                    continue;
                }
                Force::Pulse { body, x, z, tau } => {
                    let decay = (-t / tau).exp();
                    (body, x * decay, z * decay)
                }
                Force::Drag { body, c } => (body, -c * motions[body].xd, -c * motions[body].zd),
                Force::Input { body } => {
                    let m = &motions[body];
                    (body, -push(0, &[m.x, m.xd]), -0.5 * push(0, &[m.z, m.zd]))
                }
            };
            for (i, moved) in unit.iter().enumerate() {
                let dx = moved[body].xd - at_rest[body].xd;
                let dz = moved[body].zd - at_rest[body].zd;
                forces[i] += fx * dx + fz * dz;
            }
        }
        forces
    }
}
