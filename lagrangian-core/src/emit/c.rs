//! C99 code for a compiled model: one function per routine, for embedding a
//! model in C programs (and, later, in an FMU).
//!
//! # The interface
//!
//! [`emit_c`] writes one translation unit. With `<p>` the prefix
//! ([`COptions::prefix`], by default the model's name in snake case) and
//! `<P>` the same in capitals, it defines
//!
//! ```c
//! typedef double (*lagrangian_input)(void *context, int index, const double *args, int count);
//!
//! #define <P>_DIMENSION        /* n, the number of coordinates */
//! #define <P>_PARAMETERS       /* the number of parameters */
//! #define <P>_INPUTS           /* the number of input functions */
//! #define <P>_INPUT_ARGUMENTS  /* the length of <p>_input_arguments' output */
//! #define <P>_HAS_JACOBIANS    /* 1 when the spec asks for `jacobians;` */
//! extern const char *const <p>_model_name;
//! extern const char *const <p>_coordinate_names[]; /* each list ends with NULL */
//! extern const char *const <p>_parameter_names[];
//! extern const char *const <p>_input_names[];
//! void <p>_default_parameters(double *p);
//!
//! void <p>_dynamics(const double *p, double t, const double *q, const double *qd,
//!                   lagrangian_input input, void *context, double *mass, double *forcing);
//! void <p>_energies(const double *p, double t, const double *q, const double *qd,
//!                   lagrangian_input input, void *context, double *energies);
//! void <p>_dynamics_and_powers(const double *p, double t, const double *q, const double *qd,
//!                   lagrangian_input input, void *context,
//!                   double *mass, double *forcing, double *energies);
//! void <p>_jacobians(const double *p, double t, const double *q, const double *qd,
//!                   const double *qdd, lagrangian_input input, void *context,
//!                   double *forcing_q, double *forcing_qd, double *mass_times_acceleration_q);
//! void <p>_input_arguments(const double *p, double t, const double *q, const double *qd,
//!                   lagrangian_input input, void *context, double *arguments);
//!
//! /* Only for a spec with outputs (`output NAME [unit] = expr;`): */
//! #define <P>_OUTPUTS          /* the number of outputs */
//! extern const char *const <p>_output_names[];
//! void <p>_outputs(const double *p, double t, const double *q, const double *qd,
//!                   const double *qdd, lagrangian_input input, void *context, double *outputs);
//!
//! /* Only for a spec with constraints (`constraint NAME = expr;`): */
//! #define <P>_CONSTRAINTS      /* m, the number of constraints */
//! extern const char *const <p>_constraint_names[];
//! void <p>_constraints(const double *p, double t, const double *q, const double *qd,
//!                   lagrangian_input input, void *context, double *constraints);
//! ```
//!
//! * `p` holds the parameters in declaration order; `q`, `qd` (and `qdd`)
//!   hold `n` values each.
//! * `mass` is row-major `n × n`, both triangles written; `forcing` holds
//!   `n` values. The equations are `M(q, t) q̈ = f(q, q̇, t)`.
//! * `energies` holds 5 values in the order of `Energies::FIELDS`: `T`,
//!   `V`, `D`, `Σ ∂D/∂q̇·q̇`, `Σ Q·q̇`; `<p>_dynamics_and_powers` writes the
//!   last two only.
//! * The Jacobian blocks are row-major `n × n` (`JACOBIAN_BLOCKS`); the
//!   function exists when `<P>_HAS_JACOBIANS` is 1.
//! * `arguments` receives the arguments of every input call of the
//!   dynamics, concatenated in the order of the model's input sites.
//! * `outputs` receives the value of each output, in declaration order, at
//!   `(t, q, q̇, q̈)`: pass the accelerations the dynamics give there.
//! * `constraints` receives `g` (m), `∂g/∂t` (m), `G = ∂g/∂q` (m × n,
//!   row-major) and `γ` (m, with `G q̈ = γ`), concatenated; the constrained
//!   equations are `M q̈ = f + Gᵀλ`, `G q̈ = γ`.
//! * Input functions are called as `input(context, index, args, count)`
//!   with the index in declaration order; `context` is passed through
//!   untouched. With `input == NULL` every input call yields NaN.
//!
//! # Agreement with the Rust code
//!
//! Every function performs the operations of the program routine's
//! [`schedule`](super::schedule), in the same order, with `sin`, `cos`,
//! `exp`, `log`, `sqrt` and `pow` of `<math.h>`, the functions Rust's `f64`
//! methods call. Integer powers go through a helper that multiplies by
//! binary decomposition in the order of Rust's `powi` (compiler-builtins'
//! `__powidf2`; not the correctly rounded `pow`), so with IEEE double
//! arithmetic, the same `libm` and no contraction of `a * b + c` into fused
//! multiply-adds (`-ffp-contract=off`, the default of GCC's ISO modes such
//! as `-std=c99`), the results agree bit for bit with the interpreter's
//! (a test checks it). Do not compile with `-ffast-math`.

