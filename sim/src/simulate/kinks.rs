//! The kinks of the inputs of time inside a step: what the step's stages
//! see (`[simulation] time_kinks`).
//!
//! By default (`"smoothed"`) every input of time with a kink inside the
//! step an adaptive explicit method tries — a time table interpolated
//! linearly — takes its smooth stand-in over that step
//! ([`crate::components::StandIn`]: the cubic with the table's values at both
//! ends and its integral and first moment over the step), so that the
//! step's error estimate measures the dynamics and not the kink. `"exact"`
//! has the stages read the table as it is: a step across a kink is then
//! rejected until it is short enough for the kink not to matter.
//!
//! A table with `stop_at_kinks = true` has no kink inside a step (every step
//! ends at its kinks), and the monotone cubic has none but where its rows
//! end; the output samples read every input as it is.

use crate::components::{BoundInputs, Port, Smoothness, StandIn};
use lagrangian_runtime::{InputFunctions, LagrangianSystem};

/// An input of time with kinks.
#[derive(Clone, Debug, PartialEq)]
struct Kinked {
    input: usize,
    /// Its kinks, in increasing order.
    kinks: Vec<f64>,
    /// Whether it is linear between them ([`Smoothness::Linear`]).
    linear: bool,
}

/// The inputs of time with kinks.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct KinkedInputs {
    inputs: Vec<Kinked>,
}

impl KinkedInputs {
    /// The inputs of `system` that every call site passes the time alone,
    /// bound to the value of a component with kinks ([`Smoothness::kinks`]).
    /// `time_sites`: [`super::stops::time_sites`] of `system`.
    pub(crate) fn of<const N: usize, S: LagrangianSystem<N>>(
        system: &S,
        inputs: &BoundInputs,
        time_sites: &[bool],
    ) -> KinkedInputs {
        let sites: Vec<(usize, bool)> = (system.input_sites().iter().map(|s| s.0))
            .zip(time_sites.iter().copied())
            .collect();
        let mut kinked = Vec::new();
        for (input, binding) in inputs.bindings.iter().enumerate() {
            let calls: Vec<bool> = (sites.iter().filter(|s| s.0 == input))
                .map(|s| s.1)
                .collect();
            let Some(binding) = binding else { continue };
            if binding.port != Port::Value || calls.is_empty() || calls.contains(&false) {
                continue;
            }
            let smoothness = inputs.components[binding.component].component.smoothness();
            if let Some(kinks) = smoothness.kinks()
                && !kinks.is_empty()
            {
                let linear = matches!(smoothness, Smoothness::Linear { .. });
                let kinks = kinks.to_vec();
                kinked.push(Kinked {
                    input,
                    kinks,
                    linear,
                });
            }
        }
        KinkedInputs { inputs: kinked }
    }

    /// The kinks of all the inputs, in increasing order.
    pub(crate) fn kinks(&self) -> Vec<f64> {
        let mut kinks: Vec<f64> = (self.inputs.iter())
            .flat_map(|kinked| kinked.kinks.iter().copied())
            .collect();
        kinks.sort_by(f64::total_cmp);
        kinks.dedup();
        kinks
    }

