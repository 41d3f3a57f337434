//! Translating `syn` expressions into canonical symbolic expressions.

use super::constant::{self, Constants};
use super::domain::{Domain, DomainCheck};
use crate::diagnostic::{Diagnostic, SpanRange, closest};
use crate::expr::{
    CoordinateSymbols, EngineError, ExprId, Func, MAX_EXPANDED_TERMS, MAX_EXPONENT, MAX_NODES,
    MAX_PRODUCT_TERMS, Store, SymbolId,
};
use crate::rational::Rational;
use proc_macro2::Span;
use rustc_hash::FxHashMap;
use syn::spanned::Spanned;
use syn::{BinOp, Expr, Lit, UnOp};

/// What a name in an expression refers to.
#[derive(Clone, Debug)]
pub(super) enum Binding {
    /// A value: coordinate, parameter, formal argument, time, π.
    Value(ExprId),
    /// A `let` definition, with the input calls it contains.
    Definition(ExprId, Vec<(usize, SpanRange)>),
    /// An input function with its arity.
    Input(usize, usize),
    /// A `let` whose definition has an error (reported there).
    Failed,
    /// An output: computed after the solve, not a value expressions can use.
    Output,
    /// A constraint's name: it names the equation and its multiplier, not a
    /// value expressions can use.
    Constraint,
}

/// Name resolution and the model's symbols, shared by all statements.
pub(super) struct Scope {
    pub names: FxHashMap<String, (Binding, Span)>,
    pub coordinates: Vec<CoordinateSymbols>,
    pub time: SymbolId,
    pub velocities: Vec<SymbolId>,
    /// Values of the constant `let`s, for exponents.
    pub constants: Constants,
    /// The calls with a restricted domain lowered so far, in order.
    pub domain_checks: std::cell::RefCell<Vec<DomainCheck>>,
}

/// The result of lowering one expression.
pub(super) struct Lowered {
    pub value: ExprId,
    pub input_calls: Vec<(usize, SpanRange)>,
}

/// The built-in calls that are not an atom of the expression engine (those
/// are [`Func::ALL`]), with their number of arguments. `tan`, `cot` and `sec`
/// are rewritten in sines and cosines, `sqrt` and `pow` are powers.
const FUNCTIONS: &[(&str, usize)] = &[
    ("tan", 1),
    ("cot", 1),
    ("sec", 1),
    ("sqrt", 1),
    ("pow", 2),
    ("dot", 1),
    ("ddot", 1),
];

/// The number of arguments of the built-in function `name`, if it is one.
pub(super) fn builtin_arity(name: &str) -> Option<usize> {
    match Func::named(name) {
        Some(f) => Some(f.arity()),
        None => FUNCTIONS.iter().find(|(f, _)| *f == name).map(|&(_, n)| n),
    }
}

/// Every built-in function name, for suggestions.
fn builtin_names<'n>() -> impl Iterator<Item = &'n str> {
    (Func::ALL.iter().map(|f| f.name())).chain(FUNCTIONS.iter().map(|(f, _)| *f))
}

pub(super) struct ExpressionLowering<'a> {
    pub store: &'a mut Store,
    pub scope: &'a Scope,
    pub input_names: &'a [String],
    input_calls: Vec<(usize, SpanRange)>,
    /// `ddot(q)` is allowed (outputs and hand-derived equations only).
    accelerations: bool,
}

impl<'a> ExpressionLowering<'a> {
    pub fn new(store: &'a mut Store, scope: &'a Scope, input_names: &'a [String]) -> Self {
        ExpressionLowering {
            store,
            scope,
            input_names,
            input_calls: Vec::new(),
            accelerations: false,
        }
    }

    /// Allows `ddot(q)`, the second time derivative (outputs and
    /// hand-derived equations).
    pub fn with_accelerations(mut self) -> Self {
        self.accelerations = true;
        self
    }

    pub fn lower(mut self, expr: &Expr) -> Result<Lowered, Diagnostic> {
        let value = self.expr(expr)?;
        if let Some(error) = self.store.take_errors().into_iter().next() {
            let span = SpanRange::of(expr);
            let what = "this expression";
            return Err(engine_diagnostic(
                self.store,
                self.input_names,
                error,
                span,
                what,
            ));
        }
        Ok(Lowered {
            value,
            input_calls: self.input_calls,
        })
    }

