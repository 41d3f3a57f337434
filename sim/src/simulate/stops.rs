//! The kinks of the inputs that are functions of time: the points of a
//! time table interpolated linearly where the force's slope jumps, for the
//! tables that ask for steps to end there (`stop_at_kinks`). The
//! integrator ends a step at each of them instead of stepping across (the
//! other tables' kinks are stepped across: see [`super::kinks`]).
//!
//! Which inputs are functions of time is found once per run: an input whose
//! argument equals the time at two probe times (at the zero state) is one —
//! what a spec's `barrier(t)` compiles to.

use crate::components::BoundInputs;
use lagrangian_runtime::{LagrangianSystem, NoInputs};
use nalgebra::SVector;

/// Two probe times, far from any breakpoint a table is likely to have.
const PROBES: [f64; 2] = [std::f64::consts::FRAC_1_PI, std::f64::consts::E];

/// The breakpoints of the time tables of a run, in increasing order, with
/// the position of the next one after the last time asked about.
#[derive(Clone, Debug, Default)]
pub(crate) struct TimeStops {
    points: Vec<f64>,
    next: usize,
}

impl TimeStops {
    /// The breakpoints of the components bound to inputs whose argument is
    /// the time.
    /// `time_sites`: [`time_sites`] of `system`.
    pub(crate) fn of<const N: usize, S: LagrangianSystem<N>>(
        system: &S,
        inputs: &BoundInputs,
        time_sites: &[bool],
    ) -> TimeStops {
        let mut points = Vec::new();
        for component in time_components(system, inputs, time_sites) {
            points.extend_from_slice(inputs.components[component].component.smoothness().stops());
        }
        points.sort_by(f64::total_cmp);
        points.dedup();
        TimeStops { points, next: 0 }
    }

    /// The first breakpoint after `t`, if any. Times asked about usually
    /// increase, so the search starts where the last one ended.
    pub(crate) fn after(&mut self, t: f64) -> Option<f64> {
        let behind = self.next > 0 && self.points[self.next - 1] > t;
        if behind || self.points.get(self.next + 8).is_some_and(|&p| p <= t) {
            self.next = self.points.partition_point(|&p| p <= t);
        }
        while self.points.get(self.next).is_some_and(|&p| p <= t) {
            self.next += 1;
        }
        self.points.get(self.next).copied()
    }
}

/// The components bound to an input of one argument that is the time.
fn time_components<const N: usize, S: LagrangianSystem<N>>(
    system: &S,
    inputs: &BoundInputs,
    time_sites: &[bool],
) -> Vec<usize> {
    let mut components = Vec::new();
    for (&(input, _), &is_time) in system.input_sites().iter().zip(time_sites) {
        if let (true, Some(Some(binding))) = (is_time, inputs.bindings.get(input)) {
            components.push(binding.component);
        }
    }
    components
}

/// For each input site of the dynamics, in order: whether its input takes
/// one argument, the time.
pub(super) fn time_sites<const N: usize, S: LagrangianSystem<N>>(system: &S) -> Vec<bool> {
    let count = system.input_sites().iter().map(|s| s.1).sum();
    let zero = SVector::<f64, N>::zeros();
    let arguments = PROBES.map(|t| {
        let mut out = vec![0.0; count];
        system.input_arguments(t, &zero, &zero, &NoInputs, &mut out);
        out
    });
    let mut offset = 0;
    let mut sites = Vec::with_capacity(system.input_sites().len());
    for &(_, arity) in system.input_sites() {
        sites.push(arity == 1 && (0..2).all(|k| arguments[k][offset] == PROBES[k]));
        offset += arity;
    }
    sites
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_next_breakpoint_after_any_time_in_any_order() {
        let points: Vec<f64> = (0..40).map(|k| 0.5 * k as f64).collect();
        let mut stops = TimeStops {
            points: points.clone(),
            next: 0,
        };
        let reference = |t: f64| points.iter().copied().find(|&p| p > t);
        let mut probes: Vec<f64> = (0..300).map(|k| -1.0 + 0.07 * k as f64).collect();
        probes.extend([3.0, 0.0, 19.5, 25.0, 1.0, 1.0, 7.25, -3.0]);
        for t in probes {
            assert_eq!(stops.after(t), reference(t), "t = {t}");
        }
        assert_eq!(TimeStops::default().after(1.0), None);
    }

    /// A spring–mass–damper pushed by a force table with kinks at 10, 20
    /// and 30 ms (and its ends at 0 and 50 ms), integrated at rtol 1e-8.
    fn pushed(options: &str) -> (Vec<f64>, crate::ode::Stats) {
        use crate::ode::{self, PhaseState};
        use crate::scenario::{ModelNames, Scenario};
        use crate::simulate::CrashProblem;
        let model = lagrangian_core::interpret(include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../specs/spring_mass_damper.lpm"
        )))
        .unwrap();
        let names = ModelNames::of_interpreted(&model);
        let system = lagrangian_runtime::Interpreted::<1>::new(model).unwrap();
        let dir = std::env::temp_dir().join(format!("lagrangian-stops-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let table = "t,F\n0,0\n0.01,50\n0.02,-20\n0.03,0\n0.05,0\n";
        std::fs::write(dir.join("push.csv"), table).unwrap();
        let text = format!(
            "[simulation]\nt_end = 0.05\nrtol = 1e-8\natol = 1e-10\n[components.table]\ntype = \"table\"\nfile = \"push.csv\"\ncolumns = {{ push = \"F\" }}\n{options}\n"
        );
        let scenario = Scenario::parse(&text, Some(&dir.join("s.toml")), &names, &[]).unwrap();
        let mut problem = CrashProblem::new(&system, scenario.inputs.clone());
        let y0 = PhaseState::zeros();
        problem.start(0.0, &y0).unwrap();
        let mut ends = Vec::new();
        let options = &scenario.options;
        let outcome = ode::integrate(
            scenario.method,
            &mut problem,
            (0.0, y0),
            0.05,
            options,
            &mut |_, step| ends.push(step.t1()),
        )
        .unwrap();
        std::fs::remove_dir_all(&dir).ok();
        (ends, outcome.stats)
    }

    #[test]
    fn steps_end_at_the_kinks_of_a_time_table_that_asks_for_it() {
        let (ends, stats) = pushed("stop_at_kinks = true");
        for kink in [0.01, 0.02, 0.03] {
            assert!(
                ends.iter().any(|t| (t - kink).abs() < 1e-15),
                "no step ends at {kink}: {ends:?}"
            );
        }
        assert!(stats.rejected_steps <= 1, "{stats:?}");
        // By default the steps cross them (reading the table's smooth
        // stand-in); corners this sharp still cost rejections.
        let (ends, across) = pushed("");
        assert!(!ends.iter().any(|t| (t - 0.02).abs() < 1e-15), "{ends:?}");
        assert!(across.rejected_steps > 3, "{across:?}");
        // The monotone cubic has no kinks to stop at.
        let (ends, _) = pushed("stop_at_kinks = true\ninterpolation = \"pchip\"");
        assert!(!ends.iter().any(|t| (t - 0.02).abs() < 1e-15), "{ends:?}");
    }
}
