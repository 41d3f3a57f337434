lagrangian::lagrangian! {
    model Cart;
    coordinates { x }
    parameters { m = 1.0 }
    inputs { push(t) }
    kinetic = 0.5 * m * pow(dot(x), 2);
    force x = push(t, x);
}

fn main() {}
