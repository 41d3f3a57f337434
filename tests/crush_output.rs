//! A crush channel taken from a spec output (`metrics.crush = "intrusion"`):
//! its rate and acceleration come from differences of the output along the
//! motion (sim/src/simulate/output_motion.rs). Checked against
//!
//! * a closed form: a mass in free flight past a pole moving along x
//!   (tests/specs/pole_intrusion.lpm). With the relative position
//!   `r(t) = r₀ + w t` (`w = (ẋ − u, ẏ)`, straight lines) and `d = |r|`, the
//!   intrusion is `R − d`, its rate `−(r·w)/d` and its acceleration
//!   `−(r × w)²/d³`, largest `|w|²/b` at the closest approach `d = b`;
//! * the same combination written in `metrics.crush`: the car-to-car
//!   scenario's crush `"xa - xb"` and its output `crush = xa - xb`, whose
//!   metrics must agree within 1e-9 (the differences of a linear output
//!   have no truncation error).
//!
//! And the refusals: an output that reads a velocity or an input, a
//! misspelt output, a model that does not say what its outputs read.

use lagrangian::scenario::{ModelNames, Override, Scenario};
use lagrangian::simulate::{SimulationResult, Summary, simulate, simulate_summary};
use lagrangian::{Interpreted, LagrangianSystem};
use lagrangian_core::Compiled;
use std::path::Path;

const STANDARD_GRAVITY: f64 = 9.80665;
const POLE_SPEC: &str = "tests/specs/pole_intrusion.lpm";
const POLE_SCENARIO: &str = "tests/specs/pole_intrusion.toml";

mod compiled {
    lagrangian::lagrangian!(file = "tests/specs/pole_intrusion.lpm");
}

fn interpreted<const N: usize>(spec: &str) -> Interpreted<N> {
    let source = std::fs::read_to_string(spec).unwrap();
    Interpreted::new(Compiled::from_source(&source).unwrap().interpreted()).unwrap()
}

fn load<const N: usize, S: LagrangianSystem<N>>(
    model: &S,
    scenario: &str,
    settings: &[String],
) -> Result<Scenario, String> {
    let settings = Override::parse_all(settings).map_err(|e| e.to_string())?;
    Scenario::load(Path::new(scenario), &ModelNames::of(model), &settings)
        .map_err(|e| e.to_string())
}

/// The pole's closed form (see the module documentation): parameters
/// `R = 0.5`, `xp = 0`, `u = 2` of the spec, the mass at `(12, 3)` m/s,
/// closest approach `b = 0.3` m, starting on the disc's edge.
struct Pole {
    r0: [f64; 2],
    w: [f64; 2],
    velocity: [f64; 2],
    radius: f64,
    b: f64,
}

impl Pole {
    fn new() -> Pole {
        let (radius, b, u, velocity): (f64, f64, f64, [f64; 2]) = (0.5, 0.3, 2.0, [12.0, 3.0]);
        let w = [velocity[0] - u, velocity[1]];
        let speed = w[0].hypot(w[1]);
        let (along, across) = ([w[0] / speed, w[1] / speed], [-w[1] / speed, w[0] / speed]);
        let s0 = (radius * radius - b * b).sqrt();
        let r0 = [0, 1].map(|k| b * across[k] - s0 * along[k]);
        Pole {
            r0,
            w,
            velocity,
            radius,
            b,
        }
    }

    /// The initial state, as settings (`xp = 0`: `r₀` is the position).
    fn settings(&self) -> Vec<String> {
        vec![
            format!("initial.coordinates.x={:?}", self.r0[0]),
            format!("initial.coordinates.y={:?}", self.r0[1]),
            format!("initial.velocities.x={:?}", self.velocity[0]),
            format!("initial.velocities.y={:?}", self.velocity[1]),
        ]
    }

    /// Intrusion, its rate and its acceleration at `t`.
    fn at(&self, t: f64) -> [f64; 3] {
        let r = [0, 1].map(|k| self.r0[k] + self.w[k] * t);
        let d = r[0].hypot(r[1]);
        let dot = r[0] * self.w[0] + r[1] * self.w[1];
        let cross = r[0] * self.w[1] - r[1] * self.w[0];
        [self.radius - d, -dot / d, -cross * cross / d.powi(3)]
    }

    fn speed_squared(&self) -> f64 {
        self.w[0] * self.w[0] + self.w[1] * self.w[1]
    }
}

fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(f64::MIN_POSITIVE)
}

