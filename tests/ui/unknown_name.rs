lagrangian::lagrangian! {
    model Pendulum;
    coordinates { theta }
    parameters { m = 1.0, l = 1.0 }
    kinetic = 0.5 * m * pow(l * dot(thta), 2);
}

fn main() {}