use super::backend::{self, Backend, Fragment};
use super::names::Locals;
use super::schedule::{BinaryOp, Function, Load, Schedule, schedule};
use crate::Compiled;
use crate::expr::{Func, Precedence};
use crate::program::{Op, RoutineKind};
use lagrangian_runtime::layout::{JacobianBlock, OutputSlot};
use std::fmt::Write;

/// How the C code is named.
#[derive(Clone, Debug, Default)]
pub struct COptions {
    /// Prefix of every external name (`<prefix>_dynamics`, …); by default
    /// the model's name in snake case (`YarisDoublePendulum` →
    /// `yaris_double_pendulum`).
    pub prefix: Option<String>,
}

/// The C translation unit of a compiled model (see the module docs).
pub fn emit_c(compiled: &Compiled, options: &COptions) -> String {
    crate::depth::with_large_stack(|| emit_c_deep(compiled, options))
}

fn emit_c_deep(compiled: &Compiled, options: &COptions) -> String {
    let model = &compiled.model;
    let prefix = match &options.prefix {
        Some(prefix) => spell(prefix),
        None => snake_case(&model.name),
    };
    // The model's own helpers, `<prefix>_powi` and `<prefix>_input`, too.
    let own = [format!("{prefix}_powi"), format!("{prefix}_input")];
    let reserved: Vec<&str> = (RESERVED.iter().flat_map(|s| s.split_whitespace()))
        .chain(own.iter().map(String::as_str))
        .collect();
    let syntax = CSyntax {
        locals: Locals::new(model, &reserved, spell),
        prefix: prefix.clone(),
    };
    let mut out = preamble(compiled, &prefix);
    out.push_str(&helpers(compiled, &prefix));
    for kind in [
        RoutineKind::Dynamics,
        RoutineKind::Energies,
        RoutineKind::DynamicsAndPowers,
        RoutineKind::Jacobians,
        RoutineKind::InputArguments,
        RoutineKind::Outputs,
        RoutineKind::Switching,
        RoutineKind::Constraints,
    ] {
        if let Some(routine) = compiled.program.routine(kind) {
            let schedule = schedule(&compiled.program, routine);
            out.push_str(&routine_function(&syntax, &schedule, model.dimension()));
        }
    }
    out
}

/// The header comment, the includes, the input type and the metadata.
fn preamble(compiled: &Compiled, prefix: &str) -> String {
    let model = &compiled.model;
    let coordinates: Vec<&str> = model.coordinates.iter().map(|c| c.name.as_str()).collect();
    let mut out = String::new();
    let _ = writeln!(
        out,
        "/* @generated by `lagrangian` from the spec of `{}`: do not edit.\n *\n \
         * {} coordinate(s) ({}), equations M(q, t) q'' = f(q, q', t). The\n \
         * interface is described in the docs of `lagrangian_core::emit::c`. */\n",
        model.name,
        model.dimension(),
        coordinates.join(", ")
    );
    out.push_str("#include <math.h>\n#include <stddef.h>\n\n");
    out.push_str(
        "#ifndef LAGRANGIAN_INPUT_DEFINED\n#define LAGRANGIAN_INPUT_DEFINED\n\
         /* Value of input function `index` (declaration order) at args[0..count). */\n\
         typedef double (*lagrangian_input)(void *context, int index, const double *args, int count);\n\
         #endif\n\n",
    );
    out.push_str(&metadata(compiled, prefix));
    out
}

