//! From derived expressions to one optimized straight-line [`Program`].
//!
//! * Every sum is factored by greedy multivariate Horner: the variable that
//!   occurs in most terms is factored out, recursively.
//! * `sin`/`cos` of integer combinations of symbols (`θ1 − θ2`, `2θ`) are
//!   lowered with the angle-addition formulas onto the sine and cosine of each
//!   symbol, so each coordinate's sine and cosine is computed once.
//! * Operations are hash-consed (operands of `+` and `·` in canonical order),
//!   which eliminates common subexpressions across all outputs.
//! * Signs travel with registers, so `a − b` costs one subtraction, not a
//!   negation and an addition.

use crate::derive::Derivation;
use crate::expr::{ExprId, Func, Node, Store, SymbolKind};
use crate::program::{Op, Program, Reg, Routine, RoutineKind};
use crate::rational::Rational;
use lagrangian_runtime::functions::Elementary;
use lagrangian_runtime::layout::mass_entries;
use rustc_hash::FxHashMap;

mod from_graph;
mod shift;

pub use from_graph::build_program_from_graph;

/// A register whose value is to be negated when `negative` is set.
#[derive(Clone, Copy, Debug)]
struct Signed {
    reg: Reg,
    negative: bool,
}

impl Signed {
    fn plus(reg: Reg) -> Signed {
        Signed {
            reg,
            negative: false,
        }
    }

    fn flip(self, flip: bool) -> Signed {
        Signed {
            reg: self.reg,
            negative: self.negative != flip,
        }
    }
}

/// A factor `base^unit` that Horner treats as one variable (`unit` = ±1 or ±1/k).
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
struct Var {
    base: ExprId,
    unit: Rational,
}

/// One term `coefficient · Π var^degree` of a sum being factored.
#[derive(Clone, Debug)]
struct Term {
    coefficient: Rational,
    /// `(variable rank, degree)`, sorted by variable rank.
    vars: Vec<(u32, u128)>,
}

struct Builder<'a> {
    store: &'a mut Store,
    ops: Vec<Op>,
    dedup: FxHashMap<Op, Reg>,
    memo: FxHashMap<ExprId, Signed>,
    trig: FxHashMap<Vec<(ExprId, i64)>, (Signed, Signed)>,
    vars: Vec<Var>,
    var_index: FxHashMap<Var, u32>,
    var_regs: FxHashMap<u32, Signed>,
    /// Variables that are shifted coordinates `q + Σ ±p` (see `shift`).
    shifted_vars: rustc_hash::FxHashSet<u32>,
}

/// Builds the program for all outputs of `derivation`.
pub fn build_program(store: &mut Store, derivation: &Derivation) -> Program {
    let outputs = RoutineOutputs {
        dimension: derivation.dimension,
        mass: mass_entries(derivation.dimension)
            .map(|(i, j)| derivation.mass(i, j))
            .collect(),
        forcing: derivation.forcing.clone(),
        energies: [
            derivation.kinetic,
            derivation.potential,
            derivation.dissipation,
            derivation.damping_power,
            derivation.external_power,
        ],
        jacobians: derivation.jacobians.as_ref().map(|j| {
            let blocks = [&j.forcing_q, &j.forcing_qd, &j.mass_times_acceleration_q];
            blocks.into_iter().flatten().copied().collect()
        }),
        outputs: derivation.outputs.clone(),
        constraints: derivation.constraints.outputs().collect(),
        switching: crate::switching::switching_functions(store, derivation),
    };
    let mut b = Builder::new(store);
    assemble(&mut b, &outputs, |b, e| b.output(e))
}

