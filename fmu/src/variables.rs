//! The FMU's variables and their value references: one table, read by the
//! runtime (what `fmi2GetReal`/`fmi2SetReal` of a reference mean) and by
//! `lpm export-fmu` (the `<ModelVariables>` of modelDescription.xml), so
//! that the two cannot disagree.
//!
//! The order is fixed: coordinates `q`, rates `q̇` (together the continuous
//! states), accelerations `q̈`, parameters, inputs the scenario leaves
//! unbound, the spec's outputs, then the scenario's crush and deceleration
//! and the components' columns (crush force, weld moment). The value
//! reference of a variable is its position in the table.
//!
//! Names: the spec's own (coordinates, parameters, inputs, outputs) are
//! identifiers, and what the FMU adds lives in a namespace of its own that
//! no identifier can take: `der(q)` and `der(der(q))` for the rates and
//! accelerations, [`METRICS`]`.crush` and `metrics.deceleration` for the
//! scenario's crush signal, `COMPONENT.COLUMN` (`front_end.force`) for the
//! components' columns. So every spec exports under its own names; a clash
//! left (a component called `metrics` with a column `crush`, which no
//! component has today) is an error naming both variables.

/// The namespace of the variables the FMU adds from the scenario's
/// `[metrics]` (`metrics.crush`, `metrics.deceleration`).
pub const METRICS: &str = "metrics";

use lagrangian_core::spec::Model;
use lagrangian_sim::scenario::Scenario;

/// What a variable is the value of.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Quantity {
    /// Coordinate `q_i`: a continuous state.
    Coordinate(usize),
    /// Rate `q̇_i`: a continuous state, the derivative of `q_i`.
    Rate(usize),
    /// Acceleration `q̈_i`: the derivative of `q̇_i`.
    Acceleration(usize),
    /// Spec parameter `i`.
    Parameter(usize),
    /// Spec input `i`, which the scenario does not bind: a constant the
    /// host sets.
    Input(usize),
    /// Spec output `i` (`output NAME [unit] = expr;`).
    Output(usize),
    /// The scenario's crush signal (`[metrics] crush`).
    Crush,
    /// The crush signal's deceleration `−c̈`.
    Deceleration,
    /// Column `i` of the scenario's components (`front_end.force`).
    Column(usize),
    /// The rate of the components' internal state `i` (a Bouc–Wen
    /// spring's `z`, a dissipated energy; the last columns of the
    /// components, in order): the derivative of a continuous state.
    InternalRate(usize),
}

/// The FMI causality of a variable.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Causality {
    /// Set by the host before initialization (and between steps: tunable).
    Parameter,
    /// Set by the host during the run.
    Input,
    /// Read by the host.
    Output,
    /// Internal, readable (the accelerations).
    Local,
}

impl Causality {
    /// Its name after an article, for messages (`an output`).
    pub fn with_article(self) -> &'static str {
        match self {
            Causality::Parameter => "a parameter",
            Causality::Input => "an input",
            Causality::Output => "an output",
            Causality::Local => "a local variable",
        }
    }

    /// The attribute value in modelDescription.xml.
    pub fn name(self) -> &'static str {
        match self {
            Causality::Parameter => "parameter",
            Causality::Input => "input",
            Causality::Output => "output",
            Causality::Local => "local",
        }
    }
}

/// One scalar variable of the FMU.
#[derive(Clone, Debug, PartialEq)]
pub struct Variable {
    /// Its name in modelDescription.xml (unique).
    pub name: String,
    /// What it is the value of.
    pub quantity: Quantity,
    /// Its unit as the spec writes it, if any.
    pub unit: Option<String>,
    /// Its description, from the spec's doc comment.
    pub description: String,
    /// The start value of a parameter or an input (`None`: calculated).
    pub start: Option<f64>,
}

