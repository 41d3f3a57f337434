//! The C backend's code compiles with the system C compiler and computes
//! what the interpreter computes, bit for bit.
//!
//! Each model's C is compiled together with a small driver that reads
//! parameters and states from stdin, calls every routine and prints the
//! outputs with `%.17g` (which reads back exactly). No tolerance is needed
//! anywhere: the C calls the `libm` functions that Rust's `f64` methods call
//! (`sin`, `cos`, `exp`, `log`, `sqrt`, `pow`), and its integer-power helper
//! multiplies in the order of Rust's `powi`, which the interpreter calls.
//! The compiler is `cc`; without one the test fails and says so.

use lagrangian_core::Compiled;
use lagrangian_core::emit::c::{COptions, emit_c};
use lagrangian_core::program::{EvalContext, RoutineKind};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// The input functions of both sides: every value depends on the index and
/// on every argument, so wiring mistakes show. The C driver computes the
/// same operations in the same order, with `scale` passed as the context.
fn input_value(scale: f64, index: usize, args: &[f64]) -> f64 {
    let mut v = scale * index as f64 + 0.5;
    for (k, a) in args.iter().enumerate() {
        v += (a * (k as f64 + 1.5)).sin();
    }
    v
}

const SCALE: f64 = 0.25;

/// The driver: parameters, then a count of states, then `t q qd qdd` per
/// state on stdin; every routine's outputs on stdout, one per line.
fn driver(prefix: &str) -> String {
    let upper = prefix.to_uppercase();
    format!(
        r#"#include <stdio.h>
#include <stdlib.h>
#include "model.c"

#define N {upper}_DIMENSION

static double inputs(void *context, int index, const double *args, int count)
{{
    double v = *(const double *)context * index + 0.5;
    for (int k = 0; k < count; k++) {{
        v += sin(args[k] * (k + 1.5));
    }}
    return v;
}}

static double read(void)
{{
    double x;
    if (scanf("%lf", &x) != 1) {{
        fprintf(stderr, "driver: bad input\n");
        exit(2);
    }}
    return x;
}}

static void print(const double *values, int count)
{{
    for (int i = 0; i < count; i++) {{
        printf("%.17g\n", values[i]);
    }}
}}

int main(void)
{{
    double p[{upper}_PARAMETERS + 1], q[N], qd[N], qdd[N];
    double mass[N * N], forcing[N], energies[5];
    double arguments[{upper}_INPUT_ARGUMENTS + 1];
    double scale = {SCALE:?};
    for (int i = 0; i < {upper}_PARAMETERS; i++) {{
        p[i] = read();
    }}
    int states = (int)read();
    for (int s = 0; s < states; s++) {{
        double t = read();
        for (int i = 0; i < N; i++) q[i] = read();
        for (int i = 0; i < N; i++) qd[i] = read();
        for (int i = 0; i < N; i++) qdd[i] = read();
        (void)qdd;
        {prefix}_dynamics(p, t, q, qd, inputs, &scale, mass, forcing);
        print(mass, N * N);
        print(forcing, N);
        {prefix}_energies(p, t, q, qd, inputs, &scale, energies);
        print(energies, 5);
        {prefix}_dynamics_and_powers(p, t, q, qd, inputs, &scale, mass, forcing, energies);
        print(mass, N * N);
        print(forcing, N);
        print(energies + 3, 2);
#if {upper}_HAS_JACOBIANS
        double blocks[3][N * N];
        {prefix}_jacobians(p, t, q, qd, qdd, inputs, &scale, blocks[0], blocks[1], blocks[2]);
        print(blocks[0], 3 * N * N);
#endif
        {prefix}_input_arguments(p, t, q, qd, NULL, NULL, arguments);
        print(arguments, {upper}_INPUT_ARGUMENTS);
#ifdef {upper}_OUTPUTS
        double outputs[{upper}_OUTPUTS];
        {prefix}_outputs(p, t, q, qd, qdd, inputs, &scale, outputs);
        print(outputs, {upper}_OUTPUTS);
#endif
    }}
    return 0;
}}
"#
    )
}