    /// Turns errors recorded by the engine into a diagnostic at `span`.
    fn check_engine(&mut self, span: SpanRange, what: &str) -> Result<(), Diagnostic> {
        match self.store.take_errors().into_iter().next() {
            None => Ok(()),
            Some(error) => Err(engine_diagnostic(
                self.store,
                self.input_names,
                error,
                span,
                what,
            )),
        }
    }

    fn expr(&mut self, expr: &Expr) -> Result<ExprId, Diagnostic> {
        match expr {
            Expr::Lit(lit) => literal(&lit.lit).map(|r| self.store.num(r)),
            Expr::Paren(p) => self.expr(&p.expr),
            Expr::Group(g) => self.expr(&g.expr),
            Expr::Unary(u) => match u.op {
                UnOp::Neg(_) => {
                    let v = self.expr(&u.expr)?;
                    Ok(self.store.neg(v))
                }
                UnOp::Deref(_) => Err(Diagnostic::new(
                    SpanRange::of(expr),
                    "`**` is not a power in Rust syntax: `x ** 2` reads as `x * (*2)`, \
                     a product with a dereference",
                )
                .with_help("write the power as `pow(x, 2)` or `x.powi(2)`")),
                _ => Err(unsupported(expr, "this unary operator")),
            },
            Expr::Binary(b) => self.binary(b),
            Expr::Path(p) => {
                let ident = p.path.get_ident().filter(|_| p.qself.is_none());
                let Some(ident) = ident else {
                    return Err(Diagnostic::new(
                        SpanRange::of(p),
                        "paths are not allowed in a spec; use a plain name",
                    ));
                };
                self.name(ident)
            }
            Expr::Call(call) => {
                let Expr::Path(p) = &*call.func else {
                    return Err(unsupported(&call.func, "this kind of call"));
                };
                let Some(ident) = p.path.get_ident() else {
                    return Err(Diagnostic::new(
                        SpanRange::of(p),
                        "expected a function name",
                    ));
                };
                let args: Vec<&Expr> = call.args.iter().collect();
                self.call(ident, &args, SpanRange::of(call))
            }
            Expr::MethodCall(m) => {
                let mut args = vec![&*m.receiver];
                args.extend(m.args.iter());
                self.method(&m.method, &args, SpanRange::of(m))
            }
            _ => Err(unsupported(expr, "this expression")),
        }
    }

    fn binary(&mut self, b: &syn::ExprBinary) -> Result<ExprId, Diagnostic> {
        if let BinOp::BitXor(op) = b.op {
            return Err(Diagnostic::new(
                op.span(),
                "`^` is bitwise XOR in Rust syntax and binds more loosely than `+` \
                 (`x^2 + y` would mean `x^(2 + y)`)",
            )
            .with_help("write the power as `pow(x, 2)` or `x.powi(2)`"));
        }
        // `a + b − c …` (and `a * b / c …`) is a left-deep tree as deep as it
        // is long: its left spine is walked with a loop, not recursion.
        let (mut spine, mut deepest) = (Vec::new(), b);
        loop {
            spine.push(deepest);
            match &*deepest.left {
                Expr::Binary(inner) if is_arithmetic(inner.op) => deepest = inner,
                _ => break,
            }
        }
        let mut value = self.expr(&deepest.left)?;
        for node in spine.into_iter().rev() {
            let rhs = self.expr(&node.right)?;
            value = self.apply(node, value, rhs)?;
        }
        Ok(value)
    }

    /// `lhs op rhs` for the operator of `b`.
    fn apply(
        &mut self,
        b: &syn::ExprBinary,
        lhs: ExprId,
        rhs: ExprId,
    ) -> Result<ExprId, Diagnostic> {
        match b.op {
            BinOp::Add(_) => Ok(self.store.add(lhs, rhs)),
            BinOp::Sub(_) => Ok(self.store.sub(lhs, rhs)),
            BinOp::Mul(_) => Ok(self.store.mul(lhs, rhs)),
            BinOp::Div(_) => {
                if rhs == Store::ZERO {
                    return Err(Diagnostic::new(SpanRange::of(&b.right), "division by zero"));
                }
                let divisor = SpanRange::of(&b.right);
                self.restricted(Domain::NonZero, "the divisor", rhs, divisor);
                Ok(self.store.div(lhs, rhs))
            }
            _ => Err(Diagnostic::new(
                b.op.span(),
                "unsupported operator in a spec; only `+`, `-`, `*` and `/` are allowed",
            )),
        }
    }

