//! The interpreter: a compiled model's routines as flat lists of
//! three-address instructions over one register file.
//!
//! The register file is laid out as `[constants | parameters | q | q̇ | q̈ | t |
//! temporaries]` ([`RegisterLayout`]). Constants are written when the file is
//! made and parameters when they change, and the state is copied into its
//! slots at each call, so the instruction lists hold arithmetic and input
//! calls only. The compiler (`lagrangian-core`) lowers its optimized program
//! to a tape instruction by instruction, in the program's order, so a tape
//! computes bit for bit what the program and the emitted Rust do. A routine
//! runs as steps, where an operation read once is fused into its reader
//! (superinstructions rounded as the separate operations are: `code`).

use crate::InputFunctions;
use crate::functions::Func;
use crate::layout::RoutineKind;
use std::fmt;

mod code;
mod derived;

pub use derived::DerivedRoutine;

/// One instruction: destination register first, then the operands.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Instruction {
    /// `dst = a + b`.
    Add(u32, u32, u32),
    /// `dst = a − b`.
    Sub(u32, u32, u32),
    /// `dst = a · b`.
    Mul(u32, u32, u32),
    /// `dst = a / b`.
    Div(u32, u32, u32),
    /// `dst = −a`.
    Neg(u32, u32),
    /// `dst = sin a`.
    Sin(u32, u32),
    /// `dst = cos a`.
    Cos(u32, u32),
    /// `dst = exp a`.
    Exp(u32, u32),
    /// `dst = ln a`.
    Ln(u32, u32),
    /// `dst = √a`.
    Sqrt(u32, u32),
    /// `dst = a^k` for an integer `k`.
    Powi(u32, u32, i32),
    /// `dst = a^b` with the exponent in register `b`.
    Powf(u32, u32, u32),
    /// `dst = f(a)` or `f(a, b)` for a function other than those above
    /// (a one-argument function reads `a` only).
    Call {
        /// The function.
        function: Func,
        /// Destination register.
        dst: u32,
        /// The argument registers (`[a, a]` for a one-argument function).
        args: [u32; 2],
    },
    /// `dst = input[index](registers of arguments[start..start + count])`.
    Input {
        /// Destination register.
        dst: u32,
        /// The input function's index.
        index: u32,
        /// First argument register in [`Tape::new`]'s `arguments`.
        start: u32,
        /// Number of arguments.
        count: u32,
    },
}

impl Instruction {
    /// The registers it writes and reads.
    fn registers(&self) -> (u32, [Option<u32>; 2]) {
        use Instruction::*;
        match *self {
            Add(d, a, b) | Sub(d, a, b) | Mul(d, a, b) | Div(d, a, b) | Powf(d, a, b) => {
                (d, [Some(a), Some(b)])
            }
            Neg(d, a)
            | Sin(d, a)
            | Cos(d, a)
            | Exp(d, a)
            | Ln(d, a)
            | Sqrt(d, a)
            | Powi(d, a, _) => (d, [Some(a), None]),
            Call { dst, args, .. } => (dst, args.map(Some)),
            Input { dst, .. } => (dst, [None, None]),
        }
    }
}

/// The instructions and output registers of one routine.
#[derive(Clone, Debug, PartialEq)]
pub struct TapeRoutine {
    /// What it computes (for a [`DerivedRoutine`], the routine whose outputs
    /// it computes some of).
    pub kind: RoutineKind,
    /// Its instructions, in order.
    pub instructions: Vec<Instruction>,
    /// The registers holding its outputs, in the order of [`RoutineKind`].
    pub outputs: Vec<u32>,
}

/// The sizes of the register file's regions.
#[derive(Clone, Debug, PartialEq)]
pub struct RegisterLayout {
    /// The values of the constant registers, which come first.
    pub constants: Vec<f64>,
    /// Number of parameters.
    pub parameters: usize,
    /// Number of coordinates `n` (the file holds `q`, `q̇` and `q̈`).
    pub dimension: usize,
    /// Number of temporaries, after the time slot.
    pub temporaries: usize,
}

impl RegisterLayout {
    /// The register of parameter `i`.
    pub fn parameter(&self, i: usize) -> u32 {
        (self.constants.len() + i) as u32
    }

