//! Runs of small specs under scenarios that once went wrong.

use super::*;
use crate::scenario::ModelNames;
use lagrangian_runtime::Interpreted;

const SPRING: &str = include_str!("../../../specs/spring_mass_damper.lpm");

fn spring() -> (Interpreted<1>, ModelNames) {
    let model = lagrangian_core::interpret(SPRING).unwrap();
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

const YARIS: &str = include_str!("../../../specs/yaris_double_pendulum.lpm");
const FULL_FRONTAL: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../specs/scenarios/yaris_full_frontal.toml"
);

#[test]
fn a_car_that_starts_short_of_the_barrier_is_not_pulled_across_the_gap() {
    let model = lagrangian_core::interpret(YARIS).unwrap();
    let names = ModelNames::of_interpreted(&model);
    let system = Interpreted::<3>::new(model).unwrap();
    // 5 cm short of the barrier (r > 0 is a gap), closing at 15.56 m/s.
    let settings = ["initial.coordinates.r=0.05", "simulation.t_end=0.01"].map(String::from);
    let scenario = Scenario::load(
        std::path::Path::new(FULL_FRONTAL),
        &names,
        &crate::scenario::Override::parse_all(&settings).unwrap(),
    )
    .unwrap();
    let result = simulate(&system, &scenario).unwrap();
    let crush = result
        .input_columns
        .iter()
        .position(|c| c == "crush")
        .unwrap();
    let contact = 0.05 / 15.5556;
    for s in &result.samples {
        if s.t < contact {
            assert_eq!(s.inputs[crush], 0.0, "force across the gap at t = {}", s.t);
            assert!(s.a[0].abs() < 5.0, "r̈ = {} at t = {}", s.a[0], s.t);
        } else {
            // In contact the barrier pushes: F = k·r + c·ṙ < 0 for r < 0.
            assert!(s.inputs[crush] < 0.0, "{} at t = {}", s.inputs[crush], s.t);
        }
    }
    let [event] = result.events.as_slice() else {
        panic!("{:?}", result.events)
    };
    assert!(
        event.description.starts_with("contact at crush 0.0000 m"),
        "{event:?}"
    );
    assert!((event.t - contact).abs() < 2e-6, "{} vs {contact}", event.t);
}

#[test]
fn a_summary_only_run_reports_what_the_full_run_reports() {
    let model = lagrangian_core::interpret(YARIS).unwrap();
    let names = ModelNames::of_interpreted(&model);
    let system = Interpreted::<3>::new(model).unwrap();
    for method in ["dopri5", "tr-bdf2"] {
        let settings = [format!("simulation.method=\"{method}\"")];
        let scenario = Scenario::load(
            std::path::Path::new(FULL_FRONTAL),
            &names,
            &crate::scenario::Override::parse_all(&settings).unwrap(),
        )
        .unwrap();
        let full = simulate(&system, &scenario).unwrap();
        let summary = simulate_summary(&system, &scenario).unwrap();
        assert_eq!(summary, full.summary, "{method}");
        // The online accumulator agrees with the samples it saw: the peak
        // crush is the largest sampled crush, refined (never smaller).
        let sampled = full
            .samples
            .iter()
            .map(|s| -s.q[0])
            .fold(f64::MIN, f64::max);
        let refined = summary.max_crush_m.unwrap();
        assert!(
            refined >= sampled && refined - sampled < 1e-6,
            "{refined} vs {sampled}"
        );
        let decel = full
            .samples
            .iter()
            .map(|s| s.a[0] / crate::pulse::STANDARD_GRAVITY)
            .fold(f64::MIN, f64::max);
        assert_eq!(summary.peak_deceleration_g, Some(decel));
    }
}

