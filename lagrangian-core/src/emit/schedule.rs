//! What an emitted routine computes, in which order, independent of the
//! target language: the loads it needs, the temporaries it defines and the
//! expression of each output.
//!
//! A [`Schedule`] performs exactly the operations of its program routine, in
//! the same order, so every backend that writes one faithfully computes what
//! [`Program::run`] does, bit for bit. The decisions it makes are the ones
//! that keep the emitted code short without changing a single operation:
//!
//! * a value used once is written inline, where it is used;
//! * constants and the time are always written inline;
//! * an input-function call is always a statement of its own (it may be
//!   expensive, and a reader looks for it);
//! * `sin x` and `cos x` of one argument are one statement
//!   ([`Statement::SinCos`]) defining two temporaries;
//! * every other value used more than once is a temporary, numbered in
//!   program order;
//! * loads (parameters, coordinates, velocities, accelerations) come first,
//!   in that order and by index.

use crate::expr::Func;
use crate::program::{Op, Program, Reg, Routine, RoutineKind};
use lagrangian_runtime::layout::OutputSlot;
use rustc_hash::FxHashMap;

/// A value the routine reads from its arguments.
///
/// The derived order is the load order: parameters, then coordinates,
/// velocities and accelerations, each by index.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Load {
    /// Parameter `i`, in declaration order.
    Parameter(u32),
    /// Coordinate `q[i]`.
    Coordinate(u32),
    /// Velocity `q̇[i]`.
    Velocity(u32),
    /// Acceleration `q̈[i]` (only the Jacobians read them).
    Acceleration(u32),
}

impl Load {
    /// The load an operation performs, if it is one.
    pub fn of(op: &Op) -> Option<Load> {
        match op {
            Op::Parameter(i) => Some(Load::Parameter(*i)),
            Op::Coordinate(i) => Some(Load::Coordinate(*i)),
            Op::Velocity(i) => Some(Load::Velocity(*i)),
            Op::Acceleration(i) => Some(Load::Acceleration(*i)),
            _ => None,
        }
    }
}

/// A binary arithmetic operation; all of them associate to the left.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BinaryOp {
    /// `a + b`.
    Add,
    /// `a - b`.
    Sub,
    /// `a * b`.
    Mul,
    /// `a / b`.
    Div,
}

/// A function of one value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Function {
    /// `sin x`.
    Sin,
    /// `cos x`.
    Cos,
    /// `exp x`.
    Exp,
    /// The natural logarithm.
    Ln,
    /// `√x`.
    Sqrt,
    /// `xⁿ` for an integer `n`, by Rust's `powi` (see the backends for how
    /// they match it).
    Powi(i32),
    /// `xʸ` for a constant `y`, by `powf`.
    Powf(f64),
}

/// An expression tree over loads, constants, the time and temporaries.
#[derive(Clone, Debug, PartialEq)]
pub enum Expression {
    /// A floating-point constant.
    Constant(f64),
    /// The time `t`.
    Time,
    /// A value read from the arguments.
    Load(Load),
    /// Temporary `k`, defined by an earlier statement.
    Temporary(usize),
    /// Input function `index` at the arguments.
    Input {
        /// The input function's index, in declaration order.
        index: u32,
        /// Its arguments.
        arguments: Vec<Expression>,
    },
    /// `-x`.
    Negate(Box<Expression>),
    /// `a ∘ b`.
    Binary(BinaryOp, Box<Expression>, Box<Expression>),
    /// `f(x)`.
    Call(Function, Box<Expression>),
    /// `f(a, …)` for a function of the spec language other than those of
    /// [`Function`] (`asin`, `atan2`, `abs`, …).
    Apply(Func, Vec<Expression>),
}

impl Expression {
    /// Whether the expression is a leaf that costs nothing to repeat.
    fn is_leaf(&self) -> bool {
        matches!(
            self,
            Expression::Constant(_)
                | Expression::Time
                | Expression::Load(_)
                | Expression::Temporary(_)
        )
    }
}

