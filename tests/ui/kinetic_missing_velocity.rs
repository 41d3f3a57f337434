lagrangian::lagrangian! {
    model TwoCarts;
    coordinates { x, y }
    parameters { m = 1.0, k = 1.0 }
    kinetic = 0.5 * m * pow(dot(x), 2);
    potential = 0.5 * k * pow(x - y, 2);
}

fn main() {}
