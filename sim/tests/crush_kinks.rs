//! A crush element pushed through the breakpoints of its force–deflection
//! curve: with `stop_at_kinks` (the default) each crossing is an event
//! located at the time the closed-form trajectory of the piecewise-linear
//! spring–mass gives, and no step straddles a kink; without it the steps
//! cross them, with rejections. Either way the force is the curve's.

use lagrangian_runtime::Interpreted;
use lagrangian_sim::components::Events;
use lagrangian_sim::components::crush::{CrushElement, LoadingCurve, Unloading};
use lagrangian_sim::curve::{ForceCurve, Outside, SecantCurve};
use lagrangian_sim::scenario::{ModelNames, Scenario};
use lagrangian_sim::simulate::{SimulationResult, simulate};

const WALL: &str = include_str!("../../specs/wall_impact.lpm");

/// The body's mass \[kg\] (the spec's default) and speed at contact \[m/s\].
const MASS: f64 = 1500.0;
const SPEED: f64 = 5.0;
/// The force–deflection curve: (0, 0) and these points, linear between and
/// continued beyond the last, so its kinks are the inner points.
const DEFLECTIONS: [f64; 4] = [0.01, 0.02, 0.04, 0.08];
const FORCES: [f64; 4] = [100e3, 150e3, 400e3, 500e3];

/// The crush element's events: 2 separation, 4 and 5 the deflection below
/// and above a breakpoint of its loading curve.
const SEPARATION: usize = 2;
const BELOW: usize = 4;
const ABOVE: usize = 5;

/// The closed form: on the segment `[x_i, x_{i+1}]` the force is
/// `F_i + k_i (x − x_i)`, so `x − x_e = A sin θ`, `ẋ/ω = A cos θ` with
/// `ω² = k_i/m`, `x_e = x_i − F_i/k_i` and `θ` growing at `ω`. Returns the
/// times the deflection reaches each inner breakpoint on the way in, and
/// the time of the maximum deflection (ẋ = 0, θ = π/2).
fn closed_form() -> (Vec<f64>, f64) {
    let xs: Vec<f64> = std::iter::once(0.0).chain(DEFLECTIONS).collect();
    let fs: Vec<f64> = std::iter::once(0.0).chain(FORCES).collect();
    let (mut t, mut v) = (0.0, SPEED);
    let mut crossings = Vec::new();
    for i in 0..xs.len() - 1 {
        let k = (fs[i + 1] - fs[i]) / (xs[i + 1] - xs[i]);
        let omega = (k / MASS).sqrt();
        let equilibrium = xs[i] - fs[i] / k;
        let phase = |x: f64, v: f64| (x - equilibrium).atan2(v / omega);
        let start = phase(xs[i], v);
        // The work of the segment, from the energy.
        let v2 = v * v - (fs[i] + fs[i + 1]) * (xs[i + 1] - xs[i]) / MASS;
        if v2 <= 0.0 {
            return (crossings, t + (std::f64::consts::FRAC_PI_2 - start) / omega);
        }
        t += (phase(xs[i + 1], v2.sqrt()) - start) / omega;
        v = v2.sqrt();
        crossings.push(t);
    }
    panic!("the body passes the last point");
}

/// The run at rtol 1e-8 to `t_end`, with `stop_at_kinks = {stop}`.
fn run(stop: bool, t_end: f64) -> SimulationResult {
    let model = lagrangian_core::interpret(WALL).unwrap();
    let names = ModelNames::of_interpreted(&model);
    let system = Interpreted::<1>::new(model).unwrap();
    let text = format!(
        "[simulation]\nt_end = {t_end}\nrtol = 1e-8\natol = 1e-10\noutput_interval = 1e-4\n\
         [initial]\nvelocities = {{ x = {SPEED} }}\n\
         [components.wall]\ntype = \"crush\"\ninputs = {{ force = \"wall\" }}\n\
         compression = \"positive\"\nforce_breakpoints = {DEFLECTIONS:?}\nforce_values = {FORCES:?}\n\
         damping_breakpoints = [1.0]\ndamping_values = [0.0, 0.0]\n\
         outside = \"extrapolate\"\nstop_at_kinks = {stop}\n"
    );
    let scenario = Scenario::parse(&text, None, &names, &[]).unwrap();
    simulate(&system, &scenario).unwrap()
}