    /// Gives each input with a kink strictly inside `[t0, t0 + h]` its
    /// stand-in over that step.
    pub(crate) fn stand_in(&self, inputs: &mut BoundInputs, t0: f64, h: f64) {
        let t1 = t0 + h;
        // A step ended at a kink (`stop_at_kinks`) ends there to rounding.
        let slack = 64.0 * f64::EPSILON * t0.abs().max(t1.abs());
        for Kinked {
            input,
            kinks,
            linear,
        } in &self.inputs
        {
            let first = kinks.partition_point(|&k| k <= t0 + slack);
            let end = first + kinks[first..].partition_point(|&k| k < t1 - slack);
            if first < end {
                let (inside, u) = (&kinks[first..end], |t: f64| inputs.value(*input, &[t]));
                let cubic = match linear {
                    true => StandIn::of_linear(t0, h, inside, u),
                    false => StandIn::of(t0, h, inside, u),
                };
                inputs.stand_in(*input, cubic);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::scenario::Choice;
    use crate::scenario::options::TimeKinks;
    use crate::scenario::{ModelNames, Scenario};
    use crate::simulate::{SimulationResult, simulate};
    use lagrangian_runtime::Interpreted;

    /// `ẍ + c ẋ + k x = F(t)` (the spring spec: m = 1 kg, k = 100 N/m, c =
    /// 0.5 N·s/m) from rest, with `F` through the rows of `PUSH`, linear
    /// between them, 0 after: the closed form piece by piece. On a piece
    /// from `ti` with `F = α + β τ` (`τ = t − ti`) the solution is the
    /// particular `A + B τ` (`B = β/k`, `A = (α − c B)/k`) plus
    /// `e^(−στ)(C cos ωτ + D sin ωτ)` matching `x` and `ẋ` at `ti`.
    fn closed_form(t: f64) -> f64 {
        closed_form_state(t).0
    }

    /// `(x, ẋ)` of [`closed_form`].
    fn closed_form_state(t: f64) -> (f64, f64) {
        let (k, c) = (100.0f64, 0.5f64);
        let (sigma, omega) = (c / 2.0, (k - c * c / 4.0).sqrt());
        let (mut x, mut v) = (0.0, 0.0);
        for w in PUSH.windows(2) {
            let ((ti, fi), (tj, fj)) = (w[0], w[1]);
            let beta = (fj - fi) / (tj - ti);
            let (b, a) = (beta / k, (fi - c * beta / k) / k);
            let (cc, dd) = (x - a, (v - b + sigma * (x - a)) / omega);
            let at = |tau: f64| {
                let (decay, (sin, cos)) = ((-sigma * tau).exp(), (omega * tau).sin_cos());
                let x = a + b * tau + decay * (cc * cos + dd * sin);
                let v =
                    b + decay * ((omega * dd - sigma * cc) * cos - (sigma * dd + omega * cc) * sin);
                (x, v)
            };
            if t <= tj {
                return at(t - ti);
            }
            (x, v) = at(tj - ti);
        }
        unreachable!("t = {t} beyond the table")
    }

    /// The push: kinks at 10, 20 and 30 ms, of 5000 N/s and more.
    const PUSH: [(f64, f64); 5] = [
        (0.0, 0.0),
        (0.01, 50.0),
        (0.02, -20.0),
        (0.03, 0.0),
        (0.05, 0.0),
    ];

    /// The spring's run pushed by [`PUSH`], its stages seeing the kinks
    /// `choice`, at rtol `rtol`.
    fn pushed(choice: TimeKinks, rtol: f64) -> SimulationResult {
        pushed_with(choice, rtol, "interpolated")
    }

    /// [`pushed`], its samples' accelerations taken as `accelerations`
    /// says.
    fn pushed_with(choice: TimeKinks, rtol: f64, accelerations: &str) -> SimulationResult {
        let model =
            lagrangian_core::interpret(include_str!("../../../specs/spring_mass_damper.lpm"))
                .unwrap();
        let names = ModelNames::of_interpreted(&model);
        let system = Interpreted::<1>::new(model).unwrap();
        static RUNS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
        let run = RUNS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let dir =
            std::env::temp_dir().join(format!("lagrangian-kinks-{}-{run}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let rows: String = PUSH.iter().map(|(t, f)| format!("{t},{f}\n")).collect();
        std::fs::write(dir.join("push.csv"), format!("t,F\n{rows}")).unwrap();
        let text = format!(
            "[simulation]\nt_end = 0.05\nrtol = {rtol}\natol = {}\noutput_interval = 1e-4\n\
             time_kinks = \"{}\"\naccelerations = \"{accelerations}\"\n[components.table]\ntype = \"table\"\nfile = \"push.csv\"\n\
             columns = {{ push = \"F\" }}\n",
            rtol * 1e-2,
            choice.name()
        );
        let scenario = Scenario::parse(&text, Some(&dir.join("s.toml")), &names, &[]).unwrap();
        let result = simulate(&system, &scenario).unwrap();
        std::fs::remove_dir_all(&dir).ok();
        result
    }

    /// The largest difference of the run's `x` from the closed form.
    fn error(run: &SimulationResult) -> f64 {
        (run.samples.iter())
            .map(|s| (s.q[0] - closed_form(s.t)).abs())
            .fold(0.0, f64::max)
    }

    #[test]
    fn smoothed_kinks_are_as_accurate_as_exact_ones_in_fewer_steps() {
        for rtol in [1e-6, 1e-8, 1e-10] {
            let [smoothed, exact] =
                [TimeKinks::Smoothed, TimeKinks::Exact].map(|c| pushed(c, rtol));
            let (s, e) = (&smoothed.stats, &exact.stats);
            // |x| ≤ 0.5 m: both within a few tolerances of the closed form
            // (at 1e-6, 1e-8, 1e-10: smoothed 1.6e-7, 7.9e-10, 1.3e-11;
            // exact 1.5e-6, 2.2e-10, 1.8e-11).
            let (es, ee) = (error(&smoothed), error(&exact));
            assert!(
                es < 20.0 * rtol && ee < 20.0 * rtol,
                "rtol {rtol}: {es:e}, {ee:e}"
            );
            // Kinks this sharp (the jerk jumps by up to 12 000 m/s³) still
            // shorten the steps around them, with fewer rejections.
            assert!(
                s.rhs_evaluations < e.rhs_evaluations && s.rejected_steps < e.rejected_steps,
                "rtol {rtol}: smoothed {s:?}, exact {e:?}"
            );
        }
    }

    /// The push at `t`: [`PUSH`] interpolated linearly.
    fn push(t: f64) -> f64 {
        let k = PUSH.partition_point(|p| p.0 <= t).clamp(1, PUSH.len() - 1);
        let ((t0, f0), (t1, f1)) = (PUSH[k - 1], PUSH[k]);
        f0 + (f1 - f0) * (t - t0) / (t1 - t0)
    }

    /// The largest difference of the run's `ẍ` from the closed form's
    /// `F − c ẋ − k x` (m = 1 kg).
    fn acceleration_error(run: &SimulationResult) -> f64 {
        let closed = |t: f64| {
            let (x, v) = closed_form_state(t);
            push(t) - 0.5 * v - 100.0 * x
        };
        (run.samples.iter())
            .map(|s| (s.a[0] - closed(s.t)).abs())
            .fold(0.0, f64::max)
    }

    #[test]
    fn the_samples_of_smoothed_steps_keep_the_kinks_of_the_push() {
        // The stages of a step across a kink see the push's smooth
        // stand-in, and so does the dense output; the samples add back
        // what the push's kinks change (`kink_rates`). |ẍ| ≤ 50 m/s².
        let smoothed = pushed(TimeKinks::Smoothed, 1e-8);
        let solved = pushed_with(TimeKinks::Smoothed, 1e-8, "exact");
        let (corrected, exact) = (acceleration_error(&smoothed), acceleration_error(&solved));
        // Measured: corrected 1.7e-6, solved at every sample 1.9e-6, the
        // interpolated stand-in's alone 0.16.
        assert!(corrected < 4e-6 && exact < 4e-6, "{corrected:e}, {exact:e}");
    }

    /// The paper's scenario with its barrier table as given, at rtol 1e-8.
    fn paper(settings: &[&str]) -> SimulationResult {
        let model =
            lagrangian_core::interpret(include_str!("../../../specs/yaris_double_pendulum.lpm"))
                .unwrap();
        let names = ModelNames::of_interpreted(&model);
        let system = Interpreted::<3>::new(model).unwrap();
        let file = std::path::Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../specs/scenarios/yaris_full_frontal.toml"
        ));
        let settings: Vec<String> = settings.iter().map(|s| s.to_string()).collect();
        let scenario = Scenario::load(
            file,
            &names,
            &crate::scenario::Override::parse_all(&settings).unwrap(),
        )
        .unwrap();
        simulate(&system, &scenario).unwrap()
    }

    #[test]
    fn the_paper_scenario_steps_across_its_barrier_table_like_across_a_smooth_one() {
        // The barrier table is a half sine with a point every millisecond.
        let smoothed = paper(&[]);
        let exact = paper(&["simulation.time_kinks=exact"]);
        let pchip = paper(&["components.barrier.interpolation=pchip"]);
        let (s, p) = (&smoothed.stats, &pchip.stats);
        let steps = |s: &crate::ode::Stats| (s.accepted_steps + s.rejected_steps) as f64;
        assert!(
            steps(s) <= 1.3 * steps(p),
            "smoothed {s:?}, smooth barrier {p:?}"
        );
        assert!(s.rejected_steps as f64 <= 0.1 * steps(s), "{s:?}");
        // The same trajectory: every coordinate within 1e-6 of its range.
        for i in 0..3 {
            let range = (exact.samples.iter()).fold(0.0f64, |m, x| m.max(x.q[i].abs()));
            for (a, b) in smoothed.samples.iter().zip(&exact.samples) {
                assert!((a.q[i] - b.q[i]).abs() < 1e-6 * range, "q{i} at {}", a.t);
            }
        }
    }

    #[test]
    fn the_choice_is_read_by_name() {
        for &choice in TimeKinks::ALL {
            assert_eq!(TimeKinks::parse(choice.name()), Some(choice));
        }
        assert_eq!(TimeKinks::parse("stop"), None);
    }
}