/// The sizes, the names and the default parameters.
fn metadata(compiled: &Compiled, prefix: &str) -> String {
    let model = &compiled.model;
    let upper = prefix.to_uppercase();
    let mut out = String::new();
    let argument_count: usize = compiled.program.input_sites.iter().map(|s| s.1).sum();
    for (name, value) in [
        ("DIMENSION", model.dimension()),
        ("PARAMETERS", model.parameters.len()),
        ("INPUTS", model.inputs.len()),
        ("INPUT_ARGUMENTS", argument_count),
        (
            "HAS_JACOBIANS",
            usize::from(compiled.program.routine(RoutineKind::Jacobians).is_some()),
        ),
    ] {
        let _ = writeln!(out, "#define {upper}_{name} {value}");
    }
    let _ = writeln!(
        out,
        "\nconst char *const {prefix}_model_name = {};",
        string(&model.name)
    );
    let coordinates: Vec<&str> = model.coordinates.iter().map(|c| c.name.as_str()).collect();
    let parameters: Vec<&str> = model.parameters.iter().map(|p| p.name.as_str()).collect();
    let inputs: Vec<&str> = model.inputs.iter().map(|i| i.name.as_str()).collect();
    for (list, names) in [
        ("coordinate", coordinates),
        ("parameter", parameters),
        ("input", inputs),
    ] {
        let mut items: Vec<String> = names.iter().map(|n| string(n)).collect();
        items.push("NULL".to_string());
        let _ = writeln!(
            out,
            "const char *const {prefix}_{list}_names[] = {{{}}};",
            items.join(", ")
        );
    }
    out.push_str(&output_metadata(model, prefix));
    // Only models with non-smooth functions have switching functions (the
    // code of the others stays as it was).
    if let Some(switching) = compiled.program.routine(RoutineKind::Switching) {
        let _ = writeln!(out, "#define {upper}_SWITCHING {}", switching.outputs.len());
    }
    out.push_str(&constraint_metadata(model, prefix));
    let _ = writeln!(out, "\n/* The parameters' default values, into p. */");
    let _ = writeln!(out, "void {prefix}_default_parameters(double *p)\n{{");
    for (i, parameter) in model.parameters.iter().enumerate() {
        let _ = writeln!(out, "    p[{i}] = {};", literal(parameter.default));
    }
    out.push_str("}\n");
    out
}

/// The number and names of the outputs, for a model with outputs (the code
/// of the others stays as it was).
fn output_metadata(model: &crate::spec::Model, prefix: &str) -> String {
    if model.outputs.is_empty() {
        return String::new();
    }
    let mut items: Vec<String> = model.outputs.iter().map(|o| string(&o.name)).collect();
    items.push("NULL".to_string());
    format!(
        "#define {}_OUTPUTS {}\nconst char *const {prefix}_output_names[] = {{{}}};\n",
        prefix.to_uppercase(),
        model.outputs.len(),
        items.join(", ")
    )
}

/// The number and names of the constraints, for a model with constraints
/// (the code of the others stays as it was).
fn constraint_metadata(model: &crate::spec::Model, prefix: &str) -> String {
    if model.constraints.is_empty() {
        return String::new();
    }
    let mut items: Vec<String> = model.constraints.iter().map(|c| string(&c.name)).collect();
    items.push("NULL".to_string());
    format!(
        "#define {}_CONSTRAINTS {}\nconst char *const {prefix}_constraint_names[] = {{{}}};\n",
        prefix.to_uppercase(),
        model.constraints.len(),
        items.join(", ")
    )
}

/// The input-call and integer-power helpers, where the routines use them.
fn helpers(compiled: &Compiled, prefix: &str) -> String {
    let program = &compiled.program;
    let used = |wanted: fn(&Op) -> bool| {
        (program.routines.iter())
            .flat_map(|routine| &routine.ops)
            .any(|&r| wanted(&program.ops[r as usize]))
    };
    let mut out = String::new();
    if used(|op| matches!(op, Op::Input { .. })) {
        let _ = write!(
            out,
            "\n/* input(context, index, args, count), or NaN without input functions. */\n\
             static double {prefix}_input(lagrangian_input input, void *context, int index, \
             const double *args, int count)\n{{\n    \
             return input ? input(context, index, args, count) : NAN;\n}}\n"
        );
    }
    for (f, parameters, value) in NON_SMOOTH_HELPERS {
        if (program.ops.iter()).any(|op| matches!(op, Op::Call(g, _) if *g == f)) {
            let name = f.name();
            let _ = write!(
                out,
                "\n/* {name} as the Rust runtime computes it (NaN stays NaN). */\n\
                 static double {prefix}_{name}({parameters})\n{{\n    return {value};\n}}\n"
            );
        }
    }
    if used(|op| matches!(op, Op::Powi(..))) {
        let _ = write!(
            out,
            "\n/* x^n by binary decomposition, multiplying in the order of Rust's powi. */\n\
             static double {prefix}_powi(double x, int n)\n{{\n    \
             unsigned int k = n < 0 ? 0u - (unsigned int)n : (unsigned int)n;\n    \
             double r = 1.0;\n    \
             for (;;) {{\n        \
             if (k & 1u) {{\n            r *= x;\n        }}\n        \
             k >>= 1;\n        \
             if (k == 0u) {{\n            break;\n        }}\n        \
             x *= x;\n    }}\n    \
             return n < 0 ? 1.0 / r : r;\n}}\n"
        );
    }
    out
}

