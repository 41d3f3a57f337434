//! The optimized straight-line program and its interpreter.
//!
//! A [`Program`] is a list of SSA operations (operation `i` defines register
//! `i`) shared by several [`Routine`]s, each of which evaluates a group of
//! outputs (mass matrix and forcing, energies, Jacobians) by running only the
//! operations its outputs depend on. The same program is emitted as Rust and
//! run by [`Program::run`], which performs exactly the same floating-point
//! operations in the same order.

use crate::expr::{Func, Inputs};

/// Register index: the result of operation number `Reg`.
pub type Reg = u32;

/// A floating-point number compared and hashed by its bits, so that
/// operations holding one are equal exactly when they compute the same
/// thing (`0.0` and `-0.0` differ, a NaN equals itself) and [`Op`] can
/// derive `Eq` and `Hash` for common-subexpression elimination.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct FloatBits(u64);

impl FloatBits {
    /// The number.
    pub fn value(self) -> f64 {
        f64::from_bits(self.0)
    }
}

impl From<f64> for FloatBits {
    fn from(value: f64) -> FloatBits {
        FloatBits(value.to_bits())
    }
}

impl std::fmt::Debug for FloatBits {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.value().fmt(f)
    }
}

/// One operation of the program; operands are registers of earlier
/// operations.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Op {
    /// A constant.
    Const(FloatBits),
    /// Parameter `i`, in declaration order.
    Parameter(u32),
    /// Coordinate `q[i]`.
    Coordinate(u32),
    /// Velocity `q̇[i]`.
    Velocity(u32),
    /// Acceleration `q̈[i]`.
    Acceleration(u32),
    /// The time `t`.
    Time,
    /// Value of input function `index` at the argument registers.
    Input {
        /// The input function, in declaration order.
        index: u32,
        /// The registers of its arguments.
        args: Box<[Reg]>,
    },
    /// `a + b`.
    Add(Reg, Reg),
    /// `a - b`.
    Sub(Reg, Reg),
    /// `a * b`.
    Mul(Reg, Reg),
    /// `a / b`.
    Div(Reg, Reg),
    /// `-a`.
    Neg(Reg),
    /// `sin a`.
    Sin(Reg),
    /// `cos a`.
    Cos(Reg),
    /// `exp a`.
    Exp(Reg),
    /// `ln a`.
    Ln(Reg),
    /// `√a`.
    Sqrt(Reg),
    /// `aⁿ` by `powi`.
    Powi(Reg, i32),
    /// `aˣ` by `powf`, for a constant `x`.
    Powf(Reg, FloatBits),
    /// A function other than those above (`asin`, `atan2`, `abs`, …) of
    /// its [`Func::arity`] argument registers.
    Call(Func, Box<[Reg]>),
}

impl Op {
    /// The constant `value`.
    pub fn constant(value: f64) -> Op {
        Op::Const(value.into())
    }

    /// `a` to the constant power `x`.
    pub fn powf(a: Reg, x: f64) -> Op {
        Op::Powf(a, x.into())
    }

    /// Registers this operation reads.
    pub fn operands(&self) -> Vec<Reg> {
        match self {
            Op::Add(a, b) | Op::Sub(a, b) | Op::Mul(a, b) | Op::Div(a, b) => vec![*a, *b],
            Op::Neg(a)
            | Op::Sin(a)
            | Op::Cos(a)
            | Op::Exp(a)
            | Op::Ln(a)
            | Op::Sqrt(a)
            | Op::Powi(a, _)
            | Op::Powf(a, _) => vec![*a],
            Op::Input { args, .. } | Op::Call(_, args) => args.to_vec(),
            Op::Const(_)
            | Op::Parameter(_)
            | Op::Coordinate(_)
            | Op::Velocity(_)
            | Op::Acceleration(_)
            | Op::Time => Vec::new(),
        }
    }

    /// Loads of constants and variables cost nothing; everything else is an operation.
    pub fn is_load(&self) -> bool {
        matches!(
            self,
            Op::Const(_)
                | Op::Parameter(_)
                | Op::Coordinate(_)
                | Op::Velocity(_)
                | Op::Acceleration(_)
                | Op::Time
        )
    }
}

pub use lagrangian_runtime::layout::RoutineKind;

/// A group of outputs and the operations needed to compute them, in order.
#[derive(Clone, Debug)]
pub struct Routine {
    /// Which outputs it computes.
    pub kind: RoutineKind,
    /// The registers of its outputs, in the order of the kind's layout
    /// ([`RoutineKind::output_slot`]).
    pub outputs: Vec<Reg>,
    /// The operations it runs, in program order: every operation its
    /// outputs depend on.
    pub ops: Vec<Reg>,
}

/// Number of operations by kind (loads excluded).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OpCounts {
    /// Additions and subtractions.
    pub add: usize,
    /// Multiplications.
    pub mul: usize,
    /// Divisions.
    pub div: usize,
    /// Negations.
    pub neg: usize,
    /// sin, cos, exp, ln, sqrt and the other functions.
    pub transcendental: usize,
    /// Integer and fractional powers.
    pub pow: usize,
    /// Input-function calls.
    pub input_calls: usize,
}