    /// The register of coordinate `q_i`.
    #[inline]
    pub fn coordinate(&self, i: usize) -> u32 {
        (self.q_base() + i) as u32
    }

    /// The register of velocity `q̇_i`.
    pub fn velocity(&self, i: usize) -> u32 {
        (self.q_base() + self.dimension + i) as u32
    }

    /// The register of acceleration `q̈_i`.
    pub fn acceleration(&self, i: usize) -> u32 {
        (self.q_base() + 2 * self.dimension + i) as u32
    }

    /// The register of the time `t`.
    #[inline]
    pub fn time(&self) -> u32 {
        (self.q_base() + 3 * self.dimension) as u32
    }

    /// The register of temporary `k`.
    pub fn temporary(&self, k: usize) -> u32 {
        self.time() + 1 + k as u32
    }

    /// The size of the register file.
    pub fn registers(&self) -> usize {
        self.time() as usize + 1 + self.temporaries
    }

    #[inline]
    fn q_base(&self) -> usize {
        self.constants.len() + self.parameters
    }
}

/// What a routine's output reads beyond the coordinates and parameters
/// ([`Tape::reads`]): a fact of the instructions it depends on, so an
/// output that reads a velocity with a factor that vanishes at run time
/// still reads it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StateReads {
    /// A velocity `q̇_k`.
    pub velocities: bool,
    /// An acceleration `q̈_k`.
    pub accelerations: bool,
    /// The time `t`.
    pub time: bool,
    /// An input function.
    pub inputs: bool,
}

impl StateReads {
    /// Whether it reads no more than the coordinates, the parameters and
    /// the time: a function `o(q, t)`.
    pub fn of_position(self) -> bool {
        !(self.velocities || self.accelerations || self.inputs)
    }
}

/// A tape whose registers or argument ranges fall outside its register
/// file: a bug in whatever built it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct InvalidTape(pub String);

impl fmt::Display for InvalidTape {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "invalid tape: {}", self.0)
    }
}

impl std::error::Error for InvalidTape {}

/// A compiled model's routines, ready to interpret (see the module
/// documentation).
#[derive(Clone, Debug)]
pub struct Tape {
    layout: RegisterLayout,
    routines: Vec<TapeRoutine>,
    /// Argument registers of the input calls.
    arguments: Vec<u32>,
    /// Each routine's instructions as they run, superinstructions fused
    /// (see `code`); every register they name is inside the file.
    steps: Vec<Vec<code::Step>>,
    /// The routines derived from those above (see `derived`), with their steps.
    derived: Vec<(DerivedRoutine, TapeRoutine, Vec<code::Step>)>,
    /// By [`RoutineKind::index`]: the position of the routine of that kind
    /// in `routines`, if the tape has one.
    by_kind: [Option<usize>; RoutineKind::ALL.len()],
}

impl Tape {
    /// A tape over the register file `layout`, with input calls reading their
    /// arguments from the registers `arguments[start..start + count]`.
    /// Checks that every register and argument range is inside the file.
    pub fn new(
        layout: RegisterLayout,
        routines: Vec<TapeRoutine>,
        arguments: Vec<u32>,
    ) -> Result<Tape, InvalidTape> {
        let size = layout.registers();
        let check = |r: u32, what: &str| {
            if (r as usize) < size {
                Ok(())
            } else {
                Err(InvalidTape(format!(
                    "{what} register {r} outside a file of {size}"
                )))
            }
        };
        for &a in &arguments {
            check(a, "argument")?;
        }
        for routine in &routines {
            for instruction in &routine.instructions {
                let (dst, operands) = instruction.registers();
                check(dst, "destination")?;
                for r in operands.into_iter().flatten() {
                    check(r, "operand")?;
                }
                if let Instruction::Input { start, count, .. } = *instruction
                    && start as usize + count as usize > arguments.len()
                {
                    return Err(InvalidTape(format!(
                        "input arguments {start}..{} outside {}",
                        start as usize + count as usize,
                        arguments.len()
                    )));
                }
            }
            for &r in &routine.outputs {
                check(r, "output")?;
            }
        }
        let steps = (routines.iter())
            .map(|routine| code::steps(routine, &layout, &arguments))
            .collect();
        let derived = derive(&layout, &routines, &arguments);
        let by_kind =
            RoutineKind::ALL.map(|kind| (routines.iter()).position(|routine| routine.kind == kind));
        Ok(Tape {
            layout,
            routines,
            arguments,
            steps,
            derived,
            by_kind,
        })
    }