/// The C definitions of `sign`, `min` and `max` as the Rust runtime
/// computes them (NaN stays NaN): function, parameters, returned value.
const NON_SMOOTH_HELPERS: [(Func, &str, &str); 3] = [
    (
        Func::Sign,
        "double x",
        "x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : x)",
    ),
    (
        Func::Min,
        "double a, double b",
        "a <= b ? a : (b < a ? b : a + b)",
    ),
    (
        Func::Max,
        "double a, double b",
        "a >= b ? a : (b > a ? b : a + b)",
    ),
];

/// The C name and output parameters of the function of a routine.
fn signature(kind: RoutineKind) -> (&'static str, Vec<&'static str>) {
    let jacobians = JacobianBlock::ALL.map(JacobianBlock::field).to_vec();
    match kind {
        RoutineKind::Dynamics => ("dynamics", vec!["mass", "forcing"]),
        RoutineKind::Energies => ("energies", vec!["energies"]),
        RoutineKind::DynamicsAndPowers => {
            ("dynamics_and_powers", vec!["mass", "forcing", "energies"])
        }
        RoutineKind::Jacobians => ("jacobians", jacobians),
        RoutineKind::InputArguments => ("input_arguments", vec!["arguments"]),
        RoutineKind::Outputs => ("outputs", vec!["outputs"]),
        RoutineKind::Switching => ("switching_functions", vec!["switching"]),
        RoutineKind::Constraints => ("constraints", vec!["constraints"]),
    }
}

/// The function evaluating one routine.
fn routine_function(syntax: &CSyntax, schedule: &Schedule, n: usize) -> String {
    let (name, outputs) = signature(schedule.kind);
    let mut inputs = vec!["p", "t", "q", "qd"];
    if matches!(schedule.kind, RoutineKind::Jacobians | RoutineKind::Outputs) {
        inputs.push("qdd");
    }
    inputs.extend(["input", "context"]);
    let mut parameters: Vec<String> = inputs
        .iter()
        .map(|&i| match i {
            "t" => "double t".to_string(),
            "input" => "lagrangian_input input".to_string(),
            "context" => "void *context".to_string(),
            other => format!("const double *{other}"),
        })
        .collect();
    parameters.extend(outputs.iter().map(|o| format!("double *{o}")));
    let mut out = format!(
        "\nvoid {}_{name}({})\n{{\n",
        syntax.prefix,
        parameters.join(", ")
    );
    // Not every routine uses every argument.
    let unused: Vec<String> = (inputs.iter().chain(&outputs))
        .map(|i| format!("(void){i};"))
        .collect();
    let _ = writeln!(out, "    {}", unused.join(" "));
    let body = backend::body(syntax, schedule);
    for statement in &body.statements {
        let _ = writeln!(out, "    {statement}");
    }
    for ((slot, _), value) in schedule.outputs.iter().zip(&body.outputs) {
        for write in place(*slot, value, n) {
            let _ = writeln!(out, "    {write}");
        }
    }
    out.push_str("}\n");
    out
}

