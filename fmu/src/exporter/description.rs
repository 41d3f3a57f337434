//! modelDescription.xml (FMI 2.0) of an exported model: both interfaces,
//! the units, the variables of [`crate::variables`] with their
//! value references, and the model structure FMPy's validator checks
//! (every output in `<Outputs>`, the state derivatives in state order in
//! `<Derivatives>`, the calculated unknowns in `<InitialUnknowns>`).

use crate::variables::{Causality, Variable, Variables};
use std::collections::BTreeSet;
use std::fmt::Write;

/// What the description says besides the variables.
pub struct About<'a> {
    /// `modelName`: the spec's model name.
    pub model_name: &'a str,
    /// The spec's doc comment.
    pub description: &'a str,
    /// `modelIdentifier`: the binary's file name without its extension.
    pub identifier: &'a str,
    /// The GUID the runtime checks.
    pub guid: &'a str,
    /// The number of event indicators.
    pub event_indicators: usize,
    /// `(stop time, tolerance, step size)` of the scenario.
    pub experiment: (f64, f64, f64),
}

/// The text of modelDescription.xml.
pub fn model_description(about: &About, variables: &Variables) -> String {
    let mut xml = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let _ = writeln!(
        xml,
        "<fmiModelDescription fmiVersion=\"2.0\" modelName=\"{}\" guid=\"{}\" description=\"{}\" \
         generationTool=\"lpm export-fmu {}\" variableNamingConvention=\"flat\" \
         numberOfEventIndicators=\"{}\">",
        escape(about.model_name),
        escape(about.guid),
        escape(about.description),
        env!("CARGO_PKG_VERSION"),
        about.event_indicators
    );
    let id = escape(about.identifier);
    let _ = writeln!(
        xml,
        "  <ModelExchange modelIdentifier=\"{id}\" canGetAndSetFMUstate=\"true\" \
         canSerializeFMUstate=\"false\" providesDirectionalDerivative=\"false\" \
         completedIntegratorStepNotNeeded=\"true\" canNotUseMemoryManagementFunctions=\"true\"/>"
    );
    let _ = writeln!(
        xml,
        "  <CoSimulation modelIdentifier=\"{id}\" canHandleVariableCommunicationStepSize=\"true\" \
         canInterpolateInputs=\"false\" maxOutputDerivativeOrder=\"0\" \
         canGetAndSetFMUstate=\"true\" canSerializeFMUstate=\"false\" \
         providesDirectionalDerivative=\"false\" canNotUseMemoryManagementFunctions=\"true\"/>"
    );
    xml.push_str(&unit_definitions(variables));
    xml.push_str(
        "  <LogCategories>\n    <Category name=\"logEvents\" description=\"the events handled (crush peak, weld failure, contact)\"/>\n    \
         <Category name=\"logStatusError\" description=\"why a call failed\"/>\n  </LogCategories>\n",
    );
    let (stop, tolerance, step) = about.experiment;
    let _ = writeln!(
        xml,
        "  <DefaultExperiment startTime=\"0.0\" stopTime=\"{}\" tolerance=\"{}\" stepSize=\"{}\"/>",
        number(stop),
        number(tolerance),
        number(step)
    );
    xml.push_str("  <ModelVariables>\n");
    for (vr, variable) in variables.list.iter().enumerate() {
        xml.push_str(&scalar_variable(vr, variable, variables.derivative_of(vr)));
    }
    xml.push_str("  </ModelVariables>\n");
    xml.push_str(&model_structure(variables));
    xml.push_str("</fmiModelDescription>\n");
    xml
}

/// One `<Unit name=…/>` per unit the variables use.
fn unit_definitions(variables: &Variables) -> String {
    let units: BTreeSet<&str> = variables
        .list
        .iter()
        .filter_map(|v| v.unit.as_deref())
        .collect();
    if units.is_empty() {
        return String::new();
    }
    let mut xml = String::from("  <UnitDefinitions>\n");
    for unit in units {
        let _ = writeln!(xml, "    <Unit name=\"{}\"/>", escape(unit));
    }
    xml.push_str("  </UnitDefinitions>\n");
    xml
}

/// `<ScalarVariable>` of value reference `vr`; `derivative` is the
/// 1-based index of the state it is the derivative of.
fn scalar_variable(vr: usize, v: &Variable, derivative: Option<usize>) -> String {
    let causality = v.causality();
    let variability = match causality {
        Causality::Parameter => "tunable",
        Causality::Input | Causality::Output | Causality::Local => "continuous",
    };
    let initial = match causality {
        Causality::Parameter => " initial=\"exact\"",
        _ => "",
    };
    let mut real = String::new();
    if let Some(unit) = &v.unit {
        let _ = write!(real, " unit=\"{}\"", escape(unit));
    }
    if let Some(index) = derivative {
        let _ = write!(real, " derivative=\"{index}\"");
    }
    if let Some(start) = v.start {
        let _ = write!(real, " start=\"{}\"", number(start));
    }
    format!(
        "    <ScalarVariable name=\"{}\" valueReference=\"{vr}\" description=\"{}\" \
         causality=\"{}\" variability=\"{variability}\"{initial}>\n      <Real{real}/>\n    </ScalarVariable>\n",
        escape(&v.name),
        escape(&v.description),
        causality.name(),
    )
}

/// `<ModelStructure>`: the outputs; the derivatives in the order of the
/// states (q̇ then q̈, so the states are q then q̇); the initial unknowns,
/// every output and derivative being calculated.
fn model_structure(variables: &Variables) -> String {
    let indices = |keep: &dyn Fn(usize, &Variable) -> bool| -> Vec<usize> {
        (variables.list.iter().enumerate())
            .filter(|&(vr, v)| keep(vr, v))
            .map(|(vr, _)| vr + 1)
            .collect()
    };
    let outputs = indices(&|_, v| v.causality() == Causality::Output);
    let derivatives = indices(&|vr, _| variables.derivative_of(vr).is_some());
    let initial = indices(&|vr, v| {
        v.causality() == Causality::Output || variables.derivative_of(vr).is_some()
    });
    let mut xml = String::from("  <ModelStructure>\n");
    for (tag, list) in [
        ("Outputs", outputs),
        ("Derivatives", derivatives),
        ("InitialUnknowns", initial),
    ] {
        if list.is_empty() {
            continue;
        }
        let _ = writeln!(xml, "    <{tag}>");
        for index in list {
            let _ = writeln!(xml, "      <Unknown index=\"{index}\"/>");
        }
        let _ = writeln!(xml, "    </{tag}>");
    }
    xml.push_str("  </ModelStructure>\n");
    xml
}

/// A number as XML's `double` reads it back exactly.
fn number(x: f64) -> String {
    format!("{x:?}")
}

/// Text for an attribute value.
fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\n' | '\r' | '\t' => out.push(' '),
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn attribute_text_is_escaped_and_numbers_read_back() {
        assert_eq!(escape("a<b & \"c\"\n"), "a&lt;b &amp; &quot;c&quot; ");
        for x in [1e-10, 60000.0, 0.1, -15.5556, 2.4e6] {
            assert_eq!(number(x).parse::<f64>(), Ok(x));
        }
    }
}