impl Variable {
    /// Its FMI causality.
    pub fn causality(&self) -> Causality {
        match self.quantity {
            Quantity::Parameter(_) => Causality::Parameter,
            Quantity::Input(_) => Causality::Input,
            Quantity::Acceleration(_) | Quantity::InternalRate(_) => Causality::Local,
            Quantity::Coordinate(_)
            | Quantity::Rate(_)
            | Quantity::Output(_)
            | Quantity::Crush
            | Quantity::Deceleration
            | Quantity::Column(_) => Causality::Output,
        }
    }

    /// Whether the host may set it.
    pub fn settable(&self) -> bool {
        matches!(self.causality(), Causality::Parameter | Causality::Input)
    }
}

/// The variables of a spec under a scenario, in value-reference order.
#[derive(Clone, Debug, PartialEq)]
pub struct Variables {
    /// The variables; a value reference is an index.
    pub list: Vec<Variable>,
    /// The number of coordinates `N` (the states are the first `2N`).
    pub dimension: usize,
}

/// Two FMU variables of one name ([`Variables::new`]): the name, and
/// what each variable is the value of.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error(
    "two FMU variables would be called `{name}`: {} and {}; rename one of them",
    origin(.first),
    origin(.second)
)]
pub struct NameClash {
    /// The name.
    pub name: String,
    /// The first variable of that name.
    pub first: Quantity,
    /// The second.
    pub second: Quantity,
}

/// The inputs of `model` the scenario leaves unbound, in input order.
pub fn unbound_inputs(scenario: &Scenario) -> Vec<usize> {
    (scenario.inputs.bindings.iter().enumerate())
        .filter(|(_, b)| b.is_none())
        .map(|(i, _)| i)
        .collect()
}

impl Variables {
    /// The variables of `model` under `scenario` (resolved against it),
    /// with `unbound` the inputs the host sets (see [`unbound_inputs`];
    /// the runtime binds them to constants before it builds this table).
    ///
    /// Two variables of one name are an error that names them (see the
    /// module's notes on names).
    pub fn new(
        model: &Model,
        scenario: &Scenario,
        unbound: &[usize],
    ) -> Result<Variables, NameClash> {
        let mut list = states(model);
        list.extend(parameters(model, scenario));
        list.extend(unbound.iter().map(|&i| {
            let input = &model.inputs[i];
            Variable {
                name: input.name.clone(),
                quantity: Quantity::Input(i),
                unit: input.unit.as_ref().map(|u| u.text.clone()),
                description: first_paragraph(&input.doc),
                start: Some(0.0),
            }
        }));
        list.extend(
            model
                .outputs
                .iter()
                .enumerate()
                .map(|(i, output)| Variable {
                    name: output.name.clone(),
                    quantity: Quantity::Output(i),
                    unit: output.unit.as_ref().map(|u| u.text.clone()),
                    description: first_paragraph(&output.doc),
                    start: None,
                }),
        );
        list.extend(crush(scenario));
        list.extend(columns(scenario));
        list.extend(internal_rates(scenario));
        unique(&list)?;
        Ok(Variables {
            list,
            dimension: model.coordinates.len(),
        })
    }

    /// The variable of value reference `vr`.
    pub fn get(&self, vr: u32) -> Option<&Variable> {
        self.list.get(vr as usize)
    }

    /// The value reference of the variable called `name`.
    pub fn reference(&self, name: &str) -> Option<u32> {
        (self.list.iter().position(|v| v.name == name)).map(|i| i as u32)
    }

    /// The name of the continuous state `i` (`q`, then `q̇`, then the
    /// components' internal states `z`: `theta1`, `der(theta1)`,
    /// `spring1.z`), for messages; `state i` past them.
    pub fn state_name(&self, i: usize) -> String {
        let n = self.dimension;
        let name = self.list.iter().find_map(|v| match v.quantity {
            Quantity::Coordinate(j) if j == i => Some(v.name.clone()),
            Quantity::Rate(j) if n + j == i => Some(v.name.clone()),
            Quantity::InternalRate(j) if 2 * n + j == i => {
                let inner = v
                    .name
                    .strip_prefix("der(")
                    .and_then(|s| s.strip_suffix(')'));
                inner.map(str::to_string)
            }
            _ => None,
        });
        name.unwrap_or_else(|| format!("state {i}"))
    }

