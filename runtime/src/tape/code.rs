//! A routine's instructions as the interpreter runs them: [`Step`]s, where
//! an arithmetic instruction whose result only one later instruction reads
//! is fused into that reader (a superinstruction: one dispatch doing two or
//! three operations).
//!
//! A fused step performs the same IEEE operations on the same operands in
//! the same order as the instructions it replaces, each rounded on its own
//! (`a * b + c` is a multiplication then an addition, never a fused
//! multiply-add), so a routine computes its outputs bit for bit as its
//! instruction list does.
//!
//! Fusing moves an instruction's operation to its reader's place, and drops
//! the write of its register. That is sound when the routine is in
//! single-assignment form — every instruction writes a temporary no other
//! instruction of the routine writes, and every temporary the routine reads
//! it has written before — so the fused operation's operands still hold
//! their values, and nothing but the reader sees the dropped register
//! ([`fusable`]). A routine not in that form (no lowered tape makes one) runs
//! unfused.

use super::{Instruction, RegisterLayout, TapeRoutine};

/// One step of a routine: a common instruction, a superinstruction, or any
/// other instruction. Registers: the destination first, then the
/// operands in the order the formula reads them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Step {
    /// `a + b`.
    Add(u32, u32, u32),
    /// `a − b`.
    Sub(u32, u32, u32),
    /// `a · b`.
    Mul(u32, u32, u32),
    /// `a / b`.
    Div(u32, u32, u32),
    /// `−a`.
    Neg(u32, u32),
    /// `a · b + c`.
    ProductPlus(u32, u32, u32, u32),
    /// `a + b · c`.
    PlusProduct(u32, u32, u32, u32),
    /// `a · b − c`.
    ProductMinus(u32, u32, u32, u32),
    /// `a − b · c`.
    MinusProduct(u32, u32, u32, u32),
    /// `(a · b) · c`.
    ProductTimes(u32, u32, u32, u32),
    /// `a · (b · c)`.
    TimesProduct(u32, u32, u32, u32),
    /// `(a + b) · c`.
    SumTimes(u32, u32, u32, u32),
    /// `a · (b + c)`.
    TimesSum(u32, u32, u32, u32),
    /// `(a − b) · c`.
    DifferenceTimes(u32, u32, u32, u32),
    /// `a · (b − c)`.
    TimesDifference(u32, u32, u32, u32),
    /// `(a + b) + c`.
    SumPlus(u32, u32, u32, u32),
    /// `a + (b + c)`.
    PlusSum(u32, u32, u32, u32),
    /// `(a − b) − c`.
    DifferenceMinus(u32, u32, u32, u32),
    /// `a − (b − c)`.
    MinusDifference(u32, u32, u32, u32),
    /// `a · b + c · d`.
    ProductsPlus(u32, [u32; 4]),
    /// `a · b − c · d`.
    ProductsMinus(u32, [u32; 4]),
    /// Any other instruction, run as the tape runs it.
    Other(Instruction),
}

/// The binary operations that fuse.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Binary {
    Add,
    Sub,
    Mul,
}

/// An operand of a reader: a register, or the fused operation `a ∘ b`.
#[derive(Clone, Copy)]
enum Operand {
    Register(u32),
    Fused(Binary, u32, u32),
}

impl Step {
    /// The superinstruction computing `left ∘ right`, or `None` when no
    /// step has that shape (a plain operation is made by the caller).
    fn fused(op: Binary, left: Operand, right: Operand, d: u32) -> Option<Step> {
        use Binary::{Add, Mul, Sub};
        use Operand::{Fused, Register};
        Some(match (op, left, right) {
            (Add, Fused(Mul, a, b), Fused(Mul, c, e)) => Step::ProductsPlus(d, [a, b, c, e]),
            (Sub, Fused(Mul, a, b), Fused(Mul, c, e)) => Step::ProductsMinus(d, [a, b, c, e]),
            (Add, Fused(Mul, a, b), Register(c)) => Step::ProductPlus(d, a, b, c),
            (Add, Register(a), Fused(Mul, b, c)) => Step::PlusProduct(d, a, b, c),
            (Sub, Fused(Mul, a, b), Register(c)) => Step::ProductMinus(d, a, b, c),
            (Sub, Register(a), Fused(Mul, b, c)) => Step::MinusProduct(d, a, b, c),
            (Mul, Fused(Mul, a, b), Register(c)) => Step::ProductTimes(d, a, b, c),
            (Mul, Register(a), Fused(Mul, b, c)) => Step::TimesProduct(d, a, b, c),
            (Mul, Fused(Add, a, b), Register(c)) => Step::SumTimes(d, a, b, c),
            (Mul, Register(a), Fused(Add, b, c)) => Step::TimesSum(d, a, b, c),
            (Mul, Fused(Sub, a, b), Register(c)) => Step::DifferenceTimes(d, a, b, c),
            (Mul, Register(a), Fused(Sub, b, c)) => Step::TimesDifference(d, a, b, c),
            (Add, Fused(Add, a, b), Register(c)) => Step::SumPlus(d, a, b, c),
            (Add, Register(a), Fused(Add, b, c)) => Step::PlusSum(d, a, b, c),
            (Sub, Fused(Sub, a, b), Register(c)) => Step::DifferenceMinus(d, a, b, c),
            (Sub, Register(a), Fused(Sub, b, c)) => Step::MinusDifference(d, a, b, c),
            // The other shapes are rare in derived equations: no step for them.
            _ => return None,
        })
    }

