//! The names a scenario and its components are resolved against: a model's
//! coordinates, parameters, inputs, outputs and constraints, with what is
//! known of their units and arguments.

use lagrangian_runtime::tape::StateReads;
use lagrangian_runtime::{InterpretedModel, LagrangianSystem};

/// The names a scenario is resolved against.
#[derive(Clone, Debug, Default)]
pub struct ModelNames {
    /// The generalized coordinates, in the model's order (the order of
    /// `q`).
    pub coordinates: Vec<String>,
    /// The parameters `[parameters]` and `--set` may set, in the model's
    /// order.
    pub parameters: Vec<String>,
    /// The input functions components are bound to, in the model's order.
    pub inputs: Vec<String>,
    /// The declared argument names of each input, where the model tells them
    /// (specs do; compiled models do not, and the number of arguments is
    /// then known from `input_sites` for the inputs the dynamics calls).
    pub input_arguments: Vec<Option<Vec<String>>>,
    /// `(input, number of arguments)` per input call of the dynamics.
    pub input_sites: Vec<(usize, usize)>,
    /// The unit of each coordinate, where the model declares it.
    pub coordinate_units: Vec<Option<String>>,
    /// The unit of each parameter, where the model declares it (empty when
    /// it does not say).
    pub parameter_units: Vec<Option<String>>,
    /// The unit of each input's value, where the model declares it (empty
    /// when it does not say).
    pub input_units: Vec<Option<String>>,
    /// The spec's declared outputs, in order.
    pub outputs: Vec<String>,
    /// The unit of each output, where declared.
    pub output_units: Vec<Option<String>>,
    /// What each output reads beyond the coordinates and parameters, where
    /// the model knows it (an interpreted one does): a crush channel may
    /// take an output that reads no velocity, acceleration or input.
    pub output_reads: Vec<Option<StateReads>>,
    /// The columns of the scenario's components (`front_end.force`) with
    /// their units, once they are bound (see [`ModelNames::with_components`]).
    pub component_columns: Vec<(String, Option<String>)>,
    /// The model's constraints, in order (`NAME.lambda`, `NAME.residual`).
    pub constraints: Vec<String>,
    /// The unit of each constraint's multiplier, where known.
    pub multiplier_units: Vec<Option<String>>,
    /// The default value of each parameter, in the order of `parameters`
    /// (what a factor `--set NAME*=x` multiplies when the scenario does not
    /// set it; empty where unknown).
    pub parameter_defaults: Vec<f64>,
}

impl ModelNames {
    /// The names of any model (compiled or interpreted).
    pub fn of<const N: usize, S: LagrangianSystem<N>>(system: &S) -> ModelNames {
        let own = |v: Vec<&str>| v.into_iter().map(str::to_string).collect();
        ModelNames {
            coordinates: own(system.coordinate_names()),
            parameters: own(system.parameter_names()),
            inputs: own(system.input_names()),
            input_arguments: vec![None; system.input_names().len()],
            input_sites: system.input_sites().to_vec(),
            outputs: own(system.output_names()),
            output_units: vec![None; system.output_names().len()],
            output_reads: match system.output_reads() {
                Some(reads) => reads.into_iter().map(Some).collect(),
                None => vec![None; system.output_names().len()],
            },
            constraints: own(system.constraint_names()),
            multiplier_units: vec![None; system.constraint_count()],
            parameter_defaults: system.parameters(),
            ..ModelNames::default()
        }
    }

    /// The names of a spec, with the declared arguments of every input.
    pub fn of_interpreted(model: &InterpretedModel) -> ModelNames {
        ModelNames {
            coordinates: model.coordinates().to_vec(),
            parameters: model.parameter_names().to_vec(),
            inputs: model.input_names().to_vec(),
            input_arguments: model.input_arguments().iter().cloned().map(Some).collect(),
            input_sites: model.input_sites().to_vec(),
            coordinate_units: model.coordinate_units().to_vec(),
            parameter_units: model.parameter_units().to_vec(),
            input_units: model.input_units().to_vec(),
            outputs: model.output_names().to_vec(),
            output_units: model.output_units().to_vec(),
            output_reads: model.output_reads().into_iter().map(Some).collect(),
            component_columns: Vec::new(),
            constraints: model.constraint_names().to_vec(),
            multiplier_units: model.multiplier_units().to_vec(),
            parameter_defaults: model.parameters().to_vec(),
        }
    }

    /// The number of arguments of input `k`, where known.
    pub fn arity(&self, k: usize) -> Option<usize> {
        match self.input_arguments.get(k) {
            Some(Some(arguments)) => Some(arguments.len()),
            _ => self
                .input_sites
                .iter()
                .find(|(input, _)| *input == k)
                .map(|&(_, arity)| arity),
        }
    }

    /// Input `k` as declared, `name(a, b)`, or its name and number of arguments.
    pub fn signature(&self, k: usize) -> String {
        let name = &self.inputs[k];
        match (self.input_arguments.get(k), self.arity(k)) {
            (Some(Some(arguments)), _) => format!("`{name}({})`", arguments.join(", ")),
            (_, Some(1)) => format!("`{name}` of 1 argument"),
            (_, Some(n)) => format!("`{name}` of {n} arguments"),
            (_, None) => format!("`{name}`"),
        }
    }
}