/// One statement of a routine body.
#[derive(Clone, Debug, PartialEq)]
pub enum Statement {
    /// `temporary = value`.
    Define {
        /// The temporary defined.
        temporary: usize,
        /// Its value.
        value: Expression,
    },
    /// `(sin, cos) = (sin x, cos x)`, computed together.
    SinCos {
        /// The temporary holding `sin x`.
        sin: usize,
        /// The temporary holding `cos x`.
        cos: usize,
        /// `x`.
        argument: Expression,
    },
}

/// A routine ready to be written by a backend.
#[derive(Clone, Debug, PartialEq)]
pub struct Schedule {
    /// Which routine it is.
    pub kind: RoutineKind,
    /// What the routine reads, in load order (see [`Load`]).
    pub loads: Vec<Load>,
    /// The statements, in program order.
    pub statements: Vec<Statement>,
    /// The number of temporaries the statements define (`0..temporaries`).
    pub temporaries: usize,
    /// Each output's slot and expression, in the routine's output order.
    pub outputs: Vec<(OutputSlot, Expression)>,
}

/// The schedule of `routine`, a routine of `program`.
pub fn schedule(program: &Program, routine: &Routine) -> Schedule {
    let ops = &program.ops;
    let uses = use_counts(ops, routine);
    let partners = sin_cos_partners(ops, routine);
    let mut builder = Builder {
        values: vec![None; ops.len()],
        loads: Vec::new(),
        statements: Vec::new(),
        temporaries: 0,
    };
    for &r in &routine.ops {
        if builder.values[r as usize].is_some() {
            continue; // the cosine or sine of a `sin_cos` pair
        }
        let op = &ops[r as usize];
        if let (Some(&partner), Op::Sin(a) | Op::Cos(a)) = (partners.get(&r), op) {
            let (sin, cos) = match op {
                Op::Sin(_) => (r, partner),
                _ => (partner, r),
            };
            builder.sin_cos(sin, cos, *a);
            continue;
        }
        if let Some(load) = Load::of(op) {
            builder.loads.push(load);
            builder.values[r as usize] = Some(Expression::Load(load));
            continue;
        }
        let value = builder.expression(op);
        let inline = uses[r as usize] <= 1 && !matches!(op, Op::Input { .. });
        if inline || value.is_leaf() {
            builder.values[r as usize] = Some(value);
        } else {
            builder.define(r, value);
        }
    }
    let n = program.dimension;
    let outputs = routine
        .outputs
        .iter()
        .enumerate()
        .map(|(k, &r)| {
            let slot = routine
                .kind
                .output_slot(n, k)
                .expect("the optimizer builds each routine's outputs in the order of its layout");
            (slot, builder.operand(r))
        })
        .collect();
    builder.loads.sort();
    Schedule {
        kind: routine.kind,
        loads: builder.loads,
        statements: builder.statements,
        temporaries: builder.temporaries,
        outputs,
    }
}

/// How often each register is read by the routine's operations and outputs.
fn use_counts(ops: &[Op], routine: &Routine) -> Vec<u32> {
    let mut uses = vec![0u32; ops.len()];
    for &r in &routine.ops {
        for operand in ops[r as usize].operands() {
            uses[operand as usize] += 1;
        }
    }
    for &r in &routine.outputs {
        uses[r as usize] += 1;
    }
    uses
}

/// For every `sin x` whose `cos x` the routine computes too (and the other
/// way round), the register of the other one.
fn sin_cos_partners(ops: &[Op], routine: &Routine) -> FxHashMap<Reg, Reg> {
    let mut sines = FxHashMap::default();
    let mut cosines = FxHashMap::default();
    for &r in &routine.ops {
        match ops[r as usize] {
            Op::Sin(a) => sines.insert(a, r),
            Op::Cos(a) => cosines.insert(a, r),
            _ => None,
        };
    }
    let mut partners = FxHashMap::default();
    for (a, &sin) in &sines {
        if let Some(&cos) = cosines.get(a) {
            partners.insert(sin, cos);
            partners.insert(cos, sin);
        }
    }
    partners
}

/// The schedule under construction.
struct Builder {
    /// How each register computed so far is written: a leaf, or a tree that
    /// its single user takes.
    values: Vec<Option<Expression>>,
    loads: Vec<Load>,
    statements: Vec<Statement>,
    temporaries: usize,
}

