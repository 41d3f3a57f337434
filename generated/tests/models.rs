//! The committed models compile and compute the textbook results.

use lagrangian_generated::double_pendulum::DoublePendulum;
use lagrangian_generated::yaris_double_pendulum::YarisDoublePendulum;
use lagrangian_runtime::nalgebra::{Vector2, Vector3};
use lagrangian_runtime::{LagrangianSystem, NoInputs};

#[test]
fn double_pendulum_mass_matrix() {
    let p = DoublePendulum::default();
    let m = p.mass_matrix(0.0, &Vector2::new(0.4, -0.1), &Vector2::zeros(), &NoInputs);
    // (m1 + m2) l1², m2 l1 l2 cos(θ1 − θ2), m2 l2² with unit masses and lengths.
    assert_eq!(m[(0, 0)], 2.0);
    assert!((m[(0, 1)] - 0.5f64.cos()).abs() < 1e-15);
    assert_eq!(m[(1, 1)], 1.0);
}

#[test]
fn yaris_mass_matrix_is_the_paper_s_with_corrections() {
    let y = YarisDoublePendulum::default();
    let m = y.mass_matrix(
        0.0,
        &Vector3::new(-0.2, 0.05, 0.1),
        &Vector3::zeros(),
        &|_: usize, _: &[f64]| 0.0,
    );
    assert_eq!(m[(0, 0)], 539.0 + 629.0);
    assert_eq!(m[(0, 1)], 0.0);
    let (r, l0, l1) = (-0.2, 0.91, 0.57);
    let expected = 539.0 * (l0 + r) * (l0 + r) + 629.0 * (l0 + r + l1) * (l0 + r + l1);
    assert!((m[(1, 1)] - expected).abs() < 1e-9 * expected);
}
