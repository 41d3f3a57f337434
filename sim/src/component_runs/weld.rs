//! Runs of the `weld` component through the simulator (moved out of
//! `components::weld`, which must not reach the run engine above it).

use crate::components::weld::*;
use crate::components::{Component, Events};
use crate::curve::Curve;
use crate::curve::Outside;

#[test]
fn fails_at_the_threshold_and_switches_curves() {
    let intact = Curve::new(vec![-0.1, 0.1], vec![-1.0e4, 1.0e4], Outside::Extrapolate).unwrap();
    let mut weld = Weld::new(intact, 100.0, Some(5.0e3), None, None, 10.0);
    let (m, dm, dc) = weld.moment(&[0.02, 1.0]).unwrap();
    assert!(
        (m - 2.1e3).abs() < 1e-9 && dm == 1.0e5 && dc == 100.0,
        "{m} {dm} {dc}"
    );
    let mut columns = [0.0; 2];
    weld.column_values(&[0.02, 1.0], &mut columns).unwrap();
    assert!((columns[0] - 2.1e3).abs() < 1e-9 && columns[1] == 0.02);
    let mut g = [0.0; 4];
    weld.event_values(&[0.05, 0.0], &mut g).unwrap();
    assert!(g[0].abs() < 1e-9 && g[1] == -1.0, "{g:?}");
    weld.on_event(0, 0.042, &[0.05, 0.0]).unwrap();
    assert_eq!(weld.failed_at(), Some(0.042));
    assert_eq!(weld.moment(&[0.05, 2.0]).unwrap(), (20.0, 0.0, 10.0));
    weld.event_values(&[0.09, 0.0], &mut g).unwrap();
    assert_eq!(g[..2], [-1.0, -1.0]);
}

/// A weld whose curves have kinks (at 0 and 0.05 rad intact, at 0 after
/// failure), held or not.
fn kinked(stop_at_kinks: bool) -> Weld {
    let intact = Curve::new(
        vec![-0.1, 0.0, 0.05, 0.1],
        vec![-1.0e4, 0.0, 1.0e4, 1.2e4],
        Outside::Extrapolate,
    )
    .unwrap();
    let post = Curve::new(
        vec![-0.1, 0.0, 0.1],
        vec![-2e3, 0.0, 1e3],
        Outside::Extrapolate,
    );
    Weld::new(intact, 0.0, Some(1.1e4), None, Some(post.unwrap()), 0.0)
        .with_stop_at_kinks(stop_at_kinks)
}

#[test]
fn each_event_function_alone_is_the_one_of_all() {
    let mut weld = kinked(true);
    weld.start(Some(&[0.01, 0.0])).unwrap();
    let angles = [-0.2, -0.05, 0.0, 0.01, 0.049, 0.06, 0.075, 0.2];
    let check = |weld: &Weld| {
        for angle in angles {
            crate::components::assert_event_value_is_event_values(weld, &[angle, 1.0]);
        }
    };
    // Intact, intact on the next segment, failed, and without holding.
    check(&weld);
    weld.on_event(3, 0.0, &[0.05, 0.0]).unwrap();
    check(&weld);
    weld.on_event(0, 0.01, &[0.075, 0.0]).unwrap();
    check(&weld);
    check(&kinked(false));
}

