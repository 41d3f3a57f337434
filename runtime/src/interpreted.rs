//! Models run by the interpreter from a compiled spec's [`Tape`], without
//! recompiling, with the same numbers as the compiled code.

use crate::InputFunctions;
use crate::error::ModelError;
use crate::layout::{
    ConstraintLayout, Energies, MechanicalEnergy, RoutineKind, mass_entries, unpack_dynamics,
};
use crate::native::{NativeRoutines, with_input_call};
use crate::tape::{DerivedRoutine, StateReads, Tape};
use std::cell::RefCell;
use std::sync::Arc;

/// What the interpreter needs to know of a model besides its tape: names,
/// units and defaults, each list in declaration order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ModelDescription {
    /// The model's name (`model Name;`).
    pub name: String,
    /// The generalized coordinates.
    pub coordinates: Vec<String>,
    /// The unit of each coordinate as written in the spec, if any.
    pub coordinate_units: Vec<Option<String>>,
    /// The parameters.
    pub parameters: Vec<String>,
    /// The default value of each parameter.
    pub parameter_defaults: Vec<f64>,
    /// The unit of each parameter as written in the spec, if any (empty
    /// where a description does not say).
    pub parameter_units: Vec<Option<String>>,
    /// The input functions.
    pub inputs: Vec<String>,
    /// The declared argument names of each input function.
    pub input_arguments: Vec<Vec<String>>,
    /// The unit of each input function's value as written in the spec, if any.
    pub input_units: Vec<Option<String>>,
    /// `(input index, number of arguments)` of every distinct input call of
    /// the dynamics, ordered by input index.
    pub input_sites: Vec<(usize, usize)>,
    /// The spec's outputs (`output NAME [unit] = expr;`), in order.
    pub outputs: Vec<String>,
    /// The unit of each output as written in the spec, if any.
    pub output_units: Vec<Option<String>>,
    /// The spec's holonomic constraints (`constraint NAME = expr;`), in order.
    pub constraints: Vec<String>,
    /// The unit of each constraint's multiplier `λ` (energy per unit of the
    /// constraint), where the spec's units are checked.
    pub multiplier_units: Vec<Option<String>>,
}

impl ModelDescription {
    /// `Err` naming the first list whose length does not fit the tape, or
    /// the first routine of the tape with the wrong number of outputs.
    fn check(&self, tape: &Tape) -> Result<(), ModelError> {
        let n = tape.dimension();
        let arguments: usize = self.input_sites.iter().map(|&(_, arity)| arity).sum();
        let lengths = [
            ("coordinates", self.coordinates.len(), n),
            ("coordinate units", self.coordinate_units.len(), n),
            ("parameters", self.parameters.len(), tape.parameters()),
            (
                "parameter defaults",
                self.parameter_defaults.len(),
                tape.parameters(),
            ),
            (
                "input arguments",
                self.input_arguments.len(),
                self.inputs.len(),
            ),
            ("input units", self.input_units.len(), self.inputs.len()),
            ("output units", self.output_units.len(), self.outputs.len()),
            (
                "outputs",
                self.outputs.len(),
                tape.output_count(RoutineKind::Outputs),
            ),
            (
                "multiplier units",
                self.multiplier_units.len(),
                self.constraints.len(),
            ),
            (
                "constraint terms",
                self.constraint_layout(n).len(),
                tape.output_count(RoutineKind::Constraints),
            ),
        ];
        for (what, found, expected) in lengths {
            if found != expected {
                return Err(ModelError::InconsistentModel(format!(
                    "{found} {what} for {expected}"
                )));
            }
        }
        for kind in RoutineKind::ALL.into_iter().filter(|&k| tape.has(k)) {
            let expected = match kind {
                RoutineKind::InputArguments => arguments,
                RoutineKind::Outputs => self.outputs.len(),
                // The compiler decides how many; any count is consistent.
                RoutineKind::Switching => tape.output_count(kind),
                RoutineKind::Constraints => self.constraint_layout(n).len(),
                RoutineKind::Dynamics
                | RoutineKind::Energies
                | RoutineKind::Jacobians
                | RoutineKind::DynamicsAndPowers => kind.output_count(n).unwrap_or(0),
            };
            if tape.output_count(kind) != expected {
                return Err(ModelError::InconsistentModel(format!(
                    "routine {kind:?} has {} outputs, not {expected}",
                    tape.output_count(kind)
                )));
            }
        }
        Ok(())
    }

