//! The syntax tree of a model specification, as written (names unresolved).

use proc_macro2::Span;
use syn::{Expr, Ident};

/// A whole spec: `model Name;` and its blocks and statements, in source order.
pub struct SpecAst {
    /// `//!` doc lines at the top of a spec file.
    pub inner_doc: Vec<String>,
    pub items: Vec<Item>,
}

/// A physical unit as written between brackets, e.g. `[N*s/m]`.
#[derive(Clone, Debug)]
pub struct UnitText {
    /// The unit between the brackets, e.g. `N*s/m`.
    pub text: String,
    /// Where it is written, for errors about it.
    pub span: Span,
}

#[derive(Clone)]
pub struct Declaration {
    pub doc: Vec<String>,
    pub name: Ident,
    /// `[…]` after the name: a family (`x[7]`) or one of its elements
    /// (`c[i]`); expansion ([`super::families`]) removes it.
    pub subscript: Option<Subscript>,
    pub unit: Option<UnitText>,
}

/// `[…]` after a name: a family's elements where it is declared (`x[7]`,
/// `m[i in 1..=7]`), one element where a statement defines it (`c[i]`).
#[derive(Clone)]
pub enum Subscript {
    /// `[7]`: elements 1 to 7.
    Count { count: usize, span: Span },
    /// `[i in 1..=7]`: elements 1 to 7, `i` naming each in the
    /// declaration's expressions.
    Ranged {
        index: Ident,
        range: Expr,
        span: Span,
    },
    /// `[expr]`: the element `expr` evaluates to.
    Element(Expr),
}

#[derive(Clone)]
pub struct ParameterDecl {
    pub decl: Declaration,
    /// Default value, a constant expression such as `2.0 * 30000.0`.
    pub value: Option<Expr>,
}

#[derive(Clone)]
pub struct InputDecl {
    pub decl: Declaration,
    pub arguments: Vec<Declaration>,
    /// Declared partial derivatives: `d(arg) = expression`.
    pub derivatives: Vec<(Ident, Expr)>,
    /// `d(arg)` without an expression: the derivative the component bound
    /// to the input supplies (expansion makes it an input of its own).
    pub supplied: Vec<Ident>,
}

/// `output NAME [unit] = expr;`, with its `///` doc lines.
#[derive(Clone)]
pub struct OutputDecl {
    pub decl: Declaration,
    pub value: Expr,
}

/// `constraint NAME = expr;`, with its `///` doc lines: `expr(q, t) = 0`.
#[derive(Clone)]
pub struct ConstraintDecl {
    pub doc: Vec<String>,
    pub name: Ident,
    /// `constraint g[i] = …;` in a loop (expansion removes it).
    pub subscript: Option<Subscript>,
    pub value: Expr,
}

/// The three scalar functions a spec may give, each at most once.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum EnergyKind {
    /// `kinetic = …;`, the kinetic energy `T` (required).
    Kinetic,
    /// `potential = …;`, the potential energy `V`.
    Potential,
    /// `dissipation = …;`, the Rayleigh dissipation function `D`, a power.
    Dissipation,
}

impl EnergyKind {
    /// The keyword that introduces it in a spec.
    pub fn keyword(self) -> &'static str {
        match self {
            EnergyKind::Kinetic => "kinetic",
            EnergyKind::Potential => "potential",
            EnergyKind::Dissipation => "dissipation",
        }
    }

    /// Its name in messages, e.g. `kinetic energy`.
    pub fn description(self) -> &'static str {
        match self {
            EnergyKind::Kinetic => "kinetic energy",
            EnergyKind::Potential => "potential energy",
            EnergyKind::Dissipation => "dissipation function",
        }
    }
}

