lagrangian::lagrangian! {
    model NonlinearSpring;
    coordinates { x }
    parameters { m = 1.0 }
    inputs { energy(x) }
    kinetic = 0.5 * m * pow(dot(x), 2);
    potential = energy(x);
}

fn main() {}