/// The values each routine outputs, as expressions of some kind `E`
/// (canonical expressions, or graph nodes), in the runtime's layout.
struct RoutineOutputs<E> {
    dimension: usize,
    /// The upper triangle of `M`, in the order of [`mass_entries`].
    mass: Vec<E>,
    forcing: Vec<E>,
    /// `T`, `V`, `D`, the damping power, the external power.
    energies: [E; 5],
    /// `∂f/∂q`, `∂f/∂q̇`, `∂(M a)/∂q`, each row-major, one after the other.
    jacobians: Option<Vec<E>>,
    outputs: Vec<E>,
    /// `g`, `g_t`, `G`, `γ` of the holonomic constraints, in the order of
    /// the runtime's `ConstraintLayout` (empty without constraints).
    constraints: Vec<E>,
    /// The switching functions of the non-smooth functions (`abs`, `sign`,
    /// `min`, `max`) of the dynamics.
    switching: Vec<E>,
}

/// The program computing `outputs`, each value made a register by `output`.
fn assemble<'s, E: Copy>(
    b: &mut Builder<'s>,
    outputs: &RoutineOutputs<E>,
    mut output: impl FnMut(&mut Builder<'s>, E) -> Reg,
) -> Program {
    let routine_outputs = b.routine_outputs(outputs, &mut output);
    let mut routines: Vec<Routine> = routine_outputs
        .into_iter()
        .map(|(kind, outputs)| Routine {
            kind,
            ops: dependency_closure(&b.ops, &outputs),
            outputs,
        })
        .collect();
    let (arguments, input_sites) = input_arguments(&b.ops, &routines[0]);
    routines.push(arguments);
    // Last, so that a smooth model gets the same program.
    if !outputs.switching.is_empty() {
        let outputs: Vec<Reg> = (outputs.switching.iter()).map(|&e| output(b, e)).collect();
        routines.push(Routine {
            kind: RoutineKind::Switching,
            ops: dependency_closure(&b.ops, &outputs),
            outputs,
        });
    }
    Program {
        dimension: outputs.dimension,
        ops: std::mem::take(&mut b.ops),
        routines,
        input_sites,
    }
}

/// The input calls of the dynamics routine: the routine that computes their
/// arguments, for event functions and diagnostics that need them without
/// evaluating the whole model, and `(input index, argument count)` of each
/// call, by input index.
fn input_arguments(ops: &[Op], dynamics: &Routine) -> (Routine, Vec<(usize, usize)>) {
    let mut calls: Vec<(u32, Vec<Reg>)> = dynamics
        .ops
        .iter()
        .filter_map(|&r| match &ops[r as usize] {
            Op::Input { index, args } => Some((*index, args.to_vec())),
            _ => None,
        })
        .collect();
    calls.sort_by_key(|(index, _)| *index);
    let input_sites = calls.iter().map(|(i, a)| (*i as usize, a.len())).collect();
    let outputs: Vec<Reg> = calls.into_iter().flat_map(|(_, a)| a).collect();
    let routine = Routine {
        kind: RoutineKind::InputArguments,
        ops: dependency_closure(ops, &outputs),
        outputs,
    };
    (routine, input_sites)
}

/// The operations `outputs` depend on, in program order.
fn dependency_closure(ops: &[Op], outputs: &[Reg]) -> Vec<Reg> {
    let mut needed = vec![false; ops.len()];
    let mut stack: Vec<Reg> = outputs.to_vec();
    while let Some(r) = stack.pop() {
        if std::mem::replace(&mut needed[r as usize], true) {
            continue;
        }
        stack.extend(ops[r as usize].operands());
    }
    (0..ops.len() as Reg)
        .filter(|&r| needed[r as usize])
        .collect()
}