/// Compiles `model.c` with the driver in `dir`; the executable's path.
fn compile(dir: &Path, c: &str, prefix: &str) -> PathBuf {
    std::fs::create_dir_all(dir).unwrap();
    std::fs::write(dir.join("model.c"), c).unwrap();
    std::fs::write(dir.join("driver.c"), driver(prefix)).unwrap();
    let exe = dir.join("driver");
    let compiler = "cc";
    let output = Command::new(compiler)
        .args(["-std=c99", "-O2", "-Wall", "-Wextra", "-pedantic", "-Werror"])
        .arg("-o")
        .arg(&exe)
        .arg(dir.join("driver.c"))
        .arg("-lm")
        .output()
        .unwrap_or_else(|e| {
            panic!("this test compiles the generated C with `{compiler}`, which cannot be run ({e}): install a C compiler")
        });
    assert!(
        output.status.success(),
        "{compiler} rejected the generated C of {}:\n{}",
        dir.display(),
        String::from_utf8_lossy(&output.stderr)
    );
    exe
}

/// A deterministic state `(t, q, q̇, q̈)` of `n` coordinates.
fn state(n: usize, k: usize) -> (f64, Vec<f64>, Vec<f64>, Vec<f64>) {
    let x = k as f64 * 0.37 - 0.4;
    let q = (0..n).map(|i| x + 0.1 * i as f64).collect();
    let qd = (0..n).map(|i| 0.5 - x * i as f64).collect();
    let qdd = (0..n).map(|i| x * x - i as f64).collect();
    (0.3 + x, q, qd, qdd)
}

/// What the driver prints for one state, computed by the interpreter.
fn expected(
    compiled: &Compiled,
    parameters: &[f64],
    s: &(f64, Vec<f64>, Vec<f64>, Vec<f64>),
) -> Vec<f64> {
    let mut model = compiled.interpreted();
    for (name, value) in compiled.model.parameters.iter().zip(parameters) {
        model.set_parameter(&name.name, *value).unwrap();
    }
    let inputs = |index: usize, args: &[f64]| input_value(SCALE, index, args);
    let (t, q, qd, qdd) = (s.0, &s.1[..], &s.2[..], &s.3[..]);
    let n = q.len();
    let (mut mass, mut forcing) = (vec![0.0; n * n], vec![0.0; n]);
    model
        .evaluate_dynamics(t, q, qd, &inputs, &mut mass, &mut forcing)
        .unwrap();
    let mut out = [mass.clone(), forcing.clone()].concat();
    let e = model.evaluate_energies(t, q, qd, &inputs).unwrap();
    out.extend([
        e.kinetic,
        e.potential,
        e.dissipation,
        e.damping_power,
        e.external_power,
    ]);
    // The interpreter has no entry point for this routine: the program's own
    // run, which the tape matches bit for bit (tested in `tape`).
    let program = &compiled.program;
    let routine = program.routine(RoutineKind::DynamicsAndPowers).unwrap();
    let ctx = EvalContext {
        t,
        q,
        qd,
        qdd,
        parameters,
        inputs: &inputs,
    };
    let mut both = vec![0.0; routine.outputs.len()];
    program.run(routine, &ctx, &mut program.registers(), &mut both);
    let powers = lagrangian_runtime::layout::unpack_dynamics(&both, n, &mut mass, &mut forcing);
    out.extend(mass.iter().chain(&forcing).chain(powers));
    if model.has_jacobians() {
        let mut blocks = vec![0.0; 3 * n * n];
        model
            .evaluate_jacobians((t, q, qd, qdd), &inputs, &mut blocks)
            .unwrap();
        out.extend(blocks);
    }
    let count = program.input_sites.iter().map(|s| s.1).sum();
    let mut arguments = vec![0.0; count];
    model
        .evaluate_input_arguments(t, q, qd, &inputs, &mut arguments)
        .unwrap();
    out.extend(arguments);
    let mut outputs = vec![0.0; model.output_names().len()];
    model
        .evaluate_outputs((t, q, qd, qdd), &inputs, &mut outputs)
        .unwrap();
    out.extend(outputs);
    out
}