    /// Where the terms of the constraint routine are, for `n` coordinates.
    fn constraint_layout(&self, n: usize) -> ConstraintLayout {
        ConstraintLayout {
            m: self.constraints.len(),
            n,
        }
    }
}

/// A derived model evaluated by the interpreter, of any dimension.
///
/// Evaluation reuses one register file, so repeated calls do not allocate;
/// the type is `Send` but not `Sync` (give each thread its own clone).
/// `lagrangian_core::Compiled::interpreted` makes one from a spec.
#[derive(Clone, Debug)]
pub struct InterpretedModel {
    description: Arc<ModelDescription>,
    tape: Arc<Tape>,
    parameters: Vec<f64>,
    /// The tape's register file, holding the constants and the parameters.
    registers: RefCell<Vec<f64>>,
    outputs: RefCell<Vec<f64>>,
    /// Native code for the tape's routines, run in its place where it has them.
    native: Option<Arc<dyn NativeRoutines>>,
}

impl InterpretedModel {
    /// The model `description` evaluated by `tape`, with default parameters.
    pub fn new(description: ModelDescription, tape: Tape) -> Result<InterpretedModel, ModelError> {
        description.check(&tape)?;
        let longest = (RoutineKind::ALL.into_iter())
            .map(|kind| tape.output_count(kind))
            .max()
            .unwrap_or(0);
        let parameters = description.parameter_defaults.clone();
        Ok(InterpretedModel {
            registers: RefCell::new(tape.registers(&parameters)),
            outputs: RefCell::new(vec![0.0; longest]),
            description: Arc::new(description),
            tape: Arc::new(tape),
            parameters,
            native: None,
        })
    }

    /// The tape the model runs.
    pub fn tape(&self) -> &Tape {
        &self.tape
    }

    /// Runs the routines `native` has code for with it instead of the tape
    /// (see [`crate::native`]); `native` must have been made for this
    /// model's tape.
    pub fn set_native(&mut self, native: Arc<dyn NativeRoutines>) {
        self.native = Some(native);
    }

    /// Whether native code runs some of the routines.
    pub fn has_native(&self) -> bool {
        self.native.is_some()
    }

    /// The number of coordinates.
    pub fn dimension(&self) -> usize {
        self.description.coordinates.len()
    }

    /// The model's name as declared in its spec.
    pub fn name(&self) -> &str {
        &self.description.name
    }

    /// The names, units and defaults of the model.
    pub fn description(&self) -> &ModelDescription {
        &self.description
    }

    /// Names of the generalized coordinates, in order.
    pub fn coordinates(&self) -> &[String] {
        &self.description.coordinates
    }

    /// Names of the parameters, in order.
    pub fn parameter_names(&self) -> &[String] {
        &self.description.parameters
    }

    /// Units of the parameters as written in the spec (empty where the
    /// description does not say).
    pub fn parameter_units(&self) -> &[Option<String>] {
        &self.description.parameter_units
    }

    /// Names of the input functions, in order.
    pub fn input_names(&self) -> &[String] {
        &self.description.inputs
    }

    /// The declared argument names of each input function.
    pub fn input_arguments(&self) -> &[Vec<String>] {
        &self.description.input_arguments
    }

    /// Units of the coordinates as written in the spec.
    pub fn coordinate_units(&self) -> &[Option<String>] {
        &self.description.coordinate_units
    }

    /// Units of the input functions' values as written in the spec.
    pub fn input_units(&self) -> &[Option<String>] {
        &self.description.input_units
    }

    /// Names of the spec's outputs, in order.
    pub fn output_names(&self) -> &[String] {
        &self.description.outputs
    }

    /// Names of the spec's constraints, in order.
    pub fn constraint_names(&self) -> &[String] {
        &self.description.constraints
    }

