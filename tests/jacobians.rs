//! The derived Jacobians agree with central finite differences of M and f.

use lagrangian::nalgebra::{SMatrix, SVector};
use lagrangian::{Jacobians, LagrangianSystem};

mod models {
    lagrangian::lagrangian!(file = "specs/yaris_double_pendulum.lpm");
}
use models::YarisDoublePendulum as Yaris;

/// A smooth crush force with its exact partial derivatives, and barrier
/// forces of time; consistent with the derivatives the spec declares.
fn inputs(index: usize, args: &[f64]) -> f64 {
    let (k, c, a) = (4.0e5, 2.0e3, 3.0e6);
    match index {
        Yaris::INPUT_CRUSH => k * args[0] + c * args[1] + a * args[0].powi(3),
        Yaris::INPUT_CRUSH_STIFFNESS => k + 3.0 * a * args[0].powi(2),
        Yaris::INPUT_CRUSH_DAMPING => c,
        Yaris::INPUT_WELD => 2.0e4 * args[0] + 300.0 * args[1] + 5.0e5 * args[0].powi(3),
        Yaris::INPUT_WELD_STIFFNESS => 2.0e4 + 1.5e6 * args[0].powi(2),
        Yaris::INPUT_WELD_DAMPING => 300.0,
        _ => 1.0e4 * (index as f64 * args[0] + 0.3).sin(),
    }
}

#[test]
fn jacobians_match_central_differences() {
    let model = Yaris::default();
    let t = 0.031;
    let q = SVector::<f64, 3>::new(-0.21, 0.047, 0.083);
    let qd = SVector::<f64, 3>::new(-11.0, 0.9, 1.7);
    let qdd = SVector::<f64, 3>::new(-300.0, 20.0, -45.0);
    let mut jac = Jacobians::default();
    model
        .jacobians(t, &q, &qd, &qdd, &inputs, &mut jac)
        .unwrap();

    let f = |q: &SVector<f64, 3>, qd: &SVector<f64, 3>| model.forcing(t, q, qd, &inputs);
    let ma = |q: &SVector<f64, 3>| model.mass_matrix(t, q, &qd, &inputs) * qdd;
    let mut fd_q = SMatrix::<f64, 3, 3>::zeros();
    let mut fd_qd = SMatrix::<f64, 3, 3>::zeros();
    let mut fd_ma = SMatrix::<f64, 3, 3>::zeros();
    for k in 0..3 {
        let hq = 1e-6 * q[k].abs().max(1e-2);
        let hv = 1e-6 * qd[k].abs().max(1.0);
        let mut e = SVector::<f64, 3>::zeros();
        e[k] = hq;
        fd_q.set_column(k, &((f(&(q + e), &qd) - f(&(q - e), &qd)) / (2.0 * hq)));
        fd_ma.set_column(k, &((ma(&(q + e)) - ma(&(q - e))) / (2.0 * hq)));
        e[k] = hv;
        fd_qd.set_column(k, &((f(&q, &(qd + e)) - f(&q, &(qd - e))) / (2.0 * hv)));
    }
    for (name, derived, fd) in [
        ("df/dq", jac.forcing_q, fd_q),
        ("df/dqd", jac.forcing_qd, fd_qd),
        ("d(Ma)/dq", jac.mass_times_acceleration_q, fd_ma),
    ] {
        let err = (derived - fd).amax() / fd.amax();
        println!("{name}: relative difference {err:.1e}");
        assert!(err < 1e-7, "{name}: {derived} vs {fd}");
    }
}
