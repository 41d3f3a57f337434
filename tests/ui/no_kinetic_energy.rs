lagrangian::lagrangian! {
    model Cart;
    coordinates { x }
    parameters { k = 1.0 }
    potential = 0.5 * k * pow(x, 2);
}

fn main() {}