    /// Units of the constraints' multipliers, where known.
    pub fn multiplier_units(&self) -> &[Option<String>] {
        &self.description.multiplier_units
    }

    /// Units of the outputs as written in the spec.
    pub fn output_units(&self) -> &[Option<String>] {
        &self.description.output_units
    }

    /// Current parameter values, in the order of
    /// [`InterpretedModel::parameter_names`].
    pub fn parameters(&self) -> &[f64] {
        &self.parameters
    }

    /// What each output of [`InterpretedModel::output_names`] reads beyond
    /// the coordinates and parameters, in order.
    pub fn output_reads(&self) -> Vec<StateReads> {
        (0..self.output_names().len())
            .map(|k| (self.tape.reads(RoutineKind::Outputs, k)).unwrap_or_default())
            .collect()
    }

    /// Whether the spec asked for Jacobians (`jacobians;`).
    pub fn has_jacobians(&self) -> bool {
        self.tape.has(RoutineKind::Jacobians)
    }

    /// Whether each entry `M_ij` of the mass matrix can be nonzero, row by
    /// row (`n × n`): `false` for those the equations make the constant zero,
    /// as the emitted code knows them (it skips their terms in the solve).
    pub fn mass_nonzeros(&self) -> Vec<bool> {
        let n = self.dimension();
        let mut nonzero = vec![true; n * n];
        for (k, (i, j)) in mass_entries(n).enumerate() {
            if self.tape.constant_output(RoutineKind::Dynamics, k) == Some(0.0) {
                nonzero[i * n + j] = false;
                nonzero[j * n + i] = false;
            }
        }
        nonzero
    }

    /// Sets a parameter by name, suggesting the closest name when unknown.
    pub fn set_parameter(&mut self, name: &str, value: f64) -> Result<(), ModelError> {
        let names = &self.description.parameters;
        match names.iter().position(|p| p == name) {
            Some(i) => {
                self.parameters[i] = value;
                self.tape
                    .set_parameters(self.registers.get_mut(), &self.parameters);
                Ok(())
            }
            None => {
                let candidates: Vec<&str> = names.iter().map(String::as_str).collect();
                Err(ModelError::unknown_parameter(name, &candidates))
            }
        }
    }

