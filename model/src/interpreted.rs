//! Models from spec files, evaluated by the core's interpreter at run time
//! (no recompilation), with the same numbers as the compiled code.

use crate::InputFunctions;
use crate::system::{Energies, Jacobians, LagrangianSystem, ModelError};
use lagrangian_core::program::{Program, RoutineKind};
use lagrangian_core::tape::Tape;
use lagrangian_core::{Compiled, SpecErrors};
use nalgebra::{SMatrix, SVector};
use std::cell::RefCell;
use std::sync::Arc;

/// A derived model evaluated by the interpreter, of any dimension.
///
/// Evaluation reuses one register file, so repeated calls do not allocate;
/// the type is `Send` but not `Sync` (give each thread its own clone).
#[derive(Clone, Debug)]
pub struct InterpretedModel {
    name: String,
    coordinates: Vec<String>,
    parameter_names: Vec<String>,
    input_names: Vec<String>,
    input_arguments: Vec<Vec<String>>,
    coordinate_units: Vec<Option<String>>,
    input_units: Vec<Option<String>>,
    program: Arc<Program>,
    tape: Arc<Tape>,
    parameters: Vec<f64>,
    /// The tape's register file, holding the constants and the parameters.
    registers: RefCell<Vec<f64>>,
    outputs: RefCell<Vec<f64>>,
}

impl InterpretedModel {
    /// Takes the program and metadata of a compiled spec, with default parameters.
    pub fn from_compiled(compiled: &Compiled) -> InterpretedModel {
        let model = &compiled.model;
        let program = compiled.program.clone();
        let longest = program
            .routines
            .iter()
            .map(|r| r.outputs.len())
            .max()
            .unwrap_or(0);
        let parameters = compiled.default_parameters();
        let tape = Tape::new(&program, parameters.len());
        InterpretedModel {
            name: model.name.clone(),
            coordinates: model.coordinates.iter().map(|c| c.name.clone()).collect(),
            parameter_names: model.parameters.iter().map(|p| p.name.clone()).collect(),
            input_names: model.inputs.iter().map(|i| i.name.clone()).collect(),
            input_arguments: model
                .inputs
                .iter()
                .map(|i| i.arguments.iter().map(|(name, _)| name.clone()).collect())
                .collect(),
            coordinate_units: model
                .coordinates
                .iter()
                .map(|c| c.unit.as_ref().map(|u| u.text.clone()))
                .collect(),
            input_units: model
                .inputs
                .iter()
                .map(|i| i.unit.as_ref().map(|u| u.text.clone()))
                .collect(),
            registers: RefCell::new(tape.registers(&parameters)),
            outputs: RefCell::new(vec![0.0; longest]),
            program: Arc::new(program),
            tape: Arc::new(tape),
            parameters,
        }
    }

    /// Parses, derives and optimizes a spec.
    pub fn from_source(source: &str) -> Result<InterpretedModel, SpecErrors> {
        Ok(InterpretedModel::from_compiled(&Compiled::from_source(
            source,
        )?))
    }

    pub fn dimension(&self) -> usize {
        self.coordinates.len()
    }

    pub fn name(&self) -> &str {
        &self.name
    }

    pub fn coordinates(&self) -> &[String] {
        &self.coordinates
    }

    pub fn parameter_names(&self) -> &[String] {
        &self.parameter_names
    }

    pub fn input_names(&self) -> &[String] {
        &self.input_names
    }

    /// The declared argument names of each input function.
    pub fn input_arguments(&self) -> &[Vec<String>] {
        &self.input_arguments
    }

    /// Units of the coordinates as written in the spec.
    pub fn coordinate_units(&self) -> &[Option<String>] {
        &self.coordinate_units
    }

    /// Units of the input functions' values as written in the spec.
    pub fn input_units(&self) -> &[Option<String>] {
        &self.input_units
    }

    pub fn parameters(&self) -> &[f64] {
        &self.parameters
    }

    pub fn program(&self) -> &Program {
        &self.program
    }

