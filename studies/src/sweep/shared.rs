//! What the runs of a sweep share. When the plan varies only the model's
//! parameters, the scenario file is parsed and its data files read once;
//! each run copies that scenario (its tables are shared, not copied) and
//! sets its parameter values. Otherwise each run resolves its own scenario
//! from the file's text with its settings ([`super::run_scenario`]).

use super::run::Settings;
use lagrangian_sim::scenario::{BaseScenario, Scenario};

/// The scenario every run of a parameter sweep starts from, resolved once.
#[derive(Clone, Debug)]
pub(crate) struct SharedScenario {
    scenario: Scenario,
    /// Per axis: the index of the parameter it sets, and for a factor
    /// (`KEY*=`) the value it multiplies.
    axes: Vec<(usize, Option<f64>)>,
}

impl SharedScenario {
    /// The shared scenario, when every axis sets a parameter and the base
    /// scenario resolves by itself; `None` otherwise.
    pub(crate) fn new(base: &BaseScenario, settings: &Settings) -> Option<SharedScenario> {
        let axes = settings.parameter_axes(&base.names.parameters)?;
        let scenario = base.resolve(&[]).ok()?;
        Some(SharedScenario { scenario, axes })
    }

    /// The scenario of the run with the axes' `values`: the same as
    /// resolving the file with the run's settings. `None` for a value that
    /// is not a finite number, which the full resolution reports.
    pub(crate) fn for_values(&self, values: &[f64]) -> Option<Scenario> {
        let mut scenario = self.scenario.clone();
        for (&(parameter, factor), &x) in self.axes.iter().zip(values) {
            let value = factor.map_or(x, |base| base * x);
            if !value.is_finite() {
                return None;
            }
            let overrides = &mut scenario.parameters;
            match overrides.iter_mut().find(|(index, _)| *index == parameter) {
                Some(entry) => entry.1 = value,
                None => overrides.push((parameter, value)),
            }
        }
        Some(scenario)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sweep::{Plan, run_scenario};
    use lagrangian_runtime::{Interpreted, LagrangianSystem};
    use lagrangian_sim::scenario::{ModelNames, Override};
    use lagrangian_sim::simulate::simulate_summary;

    #[test]
    fn a_run_from_the_shared_scenario_is_the_run_from_the_file() {
        let model = lagrangian_core::interpret(include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../specs/spring_mass_damper.lpm"
        )))
        .unwrap();
        let names = ModelNames::of_interpreted(&model);
        let system = Interpreted::<1>::new(model).unwrap();
        let text = "[simulation]\nt_end = 0.05\n[parameters]\nc = 2.0\n[initial]\nvelocities = { x = 1.0 }\n[components.c]\ntype = \"constant\"\nvalues = { push = 1.0 }\n";
        let base = BaseScenario {
            text: text.to_string(),
            file: None,
            names,
            settings: vec![Override::number("m", 2.0)],
            files: std::sync::Arc::new(lagrangian_sim::files::Disk),
        };
        let grid = ["k=50,200.5", "c*=0.5,3"].map(String::from);
        let plan = Plan::grid(&grid).unwrap();
        let settings = Settings::new(&plan, &base, &system.parameters()).unwrap();
        let shared = SharedScenario::new(&base, &settings).expect("parameters only");
        for run in 0..plan.len() {
            let values = plan.point(run);
            let from_file = run_scenario(&base, &settings, &values).unwrap();
            let from_shared = shared.for_values(&values).unwrap();
            let summary = |s: &Scenario| format!("{:?}", simulate_summary(&system, s));
            assert_eq!(summary(&from_shared), summary(&from_file), "run {run}");
        }
        // A value that is not finite is left to the file's resolution, which
        // reports it.
        assert!(shared.for_values(&[f64::NAN, 1.0]).is_none());
        // An axis other than a parameter: every run resolves its own.
        let plan = Plan::grid(&["simulation.t_end=0.01,0.02".to_string()]).unwrap();
        let settings = Settings::new(&plan, &base, &system.parameters()).unwrap();
        assert!(SharedScenario::new(&base, &settings).is_none());
    }
}
