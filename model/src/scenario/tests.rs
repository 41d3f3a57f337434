//! Scenario files that do not fit their spec or hold values out of range.

use super::*;
use crate::InterpretedModel;

const SPRING: &str = include_str!("../../../specs/spring_mass_damper.lpm");

fn names() -> ModelNames {
    let model = InterpretedModel::from_source(SPRING).unwrap();
    ModelNames {
        coordinates: model.coordinates().to_vec(),
        parameters: model.parameter_names().to_vec(),
        inputs: model.input_names().to_vec(),
        input_sites: model.input_sites().to_vec(),
    }
}

fn error(text: &str, settings: &[&str]) -> String {
    let settings: Vec<String> = settings.iter().map(|s| s.to_string()).collect();
    match Scenario::parse(text, None, &names(), &settings) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

const PUSH: &str = "[components.c]\ntype = \"constant\"\nvalues = { push = 1.0 }\n";

#[test]
fn non_finite_and_out_of_range_numbers_name_their_key() {
    let e = error(
        &format!("[simulation]\nt_end = 0.01\noutput_interval = inf\n{PUSH}"),
        &[],
    );
    assert_eq!(
        e,
        "simulation.output_interval = inf: must be a positive, finite number"
    );
    let e = error(
        &format!("[simulation]\nt_end = 1e300\noutput_interval = 1e-300\n{PUSH}"),
        &[],
    );
    assert_eq!(
        e,
        "simulation.output_interval = 1e-300: gives inf samples over t_end = 1e300 s, more than 1e6; use a longer interval"
    );
    let cases = [
        ("[simulation]\nt_end = inf\n", "simulation.t_end = inf"),
        ("[simulation]\nrtol = nan\n", "simulation.rtol = NaN"),
        ("[simulation]\natol = -inf\n", "simulation.atol = -inf"),
        ("[simulation]\nmax_step = 0.0\n", "simulation.max_step = 0"),
        (
            "[simulation]\nmethod = \"rk4\"\nstep = inf\n",
            "simulation.step = inf",
        ),
        ("[parameters]\nk = nan\n", "parameters.k = NaN"),
        (
            "[initial]\ncoordinates = { x = inf }\n",
            "initial.coordinates.x = inf",
        ),
        (
            "[initial]\nvelocities = { x = nan }\n",
            "initial.velocities.x = NaN",
        ),
    ];
    for (section, key) in cases {
        let e = error(&format!("{section}{PUSH}"), &[]);
        assert!(e.starts_with(&format!("{key}: must be")), "{section}: {e}");
    }
    let e = error(
        "[components.c]\ntype = \"constant\"\nvalues = { push = nan }\n",
        &[],
    );
    assert!(
        e.starts_with("components.c.values.push = NaN: must be"),
        "{e}"
    );
    let e = error(PUSH, &["k=inf"]);
    assert!(e.starts_with("parameters.k = inf: must be"), "{e}");
    let e = error("", &["push=-inf"]);
    assert!(e.starts_with("--set push = -inf: must be"), "{e}");
    let weld = "[components.w]\ntype = \"weld\"\ninputs = { moment = \"push\" }\ncurve = [[0.0, 0.0], [1.0, 1.0]]\n";
    let e = error(&format!("{weld}failure_moment = -1.0\n"), &[]);
    assert!(
        e.starts_with("components.w.failure_moment = -1: must be"),
        "{e}"
    );
    let e = error(&format!("{weld}damping = inf\n"), &[]);
    assert!(e.starts_with("components.w.damping = inf: must be"), "{e}");
}
