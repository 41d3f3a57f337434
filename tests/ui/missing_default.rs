lagrangian::lagrangian! {
    model Cart;
    coordinates { x }
    parameters { m [kg] }
    kinetic = 0.5 * m * pow(dot(x), 2);
}

fn main() {}
