//! The components' tests that run the simulator: each file takes one
//! component (or family) through a scenario and a run. They live above both
//! the components and the run engine, so that `components` never reaches up.

mod bouc_wen;
mod contact;
mod crush_energy;
mod dahl;
mod friction;
mod kelvin_voigt;
mod lugre;
mod maxwell;
mod stick_slip;
mod test_spring;
mod weld;