/// The largest deviation of the samples' crush, rate and acceleration from
/// `exact`, each relative to the largest magnitude of its exact values.
fn largest_deviation(result: &SimulationResult, exact: impl Fn(f64) -> [f64; 3]) -> [f64; 3] {
    let mut deviation = [0.0f64; 3];
    let mut scale = [0.0f64; 3];
    for s in &result.samples {
        let got = s.crush.expect("the run records its crush channel");
        let want = exact(s.t);
        for k in 0..3 {
            deviation[k] = deviation[k].max((got[k] - want[k]).abs());
            scale[k] = scale[k].max(want[k].abs());
        }
    }
    [0, 1, 2].map(|k| deviation[k] / scale[k])
}

#[test]
fn a_pole_intrusion_has_the_rate_and_acceleration_of_its_closed_form() {
    let pole = Pole::new();
    let model = interpreted::<2>(POLE_SPEC);
    let scenario = load(&model, POLE_SCENARIO, &pole.settings()).unwrap();
    let result = simulate(&model, &scenario).unwrap();
    let deviation = largest_deviation(&result, |t| pole.at(t));
    println!(
        "pole: largest deviation of crush, rate, acceleration {:?}",
        deviation.map(|d| format!("{d:.2e}"))
    );
    assert!(deviation[0] < 1e-12, "{deviation:?}");
    assert!(deviation[1] < 1e-8 && deviation[2] < 1e-8, "{deviation:?}");
    let s = &result.summary;
    // The peak deceleration is the largest over the samples: of the closed
    // form at the same times.
    let peak = (result.samples.iter())
        .map(|x| -pole.at(x.t)[2] / STANDARD_GRAVITY)
        .fold(f64::MIN, f64::max);
    let off = relative(s.peak_deceleration_g.unwrap(), peak);
    println!(
        "pole: peak deceleration {:?} g, {off:.2e} from the closed form",
        peak
    );
    assert!(off < 1e-8, "{off:e}");
    assert!(relative(peak * STANDARD_GRAVITY, pole.speed_squared() / pole.b) < 1e-6);
    // Max crush `R − b` at the closest approach `t* = √(R² − b²)/|w|`.
    let closest = (pole.radius.powi(2) - pole.b.powi(2)).sqrt() / pole.speed_squared().sqrt();
    assert!(relative(s.max_crush_m.unwrap(), pole.radius - pole.b) < 1e-9);
    assert!(relative(s.time_of_max_crush_s.unwrap(), closest) < 1e-6);
    assert!(relative(s.time_to_zero_velocity_s.unwrap(), closest) < 1e-6);
    // ESW `v₀²/(2 g₀ c_max)`, `v₀ = √(R² − b²)|w|/R`; rebound `−ȯ` at the end.
    let v0 = -pole.at(0.0)[1];
    let esw = v0 * v0 / (2.0 * STANDARD_GRAVITY * (pole.radius - pole.b));
    assert!(relative(s.equivalent_square_wave_g.unwrap(), esw) < 1e-9);
    let end = result.samples.last().unwrap().t;
    assert!(relative(s.rebound_velocity_mps.unwrap(), pole.at(end)[1].abs()) < 1e-9);
    assert!(result.warnings.is_empty(), "{:?}", result.warnings);
}

/// The summary's crush metrics, by name.
fn crush_metrics(s: &Summary) -> Vec<(&'static str, Option<f64>)> {
    vec![
        ("max_crush_m", s.max_crush_m),
        ("time_of_max_crush_s", s.time_of_max_crush_s),
        ("time_to_zero_velocity_s", s.time_to_zero_velocity_s),
        ("permanent_crush_m", s.permanent_crush_m),
        ("peak_deceleration_g", s.peak_deceleration_g),
        ("rebound_velocity_mps", s.rebound_velocity_mps),
        ("peak_deceleration_cfc60_g", s.peak_deceleration_cfc60_g),
        ("equivalent_square_wave_g", s.equivalent_square_wave_g),
        ("olc_g", s.olc_g),
        ("asi", s.asi),
    ]
}

/// The largest relative difference between the crush metrics of `a` and
/// `b`, each present in both.
fn metrics_difference(a: &Summary, b: &Summary) -> f64 {
    let mut largest = 0.0f64;
    for ((name, x), (_, y)) in crush_metrics(a).into_iter().zip(crush_metrics(b)) {
        let (x, y) = (x.unwrap_or_else(|| panic!("{name}")), y.unwrap());
        println!("  {name}: {x:?} vs {y:?}");
        largest = largest.max(relative(x, y));
    }
    largest
}

