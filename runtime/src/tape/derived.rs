//! Routines a tape derives from the compiler's when it is made: some of a
//! routine's outputs, computed by only the instructions they depend on.
//!
//! The compiler builds each routine for all of its outputs; a caller that
//! reads a few of them (the samples of a simulation read `T` and `V` of the
//! energies, not the power of the forces, whose input calls cost most) runs
//! the derived routine instead. Its instructions are the source routine's,
//! in the same order, less those no kept output depends on, so it computes
//! the kept outputs bit for bit as the source routine does. The compiler
//! need not know them: a derived routine is a fact of the tape alone.

use super::{Instruction, RegisterLayout, StateReads, TapeRoutine, code};
use crate::layout::{Energy, RoutineKind};

/// A routine derived from one of the compiler's (see the module
/// documentation).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DerivedRoutine {
    /// `T` and `V`, in that order: the mechanical energy, from
    /// [`RoutineKind::Energies`] without the dissipation and the powers
    /// (the fields of [`MechanicalEnergy`](crate::layout::MechanicalEnergy)).
    MechanicalEnergy,
}

impl DerivedRoutine {
    /// Every derived routine.
    pub const ALL: [DerivedRoutine; 1] = [DerivedRoutine::MechanicalEnergy];

    /// The routine it is derived from, and the positions among that
    /// routine's outputs of its own outputs, in order.
    pub fn definition(self) -> (RoutineKind, &'static [usize]) {
        match self {
            DerivedRoutine::MechanicalEnergy => (
                RoutineKind::Energies,
                &[Energy::Kinetic as usize, Energy::Potential as usize],
            ),
        }
    }
}

/// The routine computing outputs `keep` (positions among its outputs) of
/// `routine`: the instructions they depend on, in order, found by a
/// backward liveness pass over the registers (an instruction is kept when a
/// later kept instruction or a kept output reads the value it writes, so a
/// register written more than once is followed write by write). `None` when
/// a position is beyond the routine's outputs. `arguments` are the tape's
/// input-argument registers; every register must be below `registers`.
pub(super) fn pruned(
    routine: &TapeRoutine,
    keep: &[usize],
    arguments: &[u32],
    registers: usize,
) -> Option<TapeRoutine> {
    let outputs = (keep.iter())
        .map(|&k| routine.outputs.get(k).copied())
        .collect::<Option<Vec<u32>>>()?;
    let mut live = vec![false; registers];
    for &o in &outputs {
        live[o as usize] = true;
    }
    let mut kept = vec![false; routine.instructions.len()];
    for (k, instruction) in routine.instructions.iter().enumerate().rev() {
        let (dst, _) = instruction.registers();
        if !live[dst as usize] {
            continue;
        }
        kept[k] = true;
        // The value read before this instruction is another one.
        live[dst as usize] = false;
        for r in code::reads(instruction, arguments) {
            live[r as usize] = true;
        }
    }
    let instructions: Vec<Instruction> = (routine.instructions.iter())
        .zip(kept)
        .filter_map(|(&instruction, kept)| kept.then_some(instruction))
        .collect();
    Some(TapeRoutine {
        kind: routine.kind,
        instructions,
        outputs,
    })
}

/// What one output of a routine reads of the state and the inputs: the
/// registers and input calls the instructions it depends on read (those of
/// [`pruned`]).
pub(super) fn reads(
    routine: &TapeRoutine,
    k: usize,
    arguments: &[u32],
    layout: &RegisterLayout,
) -> Option<StateReads> {
    let slice = pruned(routine, &[k], arguments, layout.registers())?;
    let mut registers: Vec<u32> = slice.outputs.clone();
    let mut inputs = false;
    for instruction in &slice.instructions {
        inputs |= matches!(instruction, Instruction::Input { .. });
        registers.extend(code::reads(instruction, arguments));
    }
    let n = layout.dimension;
    let within = |first: u32| {
        let range = first..first + n as u32;
        registers.iter().any(|r| range.contains(r))
    };
    Some(StateReads {
        velocities: n > 0 && within(layout.velocity(0)),
        accelerations: n > 0 && within(layout.acceleration(0)),
        time: registers.contains(&layout.time()),
        inputs,
    })
}

#[cfg(test)]
mod tests {
    use super::super::{RegisterLayout, Tape};
    use super::*;
    use crate::NoInputs;
    use std::cell::Cell;

    fn layout(temporaries: usize) -> RegisterLayout {
        RegisterLayout {
            constants: vec![2.0],
            parameters: 0,
            dimension: 1,
            temporaries,
        }
    }

    /// An energies routine whose `T` and `V` are arithmetic on `q` and `q̇`
    /// and whose power calls input 0 at `q`.
    fn energies_with_an_input_call() -> (RegisterLayout, TapeRoutine, Vec<u32>) {
        let layout = layout(5);
        let (x, v) = (layout.coordinate(0), layout.velocity(0));
        let t = |k| layout.temporary(k);
        let instructions = vec![
            Instruction::Mul(t(0), v, v),
            Instruction::Input {
                dst: t(1),
                index: 0,
                start: 0,
                count: 1,
            },
            Instruction::Div(t(2), t(0), 0),
            Instruction::Mul(t(3), t(1), v),
            Instruction::Mul(t(4), x, x),
        ];
        let routine = TapeRoutine {
            kind: RoutineKind::Energies,
            instructions,
            // T, V, D, damping power, external power.
            outputs: vec![t(2), t(4), 0, 0, t(3)],
        };
        (layout, routine, vec![x])
    }