#[test]
fn each_breakpoint_crossing_is_located_where_the_closed_form_puts_it() {
    let (crossings, peak) = closed_form();
    assert_eq!(crossings.len(), 3);
    // Elastic and undamped: back out through the same breakpoints in
    // mirror image, separating at 2·peak with the speed it came in with.
    let separation = 2.0 * peak;
    let t_end = separation + 1e-3;
    let held = run(true, t_end);
    let mut expected: Vec<(usize, f64)> = crossings.iter().map(|&t| (ABOVE, t)).collect();
    expected.extend(crossings.iter().rev().map(|&t| (BELOW, separation - t)));
    expected.push((SEPARATION, separation));
    let events = &held.stats.events;
    assert_eq!(events.len(), expected.len(), "{events:?}");
    for (&(k, t), &(k_expected, t_expected)) in events.iter().zip(&expected) {
        assert_eq!(k, k_expected, "{events:?}");
        // The integration's error, ≈ 1e-10 s after the peak at rtol 1e-8.
        assert!((t - t_expected).abs() < 1e-9, "{t} ≠ {t_expected}");
    }
    // The kinks are not changes of regime: the log shows the separation.
    let [logged] = held.events.as_slice() else {
        panic!("{:?}", held.events)
    };
    assert!(logged.description.starts_with("separation"), "{logged:?}");
    // Stepping across the kinks instead: no event but the separation, and
    // the rejected steps the held segments avoid.
    let across = run(false, t_end);
    assert_eq!(across.stats.events.len(), 1, "{:?}", across.stats.events);
    let rejected = (held.stats.rejected_steps, across.stats.rejected_steps);
    assert!(
        rejected.0 <= 4 && rejected.1 >= 5 * rejected.0 + 5,
        "{rejected:?}"
    );
    assert!(held.stats.accepted_steps < across.stats.accepted_steps);
    // Both end in free flight at the closed form's position and speed; the
    // held run closer (the error control sees no kink inside a step).
    for (result, tolerance) in [(&held, (1e-9, 1e-7)), (&across, (1e-7, 1e-5))] {
        let last = result.samples.last().unwrap();
        let x = -SPEED * (last.t - separation);
        assert!((last.q[0] - x).abs() < tolerance.0, "{} ≠ {x}", last.q[0]);
        assert!((last.v[0] + SPEED).abs() < tolerance.1, "{}", last.v[0]);
    }
}

#[test]
fn the_held_force_is_the_curve_at_every_sample() {
    let curve = ForceCurve::new(&DEFLECTIONS, &FORCES, Outside::Extrapolate).unwrap();
    let result = run(true, 2.0 * closed_form().1);
    let force = (result.component_columns.iter())
        .position(|(name, _)| name == "wall.force")
        .unwrap();
    let mut compared = 0;
    for s in result.samples.iter().filter(|s| s.q[0] > 0.0) {
        assert_eq!(
            s.components[force],
            curve.force(s.q[0]).unwrap().0,
            "{}",
            s.t
        );
        compared += 1;
    }
    assert!(compared > 100, "{compared}");
}

/// The paper's front end (secant stiffness and damping curves, plastic
/// unloading off), held or not.
fn paper_front_end(stop_at_kinks: bool) -> CrushElement {
    let breakpoints = [0.05, 0.10, 0.25, 0.45, 0.60, 0.80];
    let k = [2.4e6, 2.4e6, 2.1e6, 0.94e6, 0.567e6, 0.50e6, 0.5625e6];
    let rates = [1.0, 3.0, 6.0, 10.0, 14.0, 16.0];
    let c = [3000.0, 3000.0, 2800.0, 2500.0, 2200.0, 2000.0, 2000.0];
    let loading = SecantCurve::new(&breakpoints, &k, Outside::Hold).unwrap();
    let damping = SecantCurve::new(&rates, &c, Outside::Hold).unwrap();
    let loading = LoadingCurve::SecantStiffness(loading);
    CrushElement::new(loading, damping, Unloading::Elastic, -1.0, true)
        .with_stop_at_kinks(stop_at_kinks)
}

#[test]
fn walked_through_its_kinks_by_its_events_the_element_gives_the_curves_force() {
    let mut held = paper_front_end(true);
    let unheld = paper_front_end(false);
    // Crush from 0 to 0.7 m (r = −crush) while the rate falls from 15 m/s
    // to 0, and back: every breakpoint of both curves is crossed twice.
    let path: Vec<[f64; 2]> = (0..=2000)
        .chain((0..2000).rev())
        .map(|i| {
            let s = i as f64 / 2000.0;
            [-0.7 * s, -15.0 * (1.0 - s)]
        })
        .collect();
    held.start(Some(&path[0])).unwrap();
    let events = held.list();
    let (mut before, mut after) = ([0.0; 8], [0.0; 8]);
    let mut crossings = 0;
    for pair in path.windows(2) {
        held.event_values(&pair[0], &mut before).unwrap();
        held.event_values(&pair[1], &mut after).unwrap();
        for k in 4..8 {
            if events[k].direction.crosses(before[k], after[k]) {
                assert_eq!(held.on_event(k, 0.0, &pair[1]).unwrap(), "");
                crossings += 1;
            }
        }
        let (force, reference) = (held.force(&pair[1]), unheld.force(&pair[1]));
        let (force, reference) = (force.unwrap(), reference.unwrap());
        assert!(
            (force - reference).abs() <= 1e-12 * reference.abs(),
            "{pair:?}: {force} ≠ {reference}"
        );
    }
    // 5 kinks of k (0.05 … 0.6 m; 0.8 m is not reached) and 4 of c
    // (1, 6, 10, 14 m/s: c is linear across 3 m/s), each way.
    assert_eq!(crossings, 2 * (5 + 4));
}
