//! The interface every derived model implements, compiled or interpreted.

use crate::{Energies, InputFunctions, MechanicalEnergy, ModelError};
use nalgebra::{SMatrix, SVector};

/// Jacobians of the equations of motion `M(q) q̈ = f(q, q̇, t)` (the blocks of
/// [`crate::layout::JACOBIAN_BLOCKS`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Jacobians<const N: usize> {
    /// `∂f_i/∂q_k`.
    pub forcing_q: SMatrix<f64, N, N>,
    /// `∂f_i/∂q̇_k`.
    pub forcing_qd: SMatrix<f64, N, N>,
    /// `∂(M a)_i/∂q_k` for the acceleration vector `a` passed in.
    pub mass_times_acceleration_q: SMatrix<f64, N, N>,
}

impl<const N: usize> Default for Jacobians<N> {
    fn default() -> Self {
        Jacobians {
            forcing_q: SMatrix::zeros(),
            forcing_qd: SMatrix::zeros(),
            mass_times_acceleration_q: SMatrix::zeros(),
        }
    }
}

/// A mechanical model in the form `M(q, t) q̈ = f(q, q̇, t)` with `N` coordinates.
///
/// The `lagrangian!` macro implements it for the type it generates; the
/// in-place methods are what implementors write, the others build on them.
pub trait LagrangianSystem<const N: usize> {
    /// The model's name as declared in its spec.
    fn model_name(&self) -> &str;

    /// Names of the generalized coordinates, in order.
    fn coordinate_names(&self) -> Vec<&str>;

    /// Names of the parameters, in order.
    fn parameter_names(&self) -> Vec<&str>;

    /// Names of the input functions, in order (the `index` of [`InputFunctions::value`]).
    fn input_names(&self) -> Vec<&str>;

    /// Current parameter values, in the order of [`LagrangianSystem::parameter_names`].
    fn parameters(&self) -> Vec<f64>;

    /// Sets a parameter by name.
    fn set_parameter(&mut self, name: &str, value: f64) -> Result<(), ModelError>;

    /// Writes `M(q, t)` and `f(q, q̇, t)` at one state.
    fn mass_matrix_and_forcing<I: InputFunctions + ?Sized>(
        &self,
        t: f64,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        inputs: &I,
        mass: &mut SMatrix<f64, N, N>,
        forcing: &mut SVector<f64, N>,
    );

    /// `T`, `V`, `D` and the powers of dissipation and of the generalized forces.
    fn energies<I: InputFunctions + ?Sized>(
        &self,
        t: f64,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        inputs: &I,
    ) -> Energies;

    /// `T` and `V` of [`LagrangianSystem::energies`], bit for bit: for a
    /// caller that reads nothing else of them. A model may compute them
    /// without the rest (the interpreted one does, without the input calls
    /// only the powers make); by default they are taken from `energies`.
    fn mechanical_energy<I: InputFunctions + ?Sized>(
        &self,
        t: f64,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        inputs: &I,
    ) -> MechanicalEnergy {
        self.energies(t, q, qd, inputs).mechanical()
    }

    /// Writes `M` and `f` as [`LagrangianSystem::mass_matrix_and_forcing`]
    /// does and returns the powers `[Σ ∂D/∂q̇·q̇, Σ Q·q̇]` of
    /// [`LagrangianSystem::energies`], in one pass where the model shares
    /// their operations and input calls (the generated code does).
    #[allow(clippy::too_many_arguments)]
    fn mass_matrix_forcing_and_powers<I: InputFunctions + ?Sized>(
        &self,
        t: f64,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        inputs: &I,
        mass: &mut SMatrix<f64, N, N>,
        forcing: &mut SVector<f64, N>,
    ) -> [f64; 2] {
        self.mass_matrix_and_forcing(t, q, qd, inputs, mass, forcing);
        let energies = self.energies(t, q, qd, inputs);
        [energies.damping_power, energies.external_power]
    }

    /// The input-function calls of the dynamics: `(input index, number of
    /// arguments)` per distinct call, ordered by input index.
    fn input_sites(&self) -> &[(usize, usize)];

    /// The arguments of every call of [`LagrangianSystem::input_sites`] at
    /// this state, concatenated (`out` holds at least their total count).
    /// An argument that calls an input (friction under a contact's normal
    /// force, `rub(dot(x), press(y, dot(y)))`) calls it through `inputs`.
    fn input_arguments<I: InputFunctions + ?Sized>(
        &self,
        t: f64,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        inputs: &I,
        out: &mut [f64],
    );

    /// Writes `∂f/∂q`, `∂f/∂q̇` and `∂(M a)/∂q` for the accelerations `qdd`.
    fn jacobians<I: InputFunctions + ?Sized>(
        &self,
        t: f64,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        qdd: &SVector<f64, N>,
        inputs: &I,
        out: &mut Jacobians<N>,
    ) -> Result<(), ModelError> {
        let _ = (t, q, qd, qdd, inputs, out);
        Err(ModelError::JacobiansNotDerived)
    }

    /// Names of the spec's outputs (`output NAME [unit] = expr;`), in
    /// declaration order; empty for a model without outputs.
    fn output_names(&self) -> Vec<&str> {
        Vec::new()
    }

    /// What each output of [`LagrangianSystem::output_names`] reads beyond
    /// the coordinates and parameters (velocities, accelerations, the time,
    /// input functions), where the model knows it (an interpreted one
    /// does, from its tape); `None` by default.
    fn output_reads(&self) -> Option<Vec<crate::tape::StateReads>> {
        None
    }