    #[inline]
    pub(crate) fn check(&self, values: &[f64]) -> Result<(), ModelError> {
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
    #[inline(always)]
    pub(crate) fn run<I: InputFunctions + ?Sized, R>(
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
        if !self.run_native(kind, state, inputs, &mut registers, out)
            && !self.tape.run(kind, state, inputs, &mut registers, out)
        {
            return Err(ModelError::JacobiansNotDerived);
        }
        Ok(take(out))
    }

    /// Runs routine `kind` as native code; `false` when there is none for it.
    #[inline(always)]
    fn run_native<I: InputFunctions + ?Sized>(
        &self,
        kind: RoutineKind,
        state: (f64, &[f64], &[f64], &[f64]),
        inputs: &I,
        registers: &mut [f64],
        out: &mut [f64],
    ) -> bool {
        let Some(native) = &self.native else {
            return false;
        };
        self.tape.load_state(state, registers);
        with_input_call(inputs, |call| native.run(kind, registers, out, call))
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
            unpack_dynamics(out, n, mass, forcing);
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
            let mut values = [0.0; 5];
            values.copy_from_slice(&out[..5]);
            Energies::from_outputs(&values)
        })
    }

    /// `T` and `V` at one state, bit for bit those of
    /// [`InterpretedModel::evaluate_energies`], by the tape's
    /// [`DerivedRoutine::MechanicalEnergy`]: without the operations and
    /// input calls only the dissipation and the powers need.
    pub fn evaluate_mechanical_energy<I: InputFunctions + ?Sized>(
        &self,
        t: f64,
        q: &[f64],
        qd: &[f64],
        inputs: &I,
    ) -> Result<MechanicalEnergy, ModelError> {
        self.check(q)?;
        self.check(qd)?;
        let which = DerivedRoutine::MechanicalEnergy;
        let state = (t, q, qd, &[][..]);
        let mut registers = self.registers.borrow_mut();
        let mut out = [0.0; 2];
        let native = self.native.as_ref().is_some_and(|native| {
            self.tape.load_state(state, &mut registers);
            with_input_call(inputs, |call| {
                native.run_derived(which, &registers, &mut out, call)
            })
        });
        if native || (self.tape).run_derived(which, state, inputs, &mut registers, &mut out) {
            let [kinetic, potential] = out;
            return Ok(MechanicalEnergy { kinetic, potential });
        }
        drop(registers);
        // No energies routine to derive it from: the error of the energies.
        self.evaluate_energies(t, q, qd, inputs)
            .map(|e| e.mechanical())
    }

    /// `(input index, number of arguments)` of every input call of the dynamics.
    pub fn input_sites(&self) -> &[(usize, usize)] {
        &self.description.input_sites
    }

    /// The arguments of every input call at one state (see
    /// [`InterpretedModel::input_sites`]), concatenated into `out`.
    #[inline]
    pub fn evaluate_input_arguments<I: InputFunctions + ?Sized>(
        &self,
        t: f64,
        q: &[f64],
        qd: &[f64],
        inputs: &I,
        out: &mut [f64],
    ) -> Result<(), ModelError> {
        self.run(
            RoutineKind::InputArguments,
            (t, q, qd, &[]),
            inputs,
            |values| out[..values.len()].copy_from_slice(values),
        )
    }

    /// `∂f/∂q`, `∂f/∂q̇`, `∂(M a)/∂q` at `(t, q, q̇, a)`, each row-major
    /// `n × n`, concatenated into `out`.
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

    /// The number of switching functions (0 for a smooth model; see
    /// [`RoutineKind::Switching`]).
    pub fn switching_count(&self) -> usize {
        self.tape.output_count(RoutineKind::Switching)
    }

    /// The switching functions at `(t, q, q̇)` into `out`; nothing for a
    /// smooth model.
    pub fn evaluate_switching<I: InputFunctions + ?Sized>(
        &self,
        t: f64,
        q: &[f64],
        qd: &[f64],
        inputs: &I,
        out: &mut [f64],
    ) -> Result<(), ModelError> {
        self.run_optional(RoutineKind::Switching, (t, q, qd, &[]), inputs, out)
    }

    /// The outputs at `(t, q, q̇, q̈)`, in the order of
    /// [`InterpretedModel::output_names`], into `out`; nothing for a model
    /// without outputs.
    pub fn evaluate_outputs<I: InputFunctions + ?Sized>(
        &self,
        state: (f64, &[f64], &[f64], &[f64]),
        inputs: &I,
        out: &mut [f64],
    ) -> Result<(), ModelError> {
        if self.tape.has(RoutineKind::Outputs) {
            self.check(state.3)?;
        }
        self.run_optional(RoutineKind::Outputs, state, inputs, out)
    }

    /// The constraint terms `g`, `g_t`, `G`, `γ` at `(t, q, q̇)` (in the
    /// order of [`ConstraintLayout`]) into `out`; nothing for a model
    /// without constraints.
    pub fn evaluate_constraints<I: InputFunctions + ?Sized>(
        &self,
        t: f64,
        q: &[f64],
        qd: &[f64],
        inputs: &I,
        out: &mut [f64],
    ) -> Result<(), ModelError> {
        self.run_optional(RoutineKind::Constraints, (t, q, qd, &[]), inputs, out)
    }

    /// Runs the routine `kind` that a model may lack, copying its values
    /// into the start of `out`; nothing when the model has no such routine.
    fn run_optional<I: InputFunctions + ?Sized>(
        &self,
        kind: RoutineKind,
        state: (f64, &[f64], &[f64], &[f64]),
        inputs: &I,
        out: &mut [f64],
    ) -> Result<(), ModelError> {
        if !self.tape.has(kind) {
            return Ok(());
        }
        self.run(kind, state, inputs, |values| {
            out[..values.len()].copy_from_slice(values)
        })
    }
}
