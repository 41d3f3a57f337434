// With units declared, calls with the wrong number of arguments are
// reported by the lowering, at the call; the dimension checker must not
// panic on them first.
lagrangian::lagrangian! {
    model Pendulum;
    coordinates { theta [rad] }
    parameters { m [kg] = 1.0, l [m] = 1.0 }
    let a = sin();
    let b = sqrt();
    let c = dot();
    let d = pow(theta);
    let e = theta.powi();
    let f = theta.sin(2);
    kinetic = 0.5 * m * pow(l * dot(theta), 2);
}

fn main() {}