    /// Runs the step on the register file at `r`; `other` runs
    /// [`Step::Other`].
    ///
    /// # Safety
    ///
    /// Every register the step names must be inside the file at `r`.
    #[inline(always)]
    pub(super) unsafe fn run(self, r: *mut f64, other: impl FnOnce(Instruction)) {
        // SAFETY: the caller guarantees every register is in the file.
        let v = |k: u32| unsafe { *r.add(k as usize) };
        let (d, value) = match self {
            Step::Add(d, a, b) => (d, v(a) + v(b)),
            Step::Sub(d, a, b) => (d, v(a) - v(b)),
            Step::Mul(d, a, b) => (d, v(a) * v(b)),
            Step::Div(d, a, b) => (d, v(a) / v(b)),
            Step::Neg(d, a) => (d, -v(a)),
            Step::ProductPlus(d, a, b, c) => (d, v(a) * v(b) + v(c)),
            Step::PlusProduct(d, a, b, c) => (d, v(a) + v(b) * v(c)),
            Step::ProductMinus(d, a, b, c) => (d, v(a) * v(b) - v(c)),
            Step::MinusProduct(d, a, b, c) => (d, v(a) - v(b) * v(c)),
            Step::ProductTimes(d, a, b, c) => (d, (v(a) * v(b)) * v(c)),
            Step::TimesProduct(d, a, b, c) => (d, v(a) * (v(b) * v(c))),
            Step::SumTimes(d, a, b, c) => (d, (v(a) + v(b)) * v(c)),
            Step::TimesSum(d, a, b, c) => (d, v(a) * (v(b) + v(c))),
            Step::DifferenceTimes(d, a, b, c) => (d, (v(a) - v(b)) * v(c)),
            Step::TimesDifference(d, a, b, c) => (d, v(a) * (v(b) - v(c))),
            Step::SumPlus(d, a, b, c) => (d, (v(a) + v(b)) + v(c)),
            Step::PlusSum(d, a, b, c) => (d, v(a) + (v(b) + v(c))),
            Step::DifferenceMinus(d, a, b, c) => (d, (v(a) - v(b)) - v(c)),
            Step::MinusDifference(d, a, b, c) => (d, v(a) - (v(b) - v(c))),
            Step::ProductsPlus(d, [a, b, c, e]) => (d, v(a) * v(b) + v(c) * v(e)),
            Step::ProductsMinus(d, [a, b, c, e]) => (d, v(a) * v(b) - v(c) * v(e)),
            Step::Other(instruction) => return other(instruction),
        };
        // SAFETY: as above.
        unsafe { *r.add(d as usize) = value };
    }
}

/// The binary operation and operands of a fusable instruction.
fn binary(instruction: Instruction) -> Option<(Binary, u32, u32, u32)> {
    match instruction {
        Instruction::Add(d, a, b) => Some((Binary::Add, d, a, b)),
        Instruction::Sub(d, a, b) => Some((Binary::Sub, d, a, b)),
        Instruction::Mul(d, a, b) => Some((Binary::Mul, d, a, b)),
        Instruction::Div(..)
        | Instruction::Neg(..)
        | Instruction::Sin(..)
        | Instruction::Cos(..)
        | Instruction::Exp(..)
        | Instruction::Ln(..)
        | Instruction::Sqrt(..)
        | Instruction::Powi(..)
        | Instruction::Powf(..)
        | Instruction::Call { .. }
        | Instruction::Input { .. } => None,
    }
}