    fn name(&mut self, ident: &syn::Ident) -> Result<ExprId, Diagnostic> {
        let name = ident.to_string();
        match self.scope.names.get(&name) {
            Some((Binding::Value(v), _)) => Ok(*v),
            Some((Binding::Failed, _)) => Err(Diagnostic::follows_earlier(ident.span())),
            Some((Binding::Definition(v, calls), _)) => {
                self.input_calls.extend(calls.iter().cloned());
                Ok(*v)
            }
            Some((Binding::Input(_, arity), decl)) => Err(Diagnostic::new(
                ident.span(),
                format!("input function `{name}` must be called with its {arity} argument(s)"),
            )
            .with_note(format!("`{name}` is declared here"), *decl)),
            Some((Binding::Output, decl)) => Err(Diagnostic::new(
                ident.span(),
                format!("`{name}` is an output, which expressions cannot use"),
            )
            .with_note(format!("`{name}` is declared here"), *decl)
            .with_help("name the expression with `let` and use that name in both places")),
            Some((Binding::Constraint, decl)) => Err(Diagnostic::new(
                ident.span(),
                format!("`{name}` is a constraint, which expressions cannot use"),
            )
            .with_note(format!("`{name}` is declared here"), *decl)
            .with_help("name the expression with `let` and use that name in both places")),
            None if builtin_arity(&name).is_some() => Err(Diagnostic::new(
                ident.span(),
                format!("`{name}` is a function; call it as `{name}(…)`"),
            )),
            None => Err(self.unknown(ident, "name")),
        }
    }

    fn unknown(&self, ident: &syn::Ident, what: &str) -> Diagnostic {
        let name = ident.to_string();
        let mut candidates: Vec<&str> = self.scope.names.keys().map(String::as_str).collect();
        candidates.extend(builtin_names());
        let diagnostic = Diagnostic::new(ident.span(), format!("unknown {what} `{name}`"));
        match closest(&name, candidates) {
            Some(best) => diagnostic.with_help(format!("did you mean `{best}`?")),
            None => diagnostic.with_help(
                "declare it under `coordinates`, `parameters` or `inputs`, or with `let`",
            ),
        }
    }

    fn call(
        &mut self,
        ident: &syn::Ident,
        args: &[&Expr],
        span: SpanRange,
    ) -> Result<ExprId, Diagnostic> {
        let name = ident.to_string();
        // A declared name hides a function that is not reserved.
        if !self.scope.names.contains_key(&name)
            && let Some(arity) = builtin_arity(&name)
        {
            check_arity(ident, &name, arity, args.len(), span)?;
            return self.builtin(&name, args, span);
        }
        match self.scope.names.get(&name) {
            Some((Binding::Input(index, arity), _)) => {
                let (index, arity) = (*index, *arity);
                check_arity(ident, &name, arity, args.len(), span)?;
                // An argument may call inputs itself: they are evaluated
                // innermost first, wherever the call is evaluated.
                let values = args
                    .iter()
                    .map(|a| self.expr(a))
                    .collect::<Result<Vec<_>, _>>()?;
                self.input_calls.push((index, span));
                Ok(self.store.input_call(index, values))
            }
            Some(_) => Err(Diagnostic::new(
                ident.span(),
                format!("`{name}` is not a function"),
            )),
            None => Err(self.unknown(ident, "function")),
        }
    }