impl<'a> Builder<'a> {
    fn new(store: &'a mut Store) -> Builder<'a> {
        Builder {
            store,
            ops: Vec::new(),
            dedup: FxHashMap::default(),
            memo: FxHashMap::default(),
            trig: FxHashMap::default(),
            vars: Vec::new(),
            var_index: FxHashMap::default(),
            var_regs: FxHashMap::default(),
            shifted_vars: Default::default(),
        }
    }

    /// The output registers of each routine but the input arguments, the
    /// dynamics first, in the order of the runtime's layout.
    fn routine_outputs<E: Copy>(
        &mut self,
        values: &RoutineOutputs<E>,
        output: &mut impl FnMut(&mut Self, E) -> Reg,
    ) -> Vec<(RoutineKind, Vec<Reg>)> {
        let mut dynamics: Vec<Reg> = values.mass.iter().map(|&e| output(self, e)).collect();
        for &f in &values.forcing {
            dynamics.push(output(self, f));
        }
        let [
            kinetic,
            potential,
            dissipation,
            damping_power,
            external_power,
        ] = values.energies;
        let dynamics_and_powers = dynamics
            .iter()
            .copied()
            .chain([output(self, damping_power), output(self, external_power)])
            .collect();
        let energies = [
            kinetic,
            potential,
            dissipation,
            damping_power,
            external_power,
        ]
        .into_iter()
        .map(|e| output(self, e))
        .collect();
        let mut outputs = vec![
            (RoutineKind::Dynamics, dynamics),
            (RoutineKind::Energies, energies),
            (RoutineKind::DynamicsAndPowers, dynamics_and_powers),
        ];
        if let Some(j) = &values.jacobians {
            let regs = j.iter().map(|&e| output(self, e)).collect();
            outputs.push((RoutineKind::Jacobians, regs));
        }
        // Last, so that a model without outputs gets the same program.
        if !values.outputs.is_empty() {
            let regs = values.outputs.iter().map(|&e| output(self, e)).collect();
            outputs.push((RoutineKind::Outputs, regs));
        }
        // After the outputs, for the same reason.
        if !values.constraints.is_empty() {
            let regs = values
                .constraints
                .iter()
                .map(|&e| output(self, e))
                .collect();
            outputs.push((RoutineKind::Constraints, regs));
        }
        outputs
    }

    fn op(&mut self, op: Op) -> Reg {
        let op = match op {
            Op::Add(a, b) if b < a => Op::Add(b, a),
            Op::Mul(a, b) if b < a => Op::Mul(b, a),
            other => other,
        };
        if let Some(&r) = self.dedup.get(&op) {
            return r;
        }
        let r = self.ops.len() as Reg;
        self.ops.push(op.clone());
        self.dedup.insert(op, r);
        r
    }

    fn constant(&mut self, value: f64) -> Reg {
        self.op(Op::constant(value))
    }

    /// A register holding exactly the value of `e` (negation materialized).
    fn output(&mut self, e: ExprId) -> Reg {
        let s = self.expr(e);
        self.materialize(s)
    }

    fn materialize(&mut self, s: Signed) -> Reg {
        if s.negative {
            self.op(Op::Neg(s.reg))
        } else {
            s.reg
        }
    }

    fn expr(&mut self, e: ExprId) -> Signed {
        if let Some(&s) = self.memo.get(&e) {
            return s;
        }
        let s = match self.store.node(e).clone() {
            Node::Num(c) => {
                let r = self.constant(c.to_f64().abs());
                Signed::plus(r).flip(c.is_negative())
            }
            Node::Sym(s) => {
                let op = match self.store.symbol_info(s).kind {
                    SymbolKind::Coordinate(i) => Op::Coordinate(i as u32),
                    SymbolKind::Velocity(i) => Op::Velocity(i as u32),
                    SymbolKind::Acceleration(i) => Op::Acceleration(i as u32),
                    SymbolKind::Parameter(i) => Op::Parameter(i as u32),
                    SymbolKind::Time => Op::Time,
                    SymbolKind::Pi => Op::constant(std::f64::consts::PI),
                    // Formal arguments only occur inside declared derivative templates,
                    // which are substituted before anything is emitted.
                    SymbolKind::InputArgument { .. } => Op::constant(f64::NAN),
                };
                Signed::plus(self.op(op))
            }
            Node::Func(f, args) => self.function(f, &args),
            Node::Input(index, args) => {
                let regs = args.iter().map(|&a| self.output(a)).collect();
                Signed::plus(self.op(Op::Input { index, args: regs }))
            }
            Node::Add(_) | Node::Mul(_) => {
                let terms = self.terms_of(e);
                self.horner(terms)
            }
        };
        self.memo.insert(e, s);
        s
    }

    fn function(&mut self, f: Func, args: &[ExprId]) -> Signed {
        let u = args[0];
        if matches!(f, Func::Sin | Func::Cos)
            && let Some(linear) = self.integer_linear_form(u)
        {
            let (sin, cos) = self.sincos(&linear);
            return if f == Func::Sin { sin } else { cos };
        }
        let args: Vec<Signed> = args.iter().map(|&a| self.expr(a)).collect();
        self.apply(f, &args)
    }

    /// `f(args)` for arguments already in registers.
    fn apply(&mut self, f: Func, args: &[Signed]) -> Signed {
        let arg = args[0];
        match f.elementary() {
            Some(Elementary::Sin) => Signed::plus(self.op(Op::Sin(arg.reg))).flip(arg.negative),
            Some(Elementary::Cos) => Signed::plus(self.op(Op::Cos(arg.reg))),
            Some(Elementary::Exp) => {
                let a = self.materialize(arg);
                Signed::plus(self.op(Op::Exp(a)))
            }
            Some(Elementary::Ln) => {
                let a = self.materialize(arg);
                Signed::plus(self.op(Op::Ln(a)))
            }
            None => {
                let regs: Vec<Reg> = args.iter().map(|&a| self.materialize(a)).collect();
                Signed::plus(self.op(Op::Call(f, regs.into_boxed_slice())))
            }
        }
    }

    /// `u = Σ n_k s_k` with integer `n_k` and symbols `s_k`, when that is worth
    /// lowering (more than one symbol, or a multiple angle).
    fn integer_linear_form(&self, u: ExprId) -> Option<Vec<(ExprId, i64)>> {
        let terms = self.store.terms(u);
        let mut linear = Vec::with_capacity(terms.len());
        for (t, c) in terms {
            self.store.as_symbol(t)?;
            let n = c.to_i64()?;
            if n.abs() > 16 {
                return None;
            }
            linear.push((t, n));
        }
        let worth = linear.len() > 1 || linear.first().is_some_and(|(_, n)| n.abs() > 1);
        worth.then_some(linear)
    }

    /// `(sin u, cos u)` for `u = Σ n_k s_k` by the angle-addition formulas.
    fn sincos(&mut self, linear: &[(ExprId, i64)]) -> (Signed, Signed) {
        if let Some(&r) = self.trig.get(linear) {
            return r;
        }
        let result = match linear {
            [] => (
                Signed::plus(self.constant(0.0)),
                Signed::plus(self.constant(1.0)),
            ),
            [(s, 1)] => {
                let a = self.expr(*s).reg;
                (
                    Signed::plus(self.op(Op::Sin(a))),
                    Signed::plus(self.op(Op::Cos(a))),
                )
            }
            _ if linear[0].1 < 0 => {
                let flipped: Vec<_> = linear.iter().map(|&(s, n)| (s, -n)).collect();
                let (sin, cos) = self.sincos(&flipped);
                (sin.flip(true), cos)
            }
            [(s, n)] => self.angle_sum(&[(*s, 1)], &[(*s, n - 1)]),
            _ => self.angle_sum(&linear[..1], &linear[1..]),
        };
        self.trig.insert(linear.to_vec(), result);
        result
    }

    /// `sin(a+b) = sa·cb + ca·sb`, `cos(a+b) = ca·cb − sa·sb`.
    fn angle_sum(&mut self, a: &[(ExprId, i64)], b: &[(ExprId, i64)]) -> (Signed, Signed) {
        let (sa, ca) = self.sincos(a);
        let (sb, cb) = self.sincos(b);
        let sa_cb = self.mul(sa, cb);
        let ca_sb = self.mul(ca, sb);
        let ca_cb = self.mul(ca, cb);
        let sa_sb = self.mul(sa, sb);
        let sin = self.add(sa_cb, ca_sb);
        let cos = self.add(ca_cb, sa_sb.flip(true));
        (sin, cos)
    }

    fn mul(&mut self, a: Signed, b: Signed) -> Signed {
        Signed::plus(self.op(Op::Mul(a.reg, b.reg))).flip(a.negative != b.negative)
    }

    fn add(&mut self, a: Signed, b: Signed) -> Signed {
        match (a.negative, b.negative) {
            (false, false) => Signed::plus(self.op(Op::Add(a.reg, b.reg))),
            (false, true) => Signed::plus(self.op(Op::Sub(a.reg, b.reg))),
            (true, false) => Signed::plus(self.op(Op::Sub(b.reg, a.reg))),
            (true, true) => Signed::plus(self.op(Op::Add(a.reg, b.reg))).flip(true),
        }
    }

    /// The sum `e` as Horner terms over variables.
    fn terms_of(&mut self, e: ExprId) -> Vec<Term> {
        let terms = self.store.terms(e);
        terms
            .into_iter()
            .map(|(t, coefficient)| {
                let mut vars: Vec<(u32, u128)> = self
                    .store
                    .factors(t)
                    .into_iter()
                    .map(|(base, exp)| {
                        let degree = exp.numer().unsigned_abs();
                        let sign = if exp.is_negative() { -1 } else { 1 };
                        let unit = Rational::new(sign, exp.denom()).unwrap_or(Rational::ONE);
                        (self.var(Var { base, unit }), degree)
                    })
                    .collect();
                vars.sort();
                Term { coefficient, vars }
            })
            .collect()
    }

    fn var(&mut self, v: Var) -> u32 {
        if let Some(&i) = self.var_index.get(&v) {
            return i;
        }
        let i = self.vars.len() as u32;
        self.vars.push(v);
        self.var_index.insert(v, i);
        i
    }

    /// The register of variable `base^unit`.
    fn var_reg(&mut self, index: u32) -> Signed {
        if let Some(&r) = self.var_regs.get(&index) {
            return r;
        }
        let Var { base, unit } = self.vars[index as usize];
        let b = self.expr(base);
        let r = if unit.is_one() {
            b
        } else if unit == Rational::MINUS_ONE {
            let one = self.constant(1.0);
            Signed::plus(self.op(Op::Div(one, b.reg))).flip(b.negative)
        } else {
            let b = self.materialize(b);
            let root = if unit.denom() == 2 {
                self.op(Op::Sqrt(b))
            } else {
                self.op(Op::powf(b, 1.0 / unit.denom() as f64))
            };
            if unit.is_negative() {
                let one = self.constant(1.0);
                Signed::plus(self.op(Op::Div(one, root)))
            } else {
                Signed::plus(root)
            }
        };
        self.var_regs.insert(index, r);
        r
    }

    /// `var^degree` with multiplications for small degrees.
    fn power(&mut self, var: u32, degree: u128) -> Signed {
        let v = self.var_reg(var);
        self.raise(v, degree)
    }

    /// `v^degree`: multiplications up to the cube, then `powi`. The store
    /// keeps exponents within [`crate::expr::MAX_EXPONENT`]; a degree beyond
    /// `i32` would still be exact, as `(v^⌊d/2⌋)² · v^(d mod 2)`.
    fn raise(&mut self, v: Signed, degree: u128) -> Signed {
        match degree {
            1 => v,
            2 => self.mul(v, v),
            3 => {
                let sq = self.mul(v, v);
                self.mul(sq, v)
            }
            _ => match i32::try_from(degree) {
                Ok(n) => {
                    let r = self.op(Op::Powi(v.reg, n));
                    Signed::plus(r).flip(v.negative && n % 2 == 1)
                }
                Err(_) => {
                    let half = self.raise(v, degree / 2);
                    let square = self.mul(half, half);
                    if degree % 2 == 1 {
                        self.mul(square, v)
                    } else {
                        square
                    }
                }
            },
        }
    }

    fn monomial(&mut self, term: &Term) -> Signed {
        let mut acc: Option<Signed> = None;
        for &(var, degree) in &term.vars {
            let p = self.power(var, degree);
            acc = Some(match acc {
                None => p,
                Some(a) => self.mul(a, p),
            });
        }
        let c = term.coefficient;
        let magnitude = c.to_f64().abs();
        let value = match acc {
            None => Signed::plus(self.constant(magnitude)),
            Some(a) if magnitude == 1.0 => a,
            Some(a) => {
                let k = Signed::plus(self.constant(magnitude));
                self.mul(a, k)
            }
        };
        value.flip(c.is_negative())
    }

    /// Greedy multivariate Horner factorization of `Σ terms`.
    fn horner(&mut self, terms: Vec<Term>) -> Signed {
        let mut terms = self.shifted(terms);
        match terms.len() {
            0 => return Signed::plus(self.constant(0.0)),
            1 => return self.monomial(&terms[0]),
            _ => {}
        }
        if let Some(common) = common_coefficient(&terms) {
            for t in &mut terms {
                t.coefficient = t.coefficient.checked_div(common).unwrap_or(t.coefficient);
            }
            let inner = self.horner(terms);
            let k = Signed::plus(self.constant(common.to_f64().abs()));
            return self.mul(inner, k).flip(common.is_negative());
        }
        let mut counts: FxHashMap<u32, usize> = FxHashMap::default();
        for t in &terms {
            for &(v, _) in &t.vars {
                *counts.entry(v).or_default() += 1;
            }
        }
        let best = counts
            .into_iter()
            .filter(|&(_, c)| c >= 2)
            .max_by(|a, b| a.1.cmp(&b.1).then(b.0.cmp(&a.0)))
            .map(|(v, _)| v);
        let Some(v) = best else {
            // No shared variable: a plain sum, positive terms first.
            terms.sort_by_key(|t| t.coefficient.is_negative());
            let mut acc: Option<Signed> = None;
            for t in &terms {
                let m = self.monomial(t);
                acc = Some(match acc {
                    None => m,
                    Some(a) => self.add(a, m),
                });
            }
            return acc.unwrap_or_else(|| Signed::plus(self.constant(0.0)));
        };
        let (mut with, rest): (Vec<Term>, Vec<Term>) = terms
            .into_iter()
            .partition(|t| t.vars.iter().any(|&(w, _)| w == v));
        for t in &mut with {
            if let Some(pos) = t.vars.iter().position(|&(w, _)| w == v) {
                if t.vars[pos].1 == 1 {
                    t.vars.remove(pos);
                } else {
                    t.vars[pos].1 -= 1;
                }
            }
        }
        let inner = self.horner(with);
        let factor = self.var_reg(v);
        let product = self.mul(factor, inner);
        if rest.is_empty() {
            product
        } else {
            let r = self.horner(rest);
            self.add(product, r)
        }
    }
}

/// `c` when every coefficient is `±c` with `c ≠ 1` (factored out once).
fn common_coefficient(terms: &[Term]) -> Option<Rational> {
    let first = terms.first()?.coefficient;
    let magnitude = if first.is_negative() {
        first.checked_neg()?
    } else {
        first
    };
    if magnitude.is_one() {
        return None;
    }
    let all = terms
        .iter()
        .all(|t| t.coefficient == magnitude || t.coefficient.checked_neg() == Some(magnitude));
    all.then_some(magnitude)
}