/// The registers `instruction` reads (input arguments from `arguments`).
pub(super) fn reads(instruction: &Instruction, arguments: &[u32]) -> Vec<u32> {
    if let Instruction::Input { start, count, .. } = *instruction {
        return arguments[start as usize..(start + count) as usize].to_vec();
    }
    let (_, operands) = instruction.registers();
    operands.into_iter().flatten().collect()
}

/// How often the routine reads each register (its outputs included), when
/// it is in single-assignment form (see the module documentation).
fn fusable(routine: &TapeRoutine, layout: &RegisterLayout, arguments: &[u32]) -> Option<Vec<u32>> {
    let first_temporary = layout.temporary(0);
    let mut written = vec![false; layout.registers()];
    let mut read_count = vec![0u32; layout.registers()];
    for instruction in &routine.instructions {
        for r in reads(instruction, arguments) {
            if r >= first_temporary && !written[r as usize] {
                return None;
            }
            read_count[r as usize] += 1;
        }
        let (d, _) = instruction.registers();
        if d < first_temporary || std::mem::replace(&mut written[d as usize], true) {
            return None;
        }
    }
    for &o in &routine.outputs {
        read_count[o as usize] += 1;
    }
    Some(read_count)
}

/// The steps of `routine`: its instructions, each arithmetic one read once
/// (and not an output) fused into its reader where a step has the shape.
pub(super) fn steps(
    routine: &TapeRoutine,
    layout: &RegisterLayout,
    arguments: &[u32],
) -> Vec<Step> {
    let instructions = &routine.instructions;
    let Some(read_count) = fusable(routine, layout, arguments) else {
        return instructions.iter().map(|&i| plain(i)).collect();
    };
    // The instruction writing each register, while it may still be fused.
    let mut writer = vec![u32::MAX; layout.registers()];
    let mut absorbed = vec![false; instructions.len()];
    let mut made: Vec<Option<Step>> = vec![None; instructions.len()];
    for (k, &instruction) in instructions.iter().enumerate() {
        if let Some((op, d, a, b)) = binary(instruction) {
            let operand = |r: u32| {
                let w = writer[r as usize];
                match (w != u32::MAX && read_count[r as usize] == 1)
                    .then(|| binary(instructions[w as usize]))
                    .flatten()
                {
                    Some((inner, _, x, y)) => (Operand::Fused(inner, x, y), Some(w as usize)),
                    None => (Operand::Register(r), None),
                }
            };
            let ((left, lw), (right, rw)) = (operand(a), operand(b));
            made[k] = best(op, (left, lw), (right, rw), a, b, d, &mut absorbed);
            if made[k].is_none() {
                writer[d as usize] = k as u32;
            }
        }
    }
    (instructions.iter().enumerate())
        .filter(|&(k, _)| !absorbed[k])
        .map(|(k, &i)| made[k].unwrap_or_else(|| plain(i)))
        .collect()
}

/// The superinstruction for `left ∘ right`, fusing both operands, else the
/// left, else the right; marks the writers it absorbs.
fn best(
    op: Binary,
    (left, left_writer): (Operand, Option<usize>),
    (right, right_writer): (Operand, Option<usize>),
    a: u32,
    b: u32,
    d: u32,
    absorbed: &mut [bool],
) -> Option<Step> {
    let (plain_a, plain_b) = (Operand::Register(a), Operand::Register(b));
    let tries = [
        (left, right, [left_writer, right_writer]),
        (left, plain_b, [left_writer, None]),
        (plain_a, right, [None, right_writer]),
    ];
    for (l, r, writers) in tries {
        if writers.iter().all(Option::is_none) {
            continue;
        }
        if let Some(step) = Step::fused(op, l, r, d) {
            for w in writers.into_iter().flatten() {
                absorbed[w] = true;
            }
            return Some(step);
        }
    }
    None
}

/// The step running `instruction` alone.
fn plain(instruction: Instruction) -> Step {
    match instruction {
        Instruction::Add(d, a, b) => Step::Add(d, a, b),
        Instruction::Sub(d, a, b) => Step::Sub(d, a, b),
        Instruction::Mul(d, a, b) => Step::Mul(d, a, b),
        Instruction::Div(d, a, b) => Step::Div(d, a, b),
        Instruction::Neg(d, a) => Step::Neg(d, a),
        other => Step::Other(other),
    }
}

#[cfg(test)]
mod tests {
    use super::super::Tape;
    use super::*;
    use crate::layout::RoutineKind;
    use std::collections::BTreeSet;

