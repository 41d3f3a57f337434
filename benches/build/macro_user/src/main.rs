//! One inline spec and one evaluation of q̈: what a new user of the macro builds.

use lagrangian::nalgebra::Vector1;
use lagrangian::{LagrangianSystem, NoInputs, lagrangian};

lagrangian! {
    model Pendulum;
    coordinates { theta [rad] }
    parameters { m [kg] = 1.0, l [m] = 2.0, g [m/s^2] = 9.81 }
    let x = l * sin(theta);
    let y = -l * cos(theta);
    kinetic = 0.5 * m * (pow(dot(x), 2) + pow(dot(y), 2));
    potential = m * g * y;
}

fn main() {
    let model = Pendulum::default();
    let qdd = model
        .accelerations(0.0, &Vector1::new(0.3), &Vector1::new(0.0), &NoInputs)
        .expect("M is positive definite");
    println!("{}", qdd[0]);
}
