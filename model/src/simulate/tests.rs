//! Runs of small specs under scenarios that once went wrong.

use super::*;
use crate::scenario::ModelNames;
use crate::{Interpreted, InterpretedModel};

const SPRING: &str = include_str!("../../../specs/spring_mass_damper.lpm");

fn spring() -> (Interpreted<1>, ModelNames) {
    let model = InterpretedModel::from_source(SPRING).unwrap();
    let names = ModelNames::of_interpreted(&model);
    (Interpreted::new(model).unwrap(), names)
}

#[test]
fn an_output_interval_past_the_scenario_check_still_ends() {
    let (model, names) = spring();
    let text = "[simulation]\nt_end = 0.01\n[components.c]\ntype = \"constant\"\nvalues = { push = 1.0 }\n";
    let mut scenario = Scenario::parse(text, None, &names, &[]).unwrap();
    for interval in [f64::INFINITY, f64::NAN] {
        scenario.output_interval = interval;
        let result = simulate(&model, &scenario).unwrap();
        assert!(
            result.samples.len() <= 2,
            "{interval}: {}",
            result.samples.len()
        );
        assert_eq!(result.samples[0].t, 0.0);
    }
}