#[test]
fn channels_report_the_extremes_of_an_undamped_oscillation() {
    // m = 1 kg, k = 100 N/m, no damping, no force, x(0) = 0, ẋ(0) = 1 m/s:
    // x = 0.1·sin(10t), ẋ = cos(10t), ẍ = −10·sin(10t).
    let (model, names) = spring();
    let text = "[simulation]\nt_end = 0.5\nrtol = 1e-10\natol = 1e-12\n\
        [parameters]\nc = 0.0\n[initial]\nvelocities = { x = 1.0 }\n\
        [metrics]\ndisplacement = [\"x\"]\nvelocity = [\"-x_dot\"]\nacceleration = [\"x_ddot\"]\n\
        [components.c]\ntype = \"constant\"\nvalues = { push = 0.0 }\n";
    let scenario = Scenario::parse(text, None, &names, &[]).unwrap();
    let summary = simulate(&model, &scenario).unwrap().summary;
    let [x, v, a] = &summary.channels.0[..] else {
        panic!("{:?}", summary.channels)
    };
    let quarter = std::f64::consts::PI / 20.0;
    let close = |got: Option<f64>, want: f64, tol: f64| {
        let got = got.unwrap();
        assert!((got - want).abs() < tol, "{got} vs {want}");
    };
    assert_eq!((x.name.as_str(), x.unit.as_deref()), ("x", Some("m")));
    close(x.get("max"), 0.1, 1e-7);
    close(x.get("time_of_max_s"), quarter, 1e-4);
    close(x.get("min"), -0.1, 1e-7);
    close(x.get("time_of_min_s"), 3.0 * quarter, 1e-4);
    assert_eq!(v.unit.as_deref(), Some("m/s"));
    close(v.get("max"), 1.0, 1e-7);
    close(v.get("time_of_max_s"), 2.0 * quarter, 1e-4);
    assert_eq!(v.get("peak_g"), None);
    assert_eq!(a.unit.as_deref(), Some("m/s^2"));
    close(a.get("min"), -10.0, 1e-5);
    close(a.get("max"), 10.0, 1e-5);
    let g = 9.80665;
    close(a.get("peak_g"), 10.0 / g, 1e-6);
    // |ẍ| = 10 at π/20 and 3π/20: either is the peak.
    let peak = a.get("time_of_peak_s").unwrap();
    assert!((peak - quarter).abs() < 1e-4 || (peak - 3.0 * quarter).abs() < 1e-4);
    // 1.6 Hz passes CFC 60 and CFC 180 unchanged.
    close(a.get("cfc60_peak_g"), 10.0 / g, 1e-3);
    close(a.get("cfc180_peak_g"), 10.0 / g, 1e-3);
    // Near each peak |ẍ| ≥ 10·cos(10·Δt): 3 ms in all over the two peaks
    // is 1.5 ms about each, cos(0.0075) → 0.99997 of the peak.
    close(a.get("clip3ms_g"), 10.0 * (0.0075f64).cos() / g, 1e-3);
    // At t = 0.5 s neither x = 0.1·sin 5 nor −ẋ = −cos 5 is an extreme.
    assert!(!x.extreme_at_end && !v.extreme_at_end);
    let json = serde_json::to_value(&summary).unwrap();
    assert_eq!(json["channels"]["x_ddot"]["role"], "acceleration");
    assert_eq!(json["channels"]["-x_dot"]["unit"], "m/s");
}

#[test]
fn a_signal_still_growing_at_the_end_is_flagged() {
    let (model, names) = spring();
    let text = "[simulation]\nt_end = 0.1\n[parameters]\nc = 0.0\n\
        [initial]\nvelocities = { x = 1.0 }\n[metrics]\ndisplacement = [\"x\"]\n\
        [components.c]\ntype = \"constant\"\nvalues = { push = 0.0 }\n";
    let scenario = Scenario::parse(text, None, &names, &[]).unwrap();
    let summary = simulate(&model, &scenario).unwrap().summary;
    assert!(summary.channels.0[0].extreme_at_end);
}

/// A mass of 860 kg at 10 m/s into a crush element with a gap of 2 cm and
/// the force–deflection curve (0, 0), (0.1 m, 170 kN), (0.5 m, 180 kN).
const IMPACT: &str = "model Impact;
coordinates { x [m], }
parameters { m [kg] = 860.0, }
inputs {
    crush(x [m], v [m/s]) [N] { d(x) = crush_stiffness(x, v), d(v) = crush_damping(x, v), },
    crush_stiffness(x [m], v [m/s]) [N/m],
    crush_damping(x [m], v [m/s]) [N*s/m],
}
kinetic = 0.5 * m * pow(dot(x), 2);
force x = -crush(x, dot(x));
jacobians;
";