#[test]
fn walked_through_its_kinks_by_its_events_the_weld_gives_its_curves_moment() {
    let (mut held, mut unheld) = (kinked(true), kinked(false));
    held.start(Some(&[-0.0195, 0.0])).unwrap();
    unheld.start(Some(&[-0.0195, 0.0])).unwrap();
    // Out to 0.0905 rad (failing at 0.075 rad, 11 kN·m) and back, the
    // points off the kinks (where the slope has two values).
    let out = (0..=110).map(|i| -0.0195 + 0.001 * i as f64);
    let path: Vec<f64> = out.clone().chain(out.rev()).collect();
    let (mut before, mut after) = ([0.0; 4], [0.0; 4]);
    let mut handled = Vec::new();
    for pair in path.windows(2) {
        let (a, b) = ([pair[0], 0.0], [pair[1], 0.0]);
        for weld in [&mut held, &mut unheld] {
            weld.event_values(&a, &mut before).unwrap();
            weld.event_values(&b, &mut after).unwrap();
            let crossed = (0..4).find(|&k| EVENTS[k].direction.crosses(before[k], after[k]));
            if let Some(k) = crossed {
                let note = weld.on_event(k, pair[1], &b).unwrap();
                handled.push((weld.stop_at_kinks, k, note.is_empty()));
            }
        }
        assert_eq!(
            held.moment(&b).unwrap(),
            unheld.moment(&b).unwrap(),
            "{b:?}"
        );
    }
    // Held: the kinks at 0 and 0.05 rad out, the failure, the kink at 0
    // back; not held: the failure only.
    let expected = [
        (true, 3, true),
        (true, 3, true),
        (true, 0, false),
        (false, 0, false),
        (true, 2, true),
    ];
    assert_eq!(handled, expected);
}

/// A flywheel of 100 kg·m² on a weld, `th` its angle.
const HINGE: &str = "model Hinge;\n\
    coordinates { th [rad], }\n\
    parameters { I [kg*m^2] = 100.0, }\n\
    inputs { weld(th [rad], w [rad/s]) [N*m], }\n\
    kinetic = 0.5 * I * pow(dot(th), 2);\n\
    force th = -weld(th, dot(th));\n";

/// At 2 rad/s (200 J) into a weld of 100 kN·m/rad that fails at
/// 4 kN·m (0.04 rad, 80 J stored) onto 10 kN·m/rad (8 J there).
const SCENARIO: &str = "[simulation]\nt_end = 0.2\noutput_interval = 1e-3\n\
    [initial]\nvelocities = { th = 2.0 }\n\
    [components.weld]\ntype = \"weld\"\ninputs = { moment = \"weld\" }\n\
    curve = [[-1.0, -1.0e5], [0.0, 0.0], [1.0, 1.0e5]]\ndamping = 50.0\n\
    failure_moment = 4.0e3\npost_failure_curve = [[-1.0, -1.0e4], [0.0, 0.0], [1.0, 1.0e4]]\n\
    post_failure_damping = 5.0\n";

#[test]
fn the_energy_balance_closes_with_what_the_weld_dissipated() {
    use crate::scenario::{ModelNames, Scenario};
    use crate::simulate::simulate;
    use lagrangian_runtime::Interpreted;
    let model = lagrangian_core::interpret(HINGE).unwrap();
    let names = ModelNames::of_interpreted(&model);
    let model = Interpreted::<1>::new(model).unwrap();
    let scenario = Scenario::parse(SCENARIO, None, &names, &[]).unwrap();
    let result = simulate(&model, &scenario).unwrap();
    let failure = result.summary.weld_failure_time_s.unwrap();
    let k = (result.component_columns.iter())
        .position(|(n, _)| n == "weld.dissipated_energy")
        .unwrap();
    // T + ½·k·θ² (the curve of the moment) + dissipated = 200 J, with
    // the failure releasing 80 − 8 J beside what the dampers take.
    let mut before = 0.0;
    for s in &result.samples {
        let stiffness = if s.t < failure { 1.0e5 } else { 1.0e4 };
        let stored = 0.5 * stiffness * s.q[0] * s.q[0];
        let dissipated = s.components[k];
        let total = s.kinetic + stored + dissipated;
        assert!((total / 200.0 - 1.0).abs() < 1e-6, "t = {}: {total}", s.t);
        if s.t < failure {
            before = dissipated;
        }
    }
    let end = result.samples.last().unwrap().components[k];
    assert!(end - before > 72.0, "{before} → {end}");
    assert_eq!(result.summary.dissipated_by, [("weld".to_string(), end)]);
}
