//! The optimized straight-line program and its interpreter.
//!
//! A [`Program`] is a list of SSA operations (operation `i` defines register
//! `i`) shared by several [`Routine`]s, each of which evaluates a group of
//! outputs (mass matrix and forcing, energies, Jacobians) by running only the
//! operations its outputs depend on. The same program is emitted as Rust and
//! run by [`Program::run`], which performs exactly the same floating-point
//! operations in the same order.

use crate::expr::Inputs;
use std::hash::{Hash, Hasher};

/// Register index: the result of operation number `Reg`.
pub type Reg = u32;

/// One operation of the program.
#[derive(Clone, Debug)]
pub enum Op {
    Const(f64),
    Parameter(u32),
    Coordinate(u32),
    Velocity(u32),
    Acceleration(u32),
    Time,
    /// Value of input function `index` at the argument registers.
    Input {
        index: u32,
        args: Box<[Reg]>,
    },
    Add(Reg, Reg),
    Sub(Reg, Reg),
    Mul(Reg, Reg),
    Div(Reg, Reg),
    Neg(Reg),
    Sin(Reg),
    Cos(Reg),
    Exp(Reg),
    Ln(Reg),
    Sqrt(Reg),
    Powi(Reg, i32),
    Powf(Reg, f64),
}

impl PartialEq for Op {
    fn eq(&self, other: &Self) -> bool {
        use Op::*;
        match (self, other) {
            (Const(a), Const(b)) => a.to_bits() == b.to_bits(),
            (Powf(a, x), Powf(b, y)) => a == b && x.to_bits() == y.to_bits(),
            (Parameter(a), Parameter(b))
            | (Coordinate(a), Coordinate(b))
            | (Velocity(a), Velocity(b))
            | (Acceleration(a), Acceleration(b))
            | (Neg(a), Neg(b))
            | (Sin(a), Sin(b))
            | (Cos(a), Cos(b))
            | (Exp(a), Exp(b))
            | (Ln(a), Ln(b))
            | (Sqrt(a), Sqrt(b)) => a == b,
            (Time, Time) => true,
            (Input { index: i, args: a }, Input { index: j, args: b }) => i == j && a == b,
            (Add(a, b), Add(c, d))
            | (Sub(a, b), Sub(c, d))
            | (Mul(a, b), Mul(c, d))
            | (Div(a, b), Div(c, d)) => a == c && b == d,
            (Powi(a, n), Powi(b, m)) => a == b && n == m,
            _ => false,
        }
    }
}

impl Eq for Op {}

impl Hash for Op {
    fn hash<H: Hasher>(&self, state: &mut H) {
        std::mem::discriminant(self).hash(state);
        match self {
            Op::Const(v) => v.to_bits().hash(state),
            Op::Powf(a, x) => {
                a.hash(state);
                x.to_bits().hash(state);
            }
            Op::Parameter(a)
            | Op::Coordinate(a)
            | Op::Velocity(a)
            | Op::Acceleration(a)
            | Op::Neg(a)
            | Op::Sin(a)
            | Op::Cos(a)
            | Op::Exp(a)
            | Op::Ln(a)
            | Op::Sqrt(a) => a.hash(state),
            Op::Time => {}
            Op::Input { index, args } => {
                index.hash(state);
                args.hash(state);
            }
            Op::Add(a, b) | Op::Sub(a, b) | Op::Mul(a, b) | Op::Div(a, b) => {
                a.hash(state);
                b.hash(state);
            }
            Op::Powi(a, n) => {
                a.hash(state);
                n.hash(state);
            }
        }
    }
}

impl Op {
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
            Op::Input { args, .. } => args.to_vec(),
            _ => Vec::new(),
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

pub use lagrangian_model::layout::RoutineKind;

/// A group of outputs and the operations needed to compute them, in order.
#[derive(Clone, Debug)]
pub struct Routine {
    pub kind: RoutineKind,
    pub outputs: Vec<Reg>,
    pub ops: Vec<Reg>,
}

/// Number of operations by kind (loads excluded).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OpCounts {
    pub add: usize,
    pub mul: usize,
    pub div: usize,
    pub neg: usize,
    /// sin, cos, exp, ln, sqrt.
    pub transcendental: usize,
    pub pow: usize,
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
    pub t: f64,
    pub q: &'a [f64],
    pub qd: &'a [f64],
    /// Accelerations (only the Jacobians routine reads them).
    pub qdd: &'a [f64],
    pub parameters: &'a [f64],
    pub inputs: Inputs<'a>,
}

/// An optimized straight-line program for all outputs of a model.
#[derive(Clone, Debug)]
pub struct Program {
    pub dimension: usize,
    pub ops: Vec<Op>,
    pub routines: Vec<Routine>,
    /// Every distinct input-function call of the dynamics routine, as
    /// `(input index, number of arguments)`, ordered by input index.
    pub input_sites: Vec<(usize, usize)>,
}

impl Program {
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
                Op::Sin(_) | Op::Cos(_) | Op::Exp(_) | Op::Ln(_) | Op::Sqrt(_) => {
                    c.transcendental += 1
                }
                Op::Powi(..) | Op::Powf(..) => c.pow += 1,
                Op::Input { .. } => c.input_calls += 1,
                _ => {}
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
                Op::Const(v) => *v,
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
                Op::Powf(a, x) => reg(a).powf(*x),
            };
            registers[r as usize] = value;
        }
        for (slot, &r) in out.iter_mut().zip(&routine.outputs) {
            *slot = registers[r as usize];
        }
    }
}
