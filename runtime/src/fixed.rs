//! The interpreted model behind the fixed-size interface of compiled models,
//! and the one place that turns a run-time dimension into a constant.

use crate::error::ModelError;
use crate::interpreted::InterpretedModel;
use crate::layout::{RoutineKind, unpack_dynamics};
use crate::linalg::{Envelope, LdltPattern, solve_in_envelope, solve_with_pattern};
use crate::system::{Jacobians, LagrangianSystem};
use crate::{Energies, InputFunctions, MechanicalEnergy};
use nalgebra::{SMatrix, SVector};

/// An [`InterpretedModel`] of known dimension `N`, usable wherever a compiled
/// model is (it implements [`LagrangianSystem<N>`]).
#[derive(Clone, Debug)]
pub struct Interpreted<const N: usize>(InterpretedModel, Envelope<N>);

impl<const N: usize> Interpreted<N> {
    /// Fails when the model does not have `N` coordinates.
    pub fn new(model: InterpretedModel) -> Result<Self, ModelError> {
        if model.dimension() == N {
            Ok(Interpreted::of_dimension(model))
        } else {
            Err(ModelError::DimensionMismatch {
                expected: N,
                found: model.dimension(),
            })
        }
    }

    /// The model of any dimension inside.
    pub fn inner(&self) -> &InterpretedModel {
        &self.0
    }

    /// `model`, whose dimension is `N`, with the pattern of its solve: the
    /// zeros of its `M` and their envelope, as the emitted code has them.
    fn of_dimension(model: InterpretedModel) -> Self {
        let nonzero = model.mass_nonzeros();
        let rows = std::array::from_fn(|i| std::array::from_fn(|j| nonzero[i * N + j]));
        Interpreted(model, Envelope::of(LdltPattern::from_mass(rows)))
    }
}

/// Work on an interpreted model that needs its dimension as a constant `N`
/// (the fixed-size interface): given to [`InterpretedModel::with_dimension`].
pub trait WithDimension {
    /// What the work produces.
    type Output;

    /// Does the work on the model as an `Interpreted<N>`.
    fn run<const N: usize>(self, model: Interpreted<N>) -> Self::Output;
}

/// The largest number of coordinates [`InterpretedModel::with_dimension`]
/// handles (each dimension is compiled once into every program that uses it).
pub const MAX_INTERPRETED_DIMENSION: usize = 12;

impl InterpretedModel {
    /// Runs `work` on this model as an [`Interpreted<N>`] with `N` its
    /// dimension; models of more than [`MAX_INTERPRETED_DIMENSION`]
    /// coordinates are an error.
    pub fn with_dimension<W: WithDimension>(self, work: W) -> Result<W::Output, ModelError> {
        macro_rules! dispatch {
            ($($n:literal)*) => {
                match self.dimension() {
                    $($n => Ok(work.run(Interpreted::<$n>::of_dimension(self))),)*
                    found => Err(ModelError::UnsupportedDimension {
                        found,
                        max: MAX_INTERPRETED_DIMENSION,
                    }),
                }
            };
        }
        dispatch!(1 2 3 4 5 6 7 8 9 10 11 12)
    }
}

impl<const N: usize> LagrangianSystem<N> for Interpreted<N> {
    fn model_name(&self) -> &str {
        self.0.name()
    }

    fn coordinate_names(&self) -> Vec<&str> {
        self.0.coordinates().iter().map(String::as_str).collect()
    }

    fn parameter_names(&self) -> Vec<&str> {
        self.0
            .parameter_names()
            .iter()
            .map(String::as_str)
            .collect()
    }

    fn input_names(&self) -> Vec<&str> {
        self.0.input_names().iter().map(String::as_str).collect()
    }

    fn parameters(&self) -> Vec<f64> {
        self.0.parameters().to_vec()
    }

    fn set_parameter(&mut self, name: &str, value: f64) -> Result<(), ModelError> {
        self.0.set_parameter(name, value)
    }

    fn input_sites(&self) -> &[(usize, usize)] {
        self.0.input_sites()
    }

    fn output_names(&self) -> Vec<&str> {
        self.0.output_names().iter().map(String::as_str).collect()
    }

    fn output_reads(&self) -> Option<Vec<crate::tape::StateReads>> {
        Some(self.0.output_reads())
    }

    fn outputs<I: InputFunctions + ?Sized>(
        &self,
        t: f64,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        qdd: &SVector<f64, N>,
        inputs: &I,
        out: &mut [f64],
    ) {
        // The dimension is N by construction, so this cannot fail.
        let state = (t, q.as_slice(), qd.as_slice(), qdd.as_slice());
        let _ = self.0.evaluate_outputs(state, inputs, out);
    }

