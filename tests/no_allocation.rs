//! Integrating a compiled model with a fixed-size state does not allocate
//! per step: the allocation count of a run does not grow with its length.

use lagrangian::LagrangianSystem;
use lagrangian::ModelError;
use lagrangian::nalgebra::Vector3;
use lagrangian::ode::explicit;
use lagrangian::ode::tableau::DOPRI5;
use lagrangian::ode::{OdeProblem, Options, PhaseState};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;
static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

mod models {
    lagrangian::lagrangian!(file = "specs/yaris_double_pendulum.lpm");
}

/// The paper's model with a linear crush spring and no other inputs.
struct Problem(models::YarisDoublePendulum);

fn inputs(index: usize, args: &[f64]) -> f64 {
    match index {
        models::YarisDoublePendulum::INPUT_CRUSH => 8.0e5 * args[0] + 3.0e3 * args[1],
        _ => 0.0,
    }
}

impl OdeProblem<PhaseState<3>> for Problem {
    type Error = ModelError;

    fn rhs(&mut self, t: f64, y: &PhaseState<3>, dy: &mut PhaseState<3>) -> Result<(), ModelError> {
        let a = self.0.accelerations(t, &y.q, &y.v, &inputs)?;
        let e = self.0.energies(t, &y.q, &y.v, &inputs);
        *dy = PhaseState {
            q: y.v,
            v: a,
            work: [e.damping_power, e.external_power],
            z: Default::default(),
        };
        Ok(())
    }
}

fn allocations_for(t_end: f64) -> (usize, usize) {
    let mut problem = Problem(models::YarisDoublePendulum::default());
    let y0 = PhaseState::new(Vector3::new(0.0, -0.1, 0.0), Vector3::new(-15.0, 0.0, 0.0));
    let options = Options {
        rtol: 1e-8,
        atol: 1e-10,
        ..Options::default()
    };
    let before = ALLOCATIONS.load(Ordering::Relaxed);
    let out = explicit::integrate(
        &DOPRI5,
        &mut problem,
        0.0,
        y0,
        t_end,
        &options,
        &mut |_, _| {},
    )
    .unwrap();
    (
        ALLOCATIONS.load(Ordering::Relaxed) - before,
        out.stats.accepted_steps,
    )
}

#[test]
fn allocations_do_not_grow_with_the_number_of_steps() {
    let (short, short_steps) = allocations_for(0.02);
    let (long, long_steps) = allocations_for(0.2);
    println!("{short} allocations for {short_steps} steps, {long} for {long_steps} steps");
    assert!(long_steps > 5 * short_steps);
    assert_eq!(short, long);
}