    pub fn has_jacobians(&self) -> bool {
        self.program.routine(RoutineKind::Jacobians).is_some()
    }

    /// Sets a parameter by name, suggesting the closest name when unknown.
    pub fn set_parameter(&mut self, name: &str, value: f64) -> Result<(), ModelError> {
        match self.parameter_names.iter().position(|p| p == name) {
            Some(i) => {
                self.parameters[i] = value;
                self.tape
                    .set_parameters(self.registers.get_mut(), &self.parameters);
                Ok(())
            }
            None => Err(ModelError::UnknownParameter {
                name: name.to_string(),
                suggestion: lagrangian_core::diagnostic::closest(
                    name,
                    self.parameter_names.iter().map(String::as_str),
                )
                .map(str::to_string),
            }),
        }
    }

    fn check(&self, values: &[f64]) -> Result<(), ModelError> {
        if values.len() == self.dimension() {
            Ok(())
        } else {
            Err(ModelError::DimensionMismatch {
                expected: self.dimension(),
                found: values.len(),
            })
        }
    }

    /// Runs one routine and hands its outputs to `take`.
    fn run<I: InputFunctions + ?Sized, R>(
        &self,
        kind: RoutineKind,
        state: (f64, &[f64], &[f64], &[f64]),
        inputs: &I,
        take: impl FnOnce(&[f64]) -> R,
    ) -> Result<R, ModelError> {
        self.check(state.1)?;
        self.check(state.2)?;
        let mut registers = self.registers.borrow_mut();
        let mut outputs = self.outputs.borrow_mut();
        let out = &mut outputs[..self.tape.output_count(kind)];
        if !self.tape.run(kind, state, inputs, &mut registers, out) {
            return Err(ModelError::JacobiansNotDerived);
        }
        Ok(take(out))
    }

    /// `M` (row-major `n × n`) and `f` at one state.
    pub fn evaluate_dynamics<I: InputFunctions + ?Sized>(
        &self,
        t: f64,
        q: &[f64],
        qd: &[f64],
        inputs: &I,
        mass: &mut [f64],
        forcing: &mut [f64],
    ) -> Result<(), ModelError> {
        let n = self.dimension();
        self.run(RoutineKind::Dynamics, (t, q, qd, &[]), inputs, |out| {
            let mut k = 0;
            for i in 0..n {
                for j in i..n {
                    mass[i * n + j] = out[k];
                    mass[j * n + i] = out[k];
                    k += 1;
                }
            }
            forcing[..n].copy_from_slice(&out[k..k + n]);
        })
    }

    /// Energy bookkeeping at one state.
    pub fn evaluate_energies<I: InputFunctions + ?Sized>(
        &self,
        t: f64,
        q: &[f64],
        qd: &[f64],
        inputs: &I,
    ) -> Result<Energies, ModelError> {
        self.run(RoutineKind::Energies, (t, q, qd, &[]), inputs, |out| {
            Energies {
                kinetic: out[0],
                potential: out[1],
                dissipation: out[2],
                damping_power: out[3],
                external_power: out[4],
            }
        })
    }

    /// `(input index, number of arguments)` of every input call of the dynamics.
    pub fn input_sites(&self) -> &[(usize, usize)] {
        &self.program.input_sites
    }

    /// The arguments of every input call at one state (see [`InterpretedModel::input_sites`]).
    pub fn evaluate_input_arguments(
        &self,
        t: f64,
        q: &[f64],
        qd: &[f64],
        out: &mut [f64],
    ) -> Result<(), ModelError> {
        self.run(
            RoutineKind::InputArguments,
            (t, q, qd, &[]),
            &crate::NoInputs,
            |values| out[..values.len()].copy_from_slice(values),
        )
    }