    fn switching_count(&self) -> usize {
        self.0.switching_count()
    }

    fn switching_functions<I: InputFunctions + ?Sized>(
        &self,
        t: f64,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        inputs: &I,
        out: &mut [f64],
    ) {
        // The dimension is N by construction, so this cannot fail.
        let _ = (self.0).evaluate_switching(t, q.as_slice(), qd.as_slice(), inputs, out);
    }

    fn constraint_names(&self) -> Vec<&str> {
        (self.0.constraint_names().iter())
            .map(String::as_str)
            .collect()
    }

    fn constraints<I: InputFunctions + ?Sized>(
        &self,
        t: f64,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        inputs: &I,
        out: &mut [f64],
    ) {
        // The dimension is N by construction, so this cannot fail.
        let _ = (self.0).evaluate_constraints(t, q.as_slice(), qd.as_slice(), inputs, out);
    }

    fn input_arguments<I: InputFunctions + ?Sized>(
        &self,
        t: f64,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        inputs: &I,
        out: &mut [f64],
    ) {
        // The dimension is N by construction, so this cannot fail.
        let _ = (self.0).evaluate_input_arguments(t, q.as_slice(), qd.as_slice(), inputs, out);
    }

    fn solve_mass(
        &self,
        mass: &SMatrix<f64, N, N>,
        b: &SVector<f64, N>,
    ) -> Option<SVector<f64, N>> {
        match self.1.is_narrow() {
            true => solve_in_envelope(mass, b, &self.1),
            false => solve_with_pattern(mass, b, self.1.pattern()),
        }
    }

    fn mass_matrix_and_forcing<I: InputFunctions + ?Sized>(
        &self,
        t: f64,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        inputs: &I,
        mass: &mut SMatrix<f64, N, N>,
        forcing: &mut SVector<f64, N>,
    ) {
        // M is symmetric, so its column-major storage is its row-major one.
        // The dimension is N by construction, so this cannot fail.
        let state = (t, q.as_slice(), qd.as_slice(), &[][..]);
        let _ = self.0.run(RoutineKind::Dynamics, state, inputs, |out| {
            unpack_dynamics(out, N, mass.as_mut_slice(), forcing.as_mut_slice());
        });
    }

    fn mass_matrix_forcing_and_powers<I: InputFunctions + ?Sized>(
        &self,
        t: f64,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        inputs: &I,
        mass: &mut SMatrix<f64, N, N>,
        forcing: &mut SVector<f64, N>,
    ) -> [f64; 2] {
        let state = (t, q.as_slice(), qd.as_slice(), &[][..]);
        self.0
            .run(RoutineKind::DynamicsAndPowers, state, inputs, |out| {
                let powers = unpack_dynamics(out, N, mass.as_mut_slice(), forcing.as_mut_slice());
                [powers[0], powers[1]]
            })
            .unwrap_or([f64::NAN; 2])
    }

    fn energies<I: InputFunctions + ?Sized>(
        &self,
        t: f64,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        inputs: &I,
    ) -> Energies {
        self.0
            .evaluate_energies(t, q.as_slice(), qd.as_slice(), inputs)
            .unwrap_or_default()
    }

    fn mechanical_energy<I: InputFunctions + ?Sized>(
        &self,
        t: f64,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        inputs: &I,
    ) -> MechanicalEnergy {
        self.0
            .evaluate_mechanical_energy(t, q.as_slice(), qd.as_slice(), inputs)
            .unwrap_or_default()
    }

    fn jacobians<I: InputFunctions + ?Sized>(
        &self,
        t: f64,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        qdd: &SVector<f64, N>,
        inputs: &I,
        out: &mut Jacobians<N>,
    ) -> Result<(), ModelError> {
        let state = (t, q.as_slice(), qd.as_slice(), qdd.as_slice());
        self.0.check(state.3)?;
        self.0.run(RoutineKind::Jacobians, state, inputs, |values| {
            // In the order of `layout::JACOBIAN_BLOCKS`.
            let blocks = [
                &mut out.forcing_q,
                &mut out.forcing_qd,
                &mut out.mass_times_acceleration_q,
            ];
            for (b, matrix) in blocks.into_iter().enumerate() {
                *matrix = SMatrix::from_row_slice(&values[b * N * N..(b + 1) * N * N]);
            }
        })
    }
}