    /// The 1-based index (in `<ModelVariables>`) of the state that the
    /// variable `vr` is the derivative of: `q_i` for `q̇_i`, `q̇_i` for
    /// `q̈_i`, the column of internal state `z_i` for `ż_i`.
    pub fn derivative_of(&self, vr: usize) -> Option<usize> {
        match self.list[vr].quantity {
            Quantity::Rate(i) => Some(i + 1),
            Quantity::Acceleration(i) => Some(self.dimension + i + 1),
            Quantity::InternalRate(i) => {
                let is = |q: &Quantity| matches!(q, Quantity::InternalRate(_));
                let states = self.list.iter().filter(|v| is(&v.quantity)).count();
                let is_column = |q: &Quantity| matches!(q, Quantity::Column(_));
                let columns = self.list.iter().filter(|v| is_column(&v.quantity)).count();
                let column = Quantity::Column(columns - states + i);
                let state = self.list.iter().position(|v| v.quantity == column)?;
                Some(state + 1)
            }
            _ => None,
        }
    }
}

/// One line of description from `///` doc lines: their first paragraph.
pub fn first_paragraph(lines: &[String]) -> String {
    let paragraph: Vec<&str> = (lines.iter())
        .map(|l| l.trim())
        .take_while(|l| !l.is_empty())
        .collect();
    paragraph.join(" ")
}

/// `q`, `q̇` and `q̈` of every coordinate.
fn states(model: &Model) -> Vec<Variable> {
    let unit = |i: usize, suffix: &str| {
        let unit = model.coordinates[i].unit.as_ref()?;
        Some(format!("{}{suffix}", unit.text))
    };
    let mut list = Vec::new();
    let coordinates = model.coordinates.iter().enumerate();
    for (i, c) in coordinates.clone() {
        list.push(Variable {
            name: c.name.clone(),
            quantity: Quantity::Coordinate(i),
            unit: unit(i, ""),
            description: first_paragraph(&c.doc),
            start: None,
        });
    }
    for (i, c) in coordinates.clone() {
        list.push(Variable {
            name: format!("der({})", c.name),
            quantity: Quantity::Rate(i),
            unit: unit(i, "/s"),
            description: format!("rate of {}", c.name),
            start: None,
        });
    }
    for (i, c) in coordinates {
        list.push(Variable {
            name: format!("der(der({}))", c.name),
            quantity: Quantity::Acceleration(i),
            unit: unit(i, "/s^2"),
            description: format!("acceleration of {}", c.name),
            start: None,
        });
    }
    list
}

/// The spec's parameters, starting at the scenario's values.
fn parameters<'a>(model: &'a Model, scenario: &'a Scenario) -> impl Iterator<Item = Variable> + 'a {
    model.parameters.iter().enumerate().map(|(i, p)| {
        let value = (scenario.parameters.iter().rev())
            .find(|(k, _)| *k == i)
            .map_or(p.default, |&(_, v)| v);
        Variable {
            name: p.name.clone(),
            quantity: Quantity::Parameter(i),
            unit: p.unit.as_ref().map(|u| u.text.clone()),
            description: first_paragraph(&p.doc),
            start: Some(value),
        }
    })
}

/// `Err` naming the first two variables of `list` that share a name.
fn unique(list: &[Variable]) -> Result<(), NameClash> {
    let Some((first, second)) = repeated_name(list) else {
        return Ok(());
    };
    Err(NameClash {
        name: list[first].name.clone(),
        first: list[first].quantity,
        second: list[second].quantity,
    })
}

