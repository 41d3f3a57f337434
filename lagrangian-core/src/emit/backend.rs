//! What a target language supplies to write a [`Schedule`]: its syntax, and
//! nothing else.
//!
//! A backend spells literals, names, operators, calls and statements; the
//! schedule has decided what is computed and in which order, and
//! [`expression`] decides where parentheses go, on the one
//! [`Precedence`] scale, so that the written expression evaluates the
//! schedule's tree exactly (the same operations on the same operands, in the
//! same order). Where the outputs go is the backend's routine template's
//! business: it places each output by its [`OutputSlot`]
//! (`lagrangian_runtime::layout`).
//!
//! [`OutputSlot`]: lagrangian_runtime::layout::OutputSlot

use super::schedule::{BinaryOp, Expression, Function, Load, Schedule, Statement};
use crate::expr::{Func, Precedence};

/// Written code and how tightly it binds.
#[derive(Clone, Debug)]
pub struct Fragment<C> {
    /// The code.
    pub code: C,
    /// How tightly it binds.
    pub precedence: Precedence,
    /// Whether it is a numeric literal (which some targets cannot call a
    /// method on without parentheses: Rust's `(2.0).sqrt()`).
    pub literal: bool,
}

impl<C> Fragment<C> {
    /// Code that binds like a name.
    pub fn atom(code: C) -> Fragment<C> {
        Fragment {
            code,
            precedence: Precedence::Atom,
            literal: false,
        }
    }
}

/// The syntax of a target language.
pub trait Backend {
    /// Written code: an expression or a statement.
    type Code: Clone;

    /// A floating-point literal that reads back as exactly `value`.
    fn constant(&self, value: f64) -> Fragment<Self::Code>;
    /// The time argument.
    fn time(&self) -> Self::Code;
    /// The local holding a load.
    fn load(&self, load: Load) -> Self::Code;
    /// The local holding temporary `k`.
    fn temporary(&self, k: usize) -> Self::Code;
    /// `(code)`.
    fn parenthesize(&self, code: Self::Code) -> Self::Code;
    /// `left ∘ right`; the operands are parenthesized already.
    fn binary(&self, op: BinaryOp, left: Self::Code, right: Self::Code) -> Self::Code;
    /// `-operand`; the operand binds at least as tightly as a negation.
    fn negate(&self, operand: Self::Code) -> Self::Code;
    /// `f(argument)`, an atom; the backend parenthesizes the argument as its
    /// call syntax needs.
    fn call(&self, function: Function, argument: Fragment<Self::Code>) -> Self::Code;
    /// `f(arguments…)` for a function of [`Expression::Apply`], an atom;
    /// the backend parenthesizes the arguments as its call syntax needs.
    fn apply(&self, f: Func, arguments: Vec<Fragment<Self::Code>>) -> Self::Code;
    /// Input function `index` at `arguments`, an atom.
    fn input(&self, index: u32, arguments: Vec<Self::Code>) -> Self::Code;
    /// The statement reading a load into its local.
    fn load_statement(&self, load: Load) -> Self::Code;
    /// The statement defining temporary `k` as `value`.
    fn define(&self, k: usize, value: Self::Code) -> Self::Code;
    /// The statement defining temporaries `sin` and `cos` as the sine and
    /// cosine of `argument`.
    fn sin_cos(&self, sin: usize, cos: usize, argument: Fragment<Self::Code>) -> Self::Code;
}

/// A routine body in a backend's syntax.
pub struct Body<C> {
    /// The loads, then the statements.
    pub statements: Vec<C>,
    /// The expression of each output, in the schedule's output order.
    pub outputs: Vec<C>,
}

/// The statements and output expressions of `schedule`.
pub fn body<B: Backend>(backend: &B, schedule: &Schedule) -> Body<B::Code> {
    let mut statements: Vec<B::Code> = (schedule.loads.iter())
        .map(|&load| backend.load_statement(load))
        .collect();
    for statement in &schedule.statements {
        statements.push(match statement {
            Statement::Define { temporary, value } => {
                backend.define(*temporary, expression(backend, value).code)
            }
            Statement::SinCos { sin, cos, argument } => {
                backend.sin_cos(*sin, *cos, expression(backend, argument))
            }
        });
    }
    let outputs = (schedule.outputs.iter())
        .map(|(_, value)| expression(backend, value).code)
        .collect();
    Body {
        statements,
        outputs,
    }
}

/// `e` written by `backend`, parenthesized where the tree needs it.
pub fn expression<B: Backend>(backend: &B, e: &Expression) -> Fragment<B::Code> {
    let at = |fragment: Fragment<B::Code>, min: Precedence| {
        if fragment.precedence.needs_parentheses(min) {
            backend.parenthesize(fragment.code)
        } else {
            fragment.code
        }
    };
    match e {
        Expression::Constant(value) => backend.constant(*value),
        Expression::Time => Fragment::atom(backend.time()),
        Expression::Load(load) => Fragment::atom(backend.load(*load)),
        Expression::Temporary(k) => Fragment::atom(backend.temporary(*k)),
        Expression::Input { index, arguments } => {
            let arguments = (arguments.iter())
                .map(|a| at(expression(backend, a), Precedence::Sum))
                .collect();
            Fragment::atom(backend.input(*index, arguments))
        }
        Expression::Negate(x) => Fragment {
            code: backend.negate(at(expression(backend, x), Precedence::Unary)),
            precedence: Precedence::Unary,
            literal: false,
        },
        Expression::Binary(op, a, b) => {
            let precedence = match op {
                BinaryOp::Add | BinaryOp::Sub => Precedence::Sum,
                BinaryOp::Mul | BinaryOp::Div => Precedence::Product,
            };
            // Left-associative: the right operand must bind strictly tighter.
            let left = at(expression(backend, a), precedence);
            let right = at(expression(backend, b), precedence.tighter());
            Fragment {
                code: backend.binary(*op, left, right),
                precedence,
                literal: false,
            }
        }
        Expression::Call(function, x) => {
            Fragment::atom(backend.call(*function, expression(backend, x)))
        }
        Expression::Apply(f, arguments) => {
            let arguments = (arguments.iter()).map(|a| expression(backend, a)).collect();
            Fragment::atom(backend.apply(*f, arguments))
        }
    }
}
