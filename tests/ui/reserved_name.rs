lagrangian::lagrangian! {
    model Cart;
    coordinates { x }
    parameters { m = 1.0, t = 2.0 }
    kinetic = 0.5 * m * pow(dot(x), 2);
}

fn main() {}