/// The assignments that put `value` in its slot.
fn place(slot: OutputSlot, value: &str, n: usize) -> Vec<String> {
    match slot {
        OutputSlot::Mass { row, column } => {
            let (upper, lower) = (row * n + column, column * n + row);
            let mut writes = vec![format!("mass[{upper}] = {value};")];
            if row != column {
                writes.push(format!("mass[{lower}] = mass[{upper}];"));
            }
            writes
        }
        OutputSlot::Forcing(i) => vec![format!("forcing[{i}] = {value};")],
        OutputSlot::Energy(energy) => vec![format!("energies[{}] = {value};", energy.index())],
        OutputSlot::Jacobian { block, row, column } => {
            vec![format!(
                "{}[{}] = {value};",
                block.field(),
                row * n + column
            )]
        }
        OutputSlot::InputArgument(k) => vec![format!("arguments[{k}] = {value};")],
        OutputSlot::Output(k) => vec![format!("outputs[{k}] = {value};")],
        OutputSlot::Switching(k) => vec![format!("switching[{k}] = {value};")],
        OutputSlot::Constraint(k) => vec![format!("constraints[{k}] = {value};")],
    }
}

/// Names the generated code uses or C reserves, which locals must avoid.
const RESERVED: [&str; 3] = [
    // The parameters and types of the generated functions.
    "p t q qd qdd input context mass forcing energies forcing_q forcing_qd
     mass_times_acceleration_q arguments outputs constraints lagrangian_input",
    // The keywords of C99 to C23 (and GNU's `asm`).
    "auto break case char const continue default do double else enum extern float for goto if
     inline int long register restrict return short signed sizeof static struct switch typedef
     union unsigned void volatile while bool true false nullptr alignas alignof constexpr
     static_assert thread_local typeof typeof_unqual asm",
    // The functions called and the object-like macros of <math.h> and <stddef.h>.
    "sin cos exp log sqrt pow NAN INFINITY HUGE_VAL HUGE_VALF HUGE_VALL NULL M_E M_LOG2E
     M_LOG10E M_LN2 M_LN10 M_PI M_PI_2 M_PI_4 M_1_PI M_2_PI M_2_SQRTPI M_SQRT2 M_SQRT1_2 FP_NAN
     FP_INFINITE FP_ZERO FP_SUBNORMAL FP_NORMAL FP_FAST_FMA FP_ILOGB0 FP_ILOGBNAN MATH_ERRNO
     MATH_ERREXCEPT math_errhandling",
];

/// A spec name as a C identifier: without Rust's `r#`, other characters
/// than ASCII letters, digits and `_` as `uXXXX`, and not starting with `_`
/// (C reserves many such names) or a digit.
fn spell(name: &str) -> String {
    let name = name.strip_prefix("r#").unwrap_or(name);
    let mut out = String::new();
    for c in name.chars() {
        if c.is_ascii_alphanumeric() || c == '_' {
            out.push(c);
        } else {
            let _ = write!(out, "u{:04x}", c as u32);
        }
    }
    if out.is_empty() || out.starts_with(|c: char| c == '_' || c.is_ascii_digit()) {
        out.insert(0, 'v');
    }
    out
}

/// `YarisDoublePendulum` → `yaris_double_pendulum`, as a C identifier.
fn snake_case(name: &str) -> String {
    let mut out = String::new();
    let mut previous_lower = false;
    for c in spell(name).chars() {
        if c.is_ascii_uppercase() && previous_lower {
            out.push('_');
        }
        previous_lower = c.is_ascii_lowercase() || c.is_ascii_digit();
        out.push(c.to_ascii_lowercase());
    }
    out
}

