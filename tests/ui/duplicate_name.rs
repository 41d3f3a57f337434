lagrangian::lagrangian! {
    model Cart;
    coordinates { x }
    parameters { m = 1.0, k = 2.0, m = 3.0 }
    kinetic = 0.5 * m * pow(dot(x), 2);
    potential = 0.5 * k * pow(x, 2);
}

fn main() {}