    fn builtin(
        &mut self,
        name: &str,
        args: &[&Expr],
        span: SpanRange,
    ) -> Result<ExprId, Diagnostic> {
        if name == "pow" {
            let base = self.expr(args[0])?;
            let exponent = self.constant_exponent(args[1])?;
            return self.power(base, exponent, span);
        }
        if let Some(f) = Func::named(name) {
            return self.function(f, args, span);
        }
        let x = self.expr(args[0])?;
        if name == "sqrt"
            && let Some(c) = self.store.as_num(x)
            && c.is_negative()
        {
            let problem = "the square root of a negative number is not real";
            return Err(Diagnostic::new(
                span,
                format!("`sqrt` of the constant {c}: {problem}"),
            ));
        }
        Ok(match name {
            "tan" => self.store.tan(x),
            "cot" => {
                let (s, c) = (self.store.sin(x), self.store.cos(x));
                self.store.div(c, s)
            }
            "sec" => {
                let c = self.store.cos(x);
                self.store.pow(c, Rational::MINUS_ONE)
            }
            "sqrt" => {
                self.restricted(Domain::NonNegative, "the argument of", x, span);
                self.store.sqrt(x)
            }
            "ddot" => {
                if !self.accelerations {
                    return Err(acceleration_outside_outputs(span));
                }
                let velocity = self.dot(x, span)?;
                let d =
                    self.store
                        .time_derivative(velocity, &self.scope.coordinates, self.scope.time);
                self.check_engine(span, "`ddot`")?;
                d
            }
            _ => self.dot(x, span)?,
        })
    }

    /// `f(args…)` for a function of the expression engine.
    fn function(&mut self, f: Func, args: &[&Expr], span: SpanRange) -> Result<ExprId, Diagnostic> {
        let values = (args.iter())
            .map(|a| self.expr(a))
            .collect::<Result<Vec<_>, _>>()?;
        match self.store.as_num(values[0]) {
            Some(c) => check_constant_argument(f, c, span)?,
            None => {
                if let Some(domain) = f.domain() {
                    self.restricted(domain, "the argument of", values[0], span);
                }
            }
        }
        Ok(self.store.apply(f, &values))
    }

    /// Records a call whose `argument` must lie in `domain`.
    fn restricted(&self, domain: Domain, what: &'static str, argument: ExprId, span: SpanRange) {
        if self.store.as_num(argument).is_none() {
            let check = DomainCheck {
                domain,
                what,
                argument,
                span,
            };
            self.scope.domain_checks.borrow_mut().push(check);
        }
    }

    fn method(
        &mut self,
        method: &syn::Ident,
        args: &[&Expr],
        span: SpanRange,
    ) -> Result<ExprId, Diagnostic> {
        let name = method.to_string();
        if let Some(f) = Func::named(&name) {
            check_arity(method, &name, f.arity() - 1, args.len() - 1, span)?;
            return self.function(f, args, span);
        }
        match name.as_str() {
            "tan" | "sqrt" => {
                check_arity(method, &name, 0, args.len() - 1, span)?;
                self.builtin(&name, args, span)
            }
            "powi" | "powf" => {
                check_arity(method, &name, 1, args.len() - 1, span)?;
                let base = self.expr(args[0])?;
                let exponent = self.constant_exponent(args[1])?;
                if name == "powi" && !exponent.is_integer() {
                    return Err(Diagnostic::new(
                        SpanRange::of(args[1]),
                        "`powi` takes an integer exponent; use `powf` or `pow` for fractions",
                    ));
                }
                self.power(base, exponent, span)
            }
            _ => Err(
                Diagnostic::new(method.span(), format!("unsupported method `{name}`")).with_help(
                    "supported: .sin() .cos() .tan() .exp() .ln() .sqrt() .powi(n) .powf(x), \
                     and the methods of the functions (.abs(), .atan2(x), .min(b), …)",
                ),
            ),
        }
    }

    fn power(
        &mut self,
        base: ExprId,
        exponent: Rational,
        span: SpanRange,
    ) -> Result<ExprId, Diagnostic> {
        if base == Store::ZERO && exponent.is_negative() {
            return Err(Diagnostic::new(span, "zero raised to a negative power"));
        }
        if !exponent.is_integer() {
            self.restricted(Domain::NonNegative, "the base of", base, span);
        } else if exponent.is_negative() {
            self.restricted(Domain::NonZero, "the base of", base, span);
        }
        let value = self.store.pow(base, exponent);
        self.check_engine(span, "this power")?;
        if let Some(c) = self.store.as_num(base)
            && c.is_negative()
            && !exponent.is_integer()
            && self.store.as_num(value).is_none()
        {
            return Err(Diagnostic::new(
                span,
                format!("the negative constant {c} to the power {exponent} is not a real number"),
            )
            .with_help("the emitted code computes it with powf, which gives NaN"));
        }
        Ok(value)
    }