impl OpCounts {
    /// All arithmetic and function operations (input calls excluded).
    pub fn total(&self) -> usize {
        self.add + self.mul + self.div + self.neg + self.transcendental + self.pow
    }
}

/// The values a routine reads: time, state, parameters and input functions.
pub struct EvalContext<'a> {
    /// The time.
    pub t: f64,
    /// The coordinates.
    pub q: &'a [f64],
    /// The velocities.
    pub qd: &'a [f64],
    /// Accelerations (only the Jacobians routine reads them).
    pub qdd: &'a [f64],
    /// The parameters, in declaration order.
    pub parameters: &'a [f64],
    /// The input functions.
    pub inputs: Inputs<'a>,
}

/// An optimized straight-line program for all outputs of a model.
#[derive(Clone, Debug)]
pub struct Program {
    /// The number of coordinates.
    pub dimension: usize,
    /// The operations; operation `i` defines register `i`.
    pub ops: Vec<Op>,
    /// The routines, each running the operations its outputs need.
    pub routines: Vec<Routine>,
    /// Every distinct input-function call of the dynamics routine, as
    /// `(input index, number of arguments)`, ordered by input index.
    pub input_sites: Vec<(usize, usize)>,
}

impl Program {
    /// The routine of one kind (the Jacobians only when the spec asks for
    /// them).
    pub fn routine(&self, kind: RoutineKind) -> Option<&Routine> {
        self.routines.iter().find(|r| r.kind == kind)
    }

    /// Operation counts of one routine.
    pub fn counts(&self, routine: &Routine) -> OpCounts {
        let mut c = OpCounts::default();
        for &r in &routine.ops {
            match &self.ops[r as usize] {
                Op::Add(..) | Op::Sub(..) => c.add += 1,
                Op::Mul(..) => c.mul += 1,
                Op::Div(..) => c.div += 1,
                Op::Neg(..) => c.neg += 1,
                Op::Sin(_) | Op::Cos(_) | Op::Exp(_) | Op::Ln(_) | Op::Sqrt(_) | Op::Call(..) => {
                    c.transcendental += 1
                }
                Op::Powi(..) | Op::Powf(..) => c.pow += 1,
                Op::Input { .. } => c.input_calls += 1,
                Op::Const(_)
                | Op::Parameter(_)
                | Op::Coordinate(_)
                | Op::Velocity(_)
                | Op::Acceleration(_)
                | Op::Time => {}
            }
        }
        c
    }

    /// A register file large enough for [`Program::run`].
    pub fn registers(&self) -> Vec<f64> {
        vec![0.0; self.ops.len()]
    }

    /// Runs `routine`, writing its outputs, in order, to `out`.
    ///
    /// `registers` must come from [`Program::registers`]; `out` must hold
    /// `routine.outputs.len()` values.
    pub fn run(
        &self,
        routine: &Routine,
        ctx: &EvalContext,
        registers: &mut [f64],
        out: &mut [f64],
    ) {
        let mut args = [0.0f64; 8];
        for &r in &routine.ops {
            let reg = |i: &Reg| registers[*i as usize];
            let value = match &self.ops[r as usize] {
                Op::Const(v) => v.value(),
                Op::Parameter(i) => ctx.parameters[*i as usize],
                Op::Coordinate(i) => ctx.q[*i as usize],
                Op::Velocity(i) => ctx.qd[*i as usize],
                Op::Acceleration(i) => ctx.qdd[*i as usize],
                Op::Time => ctx.t,
                Op::Input { index, args: regs } => {
                    if regs.len() <= args.len() {
                        for (slot, a) in args.iter_mut().zip(regs.iter()) {
                            *slot = registers[*a as usize];
                        }
                        (ctx.inputs)(*index as usize, &args[..regs.len()])
                    } else {
                        let values: Vec<f64> = regs.iter().map(reg).collect();
                        (ctx.inputs)(*index as usize, &values)
                    }
                }
                Op::Add(a, b) => reg(a) + reg(b),
                Op::Sub(a, b) => reg(a) - reg(b),
                Op::Mul(a, b) => reg(a) * reg(b),
                Op::Div(a, b) => reg(a) / reg(b),
                Op::Neg(a) => -reg(a),
                Op::Sin(a) => reg(a).sin(),
                Op::Cos(a) => reg(a).cos(),
                Op::Exp(a) => reg(a).exp(),
                Op::Ln(a) => reg(a).ln(),
                Op::Sqrt(a) => reg(a).sqrt(),
                Op::Powi(a, n) => reg(a).powi(*n),
                Op::Powf(a, x) => reg(a).powf(x.value()),
                Op::Call(f, regs) => {
                    let a = reg(&regs[0]);
                    f.apply(a, regs.get(1).map_or(a, reg))
                }
            };
            registers[r as usize] = value;
        }
        for (slot, &r) in out.iter_mut().zip(&routine.outputs) {
            *slot = registers[r as usize];
        }
    }
}