    /// `T = q̇²/2` reads a velocity, `V = q²` the coordinate alone, the
    /// external power `wall(q)·q̇` an input and a velocity, a constant
    /// output nothing; the time register read directly is the time.
    #[test]
    fn an_output_reads_what_the_instructions_it_depends_on_read() {
        let (layout, mut routine, arguments) = energies_with_an_input_call();
        routine.outputs[3] = layout.time();
        let reads = |k| reads(&routine, k, &arguments, &layout).unwrap();
        let velocity = StateReads {
            velocities: true,
            ..StateReads::default()
        };
        assert_eq!(reads(0), velocity);
        assert_eq!(reads(1), StateReads::default());
        assert!(reads(1).of_position() && reads(2).of_position());
        let power = reads(4);
        assert!(power.inputs && power.velocities && !power.of_position());
        assert!(reads(3).time && reads(3).of_position());
        assert!(super::reads(&routine, 5, &arguments, &layout).is_none());
    }

    #[test]
    fn a_dead_input_call_is_dropped_and_the_kept_outputs_are_unchanged() {
        let (layout, routine, arguments) = energies_with_an_input_call();
        let (source, keep) = DerivedRoutine::MechanicalEnergy.definition();
        assert_eq!(source, RoutineKind::Energies);
        let derived = pruned(&routine, keep, &arguments, layout.registers()).unwrap();
        let i = &routine.instructions;
        assert_eq!(derived.instructions, [i[0], i[2], i[4]]);
        assert_eq!(derived.outputs, routine.outputs[..2]);
        let tape = Tape::new(layout, vec![routine], arguments).unwrap();
        let calls = Cell::new(0);
        let counting = |_: usize, args: &[f64]| {
            calls.set(calls.get() + 1);
            args[0] * 10.0
        };
        let state = (0.0, &[3.0][..], &[0.5][..], &[][..]);
        let mut registers = tape.registers(&[]);
        let mut all = [0.0; 5];
        assert!(tape.run(
            RoutineKind::Energies,
            state,
            &counting,
            &mut registers,
            &mut all
        ));
        assert_eq!((all, calls.get()), ([0.125, 9.0, 2.0, 2.0, 15.0], 1));
        let mut two = [0.0; 2];
        let which = DerivedRoutine::MechanicalEnergy;
        assert!(tape.run_derived(which, state, &counting, &mut registers, &mut two));
        assert_eq!((two, calls.get()), ([0.125, 9.0], 1));
    }

    /// Registers written twice: each read sees the write before it, so a
    /// write no later instruction or output reads is dropped even where
    /// another write of its register is kept.
    #[test]
    fn a_reused_register_is_followed_write_by_write() {
        let layout = layout(2);
        let x = layout.coordinate(0);
        let (a, b) = (layout.temporary(0), layout.temporary(1));
        let instructions = vec![
            Instruction::Mul(a, x, x), // a = x² (live: read by 2)
            Instruction::Neg(b, x),    // dead: b is rewritten by 2 before any read
            Instruction::Add(b, a, 0), // b = x² + 2 (kept output 0)
            Instruction::Sin(a, x),    // a = sin x (read by 4 only)
            Instruction::Mul(a, a, a), // a = sin² x (output 1)
        ];
        let routine = TapeRoutine {
            kind: RoutineKind::Energies,
            instructions: instructions.clone(),
            outputs: vec![b, a],
        };
        let registers = layout.registers();
        let first = pruned(&routine, &[0], &[], registers).unwrap();
        assert_eq!(first.instructions, [instructions[0], instructions[2]]);
        assert_eq!(first.outputs, [b]);
        let second = pruned(&routine, &[1], &[], registers).unwrap();
        assert_eq!(second.instructions, [instructions[3], instructions[4]]);
        let both = pruned(&routine, &[1, 0], &[], registers).unwrap();
        let expected = [0, 2, 3, 4].map(|k| instructions[k]);
        assert_eq!(both.instructions, expected);
        assert_eq!(both.outputs, [a, b]);
        assert_eq!(pruned(&routine, &[2], &[], registers), None);
        // Run: the derived routine (outputs 0 and 1) computes the routine's.
        let tape = Tape::new(layout, vec![routine], vec![]).unwrap();
        let state = (0.0, &[0.5][..], &[0.0][..], &[][..]);
        let mut registers = tape.registers(&[]);
        let (mut all, mut derived) = ([0.0; 2], [0.0; 2]);
        let which = DerivedRoutine::MechanicalEnergy;
        assert!(tape.run(
            RoutineKind::Energies,
            state,
            &NoInputs,
            &mut registers,
            &mut all
        ));
        assert!(tape.run_derived(which, state, &NoInputs, &mut registers, &mut derived));
        assert_eq!(all, [2.25, 0.5f64.sin() * 0.5f64.sin()]);
        assert_eq!(derived, all);
    }
}