/// The positions of the first two variables of `list` that share a name.
fn repeated_name(list: &[Variable]) -> Option<(usize, usize)> {
    let mut seen = std::collections::HashMap::new();
    (list.iter().enumerate()).find_map(|(i, v)| {
        let first = *seen.entry(v.name.as_str()).or_insert(i);
        (first != i).then_some((first, i))
    })
}

/// Where a variable comes from, in words, for the clash message.
fn origin(quantity: &Quantity) -> &'static str {
    match quantity {
        Quantity::Coordinate(_) => "the spec's coordinate",
        Quantity::Rate(_) | Quantity::Acceleration(_) => "the rate of a coordinate",
        Quantity::Parameter(_) => "the spec's parameter",
        Quantity::Input(_) => "the spec's input",
        Quantity::Output(_) => "the spec's output",
        Quantity::Crush | Quantity::Deceleration => "the scenario's crush signal",
        Quantity::Column(_) => "a column of the scenario's components",
        Quantity::InternalRate(_) => "the rate of a component's internal state",
    }
}

/// The crush signal and its deceleration, when the scenario names one; a
/// crush of outputs has no deceleration here (the simulator takes it from
/// differences along the motion, which the FMU does not evaluate), rather
/// than a variable that is always NaN.
fn crush(scenario: &Scenario) -> Vec<Variable> {
    let Some(signal) = &scenario.crush else {
        return Vec::new();
    };
    let mut variables = vec![Variable {
        name: format!("{METRICS}.crush"),
        quantity: Quantity::Crush,
        unit: signal.unit.clone(),
        description: format!("crush `{}` (compression positive)", signal.name),
        start: None,
    }];
    if signal.is_of_coordinates() {
        variables.push(Variable {
            name: format!("{METRICS}.deceleration"),
            quantity: Quantity::Deceleration,
            unit: signal.unit.as_ref().map(|u| format!("{u}/s^2")),
            description: format!("deceleration of the crush `{}`", signal.name),
            start: None,
        });
    }
    variables
}

/// The components' columns (`front_end.force`).
fn columns(scenario: &Scenario) -> impl Iterator<Item = Variable> + '_ {
    let columns = scenario.inputs.columns().into_iter().enumerate();
    columns.map(|(i, (name, unit))| Variable {
        description: format!("{name} of the scenario's component"),
        name,
        quantity: Quantity::Column(i),
        unit,
        start: None,
    })
}

/// `der(NAME.QUANTITY)` of each of the components' internal states, the
/// last columns of [`columns`]: with them the continuous states of Model
/// Exchange are `(q, q̇, z)`.
fn internal_rates(scenario: &Scenario) -> impl Iterator<Item = Variable> + '_ {
    let columns = scenario.inputs.columns();
    let states = scenario.inputs.internal_count();
    let first = columns.len() - states;
    (columns.into_iter().skip(first).enumerate()).map(|(i, (name, unit))| Variable {
        description: format!("rate of {name}"),
        name: format!("der({name})"),
        quantity: Quantity::InternalRate(i),
        unit: unit.map(|u| format!("{u}/s")),
        start: None,
    })
}

#[cfg(test)]
mod tests {
    #[test]
    fn two_variables_of_one_name_are_an_error_naming_where_each_comes_from() {
        let variable = |name: &str, quantity| super::Variable {
            name: name.to_string(),
            quantity,
            unit: None,
            description: String::new(),
            start: None,
        };
        let list = [
            variable("x", super::Quantity::Coordinate(0)),
            variable("metrics.crush", super::Quantity::Crush),
            variable("metrics.crush", super::Quantity::Column(0)),
        ];
        let clash = super::unique(&list).unwrap_err();
        assert_eq!(clash.name, "metrics.crush");
        assert_eq!(
            (clash.first, clash.second),
            (super::Quantity::Crush, super::Quantity::Column(0))
        );
        assert_eq!(
            clash.to_string(),
            "two FMU variables would be called `metrics.crush`: the scenario's crush signal \
             and a column of the scenario's components; rename one of them"
        );
        assert_eq!(super::unique(&list[..2]), Ok(()));
    }
}