    /// The number of coordinates.
    pub fn dimension(&self) -> usize {
        self.layout.dimension
    }

    /// The number of parameters.
    pub fn parameters(&self) -> usize {
        self.layout.parameters
    }

    /// A register file holding the constants and `parameters`.
    pub fn registers(&self, parameters: &[f64]) -> Vec<f64> {
        let mut registers = vec![0.0; self.layout.registers()];
        let constants = &self.layout.constants;
        registers[..constants.len()].copy_from_slice(constants);
        self.set_parameters(&mut registers, parameters);
        registers
    }

    /// Writes new parameter values into a register file.
    pub fn set_parameters(&self, registers: &mut [f64], parameters: &[f64]) {
        let base = self.layout.parameter(0) as usize;
        registers[base..base + parameters.len()].copy_from_slice(parameters);
    }

    /// Whether the tape has routine `kind`.
    pub fn has(&self, kind: RoutineKind) -> bool {
        self.routine(kind).is_some()
    }

    /// Number of outputs of routine `kind` (0 when absent).
    #[inline]
    pub fn output_count(&self, kind: RoutineKind) -> usize {
        self.routine(kind).map_or(0, |r| r.outputs.len())
    }

    /// The value of output `k` of routine `kind` when it is a constant (its
    /// register is one of the constants, written when the file is made).
    pub fn constant_output(&self, kind: RoutineKind, k: usize) -> Option<f64> {
        let register = *self.routine(kind)?.outputs.get(k)?;
        self.layout.constants.get(register as usize).copied()
    }

    #[inline]
    fn routine(&self, kind: RoutineKind) -> Option<&TapeRoutine> {
        Some(&self.routines[self.by_kind[kind.index()]?])
    }

    /// The routine `kind` and its steps.
    fn routine_and_steps(&self, kind: RoutineKind) -> Option<(&TapeRoutine, &[code::Step])> {
        let k = self.by_kind[kind.index()]?;
        Some((&self.routines[k], &self.steps[k]))
    }

    /// What output `k` of routine `kind` reads (see [`StateReads`]);
    /// `None` when the tape has no such routine or output.
    pub fn reads(&self, kind: RoutineKind, k: usize) -> Option<StateReads> {
        derived::reads(self.routine(kind)?, k, &self.arguments, &self.layout)
    }

    /// The sizes of the register file's regions.
    pub fn layout(&self) -> &RegisterLayout {
        &self.layout
    }

    /// The routines, as [`Tape::new`] was given them.
    pub fn routines(&self) -> &[TapeRoutine] {
        &self.routines
    }

    /// The argument registers of the input calls (see [`Tape::new`]).
    pub fn arguments(&self) -> &[u32] {
        &self.arguments
    }

    /// The routines [`Tape::new`] derived from the others: one for each
    /// [`DerivedRoutine`] whose source routine the tape has.
    pub fn derived_routines(&self) -> impl Iterator<Item = (DerivedRoutine, &TapeRoutine)> {
        self.derived
            .iter()
            .map(|(which, routine, _)| (*which, routine))
    }

    /// Writes `(t, q, q̇, q̈)` into the state slots of `registers`, as
    /// [`Tape::run`] does first; `q̈` may be empty. `registers` must come
    /// from [`Tape::registers`].
    ///
    /// Inlined: a caller of a fixed dimension knows `q.len()`, and the
    /// copies become a few moves instead of calls to `memcpy`.
    #[inline(always)]
    pub fn load_state(&self, state: (f64, &[f64], &[f64], &[f64]), registers: &mut [f64]) {
        let (t, q, qd, qdd) = state;
        let n = q.len();
        assert!(
            n == self.layout.dimension && qd.len() == n,
            "a state of dimension {}",
            self.layout.dimension
        );
        let base = self.layout.coordinate(0) as usize;
        let (coordinates, velocities) = registers[base..base + 2 * n].split_at_mut(n);
        for k in 0..n {
            (coordinates[k], velocities[k]) = (q[k], qd[k]);
        }
        if qdd.len() == n {
            registers[base + 2 * n..base + 3 * n].copy_from_slice(qdd);
        }
        registers[self.layout.time() as usize] = t;
    }