#[test]
fn a_linear_output_gives_the_metrics_of_the_same_combination() {
    let scenario = "specs/scenarios/car_to_car.toml";
    let model = interpreted::<3>("specs/car_to_car.lpm");
    let combination = load(&model, scenario, &[]).unwrap();
    assert_eq!(combination.crush.as_ref().unwrap().name, "xa - xb");
    let output = load(&model, scenario, &["metrics.crush=\"crush\"".into()]).unwrap();
    let of_combination = simulate(&model, &combination).unwrap();
    let of_output = simulate(&model, &output).unwrap();
    let difference = metrics_difference(&of_output.summary, &of_combination.summary);
    println!("car to car: crush metrics of the output within {difference:.2e}");
    // A run that keeps no samples (a sweep's) has the same summary.
    assert_eq!(
        simulate_summary(&model, &output).unwrap(),
        of_output.summary
    );
    assert!(difference < 1e-9, "{difference:e}");
    let deviation = largest_deviation(&of_output, |t| {
        let k = (of_combination.samples.iter())
            .position(|s| s.t == t)
            .unwrap();
        of_combination.samples[k].crush.unwrap()
    });
    println!(
        "car to car: samples' crush, rate, acceleration within {:?}",
        deviation.map(|d| format!("{d:.2e}"))
    );
    assert!(deviation.iter().all(|&d| d < 1e-8), "{deviation:?}");
    // The native code of `lpm simulate` evaluates the outputs bit for bit
    // as the tape does: the same metrics.
    let source = std::fs::read_to_string("specs/car_to_car.lpm").unwrap();
    let mut native = Compiled::from_source(&source).unwrap().interpreted();
    lagrangian_jit::accelerate(&mut native).unwrap();
    let native = Interpreted::<3>::new(native).unwrap();
    let of_native = simulate(&native, &output).unwrap();
    assert_eq!(
        format!("{:?}", of_native.summary),
        format!("{:?}", of_output.summary)
    );
}

#[test]
fn an_output_crush_channel_off_zero_at_the_start_is_flagged() {
    let pole = Pole::new();
    let model = interpreted::<2>(POLE_SPEC);
    let mut settings = pole.settings();
    // 1 cm closer to the pole: the intrusion starts at about +1 cm.
    settings[0] = format!("initial.coordinates.x={:?}", pole.r0[0] + 0.01);
    let result = simulate(&model, &load(&model, POLE_SCENARIO, &settings).unwrap()).unwrap();
    let kinds: Vec<&str> = result.warnings.iter().map(|w| w.kind()).collect();
    assert!(kinds.contains(&"crush_offset"), "{kinds:?}");
    let message = result.warnings[0].to_string();
    assert!(
        message.contains("crush channel `intrusion` starts at"),
        "{message}"
    );
}

/// The scenario file with its crush channel replaced by `crush`.
fn with_crush(crush: &str) -> String {
    let text = std::fs::read_to_string(POLE_SCENARIO).unwrap();
    text.replace("crush = \"intrusion\"", &format!("crush = {crush:?}"))
}

#[test]
fn an_output_of_velocities_or_inputs_or_a_misspelt_one_is_refused_at_load() {
    let model = interpreted::<2>(POLE_SPEC);
    let names = ModelNames::of(&model);
    let refused = |crush: &str| {
        let file = Some(Path::new(POLE_SCENARIO));
        Scenario::parse(&with_crush(crush), file, &names, &[]).map_err(|e| e.to_string())
    };
    let speed = refused("speed").unwrap_err();
    assert!(
        speed.contains("metrics.crush = \"speed\": output `speed` reads velocities (dot), so its rate and acceleration along the motion are not those of a crush"),
        "{speed}"
    );
    let pulled = refused("pulled").unwrap_err();
    assert!(
        pulled.contains("metrics.crush = \"pulled\": output `pulled` reads an input function"),
        "{pulled}"
    );
    let misspelt = refused("intrusoin").unwrap_err();
    assert!(
        misspelt.contains("metrics.crush = \"intrusoin\": column `intrusoin` does not exist in the spec; did you mean `intrusion`?"),
        "{misspelt}"
    );
    // An offset and a coordinate term are fine beside an output.
    assert!(refused("intrusion + 0.01").is_ok() && refused("closing - x").is_ok());
    // `--set` names the flag and its value.
    let set = load(&model, POLE_SCENARIO, &["metrics.crush=\"speed\"".into()]).unwrap_err();
    assert!(
        set.contains("--set metrics.crush=\"speed\": output `speed` reads velocities"),
        "{set}"
    );
}

#[test]
fn a_model_that_does_not_say_what_its_outputs_read_is_refused_at_load() {
    let model = compiled::PoleIntrusion::default();
    let e = load(&model, POLE_SCENARIO, &[]).unwrap_err();
    assert!(
        e.contains(
            "metrics.crush = \"intrusion\": the model does not say what output `intrusion` reads"
        ),
        "{e}"
    );
    // Its coordinates are still a crush channel.
    assert!(load(&model, POLE_SCENARIO, &["metrics.crush=\"x - y\"".into()]).is_ok());
}