    /// Exponents must be exact constants, so that derivatives stay exact.
    /// They are evaluated by [`constant::evaluate`], as the dimension checker does.
    fn constant_exponent(&mut self, expr: &Expr) -> Result<Rational, Diagnostic> {
        if let Some(value) = constant::evaluate(expr, &self.scope.constants)? {
            return Ok(value);
        }
        // Not a constant: report an unknown name in it first, if any.
        self.expr(expr)?;
        Err(Diagnostic::new(
            SpanRange::of(expr),
            "the exponent must be a constant number",
        )
        .with_help("write exp(y * ln(x)) for a variable exponent"))
    }

    /// `dot(e)`: the total time derivative of a function of coordinates and time.
    fn dot(&mut self, x: ExprId, span: SpanRange) -> Result<ExprId, Diagnostic> {
        if let Some(v) = self
            .scope
            .velocities
            .iter()
            .find(|v| self.store.depends_on(x, **v))
        {
            let name = self.store.symbol_info(*v).name.clone();
            return Err(Diagnostic::new(
                span,
                format!("`dot` of an expression that already contains the velocity `{name}`"),
            )
            .with_help("`dot` applies to positions (functions of the coordinates and time); accelerations cannot appear in T, V, D or forces"));
        }
        let d = self
            .store
            .time_derivative(x, &self.scope.coordinates, self.scope.time);
        self.check_engine(span, "`dot`")?;
        Ok(d)
    }
}

/// `ddot` where accelerations are not available: everywhere but in outputs
/// and `hand_derived` equations.
fn acceleration_outside_outputs(span: SpanRange) -> Diagnostic {
    Diagnostic::new(
        span,
        "`ddot` is only available in `hand_derived` equations and in outputs: \
         accelerations are what the equations of motion solve for, not an input to them",
    )
    .with_help(
        "T, V, D, forces and `let` definitions cannot contain them; to report an \
         acceleration, write `output name = ddot(…);` (a `let` may name the position)",
    )
}

/// `sqrt` and `ln` of a constant outside their domain would only show at
/// run time, as a non-finite M or f: report them at the call.
/// A constant argument outside `f`'s domain, refused where it is written.
fn check_constant_argument(f: Func, c: Rational, span: SpanRange) -> Result<(), Diagnostic> {
    match f.domain() {
        Some(domain) if !domain.contains(c.to_f64()) => Err(Diagnostic::new(
            span,
            format!("`{}` of the constant {c}: {}", f.name(), domain.refusal()),
        )),
        Some(_) | None => Ok(()),
    }
}

/// `+ - * /`, the operators a left spine may chain.
pub(super) fn is_arithmetic(op: BinOp) -> bool {
    matches!(
        op,
        BinOp::Add(_) | BinOp::Sub(_) | BinOp::Mul(_) | BinOp::Div(_)
    )
}

fn check_arity(
    ident: &syn::Ident,
    name: &str,
    expected: usize,
    found: usize,
    span: SpanRange,
) -> Result<(), Diagnostic> {
    if expected == found {
        return Ok(());
    }
    let _ = ident;
    Err(Diagnostic::new(
        span,
        format!("`{name}` takes {expected} argument(s) but {found} were given"),
    ))
}

fn unsupported(expr: &impl quote::ToTokens, what: &str) -> Diagnostic {
    Diagnostic::new(SpanRange::of(expr), format!("{what} is not supported in a spec"))
        .with_help("expressions are numbers, names, `+ - * /`, parentheses, function calls and `.powi(n)`-style methods")
}

/// An integer or decimal literal as an exact rational.
pub(super) fn literal(lit: &Lit) -> Result<Rational, Diagnostic> {
    let digits = literal_digits(lit)?;
    Rational::parse_decimal(&digits).ok_or_else(|| {
        Diagnostic::new(
            lit.span(),
            format!("the literal `{digits}` is too large, or has too many significant digits, for an exact rational of 128-bit integers"),
        )
        .with_help("coefficients in expressions are exact fractions; declare a parameter for this value (a parameter's default may be any f64, e.g. `k = 1e42`)")
    })
}

