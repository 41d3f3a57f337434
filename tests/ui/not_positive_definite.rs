lagrangian::lagrangian! {
    model TwoCarts;
    coordinates { x, y }
    parameters { m = 1.0, n = -2.0 }
    kinetic = 0.5 * m * pow(dot(x), 2) + 0.5 * n * pow(dot(y), 2);
}

fn main() {}