/// A C string literal.
fn string(text: &str) -> String {
    let mut out = String::from("\"");
    for c in text.chars() {
        match c {
            '"' | '\\' => {
                out.push('\\');
                out.push(c);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// A double literal that reads back as exactly `v`.
fn literal(v: f64) -> String {
    match v {
        v if v.is_nan() => "NAN".to_string(),
        v if v.is_infinite() && v > 0.0 => "INFINITY".to_string(),
        v if v.is_infinite() => "-INFINITY".to_string(),
        // Rust's shortest round-trip form is valid C: `9.81`, `1e-7`, `2.0`.
        v => {
            let text = format!("{v:?}");
            if text.contains(['.', 'e']) {
                text
            } else {
                format!("{text}.0")
            }
        }
    }
}

/// C's syntax for the statements and expressions of a schedule.
struct CSyntax {
    locals: Locals,
    prefix: String,
}

impl Backend for CSyntax {
    type Code = String;

    fn constant(&self, value: f64) -> Fragment<String> {
        let code = literal(value);
        let precedence = if code.starts_with('-') {
            Precedence::Unary
        } else {
            Precedence::Atom
        };
        Fragment {
            code,
            precedence,
            literal: true,
        }
    }

    fn time(&self) -> String {
        "t".to_string()
    }

    fn load(&self, load: Load) -> String {
        self.locals.load(load).to_string()
    }

    fn temporary(&self, k: usize) -> String {
        self.locals.temporary(k)
    }

    fn parenthesize(&self, code: String) -> String {
        format!("({code})")
    }

    fn binary(&self, op: BinaryOp, left: String, right: String) -> String {
        let op = match op {
            BinaryOp::Add => "+",
            BinaryOp::Sub => "-",
            BinaryOp::Mul => "*",
            BinaryOp::Div => "/",
        };
        format!("{left} {op} {right}")
    }

    fn negate(&self, operand: String) -> String {
        // `--x` would be a decrement.
        if operand.starts_with('-') {
            format!("-({operand})")
        } else {
            format!("-{operand}")
        }
    }

    fn call(&self, function: Function, argument: Fragment<String>) -> String {
        let x = argument.code;
        match function {
            Function::Sin => format!("sin({x})"),
            Function::Cos => format!("cos({x})"),
            Function::Exp => format!("exp({x})"),
            Function::Ln => format!("log({x})"),
            Function::Sqrt => format!("sqrt({x})"),
            Function::Powi(k) => format!("{}_powi({x}, {k})", self.prefix),
            Function::Powf(y) => format!("pow({x}, {})", literal(y)),
        }
    }

    fn apply(&self, f: Func, arguments: Vec<Fragment<String>>) -> String {
        let arguments: Vec<String> = arguments.into_iter().map(|a| a.code).collect();
        let arguments = arguments.join(", ");
        let name = match f {
            Func::Sign | Func::Min | Func::Max => {
                return format!("{}_{}({arguments})", self.prefix, f.name());
            }
            Func::Sin => "sin",
            Func::Cos => "cos",
            Func::Exp => "exp",
            Func::Ln => "log",
            Func::Asin => "asin",
            Func::Acos => "acos",
            Func::Atan => "atan",
            Func::Atan2 => "atan2",
            Func::Sinh => "sinh",
            Func::Cosh => "cosh",
            Func::Tanh => "tanh",
            Func::Hypot => "hypot",
            Func::Abs => "fabs",
        };
        format!("{name}({arguments})")
    }

    fn input(&self, index: u32, arguments: Vec<String>) -> String {
        let count = arguments.len();
        let args = match count {
            0 => "NULL".to_string(),
            _ => format!("(const double[]){{{}}}", arguments.join(", ")),
        };
        format!(
            "{}_input(input, context, {index}, {args}, {count})",
            self.prefix
        )
    }

    fn load_statement(&self, load: Load) -> String {
        let source = match load {
            Load::Parameter(i) => format!("p[{i}]"),
            Load::Coordinate(i) => format!("q[{i}]"),
            Load::Velocity(i) => format!("qd[{i}]"),
            Load::Acceleration(i) => format!("qdd[{i}]"),
        };
        format!("const double {} = {source};", self.load(load))
    }

    fn define(&self, k: usize, value: String) -> String {
        format!("const double {} = {value};", self.temporary(k))
    }

    fn sin_cos(&self, sin: usize, cos: usize, argument: Fragment<String>) -> String {
        let (s, c, x) = (self.temporary(sin), self.temporary(cos), argument.code);
        format!("const double {s} = sin({x}), {c} = cos({x});")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_become_c_identifiers() {
        assert_eq!(snake_case("YarisDoublePendulum"), "yaris_double_pendulum");
        assert_eq!(snake_case("PendulumChain10"), "pendulum_chain10");
        assert_eq!(spell("r#type"), "type");
        assert_eq!(spell("_x"), "v_x");
        assert_eq!(spell("θ1"), "u03b81");
    }

    #[test]
    fn literals_read_back_exactly() {
        assert_eq!(literal(9.81), "9.81");
        assert_eq!(literal(2.0), "2.0");
        assert_eq!(literal(1e-7), "1e-7");
        assert_eq!(literal(std::f64::consts::PI), "3.141592653589793");
        assert_eq!(literal(f64::NAN), "NAN");
        assert_eq!(literal(f64::NEG_INFINITY), "-INFINITY");
    }
}
