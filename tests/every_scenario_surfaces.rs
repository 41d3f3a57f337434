//! Every shipped scenario through the three ways the simulator evaluates a
//! model: the macro-compiled code (what `lagrangian!` users and `generated/`
//! run), the interpreted tape (`lpm` without native code) and the tape with
//! its routines compiled to native code (`lpm simulate`'s default). The
//! three evaluate one optimized program, so their runs must be the same bit
//! for bit: every sample, the solver's statistics, the events, the summary.
//! (Python and the FMUs against `lpm simulate`: python/tests/test_conformance.py.)

use lagrangian::scenario::{ModelNames, Scenario};
use lagrangian::simulate::{SimulationResult, simulate};
use lagrangian::{Interpreted, LagrangianSystem};
use lagrangian_core::Compiled;
use lagrangian_runtime::WithDimension;
use std::path::Path;

mod models {
    lagrangian::lagrangian!(file = "specs/car_to_car.lpm");
    lagrangian::lagrangian!(file = "specs/four_bar_linkage.lpm");
    lagrangian::lagrangian!(file = "specs/kamal_1970.lpm");
    lagrangian::lagrangian!(file = "specs/pioneer_wagon.lpm");
    lagrangian::lagrangian!(file = "specs/slider_crank.lpm");
    lagrangian::lagrangian!(file = "specs/wall_impact.lpm");
    lagrangian::lagrangian!(file = "specs/yaris_double_pendulum.lpm");
    lagrangian::lagrangian!(file = "specs/yaris_occupant.lpm");
}

/// Simulates an interpreted model, at its dimension, under a scenario.
struct Run<'a> {
    scenario: &'a Path,
}

impl WithDimension for Run<'_> {
    type Output = SimulationResult;

    fn run<const N: usize>(self, model: Interpreted<N>) -> SimulationResult {
        simulated(&model, self.scenario)
    }
}

fn simulated<const N: usize, S: LagrangianSystem<N> + Clone>(
    model: &S,
    scenario: &Path,
) -> SimulationResult {
    let scenario = Scenario::load(scenario, &ModelNames::of(model), &[]).unwrap();
    simulate(model, &scenario).unwrap()
}

/// What a run gave, every part of it that a user reads, for comparison.
fn parts(result: &SimulationResult) -> serde_json::Value {
    serde_json::json!({
        "summary": serde_json::to_value(&result.summary).unwrap(),
        "stats": format!("{:?}", result.stats),
        "events": format!("{:?}", result.events),
        "warnings": format!("{:?}", result.warnings),
    })
}

fn same_run(what: &str, a: &SimulationResult, b: &SimulationResult) {
    assert_eq!(a.samples.len(), b.samples.len(), "{what}: sample counts");
    for (k, (x, y)) in a.samples.iter().zip(&b.samples).enumerate() {
        // Bit for bit, NaN included: compare the Debug text of each sample.
        assert_eq!(format!("{x:?}"), format!("{y:?}"), "{what}: sample {k}");
    }
    assert_eq!(parts(a), parts(b), "{what}");
}

fn compare<const N: usize, M: LagrangianSystem<N> + Default + Clone>(spec: &str, scenario: &str) {
    let scenario = Path::new("specs/scenarios").join(scenario);
    let source = std::fs::read_to_string(spec).unwrap();
    let compiled = Compiled::from_source(&source).unwrap();
    let tape = compiled.interpreted();
    let mut native = tape.clone();
    lagrangian_jit::accelerate(&mut native).unwrap();
    let run = |model: lagrangian_runtime::InterpretedModel| {
        model
            .with_dimension(Run {
                scenario: &scenario,
            })
            .unwrap()
    };
    let (tape, native) = (run(tape), run(native));
    let macro_compiled = simulated(&M::default(), &scenario);
    assert!(tape.samples.len() > 10, "{spec}: a run of its scenario");
    same_run(
        &format!("{spec}: native code against the tape"),
        &native,
        &tape,
    );
    same_run(
        &format!("{spec}: compiled against the tape"),
        &macro_compiled,
        &tape,
    );
}

#[test]
fn every_scenario_runs_the_same_compiled_interpreted_and_native() {
    compare::<_, models::CarToCar>("specs/car_to_car.lpm", "car_to_car.toml");
    compare::<_, models::FourBarLinkage>("specs/four_bar_linkage.lpm", "four_bar_linkage.toml");
    compare::<_, models::Kamal1970>("specs/kamal_1970.lpm", "kamal_1970.toml");
    compare::<_, models::PioneerWagon>("specs/pioneer_wagon.lpm", "pioneer_wagon.toml");
    compare::<_, models::SliderCrank>("specs/slider_crank.lpm", "slider_crank.toml");
    compare::<_, models::WallImpact>("specs/wall_impact.lpm", "wall_impact.toml");
    compare::<_, models::YarisDoublePendulum>(
        "specs/yaris_double_pendulum.lpm",
        "yaris_full_frontal.toml",
    );
    compare::<_, models::YarisOccupant>("specs/yaris_occupant.lpm", "yaris_occupant.toml");
}