    /// Runs routine `kind` at `(t, q, q̇, q̈)` and writes its outputs to `out`;
    /// `q̈` may be empty for routines that do not use it. Returns `false`
    /// when the tape has no such routine.
    ///
    /// `registers` must come from [`Tape::registers`] (it panics on a file
    /// of another size); `q` and `qd` must have the tape's dimension and
    /// `out` room for the outputs. Only the outputs are defined afterwards:
    /// a temporary whose value feeds a single instruction may not be written.
    pub fn run<I: InputFunctions + ?Sized>(
        &self,
        kind: RoutineKind,
        state: (f64, &[f64], &[f64], &[f64]),
        inputs: &I,
        registers: &mut [f64],
        out: &mut [f64],
    ) -> bool {
        let Some((routine, steps)) = self.routine_and_steps(kind) else {
            return false;
        };
        self.run_steps((routine, steps), state, inputs, registers, out);
        true
    }

    /// Runs the derived routine `which` as [`Tape::run`] runs a routine;
    /// `false` when the tape has none (it lacks the source routine).
    pub fn run_derived<I: InputFunctions + ?Sized>(
        &self,
        which: DerivedRoutine,
        state: (f64, &[f64], &[f64], &[f64]),
        inputs: &I,
        registers: &mut [f64],
        out: &mut [f64],
    ) -> bool {
        let Some((_, routine, steps)) = self.derived.iter().find(|d| d.0 == which) else {
            return false;
        };
        self.run_steps((routine, steps), state, inputs, registers, out);
        true
    }

    /// Runs `steps`, those of `routine`, and writes its outputs to `out`
    /// (see [`Tape::run`]).
    #[inline(always)]
    fn run_steps<I: InputFunctions + ?Sized>(
        &self,
        (routine, steps): (&TapeRoutine, &[code::Step]),
        state: (f64, &[f64], &[f64], &[f64]),
        inputs: &I,
        registers: &mut [f64],
        out: &mut [f64],
    ) {
        assert_eq!(
            registers.len(),
            self.layout.registers(),
            "a file of this tape"
        );
        self.load_state(state, registers);
        let file = registers.as_mut_ptr();
        for &step in steps {
            // SAFETY: `Tape::new` checked that every register of every
            // instruction, hence of every step, is inside a file of
            // `layout.registers()`, the length of `registers` (asserted);
            // a derived routine's instructions are some of those.
            unsafe {
                step.run(file, |instruction| {
                    self.execute(
                        instruction,
                        inputs,
                        std::slice::from_raw_parts_mut(file, self.layout.registers()),
                    )
                })
            };
        }
        for (slot, &o) in out.iter_mut().zip(&routine.outputs) {
            *slot = registers[o as usize];
        }
    }

