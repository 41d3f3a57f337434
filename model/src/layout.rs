//! What each routine of a compiled model computes, and the order of its
//! outputs: the one description the optimizer builds to, the emitters write
//! from and the interpreter unpacks by.

/// Which group of outputs a routine computes.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub enum RoutineKind {
    /// The upper triangle of `M` (row by row, [`mass_entries`]), then `f`.
    Dynamics,
    /// `T, V, D, Σ ∂D/∂q̇·q̇, Σ Q·q̇` (the fields of [`Energies`], in order).
    Energies,
    /// `∂f/∂q`, `∂f/∂q̇`, `∂(M a)/∂q`, each row-major `n × n`
    /// ([`JACOBIAN_BLOCKS`]).
    Jacobians,
    /// The arguments of every input-function call of the dynamics routine,
    /// concatenated in the order of the model's input sites.
    InputArguments,
    /// The outputs of [`RoutineKind::Dynamics`], then `Σ ∂D/∂q̇·q̇` and
    /// `Σ Q·q̇`: one pass for an integrator that also integrates the
    /// dissipated energy and the work of the forces, sharing the operations
    /// and input calls the two groups have in common.
    DynamicsAndPowers,
}

/// `(i, j)` of the entries of `M` among the dynamics outputs, in order: the
/// upper triangle (`i ≤ j`), row by row; `M` is symmetric.
pub fn mass_entries(n: usize) -> impl Iterator<Item = (usize, usize)> {
    (0..n).flat_map(move |i| (i..n).map(move |j| (i, j)))
}

/// Writes the dynamics outputs `out` of a model with `n` coordinates into
/// row-major `mass` (`n × n`, both triangles) and `forcing`, and returns the
/// outputs that follow them (the powers of [`RoutineKind::DynamicsAndPowers`]).
pub fn unpack_dynamics<'a>(
    out: &'a [f64],
    n: usize,
    mass: &mut [f64],
    forcing: &mut [f64],
) -> &'a [f64] {
    let mut k = 0;
    for (i, j) in mass_entries(n) {
        mass[i * n + j] = out[k];
        mass[j * n + i] = out[k];
        k += 1;
    }
    forcing[..n].copy_from_slice(&out[k..k + n]);
    &out[k + n..]
}

/// The names of the Jacobian blocks, in output order (the fields of
/// `Jacobians`): each block is row-major `n × n`, entry `(i, k)` the
/// derivative of equation `i` by coordinate or velocity `k`.
pub const JACOBIAN_BLOCKS: [&str; 3] = ["forcing_q", "forcing_qd", "mass_times_acceleration_q"];

/// Energy bookkeeping at one state: the outputs of [`RoutineKind::Energies`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Energies {
    /// Kinetic energy `T`.
    pub kinetic: f64,
    /// Potential energy `V`.
    pub potential: f64,
    /// Rayleigh dissipation function `D`.
    pub dissipation: f64,
    /// `Σ_i ∂D/∂q̇_i q̇_i`: power dissipated by `D` (= 2D when D is quadratic).
    pub damping_power: f64,
    /// `Σ_i Q_i q̇_i`: power of the generalized forces of the force statements.
    pub external_power: f64,
}

impl Energies {
    /// The field names, in output order.
    pub const FIELDS: [&'static str; 5] = [
        "kinetic",
        "potential",
        "dissipation",
        "damping_power",
        "external_power",
    ];

    /// The energies from the outputs of an energies routine, in the order of
    /// [`Energies::FIELDS`].
    pub fn from_outputs(out: &[f64; 5]) -> Energies {
        let [
            kinetic,
            potential,
            dissipation,
            damping_power,
            external_power,
        ] = *out;
        Energies {
            kinetic,
            potential,
            dissipation,
            damping_power,
            external_power,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_mass_matrix_is_its_upper_triangle_row_by_row() {
        let entries: Vec<_> = mass_entries(3).collect();
        assert_eq!(entries, [(0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)]);
        let out = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0, 11.0];
        let (mut mass, mut forcing) = ([0.0; 9], [0.0; 3]);
        let rest = unpack_dynamics(&out, 3, &mut mass, &mut forcing);
        assert_eq!(mass, [1.0, 2.0, 3.0, 2.0, 4.0, 5.0, 3.0, 5.0, 6.0]);
        assert_eq!(forcing, [7.0, 8.0, 9.0]);
        assert_eq!(rest, [10.0, 11.0]);
    }
}
