lagrangian::lagrangian! {
    model Pendulum;
    coordinates { theta [rad] }
    parameters { m [kg] = 1.0, l [m] = 1.0, g [m/s^2] = 9.81 }
    kinetic = 0.5 * m * pow(l * dot(theta), 2);
    potential = -m * g * l * cos(theta) + m * g * theta;
}

fn main() {}