    #[inline(always)]
    fn execute<I: InputFunctions + ?Sized>(
        &self,
        instruction: Instruction,
        inputs: &I,
        r: &mut [f64],
    ) {
        use Instruction::*;
        match instruction {
            Add(d, a, b) => r[d as usize] = r[a as usize] + r[b as usize],
            Sub(d, a, b) => r[d as usize] = r[a as usize] - r[b as usize],
            Mul(d, a, b) => r[d as usize] = r[a as usize] * r[b as usize],
            Div(d, a, b) => r[d as usize] = r[a as usize] / r[b as usize],
            Neg(d, a) => r[d as usize] = -r[a as usize],
            Sin(d, a) => r[d as usize] = r[a as usize].sin(),
            Cos(d, a) => r[d as usize] = r[a as usize].cos(),
            Exp(d, a) => r[d as usize] = r[a as usize].exp(),
            Ln(d, a) => r[d as usize] = r[a as usize].ln(),
            Sqrt(d, a) => r[d as usize] = r[a as usize].sqrt(),
            Powi(d, a, k) => r[d as usize] = r[a as usize].powi(k),
            Powf(d, a, b) => r[d as usize] = r[a as usize].powf(r[b as usize]),
            Call {
                function,
                dst,
                args: [a, b],
            } => r[dst as usize] = function.apply(r[a as usize], r[b as usize]),
            Input {
                dst,
                index,
                start,
                count,
            } => {
                let args = &self.arguments[start as usize..(start + count) as usize];
                let mut buffer = [0.0f64; 8];
                r[dst as usize] = if args.len() <= buffer.len() {
                    for (slot, &a) in buffer.iter_mut().zip(args) {
                        *slot = r[a as usize];
                    }
                    inputs.value(index as usize, &buffer[..args.len()])
                } else {
                    let values: Vec<f64> = args.iter().map(|&a| r[a as usize]).collect();
                    inputs.value(index as usize, &values)
                };
            }
        }
    }
}

/// The derived routines of `routines` (see `derived`), with their steps:
/// one for each [`DerivedRoutine`] whose source routine is there and has
/// the outputs it keeps. The registers are inside the file (checked).
fn derive(
    layout: &RegisterLayout,
    routines: &[TapeRoutine],
    arguments: &[u32],
) -> Vec<(DerivedRoutine, TapeRoutine, Vec<code::Step>)> {
    let mut derived = Vec::new();
    for which in DerivedRoutine::ALL {
        let (source, keep) = which.definition();
        let Some(source) = routines.iter().find(|r| r.kind == source) else {
            continue;
        };
        if let Some(routine) = derived::pruned(source, keep, arguments, layout.registers()) {
            let steps = code::steps(&routine, layout, arguments);
            derived.push((which, routine, steps));
        }
    }
    derived
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `x² + c` with `c` a constant and `x` the first coordinate.
    fn square_plus_constant() -> (RegisterLayout, Vec<TapeRoutine>) {
        let layout = RegisterLayout {
            constants: vec![0.5],
            parameters: 1,
            dimension: 1,
            temporaries: 2,
        };
        let (x, c, k) = (layout.coordinate(0), 0, layout.parameter(0));
        let (t0, t1) = (layout.temporary(0), layout.temporary(1));
        let routine = TapeRoutine {
            kind: RoutineKind::Energies,
            instructions: vec![Instruction::Mul(t0, x, x), Instruction::Add(t1, t0, c)],
            outputs: vec![t1, k],
        };
        (layout, vec![routine])
    }

    #[test]
    fn runs_a_routine_over_the_register_file() {
        let (layout, routines) = square_plus_constant();
        assert_eq!(layout.registers(), 1 + 1 + 3 + 1 + 2);
        let tape = Tape::new(layout, routines, vec![]).unwrap();
        let mut registers = tape.registers(&[7.0]);
        let mut out = [0.0; 2];
        let state = (0.0, &[3.0][..], &[0.0][..], &[][..]);
        let no_inputs = |_: usize, _: &[f64]| f64::NAN;
        assert!(tape.run(
            RoutineKind::Energies,
            state,
            &no_inputs,
            &mut registers,
            &mut out
        ));
        assert_eq!(out, [9.5, 7.0]);
        assert!(!tape.run(
            RoutineKind::Dynamics,
            state,
            &no_inputs,
            &mut registers,
            &mut out
        ));
    }

    #[test]
    fn a_register_outside_the_file_is_refused() {
        let (layout, mut routines) = square_plus_constant();
        routines[0].instructions.push(Instruction::Neg(99, 0));
        let error = Tape::new(layout.clone(), routines, vec![]).unwrap_err();
        assert_eq!(error.0, "destination register 99 outside a file of 8");
        let input = Instruction::Input {
            dst: layout.temporary(0),
            index: 0,
            start: 0,
            count: 2,
        };
        let (_, mut routines) = square_plus_constant();
        routines[0].instructions.push(input);
        let error = Tape::new(layout, routines, vec![0]).unwrap_err();
        assert_eq!(error.0, "input arguments 0..2 outside 1");
    }
}