/// A parameter default written as a number or a negated number, as an f64:
/// defaults need not be exact, so `1e42` is fine. `None` for any other expression.
pub(super) fn literal_default(expr: &Expr) -> Option<Result<f64, Diagnostic>> {
    let (lit, negative) = match expr {
        Expr::Lit(l) => (&l.lit, false),
        Expr::Unary(u) if matches!(u.op, UnOp::Neg(_)) => match &*u.expr {
            Expr::Lit(l) => (&l.lit, true),
            _ => return None,
        },
        _ => return None,
    };
    let value = literal_digits(lit).and_then(|digits| {
        digits
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| Diagnostic::new(lit.span(), format!("`{digits}` is not a finite f64")))
    });
    Some(value.map(|v| if negative { -v } else { v }))
}

/// The decimal digits of a numeric literal, whose suffix must be none or `f64`.
fn literal_digits(lit: &Lit) -> Result<String, Diagnostic> {
    let (digits, suffix) = match lit {
        Lit::Int(i) => (i.base10_digits().to_string(), i.suffix().to_string()),
        Lit::Float(f) => (f.base10_digits().to_string(), f.suffix().to_string()),
        _ => {
            return Err(Diagnostic::new(
                lit.span(),
                "only numeric literals are allowed in expressions",
            ));
        }
    };
    if !suffix.is_empty() && suffix != "f64" {
        return Err(
            Diagnostic::new(lit.span(), format!("unsupported literal suffix `{suffix}`"))
                .with_help("units go in brackets after a declaration, e.g. `m1 [kg] = 539.0`"),
        );
    }
    Ok(digits)
}

/// Explains an engine error that happened while building `what` at `span`.
pub(crate) fn engine_diagnostic(
    store: &Store,
    input_names: &[String],
    error: EngineError,
    span: SpanRange,
    what: &str,
) -> Diagnostic {
    match error {
        EngineError::Overflow => Diagnostic::new(
            span,
            format!("exact coefficients in {what} exceed 128-bit fractions"),
        ),
        EngineError::DivisionByZero => Diagnostic::new(span, format!("division by zero in {what}")),
        EngineError::ExponentTooLarge(e) => Diagnostic::new(
            span,
            format!("{what} has the exponent {e}, beyond the supported range"),
        )
        .with_help(format!(
            "exponents are exact fractions p/q with |p| and q at most {MAX_EXPONENT}"
        )),
        EngineError::ExpansionTooLarge {
            exponent,
            sum_terms,
        } => Diagnostic::new(
            span,
            format!(
                "{what} raises a sum of {sum_terms} terms to the power {exponent}, whose expansion would have more than {MAX_EXPANDED_TERMS} terms"
            ),
        )
        .with_help(
            "powers of sums are expanded into monomials; lower the exponent, or make the sum a parameter",
        ),
        EngineError::ProductTooLarge { terms: (a, b) } => Diagnostic::new(
            span,
            format!(
                "{what} multiplies a sum of {a} terms by a sum of {b}, whose expansion would have more than {MAX_PRODUCT_TERMS} terms"
            ),
        )
        .with_help(
            "products of sums are expanded into monomials; simplify the model, or make a sum a parameter",
        ),
        EngineError::ModelTooLarge => Diagnostic::new(
            span,
            format!("{what} needs more than {MAX_NODES} distinct expressions to derive"),
        )
        .with_help(
            "products of long sums are expanded into monomials; name repeated sums with `let` on a parameter-only expression, or simplify the model",
        ),
        EngineError::MissingDerivative { input, argument } => {
            let info = &store.inputs()[input];
            let arg = store.symbol_info(info.arguments[argument]).name.clone();
            Diagnostic::new(
                span,
                format!(
                    "{what} needs the derivative of input function `{}` with respect to its argument `{arg}`, which is not declared",
                    input_names[input]
                ),
            )
            .with_help(format!(
                "declare it in the `inputs` block: `{}(…) {{ d({arg}) = … }}`",
                input_names[input]
            ))
        }
    }
}