impl Builder {
    /// The expression of register `r` where it is used: a leaf is repeated,
    /// an inlined tree is moved to its only use.
    fn operand(&mut self, r: Reg) -> Expression {
        let slot = &mut self.values[r as usize];
        match slot {
            Some(value) if value.is_leaf() => value.clone(),
            // An operand the routine did not compute: a bug in the program,
            // which shows as NaN rather than as a wrong number.
            _ => slot.take().unwrap_or(Expression::Constant(f64::NAN)),
        }
    }

    /// A new temporary.
    fn temporary(&mut self) -> usize {
        self.temporaries += 1;
        self.temporaries - 1
    }

    /// `temporary = value` for register `r`.
    fn define(&mut self, r: Reg, value: Expression) {
        let temporary = self.temporary();
        self.statements.push(Statement::Define { temporary, value });
        self.values[r as usize] = Some(Expression::Temporary(temporary));
    }

    /// `(sin, cos) = sin_cos(a)` for registers `sin` and `cos`.
    fn sin_cos(&mut self, sin: Reg, cos: Reg, a: Reg) {
        let argument = self.operand(a);
        let (s, c) = (self.temporary(), self.temporary());
        self.statements.push(Statement::SinCos {
            sin: s,
            cos: c,
            argument,
        });
        self.values[sin as usize] = Some(Expression::Temporary(s));
        self.values[cos as usize] = Some(Expression::Temporary(c));
    }