    /// `∂f/∂q`, `∂f/∂q̇`, `∂(M a)/∂q`, each row-major `n × n`, concatenated.
    pub fn evaluate_jacobians<I: InputFunctions + ?Sized>(
        &self,
        state: (f64, &[f64], &[f64], &[f64]),
        inputs: &I,
        out: &mut [f64],
    ) -> Result<(), ModelError> {
        self.check(state.3)?;
        self.run(RoutineKind::Jacobians, state, inputs, |values| {
            out[..values.len()].copy_from_slice(values)
        })
    }
}

/// An [`InterpretedModel`] of known dimension `N`, usable wherever a compiled
/// model is (it implements [`LagrangianSystem<N>`]).
#[derive(Clone, Debug)]
pub struct Interpreted<const N: usize>(InterpretedModel);

impl<const N: usize> Interpreted<N> {
    /// Fails when the model does not have `N` coordinates.
    pub fn new(model: InterpretedModel) -> Result<Self, ModelError> {
        if model.dimension() == N {
            Ok(Interpreted(model))
        } else {
            Err(ModelError::DimensionMismatch {
                expected: N,
                found: model.dimension(),
            })
        }
    }

    pub fn inner(&self) -> &InterpretedModel {
        &self.0
    }
}

impl<const N: usize> LagrangianSystem<N> for Interpreted<N> {
    fn model_name(&self) -> &str {
        self.0.name()
    }

    fn coordinate_names(&self) -> Vec<&str> {
        self.0.coordinates.iter().map(String::as_str).collect()
    }

    fn parameter_names(&self) -> Vec<&str> {
        self.0.parameter_names.iter().map(String::as_str).collect()
    }

    fn input_names(&self) -> Vec<&str> {
        self.0.input_names.iter().map(String::as_str).collect()
    }

    fn parameters(&self) -> Vec<f64> {
        self.0.parameters.clone()
    }

    fn set_parameter(&mut self, name: &str, value: f64) -> Result<(), ModelError> {
        self.0.set_parameter(name, value)
    }

    fn input_sites(&self) -> &[(usize, usize)] {
        self.0.input_sites()
    }

    fn input_arguments(&self, t: f64, q: &SVector<f64, N>, qd: &SVector<f64, N>, out: &mut [f64]) {
        // The dimension is N by construction, so this cannot fail.
        let _ = self
            .0
            .evaluate_input_arguments(t, q.as_slice(), qd.as_slice(), out);
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
        // The dimension is N by construction, so this cannot fail.
        let state = (t, q.as_slice(), qd.as_slice(), &[][..]);
        let _ = self.0.run(RoutineKind::Dynamics, state, inputs, |out| {
            unpack_dynamics(out, mass, forcing);
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
                let powers = unpack_dynamics(out, mass, forcing);
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

    fn jacobians<I: InputFunctions + ?Sized>(
        &self,
        t: f64,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        qdd: &SVector<f64, N>,
        inputs: &I,
        out: &mut Jacobians<N>,
    ) -> Result<(), ModelError> {
        let mut values = vec![0.0; 3 * N * N];
        self.0.evaluate_jacobians(
            (t, q.as_slice(), qd.as_slice(), qdd.as_slice()),
            inputs,
            &mut values,
        )?;
        let blocks = [
            &mut out.forcing_q,
            &mut out.forcing_qd,
            &mut out.mass_times_acceleration_q,
        ];
        for (b, matrix) in blocks.into_iter().enumerate() {
            for i in 0..N {
                for k in 0..N {
                    matrix[(i, k)] = values[b * N * N + i * N + k];
                }
            }
        }
        Ok(())
    }
}

/// Writes the dynamics outputs (upper triangle of `M`, row-major, then `f`)
/// and returns what follows them.
fn unpack_dynamics<'a, const N: usize>(
    out: &'a [f64],
    mass: &mut SMatrix<f64, N, N>,
    forcing: &mut SVector<f64, N>,
) -> &'a [f64] {
    let mut k = 0;
    for i in 0..N {
        for j in i..N {
            mass[(i, j)] = out[k];
            mass[(j, i)] = out[k];
            k += 1;
        }
    }
    forcing.copy_from_slice(&out[k..k + N]);
    &out[k + N..]
}