#[derive(Clone)]
pub enum Item {
    Model {
        doc: Vec<String>,
        name: Ident,
    },
    Coordinates {
        keyword: Span,
        decls: Vec<Declaration>,
    },
    Parameters {
        decls: Vec<ParameterDecl>,
    },
    Inputs {
        decls: Vec<InputDecl>,
    },
    Let {
        name: Ident,
        /// `let c[i] = …;` (expansion removes it).
        subscript: Option<Subscript>,
        value: Expr,
    },
    Energy {
        kind: EnergyKind,
        keyword: Span,
        value: Expr,
    },
    /// `force q = Q;` — a generalized force on coordinate `q`.
    GeneralizedForce {
        keyword: Span,
        coordinate: Ident,
        /// `force x[i] = …;` (expansion removes it).
        subscript: Option<Subscript>,
        value: Expr,
    },
    /// `force at (x, z) = (Fx, Fz);` — a force applied at a point.
    PointForce {
        point: Vec<Expr>,
        point_span: Span,
        components: Vec<Expr>,
        components_span: Span,
    },
    /// `output NAME [unit] = expr;` — a quantity computed at every sample
    /// after the solve, which may use the accelerations `ddot(q)`.
    Output(OutputDecl),
    /// `constraint NAME = expr;` — a holonomic constraint `expr(q, t) = 0`,
    /// held by a Lagrange multiplier.
    Constraint(ConstraintDecl),
    /// `jacobians;` — also derive ∂f/∂q, ∂f/∂q̇ and ∂(M a)/∂q.
    Jacobians {
        keyword: Span,
    },
    /// `hand_derived { … }` — equations derived by hand, for the audit.
    HandDerived(HandSection),
    /// `for i in 1..=6 { … }` — the statements once for each `i`
    /// (expansion replaces it by them).
    For {
        keyword: Span,
        index: Ident,
        range: Expr,
        items: Vec<Item>,
    },
    /// `part spring_damper(a [m], b [m]) { … }` — a reusable part
    /// ([`super::parts`] writes each instance out).
    PartDef(PartDef),
    /// `part front = spring_damper(x[1], x[2]) { k = 2e5 };` — an instance
    /// of a part.
    PartInstance(PartInstance),
}

/// A part's definition: the coordinates it acts between (its ports) and
/// the items it adds to a model for each instance.
#[derive(Clone)]
pub struct PartDef {
    pub name: Ident,
    /// The coordinates the part acts between, each a name and a unit.
    pub ports: Vec<Declaration>,
    /// Its blocks and statements, in the spec language.
    pub items: Vec<Item>,
}

/// `part NAME = PART(ARG, …) { PARAMETER = VALUE, … };`
#[derive(Clone)]
pub struct PartInstance {
    /// The instance's name, the prefix of its names (`front.k`).
    pub name: Ident,
    /// `part s[i] = …` in a loop (expansion removes it).
    pub subscript: Option<Subscript>,
    /// The part instantiated.
    pub part: Ident,
    /// An expression of the model's coordinates for each port, in order.
    pub arguments: Vec<Expr>,
    /// The parentheses around the arguments.
    pub arguments_span: Span,
    /// The part's parameter defaults this instance changes.
    pub settings: Vec<(Ident, Expr)>,
}

/// A user's own equations of motion, to be audited against the derivation.
#[derive(Clone)]
pub struct HandSection {
    pub keyword: Span,
    pub doc: Vec<String>,
    /// `convention = name;`
    pub convention: Option<Ident>,
    /// `small_angle_order = n;`
    pub small_angle_order: Option<syn::LitInt>,
    /// `symbols { name = expression, … }`: the hand derivation's own names.
    pub symbols: Vec<(Ident, Expr)>,
    /// `assume { input = expression, … }`: values of inputs the hand model lacks.
    pub assumptions: Vec<(Ident, Expr)>,
    /// `q = expression;`: the left-hand side of the equation of coordinate `q`.
    pub equations: Vec<(Ident, Expr)>,
    /// `force q = expression;`: the generalized force on `q`.
    pub forces: Vec<(Ident, Expr)>,
}
