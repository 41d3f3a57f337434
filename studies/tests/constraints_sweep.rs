//! A sweep of a constrained model (the four-bar): its table has the
//! constraint channels' extremes per run, those of the runs made one by one.

use lagrangian_runtime::Interpreted;
use lagrangian_sim::scenario::ModelNames;
use lagrangian_sim::simulate::simulate;

const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/..");

fn spec(name: &str) -> String {
    std::fs::read_to_string(format!("{ROOT}/specs/{name}.lpm")).unwrap()
}

fn scenario_text(name: &str) -> String {
    std::fs::read_to_string(format!("{ROOT}/specs/scenarios/{name}.toml")).unwrap()
}

/// A sweep's table has the constraint channels' extremes per run, the
/// numbers of the runs made one by one.
#[test]
fn a_sweep_reports_the_multipliers_and_the_drift_of_each_run() {
    use lagrangian_sim::scenario::BaseScenario;
    use lagrangian_studies::sweep::{
        Layout, Plan, Settings, SweepJob, run_scenario, run_sweep, sweep_csv,
    };
    let source = spec("four_bar_linkage");
    let interpreted = lagrangian_core::interpret(&source).unwrap();
    let defaults = interpreted.parameters().to_vec();
    let names = ModelNames::of_interpreted(&interpreted);
    let system = Interpreted::<3>::new(interpreted).unwrap();
    let text = format!(
        "{}\n[metrics]\nforce = [\"loop_x.lambda\"]\ndisplacement = [\"loop_x.residual\", \"loop_y.residual\"]\n",
        scenario_text("four_bar_linkage")
    );
    let base = BaseScenario {
        text,
        file: None,
        names,
        settings: vec![lagrangian_sim::scenario::Override::number(
            "simulation.t_end",
            0.2,
        )],
        files: std::sync::Arc::new(lagrangian_sim::files::Disk),
    };
    let plan = Plan::grid(&["m2=1.5,2.5".to_string()]).unwrap();
    let settings = Settings::new(&plan, &base, &defaults).unwrap();
    let job = SweepJob {
        base: &base,
        plan: &plan,
        settings: &settings,
        runs: 0..plan.len(),
        threads: 1,
    };
    let rows = run_sweep(&system, job, &|| {});
    let first = run_scenario(&base, &settings, &plan.point(0)).unwrap();
    let axes: Vec<String> = plan.axes().iter().map(|a| a.column()).collect();
    let csv = String::from_utf8(sweep_csv(&Layout::new(axes, &first), &rows).unwrap()).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let column = |name: &str| header.iter().position(|h| *h == name).unwrap();
    for (run, line) in lines.enumerate() {
        let cells: Vec<&str> = line.split(',').collect();
        let cell = |name: &str| cells[column(name)].parse::<f64>().unwrap();
        let scenario = run_scenario(&base, &settings, &plan.point(run)).unwrap();
        let alone = simulate(&system, &scenario).unwrap();
        let lambda = alone.samples.iter().map(|s| s.multipliers[0]);
        assert_eq!(
            cell("loop_x.lambda.max"),
            lambda.clone().fold(f64::MIN, f64::max)
        );
        assert_eq!(cell("loop_x.lambda.min"), lambda.fold(f64::MAX, f64::min));
        let drift = &alone.constraints.as_ref().unwrap().drift;
        for (k, name) in ["loop_x", "loop_y"].into_iter().enumerate() {
            let max = cell(&format!("{name}.residual.max")).abs();
            let min = cell(&format!("{name}.residual.min")).abs();
            assert_eq!(max.max(min), drift[k], "{name}");
        }
    }
}
