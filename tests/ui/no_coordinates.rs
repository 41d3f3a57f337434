lagrangian::lagrangian! {
    model Nothing;
    coordinates { }
    parameters { m = 1.0 }
    kinetic = m;
}

fn main() {}
