// A spec with an error: its model's type still exists (a stand-in), so the
// only error is the spec's own, not one at every use of the type below.
use lagrangian::nalgebra::Vector1;
use lagrangian::{LagrangianSystem, NoInputs};

lagrangian::lagrangian! {
    model Pendulum;
    coordinates { theta }
    parameters { m = 1.0, l = 2.0 }
    inputs { torque(t) }
    kinetic = 0.5 * m * pow(l * dot(thta), 2);
    force theta = torque(t);
}

fn main() {
    let p = Pendulum { l: 1.5, ..Default::default() };
    let _ = Pendulum::INPUT_TORQUE + Pendulum::PARAMETERS.len() + Pendulum::COORDINATES.len();
    let _ = p.accelerations(0.0, &Vector1::new(0.1), &Vector1::new(0.0), &NoInputs);
}