    /// Writes the value of each output of [`LagrangianSystem::output_names`]
    /// to `out` (which holds at least as many values), at the state
    /// `(t, q, q̇)` with the accelerations `qdd` (those the equations of
    /// motion give there, for the outputs to mean what the spec says). A
    /// model without outputs writes nothing.
    fn outputs<I: InputFunctions + ?Sized>(
        &self,
        t: f64,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        qdd: &SVector<f64, N>,
        inputs: &I,
        out: &mut [f64],
    ) {
        let _ = (t, q, qd, qdd, inputs, out);
    }

    /// The number of switching functions: one per distinct kink of a
    /// non-smooth function (`abs`, `sign`, `min`, `max`) in the dynamics;
    /// 0 for a smooth model.
    fn switching_count(&self) -> usize {
        0
    }

    /// Writes the value of each switching function at `(t, q, q̇)` to `out`
    /// (which holds at least [`LagrangianSystem::switching_count`] values).
    /// The dynamics are smooth between the sign changes of these values; an
    /// integrator locates each one as an event. A smooth model writes nothing.
    fn switching_functions<I: InputFunctions + ?Sized>(
        &self,
        t: f64,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        inputs: &I,
        out: &mut [f64],
    ) {
        let _ = (t, q, qd, inputs, out);
    }

    /// Names of the spec's holonomic constraints (`constraint NAME = g;`,
    /// `g(q, t) = 0`), in declaration order; empty for a model without
    /// constraints.
    fn constraint_names(&self) -> Vec<&str> {
        Vec::new()
    }

    /// The number of constraints, `m`.
    fn constraint_count(&self) -> usize {
        self.constraint_names().len()
    }

    /// Writes the constraint terms at `(t, q, q̇)` to `out` (which holds at
    /// least `m (N + 3)` values): `g`, `∂g/∂t`, `G = ∂g/∂q` (row-major
    /// `m × N`) and `γ`, with `G q̈ = γ` along a motion that keeps the
    /// constraints, in the order of [`crate::layout::ConstraintLayout`]. A
    /// model without constraints writes nothing. The constrained equations
    /// of motion are `M q̈ = f + Gᵀλ`, `G q̈ = γ` ([`crate::constrained`]).
    fn constraints<I: InputFunctions + ?Sized>(
        &self,
        t: f64,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        inputs: &I,
        out: &mut [f64],
    ) {
        let _ = (t, q, qd, inputs, out);
    }

    /// `M(q, t)` (convenience over [`LagrangianSystem::mass_matrix_and_forcing`]).
    fn mass_matrix<I: InputFunctions + ?Sized>(
        &self,
        t: f64,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        inputs: &I,
    ) -> SMatrix<f64, N, N> {
        self.mass_matrix_and_forcing_pair(t, q, qd, inputs).0
    }

    /// `f(q, q̇, t)` (convenience over [`LagrangianSystem::mass_matrix_and_forcing`]).
    fn forcing<I: InputFunctions + ?Sized>(
        &self,
        t: f64,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        inputs: &I,
    ) -> SVector<f64, N> {
        self.mass_matrix_and_forcing_pair(t, q, qd, inputs).1
    }

    /// `(M, f)` returned by value.
    fn mass_matrix_and_forcing_pair<I: InputFunctions + ?Sized>(
        &self,
        t: f64,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        inputs: &I,
    ) -> (SMatrix<f64, N, N>, SVector<f64, N>) {
        let mut mass = SMatrix::zeros();
        let mut forcing = SVector::zeros();
        self.mass_matrix_and_forcing(t, q, qd, inputs, &mut mass, &mut forcing);
        (mass, forcing)
    }

    /// `M⁻¹ b` as [`solve_mass_matrix`] computes it: a compiled model skips
    /// the terms of the entries its equations make zero (as its interpreted
    /// twin does, bit for bit); `None` when `solve_mass_matrix` gives none.
    fn solve_mass(
        &self,
        mass: &SMatrix<f64, N, N>,
        b: &SVector<f64, N>,
    ) -> Option<SVector<f64, N>> {
        solve_mass_matrix(*mass, b)
    }

    /// `q̈ = M⁻¹ f` by [`LagrangianSystem::solve_mass`].
    fn accelerations<I: InputFunctions + ?Sized>(
        &self,
        t: f64,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        inputs: &I,
    ) -> Result<SVector<f64, N>, ModelError> {
        let (mass, forcing) = self.mass_matrix_and_forcing_pair(t, q, qd, inputs);
        self.solve_mass(&mass, &forcing)
            .ok_or_else(|| ModelError::SingularMassMatrix {
                t,
                q: q.iter().copied().collect(),
            })
    }
}

/// Solves `M x = f` by `L D Lᵀ`; `None` unless `M` is numerically positive
/// definite (a proper kinetic energy makes it so: a singular `M` has a
/// coordinate without inertia, an indefinite one a negative mass or inertia)
/// and the result is finite.
pub fn solve_mass_matrix<const N: usize>(
    mass: SMatrix<f64, N, N>,
    forcing: &SVector<f64, N>,
) -> Option<SVector<f64, N>> {
    crate::linalg::solve_with_pattern(&mass, forcing, &crate::linalg::LdltPattern::DENSE)
}