/// Emits, compiles and runs `source`'s C and compares every output.
fn check(name: &str, source: &str) {
    let compiled = Compiled::from_source(source).unwrap();
    let n = compiled.model.dimension();
    let prefix = format!("m_{name}");
    let c = emit_c(
        &compiled,
        &COptions {
            prefix: Some(prefix.clone()),
        },
    );
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("c_backend_{name}"));
    let exe = compile(&dir, &c, &prefix);
    // Parameters away from the defaults, so that their wiring shows.
    let parameters: Vec<f64> = (compiled.default_parameters().iter().enumerate())
        .map(|(i, p)| p * 1.25 + 0.01 * (i + 1) as f64)
        .collect();
    let states: Vec<_> = (0..5).map(|k| state(n, k)).collect();
    let mut stdin = String::new();
    for v in &parameters {
        stdin.push_str(&format!("{v:?}\n"));
    }
    stdin.push_str(&format!("{}\n", states.len()));
    for (t, q, qd, qdd) in &states {
        for v in std::iter::once(t).chain(q).chain(qd).chain(qdd) {
            stdin.push_str(&format!("{v:?}\n"));
        }
    }
    let mut child = Command::new(&exe)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    child
        .stdin
        .take()
        .unwrap()
        .write_all(stdin.as_bytes())
        .unwrap();
    let output = child.wait_with_output().unwrap();
    assert!(output.status.success(), "{name}: the driver failed");
    let got: Vec<f64> = String::from_utf8(output.stdout)
        .unwrap()
        .lines()
        .map(|l| {
            l.parse()
                .unwrap_or_else(|_| panic!("{name}: `{l}` is not a number"))
        })
        .collect();
    let want: Vec<f64> = states
        .iter()
        .flat_map(|s| expected(&compiled, &parameters, s))
        .collect();
    assert_eq!(got.len(), want.len(), "{name}: number of outputs");
    for (k, (g, w)) in got.iter().zip(&want).enumerate() {
        let same = g.to_bits() == w.to_bits() || (g.is_nan() && w.is_nan());
        assert!(
            same,
            "{name}: output {k}: C gives {g:?}, the interpreter {w:?}"
        );
    }
}

#[test]
fn the_paper_model_in_c_matches_the_interpreter() {
    check(
        "yaris",
        include_str!("../../specs/yaris_double_pendulum.lpm"),
    );
}

#[test]
fn a_pendulum_chain_in_c_matches_the_interpreter() {
    check(
        "chain",
        &(lagrangian_core::examples::pendulum_chain(5) + "jacobians;\n"),
    );
    // Without Jacobians the function is absent and the flag says so.
    check("chain_plain", &lagrangian_core::examples::pendulum_chain(3));
}

/// Integer and fractional powers, exp, ln, sqrt, division and the time;
/// parameters named like C keywords, macros, the functions' arguments and
/// the model's own helpers (`odd_powi`, `odd_input`).
#[test]
fn powers_and_functions_in_c_match_the_interpreter() {
    let source = "model Odd; coordinates { x, y }
        parameters { a = 2.5, b = 0.5, r#type = 3.0, w [1/s] = 2.0, p = 1.5, int = 0.75, NAN = 2.0, _u = 0.5, odd_powi = 1.25, odd_input = 0.5 }
        kinetic = 0.5 * a * p * pow(dot(x), 2) * (2 + exp(x) * int) * (NAN + _u) + 0.5 * pow(dot(y), 2) * pow(2 + sin(x), -3);
        potential = pow(1 + x * x, 1/3) * b + ln(2 + x * x) + sqrt(3 + x) / (1 + pow(x, 6))
            + r#type * y * cos(w * t) + pow(y, 7) / (3 + pow(y, 2)) + pow(x * y + 2, 3/2)
            + odd_powi * pow(x, 3) + odd_input * y;
        jacobians;";
    check("odd", source);
}

/// Outputs with accelerations, input calls at their own arguments and the
/// time; a parameter named like the function's output argument.
#[test]
fn outputs_in_c_match_the_interpreter() {
    check(
        "double_pendulum",
        include_str!("../../specs/double_pendulum.lpm"),
    );
    let source = "model Cart; coordinates { x, th }
        parameters { m = 2.0, outputs = 0.5 }
        inputs { push(s) }
        kinetic = 0.5 * m * pow(dot(x), 2) + 0.5 * pow(dot(th), 2) + outputs * dot(x) * dot(th) * cos(th);
        potential = m * (1.0 - cos(th));
        force x = push(x + th);
        output a = m * ddot(x) + push(2.0 * x);
        output b = outputs * pow(dot(th), 2) + t * ddot(th);";
    check("cart", source);
}

/// The emitted C names its functions after the model unless told otherwise.
#[test]
fn the_default_prefix_is_the_model_name_in_snake_case() {
    let compiled =
        Compiled::from_source(include_str!("../../specs/yaris_double_pendulum.lpm")).unwrap();
    let c = emit_c(&compiled, &COptions::default());
    assert!(c.contains("void yaris_double_pendulum_dynamics(const double *p, double t"));
    assert!(c.contains("#define YARIS_DOUBLE_PENDULUM_DIMENSION 3\n"));
}