    /// A routine of `count` arithmetic instructions, sines, cosines and
    /// exponentials over two coordinates, two constants and the temporaries
    /// before each, mostly of the latest ones (so that many are read once);
    /// its outputs are the temporaries nothing reads.
    fn random_routine(seed: u64, count: usize) -> (RegisterLayout, TapeRoutine) {
        let layout = RegisterLayout {
            constants: vec![0.75, -1.25],
            parameters: 0,
            dimension: 2,
            temporaries: count,
        };
        let mut state = seed;
        let mut next = |n: usize| {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 33) as usize % n
        };
        let sources = [0, 1, layout.coordinate(0), layout.coordinate(1)];
        let mut instructions = Vec::new();
        let mut read = vec![false; count];
        for k in 0..count {
            let mut operand = |read: &mut [bool]| {
                if k == 0 || next(4) == 0 {
                    sources[next(4)]
                } else {
                    let back = k - 1 - next(k.min(3));
                    read[back] = true;
                    layout.temporary(back)
                }
            };
            let (d, a, b) = (layout.temporary(k), operand(&mut read), operand(&mut read));
            instructions.push(match next(11) {
                0 | 1 => Instruction::Add(d, a, b),
                2 | 3 => Instruction::Sub(d, a, b),
                4..=6 => Instruction::Mul(d, a, b),
                7 => Instruction::Div(d, a, b),
                8 => Instruction::Neg(d, a),
                9 => [Instruction::Sin(d, a), Instruction::Cos(d, a)][next(2)],
                _ => Instruction::Exp(d, a),
            });
        }
        let outputs = (0..count)
            .filter(|&k| !read[k])
            .map(|k| layout.temporary(k))
            .collect();
        let kind = RoutineKind::Energies;
        (
            layout,
            TapeRoutine {
                kind,
                instructions,
                outputs,
            },
        )
    }

    #[test]
    fn fused_steps_compute_the_instructions_bit_for_bit() {
        let mut shapes = BTreeSet::new();
        let no_inputs = |_: usize, _: &[f64]| f64::NAN;
        for seed in 0..200 {
            let (layout, routine) = random_routine(seed, 12);
            let tape = Tape::new(layout, vec![routine.clone()], vec![]).unwrap();
            for step in &tape.steps[0] {
                shapes.insert(format!("{step:?}").split('(').next().unwrap().to_string());
            }
            // The instructions one by one, unfused.
            let state = (0.0, &[0.3, -1.7][..], &[0.0, 0.0][..], &[][..]);
            let mut registers = tape.registers(&[]);
            registers[tape.layout.coordinate(0) as usize] = 0.3;
            registers[tape.layout.coordinate(1) as usize] = -1.7;
            for &instruction in &routine.instructions {
                tape.execute(instruction, &no_inputs, &mut registers);
            }
            let want: Vec<u64> = (routine.outputs.iter())
                .map(|&o| registers[o as usize].to_bits())
                .collect();
            let mut registers = tape.registers(&[]);
            let mut out = vec![0.0; routine.outputs.len()];
            assert!(tape.run(routine.kind, state, &no_inputs, &mut registers, &mut out));
            let got: Vec<u64> = out.iter().map(|x| x.to_bits()).collect();
            assert_eq!(got, want, "seed {seed}: {:?}", tape.steps[0]);
        }
        // Every kind of step was made and checked: five plain ones, the
        // sixteen superinstructions and `Other`.
        assert_eq!(shapes.len(), 22, "{shapes:?}");
    }

    #[test]
    fn a_routine_not_in_single_assignment_form_runs_unfused() {
        let layout = RegisterLayout {
            constants: vec![2.0],
            parameters: 0,
            dimension: 1,
            temporaries: 2,
        };
        let (x, t0, t1) = (
            layout.coordinate(0),
            layout.temporary(0),
            layout.temporary(1),
        );
        // t1 is written twice: moving `x · x` to its reader would read the
        // second value of t1.
        let instructions = vec![
            Instruction::Mul(t0, x, t1),
            Instruction::Add(t1, 0, 0),
            Instruction::Add(t1, t0, 0),
        ];
        let routine = TapeRoutine {
            kind: RoutineKind::Energies,
            instructions: instructions.clone(),
            outputs: vec![t1],
        };
        let steps = steps(&routine, &layout, &[]);
        assert_eq!(
            steps,
            instructions.into_iter().map(plain).collect::<Vec<_>>()
        );
    }
}