const WALL: &str = "[simulation]
t_end = 0.1
rtol = 1e-10
atol = 1e-12
[initial]
velocities = { x = 10.0 }
[components.wall]
type = \"crush\"
inputs = { force = \"crush\", stiffness = \"crush_stiffness\", damping = \"crush_damping\" }
compression = \"positive\"
force_breakpoints = [0.1, 0.5]
force_values = [170e3, 180e3]
damping_breakpoints = [1.0]
damping_values = [0.0, 0.0]
gap = 0.02
unloading = \"plastic\"
unloading_stiffness = 1e7
";

/// The impact model and its scenario, with `settings`.
fn impact(settings: &[&str]) -> (Interpreted<1>, Scenario) {
    let model = lagrangian_core::interpret(IMPACT).unwrap();
    let names = ModelNames::of_interpreted(&model);
    let settings: Vec<String> = settings.iter().map(|s| s.to_string()).collect();
    let scenario = Scenario::parse(
        WALL,
        None,
        &names,
        &crate::scenario::Override::parse_all(&settings).unwrap(),
    )
    .unwrap();
    (Interpreted::new(model).unwrap(), scenario)
}

#[test]
fn a_force_deflection_curve_behind_a_gap_stops_the_mass_where_its_energy_says() {
    let (system, scenario) = impact(&[]);
    let result = simulate(&system, &scenario).unwrap();
    let columns = [
        ("wall.force", "N"),
        ("wall.deflection", "m"),
        ("wall.dissipated_energy", "J"),
    ]
    .map(|(name, unit)| (name.to_string(), Some(unit.to_string())));
    assert_eq!(result.component_columns, columns);
    // ½·860·10² = 43 kJ = ∫F: 8.5 kJ to 0.1 m, then 170 kN·u + 12.5 kN/m·u²
    // for u = 0.2 m: the peak is at 0.3 m of deflection, 175 kN.
    let descriptions: Vec<&str> = (result.events.iter())
        .map(|e| e.description.as_str())
        .collect();
    assert_eq!(
        descriptions,
        [
            "contact at crush 0.0200 m",
            "peak crush 0.3200 m at 175.0 kN; unloading",
            // Unloading at 10 MN/m leaves 0.3 − 0.0175 m of deflection.
            "separation at crush 0.3025 m",
        ]
    );
    assert!(
        (result.events[0].t - 0.002).abs() < 1e-9,
        "{:?}",
        result.events[0]
    );
    // The columns: no force while the gap is open, then the curve's force
    // at the deflection x − gap until the peak.
    let peak = result.events[1].t;
    for s in &result.samples {
        let (force, deflection) = (s.components[0], s.components[1]);
        assert!((deflection - (s.q[0] - 0.02)).abs() < 1e-15, "t = {}", s.t);
        let expected = match deflection {
            d if d <= 0.0 => 0.0,
            d if d <= 0.1 => 1.7e6 * d,
            d => 170e3 + 25e3 * (d - 0.1),
        };
        if s.t < peak {
            assert!((force - expected).abs() < 1e-6, "{force} vs {expected}");
        }
        // Compression positive: the input's value is the force itself.
        assert_eq!(force, s.inputs[0]);
    }
    let max = (result.samples.iter()).fold(0.0_f64, |m, s| m.max(s.components[1]));
    assert!((max - 0.3).abs() < 1e-6, "{max}");
    // The spring gives back ½·k_u·(0.0175 m)²: 1.887 m/s of rebound.
    let rebound = -result.samples.last().unwrap().v[0];
    let expected = (1e7 * 0.0175_f64.powi(2) / 860.0).sqrt();
    assert!(
        (rebound - expected).abs() < 1e-6 * expected,
        "{rebound} vs {expected}"
    );
}

#[test]
fn the_tangent_stiffness_of_a_force_deflection_curve_is_its_segment_slope() {
    use crate::ode::tr_bdf2::AccelerationJacobians;
    let (system, scenario) = impact(&[]);
    let mut problem = CrashProblem::new(&system, scenario.inputs.clone());
    // 0.32 m of crush: 0.3 m of deflection, in contact, on the segment from
    // (0.1 m, 170 kN) to (0.5 m, 180 kN): ∂ẍ/∂x = −(25 kN/m)/860 kg.
    let y = PhaseState::new(SVector::from([0.32]), SVector::from([1.0]));
    problem.start(0.0, &y).unwrap();
    let (a_q, a_v) = problem.acceleration_jacobians(0.0, &y).unwrap().unwrap();
    assert!((a_q[(0, 0)] + 25e3 / 860.0).abs() < 1e-9, "{a_q}");
    assert_eq!(a_v[(0, 0)], 0.0);
    // TR-BDF2 on those Jacobians finds the same peak as Dormand–Prince.
    let (system, scenario) = impact(&["simulation.method=\"tr-bdf2\""]);
    let result = simulate(&system, &scenario).unwrap();
    let peak = &result.events[1].description;
    assert_eq!(peak, "peak crush 0.3200 m at 175.0 kN; unloading");
}

#[test]
fn the_crush_when_contact_ends_is_the_permanent_crush() {
    // The mass of the test above: contact ends at the permanent set of the
    // plastic unloading, 0.3 − 175 kN / 10 MN/m = 0.2825 m of deflection
    // behind the 2 cm gap, 0.3025 m of crush.
    let (system, scenario) = impact(&["metrics.crush=\"x\"", "metrics.contact=[\"wall\"]"]);
    let result = simulate(&system, &scenario).unwrap();
    let summary = &result.summary;
    let separation = result.events[2].t;
    assert_eq!(summary.end_of_contact_s, Some(separation));
    let permanent = summary.permanent_crush_m.unwrap();
    assert!((permanent - 0.3025).abs() < 1e-9, "{permanent}");
    assert!((summary.max_crush_m.unwrap() - 0.32).abs() < 1e-9);
    // Still in contact at the end of a shorter run: no permanent crush yet.
    let (system, scenario) = impact(&["metrics.crush=\"x\"", "simulation.t_end=0.02"]);
    let summary = simulate(&system, &scenario).unwrap().summary;
    assert_eq!(
        (summary.permanent_crush_m, summary.end_of_contact_s),
        (None, None)
    );
}

const DOUBLE_PENDULUM: &str = include_str!("../../../specs/double_pendulum.lpm");

/// A run that keeps only its summary (a sweep's) evaluates the outputs
/// when a channel reads them, to the values a full run records.
#[test]
fn outputs_are_evaluated_in_summary_only_runs_too() {
    let model = lagrangian_core::interpret(DOUBLE_PENDULUM).unwrap();
    let names = ModelNames::of_interpreted(&model);
    let system = Interpreted::<2>::new(model).unwrap();
    let text = "[simulation]\nt_end = 0.05\n[initial.coordinates]\ntheta1 = 0.5\n";
    let scenario = Scenario::parse(text, None, &names, &[]).unwrap();
    let full = simulate(&system, &scenario).unwrap();
    let columns = ["x2_position", "y2_position", "a2_magnitude"];
    assert_eq!(full.output_columns, columns);
    let last = full.samples.last().unwrap();
    assert_eq!(last.outputs.len(), 3);
    let mut problem = CrashProblem::new(&system, scenario.inputs.clone());
    let q = SVector::from_column_slice(&last.q);
    let v = SVector::from_column_slice(&last.v);
    let channel = ["metrics.displacement=[\"y2_position\"]".to_string()];
    let read = Scenario::parse(
        text,
        None,
        &names,
        &crate::scenario::Override::parse_all(&channel).unwrap(),
    )
    .unwrap();
    let needs = needs::Needs::of(&read, false, 0);
    assert!(needs.outputs && needs.accelerations && !needs.kept);
    let y = PhaseState::new(q, v);
    // At the accelerations the full run took (from the dense output).
    let a = Some(SVector::from_column_slice(&last.a));
    let (values, inputs) = sample(&mut problem, last.t, &y, &needs, 3, a).unwrap();
    assert!(inputs.is_empty());
    assert_eq!(values.as_view().outputs, &last.outputs[..]);
    // At rest the lower bob hangs 2 m below the pivot, unaccelerated.
    let rest = Scenario::parse("[simulation]\nt_end = 0.01\n", None, &names, &[]).unwrap();
    let at_rest = simulate(&system, &rest).unwrap();
    assert_eq!(at_rest.samples[0].outputs, [0.0, -2.0, 0.0]);
}

#[test]
fn a_channel_reads_a_components_column_in_a_summary_only_run_too() {
    // The peak force of the crush element above: 175 kN at 0.3 m.
    let settings = [
        "metrics.force=[\"wall.force\"]",
        "metrics.displacement=[\"1e-3 * wall.deflection\"]",
    ];
    let (system, scenario) = impact(&settings);
    let summary = simulate_summary(&system, &scenario).unwrap();
    let [deflection, force] = &summary.channels.0[..] else {
        panic!("{:?}", summary.channels)
    };
    assert_eq!(force.unit.as_deref(), Some("N"));
    assert!((force.get("max").unwrap() - 175e3).abs() < 1.0, "{force:?}");
    assert!(
        (deflection.get("max").unwrap() - 0.3e-3).abs() < 1e-9,
        "{deflection:?}"
    );
    let error = Scenario::parse(
        WALL,
        None,
        &ModelNames::of(&system),
        &[crate::scenario::Override::parse("metrics.force=[\"wall.forse\"]").unwrap()],
    );
    let error = error.unwrap_err().to_string();
    assert!(error.contains("did you mean `wall.force`?"), "{error}");
}

/// A summary-only run evaluates at its samples only what the summary and
/// the channels read, and its summary is the full run's.
#[test]
fn a_summary_only_run_evaluates_what_is_read() {
    let model = lagrangian_core::interpret(DOUBLE_PENDULUM).unwrap();
    let names = ModelNames::of_interpreted(&model);
    let system = Interpreted::<2>::new(model).unwrap();
    let text = "[simulation]\nt_end = 0.05\n[initial.coordinates]\ntheta1 = 0.5\n";
    let bare = Scenario::parse(text, None, &names, &[]).unwrap();
    let none = needs::Needs::of(&bare, false, 0);
    assert_eq!(
        (none.accelerations, none.outputs, none.components),
        (false, false, false)
    );
    // With nothing read the accelerations and the energies (the energy
    // balance takes them at the steps' ends) stay NaN; a kept sample has
    // them.
    let mut problem = CrashProblem::new(&system, bare.inputs.clone());
    let y = PhaseState::new(SVector::from([0.5, 0.0]), SVector::zeros());
    let (values, _) = sample(&mut problem, 0.0, &y, &none, 3, None).unwrap();
    assert!(values.a.iter().all(|a| a.is_nan()) && values.outputs.is_empty());
    assert!(values.potential.is_nan() && values.kinetic.is_nan());
    let kept = needs::Needs::of(&bare, true, 0);
    let (values, _) = sample(&mut problem, 0.0, &y, &kept, 3, None).unwrap();
    assert!(values.potential.is_finite() && values.potential != 0.0);
    let with = |setting: &str| {
        Scenario::parse(
            text,
            None,
            &names,
            &[crate::scenario::Override::parse(setting).unwrap()],
        )
        .unwrap()
    };
    let accelerations = with("metrics.acceleration=[\"theta1_ddot\"]");
    let needs = needs::Needs::of(&accelerations, false, 0);
    assert!(needs.accelerations && !needs.outputs && !needs.components);
    let outputs = with("metrics.displacement=[\"x2_position\"]");
    let needs = needs::Needs::of(&outputs, false, 0);
    assert!(needs.accelerations && needs.outputs && !needs.components);
    for scenario in [&bare, &accelerations, &outputs] {
        let full = simulate(&system, scenario).unwrap().summary;
        assert_eq!(simulate_summary(&system, scenario).unwrap(), full);
    }
    assert!(
        needs::Needs::of(&bare, true, 0)
            == needs::Needs {
                accelerations: true,
                outputs: true,
                output_motion: false,
                components: true,
                kept: true,
            }
    );
    assert!(needs::Needs::of(&bare, false, 1).accelerations);
}

#[test]
fn each_event_function_alone_is_the_one_of_all() {
    use crate::ode::OdeProblem;
    // The impact model with a switching function: a spring on x > 0 only.
    let source = (IMPACT.replace("jacobians;", "potential = 0.25 * k * pow(x + abs(x), 2);"))
        .replace("m [kg] = 860.0,", "m [kg] = 860.0, k [N/m] = 100.0,");
    let model = lagrangian_core::interpret(&source).unwrap();
    assert_eq!(model.switching_count(), 1);
    let names = ModelNames::of_interpreted(&model);
    let scenario = Scenario::parse(WALL, None, &names, &[]).unwrap();
    let system = Interpreted::<1>::new(model).unwrap();
    let mut problem = CrashProblem::new(&system, scenario.inputs.clone());
    let start = PhaseState::new(SVector::from([0.0]), SVector::from([10.0]));
    problem.start(0.0, &start).unwrap();
    let n = problem.event_count();
    let (mut all, mut scratch) = (vec![0.0_f64; n], vec![f64::NAN; n]);
    // Crushes before and behind the gap, each side of the curve's kink.
    for (x, v) in [
        (-0.01, 10.0),
        (0.01, 5.0),
        (0.05, 2.0),
        (0.2, -1.0),
        (0.4, 0.0),
    ] {
        let y = PhaseState::new(SVector::from([x]), SVector::from([v]));
        problem.events(0.0, &y, &mut all).unwrap();
        for (k, value) in all.iter().enumerate() {
            let alone = problem.event(k, 0.0, &y, &mut scratch).unwrap();
            assert_eq!(alone.to_bits(), value.to_bits(), "event {k} at {x}, {v}");
        }
    }
}

/// A mass pushed back by a constant force, with a parameter named `NAME`
/// that is a gap (0.025 m), not gravity.
fn pushed_mass(name: &str) -> (Interpreted<1>, ModelNames) {
    let spec = format!(
        "model PushedMass;\ncoordinates {{ x [m], }}\n\
         parameters {{ m [kg] = 2.0, {name} [m] = 0.025, k [N/m] = 0.0, }}\n\
         inputs {{ push(t [s]) [N], }}\n\
         kinetic = 0.5 * m * pow(dot(x), 2);\n\
         potential = 0.5 * k * pow(x - {name}, 2);\n\
         force x = push(t);\n"
    );
    let model = lagrangian_core::interpret(&spec).unwrap();
    let names = ModelNames::of_interpreted(&model);
    (Interpreted::new(model).unwrap(), names)
}

/// No parameter of a spec changes a unit: a gap named `g` gives the same
/// figures in g as the same gap named `gap`, and a constant deceleration of
/// 100 m/s² (200 N on 2 kg) is 100 / 9.80665 g.
#[test]
fn figures_in_g_are_in_standard_gravity_whatever_the_spec_calls_g() {
    let text = "[simulation]\nt_end = 0.15\n[initial]\nvelocities = { x = 10.0 }\n\
        [metrics]\ncrush = \"x\"\nacceleration = [\"x_ddot\"]\n\
        [components.c]\ntype = \"constant\"\nvalues = { push = -200.0 }\n";
    let run = |name: &str| {
        let (model, names) = pushed_mass(name);
        let scenario = Scenario::parse(text, None, &names, &[]).unwrap();
        simulate(&model, &scenario).unwrap().summary
    };
    let (named_g, named_gap) = (run("g"), run("gap"));
    assert_eq!(named_g, named_gap);
    let expected = 100.0 / 9.80665;
    let peak = named_g.peak_deceleration_g.unwrap();
    assert!(
        (peak / expected - 1.0).abs() < 1e-12,
        "{peak} vs {expected}"
    );
    let channel = &named_g.channels.0[0];
    let channel_peak = channel.get("peak_g").unwrap();
    assert!(
        (channel_peak / expected - 1.0).abs() < 1e-12,
        "{channel_peak}"
    );
    // The square wave of a constant deceleration is that deceleration.
    let esw = named_g.equivalent_square_wave_g.unwrap();
    assert!((esw / expected - 1.0).abs() < 1e-6, "{esw}");
}

fn interpreted<const N: usize>(spec: &str) -> (Interpreted<N>, ModelNames) {
    let model = lagrangian_core::interpret(spec).unwrap();
    let names = ModelNames::of_interpreted(&model);
    (Interpreted::new(model).unwrap(), names)
}

/// A mass at rest pushed by 1 N has no energy at the start: its balance is
/// measured against the work of the force (½ J after 1 s), not against 0.
#[test]
fn a_run_that_starts_without_energy_is_measured_against_its_energy_scale() {
    let spec = include_str!("../../../tests/bad_inputs/metrics_at_rest.lpm");
    let (model, names) = interpreted::<1>(spec);
    let scenario = Scenario::parse("[simulation]\nt_end = 1.0\n", None, &names, &[]).unwrap();
    let result = simulate(&model, &scenario).unwrap();
    let error = result.summary.energy_balance_error_rel;
    assert!(error < 1e-9, "{error}");
    assert_eq!(result.warnings, []);
    // x = t²/2: the work at 1 s is 0.5 J, all kinetic.
    let last = result.samples.last().unwrap();
    assert!((last.kinetic - 0.5).abs() < 1e-9, "{}", last.kinetic);
}

/// `asin(10 sin θ)` at θ = 0.5 is NaN from the first sample: named, with
/// that time, while the run itself succeeds.
#[test]
fn an_output_that_is_not_a_number_is_named_with_its_first_time() {
    let spec = include_str!("../../../tests/bad_inputs/metrics_asin_output.lpm");
    let (model, names) = interpreted::<1>(spec);
    let text = "[simulation]\nt_end = 0.1\n[initial]\ncoordinates = { theta = 0.5 }\n";
    let scenario = Scenario::parse(text, None, &names, &[]).unwrap();
    let result = simulate(&model, &scenario).unwrap();
    assert!(result.samples.iter().all(|s| s.outputs[0].is_nan()));
    let non_finite: Vec<&Warning> = (result.warnings.iter())
        .filter(|w| w.kind() == "non_finite")
        .collect();
    let [Warning::NonFinite { what, t, value }] = non_finite[..] else {
        panic!("{:?}", result.warnings)
    };
    assert_eq!((what.as_str(), *t), ("output `phase`", 0.0));
    assert!(value.is_nan());
    // Where it is a number throughout, no warning.
    let text = "[simulation]\nt_end = 0.1\n[initial]\ncoordinates = { theta = 0.05 }\n";
    let scenario = Scenario::parse(text, None, &names, &[]).unwrap();
    assert_eq!(simulate(&model, &scenario).unwrap().warnings, []);
}

/// The pushed mass of [`pushed_mass`] stopped short of its stop (v0/a =
/// 0.1 s) is still crushing: warned, and said on the headline line.
#[test]
fn a_pulse_cut_short_by_t_end_is_not_its_maximum() {
    let (model, names) = pushed_mass("gap");
    let text = |t_end: f64| {
        format!(
            "[simulation]\nt_end = {t_end}\n[initial]\nvelocities = {{ x = 10.0 }}\n\
             [metrics]\ncrush = \"x\"\n\
             [components.c]\ntype = \"constant\"\nvalues = {{ push = -200.0 }}\n"
        )
    };
    let scenario = Scenario::parse(&text(0.05), None, &names, &[]).unwrap();
    let result = simulate(&model, &scenario).unwrap();
    let kinds: Vec<&str> = result.warnings.iter().map(Warning::kind).collect();
    assert_eq!(kinds, ["still_crushing"]);
    // x = 10 t − 50 t² at 0.05 s: 0.375 m, at rate 5 m/s.
    assert!((result.summary.max_crush_m.unwrap() - 0.375).abs() < 1e-9);
    let lines = result.summary.text_lines();
    assert!(
        lines.starts_with(
            "  max dynamic crush      0.375 m (still crushing at t_end: not the maximum)\n"
        ),
        "{lines}"
    );
    let scenario = Scenario::parse(&text(0.15), None, &names, &[]).unwrap();
    let result = simulate(&model, &scenario).unwrap();
    assert_eq!(result.warnings, []);
    assert!(!result.summary.text_lines().contains("still crushing"));
}

/// An acceleration channel of class 1000 (`"head"`) sampled at 1 kHz: its
/// CFC 60 and CFC 180 peaks are there, its own class's peak and clip are
/// not, and a warning says why; at 10 kHz all are there, and the class's
/// peak of a 1.6 Hz signal is its raw peak.
#[test]
fn each_channel_class_is_computed_where_the_rate_gives_it() {
    let (model, names) = spring();
    let text = |interval: f64| {
        format!(
            "[simulation]\nt_end = 0.5\noutput_interval = {interval}\n[parameters]\nc = 0.0\n\
             [initial]\nvelocities = {{ x = 1.0 }}\n\
             [metrics]\nacceleration = [\"x_ddot\"]\nclasses = {{ x_ddot = \"head\" }}\n\
             [components.c]\ntype = \"constant\"\nvalues = {{ push = 0.0 }}\n"
        )
    };
    let scenario = Scenario::parse(&text(1e-3), None, &names, &[]).unwrap();
    assert_eq!(scenario.channels[0].cfc, 1000.0);
    let result = simulate(&model, &scenario).unwrap();
    let a = &result.summary.channels.0[0];
    let g = 9.80665;
    assert!((a.get("cfc60_peak_g").unwrap() - 10.0 / g).abs() < 1e-3);
    assert!((a.get("cfc180_peak_g").unwrap() - 10.0 / g).abs() < 1e-3);
    assert_eq!((a.get("cfc_peak_g"), a.get("clip3ms_g")), (None, None));
    let [w] = &result.warnings[..] else {
        panic!("{:?}", result.warnings)
    };
    assert_eq!(
        w.message(),
        "CFC 1000 needs a sample rate above 4155 Hz (SAE J211-1: 2.0775·CFC below half the \
         sample rate); samples every 1 ms give 1000 Hz: the CFC 1000 peak and 3 ms clip of \
         channel `x_ddot` are not computed"
    );
    let scenario = Scenario::parse(&text(1e-4), None, &names, &[]).unwrap();
    let result = simulate(&model, &scenario).unwrap();
    let a = &result.summary.channels.0[0];
    assert!((a.get("cfc_peak_g").unwrap() - 10.0 / g).abs() < 1e-4);
    assert!(a.get("clip3ms_g").is_some());
    assert_eq!(result.warnings, []);
    let json = serde_json::to_value(&result.summary).unwrap();
    assert_eq!(json["channels"]["x_ddot"]["cfc"], 1000.0);
}

/// A crush channel with an offset: `x + 0.5` from x = −0.5 is the crush
/// `x` from 0 — the same summary, since the offset leaves the rate and the
/// acceleration alone (k = 0: the pushed mass does not feel where it is).
#[test]
fn a_crush_channel_with_an_offset_is_the_shifted_channel() {
    let (model, names) = pushed_mass("gap");
    let run = |crush: &str, x0: f64| {
        let text = format!(
            "[simulation]\nt_end = 0.15\n[initial]\ncoordinates = {{ x = {x0} }}\n\
             velocities = {{ x = 10.0 }}\n[metrics]\ncrush = \"{crush}\"\n\
             [components.c]\ntype = \"constant\"\nvalues = {{ push = -200.0 }}\n"
        );
        let scenario = Scenario::parse(&text, None, &names, &[]).unwrap();
        simulate(&model, &scenario).unwrap()
    };
    let (plain, shifted) = (run("x", 0.0), run("x + 0.5", -0.5));
    let close = |a: Option<f64>, b: Option<f64>| (a.unwrap() - b.unwrap()).abs() < 1e-9;
    let (p, s) = (&plain.summary, &shifted.summary);
    assert!(close(p.max_crush_m, s.max_crush_m), "{p:?}\n{s:?}");
    assert!((s.max_crush_m.unwrap() - 0.5).abs() < 1e-9, "{s:?}");
    assert!(close(
        p.equivalent_square_wave_g,
        s.equivalent_square_wave_g
    ));
    assert!(close(p.time_to_zero_velocity_s, s.time_to_zero_velocity_s));
    // The state differs by 0.5 in x, so the integration rounds differently.
    assert!(close(p.peak_deceleration_g, s.peak_deceleration_g));
    assert_eq!((plain.warnings, shifted.warnings), (vec![], vec![]));
    // Without the offset the same start is a crush channel not at 0.
    let offset = run("x", -0.5);
    let kinds: Vec<&str> = offset.warnings.iter().map(Warning::kind).collect();
    assert_eq!(kinds, ["crush_offset"]);
    let names_ = names.clone();
    let error = |crush: &str| {
        let text = format!("[metrics]\ncrush = \"{crush}\"\n");
        Scenario::parse(&text, None, &names_, &[])
            .unwrap_err()
            .to_string()
    };
    assert!(
        error("0.5").contains("a constant reads no column of the run"),
        "{}",
        error("0.5")
    );
}
