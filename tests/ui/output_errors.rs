lagrangian::lagrangian! {
    model Pendulum;
    coordinates { theta [rad] }
    parameters { m [kg] = 1.0, l [m] = 1.0, g [m/s^2] = 9.81 }
    let x = l * sin(theta);
    kinetic = 0.5 * m * pow(l * dot(theta), 2);
    potential = -m * g * l * cos(theta) + 0.0 * ddot(theta);
    output x [m] = x;
    output tip_speed [m] = dot(x);
}

fn main() {}