    /// The expression of an operation that is not a load, over the values
    /// of its operands.
    fn expression(&mut self, op: &Op) -> Expression {
        let binary = |b: &mut Builder, o: BinaryOp, x: &Reg, y: &Reg| {
            let (x, y) = (b.operand(*x), b.operand(*y));
            Expression::Binary(o, Box::new(x), Box::new(y))
        };
        let call =
            |b: &mut Builder, f: Function, x: &Reg| Expression::Call(f, Box::new(b.operand(*x)));
        match op {
            Op::Const(v) => Expression::Constant(v.value()),
            Op::Time => Expression::Time,
            Op::Input { index, args } => Expression::Input {
                index: *index,
                arguments: args.iter().map(|a| self.operand(*a)).collect(),
            },
            Op::Add(a, b) => binary(self, BinaryOp::Add, a, b),
            Op::Sub(a, b) => binary(self, BinaryOp::Sub, a, b),
            Op::Mul(a, b) => binary(self, BinaryOp::Mul, a, b),
            Op::Div(a, b) => binary(self, BinaryOp::Div, a, b),
            Op::Neg(a) => Expression::Negate(Box::new(self.operand(*a))),
            Op::Sin(a) => call(self, Function::Sin, a),
            Op::Cos(a) => call(self, Function::Cos, a),
            Op::Exp(a) => call(self, Function::Exp, a),
            Op::Ln(a) => call(self, Function::Ln, a),
            Op::Sqrt(a) => call(self, Function::Sqrt, a),
            Op::Powi(a, k) => call(self, Function::Powi(*k), a),
            Op::Powf(a, x) => call(self, Function::Powf(x.value()), a),
            Op::Call(f, args) => {
                Expression::Apply(*f, args.iter().map(|a| self.operand(*a)).collect())
            }
            // Loads are handled by the caller; a load here would be read
            // from its argument like any other.
            Op::Parameter(_) | Op::Coordinate(_) | Op::Velocity(_) | Op::Acceleration(_) => {
                Load::of(op).map_or(Expression::Constant(f64::NAN), Expression::Load)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use Expression::{Constant, Temporary, Time};

    fn load(l: Load) -> Expression {
        Expression::Load(l)
    }

    fn bin(op: BinaryOp, a: Expression, b: Expression) -> Expression {
        Expression::Binary(op, Box::new(a), Box::new(b))
    }

    /// A one-coordinate program of `ops` with a single dynamics routine
    /// running all of them.
    fn program(ops: Vec<Op>, outputs: Vec<Reg>) -> (Program, Routine) {
        let routine = Routine {
            kind: RoutineKind::Dynamics,
            ops: (0..ops.len() as Reg).collect(),
            outputs,
        };
        let program = Program {
            dimension: 1,
            ops,
            routines: vec![routine.clone()],
            input_sites: Vec::new(),
        };
        (program, routine)
    }

    #[test]
    fn a_value_used_once_is_inlined_and_one_used_twice_is_a_temporary() {
        let (p, r) = program(
            vec![
                Op::Coordinate(0), // 0
                Op::Parameter(0),  // 1
                Op::Mul(0, 1),     // 2: used twice
                Op::Add(2, 2),     // 3: used once
                Op::Sqrt(3),       // 4: output
                Op::constant(2.0), // 5: a constant, used twice
                Op::Sub(5, 5),     // 6: output
            ],
            vec![4, 6],
        );
        let s = schedule(&p, &r);
        let (q, m) = (load(Load::Coordinate(0)), load(Load::Parameter(0)));
        assert_eq!(s.loads, [Load::Parameter(0), Load::Coordinate(0)]);
        assert_eq!(
            s.statements,
            [Statement::Define {
                temporary: 0,
                value: bin(BinaryOp::Mul, q, m),
            }]
        );
        assert_eq!(s.temporaries, 1);
        let sum = bin(BinaryOp::Add, Temporary(0), Temporary(0));
        assert_eq!(
            s.outputs,
            [
                (
                    OutputSlot::Mass { row: 0, column: 0 },
                    Expression::Call(Function::Sqrt, Box::new(sum))
                ),
                (
                    OutputSlot::Forcing(0),
                    bin(BinaryOp::Sub, Constant(2.0), Constant(2.0))
                ),
            ]
        );
    }

    #[test]
    fn sine_and_cosine_of_one_argument_are_one_statement() {
        let (p, r) = program(
            vec![
                Op::Coordinate(0), // 0
                Op::Time,          // 1
                Op::Cos(0),        // 2
                Op::Sin(1),        // 3: no cosine of t: a call, inlined
                Op::Sin(0),        // 4
                Op::Mul(2, 4),     // 5
                Op::Add(5, 3),     // 6
            ],
            vec![6, 2],
        );
        let s = schedule(&p, &r);
        // The pair is defined where its first member is computed; the
        // sine gets the first temporary.
        assert_eq!(
            s.statements,
            [Statement::SinCos {
                sin: 0,
                cos: 1,
                argument: load(Load::Coordinate(0)),
            }]
        );
        let sin_t = Expression::Call(Function::Sin, Box::new(Time));
        let product = bin(BinaryOp::Mul, Temporary(1), Temporary(0));
        assert_eq!(s.outputs[0].1, bin(BinaryOp::Add, product, sin_t));
        assert_eq!(s.outputs[1].1, Temporary(1));
    }

    #[test]
    fn an_input_call_is_always_a_statement() {
        let (p, r) = program(
            vec![
                Op::Velocity(0),   // 0
                Op::Coordinate(0), // 1
                Op::Neg(1),        // 2: used once, inlined into the call
                Op::Input {
                    index: 3,
                    args: vec![2, 0].into(),
                }, // 3: used once, still a statement
                Op::Powi(3, -2),   // 4
            ],
            vec![4, 0],
        );
        let s = schedule(&p, &r);
        assert_eq!(s.loads, [Load::Coordinate(0), Load::Velocity(0)]);
        let arguments = vec![
            Expression::Negate(Box::new(load(Load::Coordinate(0)))),
            load(Load::Velocity(0)),
        ];
        assert_eq!(
            s.statements,
            [Statement::Define {
                temporary: 0,
                value: Expression::Input {
                    index: 3,
                    arguments
                },
            }]
        );
        let power = Expression::Call(Function::Powi(-2), Box::new(Temporary(0)));
        assert_eq!(s.outputs[0].1, power);
        assert_eq!(s.outputs[1].1, load(Load::Velocity(0)));
    }

    /// Runs a schedule on plain numbers, operation by operation.
    fn evaluate(s: &Schedule, ctx: &crate::program::EvalContext) -> Vec<f64> {
        fn value(e: &Expression, ctx: &crate::program::EvalContext, temps: &[f64]) -> f64 {
            let v = |x: &Expression| value(x, ctx, temps);
            match e {
                Constant(c) => *c,
                Time => ctx.t,
                Expression::Load(Load::Parameter(i)) => ctx.parameters[*i as usize],
                Expression::Load(Load::Coordinate(i)) => ctx.q[*i as usize],
                Expression::Load(Load::Velocity(i)) => ctx.qd[*i as usize],
                Expression::Load(Load::Acceleration(i)) => ctx.qdd[*i as usize],
                Temporary(k) => temps[*k],
                Expression::Input { index, arguments } => {
                    let args: Vec<f64> = arguments.iter().map(v).collect();
                    (ctx.inputs)(*index as usize, &args)
                }
                Expression::Negate(x) => -v(x),
                Expression::Binary(op, a, b) => match op {
                    BinaryOp::Add => v(a) + v(b),
                    BinaryOp::Sub => v(a) - v(b),
                    BinaryOp::Mul => v(a) * v(b),
                    BinaryOp::Div => v(a) / v(b),
                },
                Expression::Call(f, x) => match f {
                    Function::Sin => v(x).sin(),
                    Function::Cos => v(x).cos(),
                    Function::Exp => v(x).exp(),
                    Function::Ln => v(x).ln(),
                    Function::Sqrt => v(x).sqrt(),
                    Function::Powi(k) => v(x).powi(*k),
                    Function::Powf(y) => v(x).powf(*y),
                },
                Expression::Apply(f, args) => {
                    let a = v(&args[0]);
                    f.apply(a, args.get(1).map_or(a, v))
                }
            }
        }
        let mut temps = vec![f64::NAN; s.temporaries];
        for statement in &s.statements {
            match statement {
                Statement::Define {
                    temporary,
                    value: e,
                } => temps[*temporary] = value(e, ctx, &temps),
                Statement::SinCos { sin, cos, argument } => {
                    let (a, b) = value(argument, ctx, &temps).sin_cos();
                    (temps[*sin], temps[*cos]) = (a, b);
                }
            }
        }
        s.outputs
            .iter()
            .map(|(_, e)| value(e, ctx, &temps))
            .collect()
    }

    /// The schedules of real models compute what their programs do, bit for
    /// bit, with the outputs in the slots of the layout.
    #[test]
    fn schedules_compute_what_the_program_does() {
        let sources = [
            include_str!("../../../specs/yaris_double_pendulum.lpm").to_string(),
            include_str!("../../../specs/elastic_pendulum.lpm").to_string(),
            crate::examples::pendulum_chain(3) + "jacobians;",
        ];
        let inputs = |index: usize, args: &[f64]| {
            args.iter()
                .fold(0.5 + index as f64, |acc, a| acc * 0.75 + a.sin())
        };
        for source in sources {
            let compiled = crate::Compiled::from_source(&source).unwrap();
            let program = &compiled.program;
            let n = program.dimension;
            let parameters = compiled.default_parameters();
            let q: Vec<f64> = (0..n).map(|i| 0.3 - 0.2 * i as f64).collect();
            let qd: Vec<f64> = (0..n).map(|i| 0.7 * i as f64 - 0.4).collect();
            let qdd: Vec<f64> = (0..n).map(|i| 1.1 + i as f64).collect();
            let ctx = crate::program::EvalContext {
                t: 0.125,
                q: &q,
                qd: &qd,
                qdd: &qdd,
                parameters: &parameters,
                inputs: &inputs,
            };
            let mut registers = program.registers();
            for routine in &program.routines {
                let s = schedule(program, routine);
                if let Some(count) = routine.kind.output_count(n) {
                    assert_eq!(s.outputs.len(), count, "{:?}", routine.kind);
                }
                let mut expected = vec![0.0; routine.outputs.len()];
                program.run(routine, &ctx, &mut registers, &mut expected);
                let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(
                    bits(&evaluate(&s, &ctx)),
                    bits(&expected),
                    "{:?}",
                    routine.kind
                );
            }
        }
    }
}
