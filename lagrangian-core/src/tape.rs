//! The interpreter's form of a [`Program`]: per routine, a flat list of
//! three-address instructions over one register file.
//!
//! The register file is laid out as `[constants | parameters | q | q̇ | q̈ | t |
//! temporaries]`. Constants are written when the file is made and parameters
//! when they change, and the state is copied into its slots at each call, so
//! the instruction lists hold arithmetic and input calls only. The
//! instructions are the program's operations in the program's order, so a
//! tape computes bit for bit what [`Program::run`] and the emitted Rust do.

use crate::expr::InputFunctions;
use crate::program::{Op, Program, Reg, RoutineKind};

/// One instruction: destination register first.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Instr {
    Add(u32, u32, u32),
    Sub(u32, u32, u32),
    Mul(u32, u32, u32),
    Div(u32, u32, u32),
    Neg(u32, u32),
    Sin(u32, u32),
    Cos(u32, u32),
    Exp(u32, u32),
    Ln(u32, u32),
    Sqrt(u32, u32),
    Powi(u32, u32, i32),
    /// `dst = a^b` with the exponent in register `b`.
    Powf(u32, u32, u32),
    /// `dst = input[index](registers of arguments[start..start + count])`.
    Input {
        dst: u32,
        index: u32,
        start: u32,
        count: u32,
    },
}

/// The instructions and output registers of one routine.
#[derive(Clone, Debug)]
struct TapeRoutine {
    kind: RoutineKind,
    instructions: Vec<Instr>,
    outputs: Vec<u32>,
}

/// A program ready to interpret (see the module documentation).
#[derive(Clone, Debug)]
pub struct Tape {
    dimension: usize,
    constants: Vec<f64>,
    parameter_base: usize,
    q_base: usize,
    time_slot: usize,
    registers: usize,
    routines: Vec<TapeRoutine>,
    /// Argument registers of the input calls.
    arguments: Vec<u32>,
}

impl Tape {
    /// Lays out the registers of `program`, which has `parameters` parameters.
    pub fn new(program: &Program, parameters: usize) -> Tape {
        let n = program.dimension;
        let mut constants = Vec::new();
        let mut slot = vec![u32::MAX; program.ops.len()];
        for (r, op) in program.ops.iter().enumerate() {
            if let Op::Const(v) = op {
                slot[r] = constants.len() as u32;
                constants.push(*v);
            }
        }
        // Powf exponents live in registers too.
        let mut exponent_slot = vec![0u32; program.ops.len()];
        for (r, op) in program.ops.iter().enumerate() {
            if let Op::Powf(_, x) = op {
                exponent_slot[r] = constants.len() as u32;
                constants.push(*x);
            }
        }
        let parameter_base = constants.len();
        let q_base = parameter_base + parameters;
        let time_slot = q_base + 3 * n;
        let mut next = time_slot as u32 + 1;
        for (r, op) in program.ops.iter().enumerate() {
            slot[r] = match op {
                Op::Const(_) => slot[r],
                Op::Parameter(i) => (parameter_base + *i as usize) as u32,
                Op::Coordinate(i) => (q_base + *i as usize) as u32,
                Op::Velocity(i) => (q_base + n + *i as usize) as u32,
                Op::Acceleration(i) => (q_base + 2 * n + *i as usize) as u32,
                Op::Time => time_slot as u32,
                _ => {
                    next += 1;
                    next - 1
                }
            };
        }
        let mut arguments = Vec::new();
        let translate = |r: Reg| -> Option<Instr> {
            let s = |a: &Reg| slot[*a as usize];
            let d = slot[r as usize];
            Some(match &program.ops[r as usize] {
                Op::Add(a, b) => Instr::Add(d, s(a), s(b)),
                Op::Sub(a, b) => Instr::Sub(d, s(a), s(b)),
                Op::Mul(a, b) => Instr::Mul(d, s(a), s(b)),
                Op::Div(a, b) => Instr::Div(d, s(a), s(b)),
                Op::Neg(a) => Instr::Neg(d, s(a)),
                Op::Sin(a) => Instr::Sin(d, s(a)),
                Op::Cos(a) => Instr::Cos(d, s(a)),
                Op::Exp(a) => Instr::Exp(d, s(a)),
                Op::Ln(a) => Instr::Ln(d, s(a)),
                Op::Sqrt(a) => Instr::Sqrt(d, s(a)),
                Op::Powi(a, k) => Instr::Powi(d, s(a), *k),
                Op::Powf(a, _) => Instr::Powf(d, s(a), exponent_slot[r as usize]),
                Op::Input { index, args } => {
                    let start = arguments.len() as u32;
                    arguments.extend(args.iter().map(s));
                    Instr::Input {
                        dst: d,
                        index: *index,
                        start,
                        count: args.len() as u32,
                    }
                }
                _ => return None,
            })
        };
        let translated: Vec<Option<Instr>> = (0..program.ops.len() as Reg).map(translate).collect();
        let routines = program
            .routines
            .iter()
            .map(|routine| TapeRoutine {
                kind: routine.kind,
                instructions: routine
                    .ops
                    .iter()
                    .filter_map(|&r| translated[r as usize])
                    .collect(),
                outputs: routine.outputs.iter().map(|&r| slot[r as usize]).collect(),
            })
            .collect();
        Tape {
            dimension: n,
            constants,
            parameter_base,
            q_base,
            time_slot,
            registers: next as usize,
            routines,
            arguments,
        }
    }

    /// A register file holding the constants and `parameters`.
    pub fn registers(&self, parameters: &[f64]) -> Vec<f64> {
        let mut registers = vec![0.0; self.registers];
        registers[..self.constants.len()].copy_from_slice(&self.constants);
        self.set_parameters(&mut registers, parameters);
        registers
    }

    /// Writes new parameter values into a register file.
    pub fn set_parameters(&self, registers: &mut [f64], parameters: &[f64]) {
        registers[self.parameter_base..self.parameter_base + parameters.len()]
            .copy_from_slice(parameters);
    }

    /// Whether the program has routine `kind`.
    pub fn has(&self, kind: RoutineKind) -> bool {
        self.routines.iter().any(|r| r.kind == kind)
    }

    /// Number of outputs of routine `kind` (0 when absent).
    pub fn output_count(&self, kind: RoutineKind) -> usize {
        self.routines
            .iter()
            .find(|r| r.kind == kind)
            .map_or(0, |r| r.outputs.len())
    }

    /// Runs routine `kind` at `(t, q, q̇, q̈)` and writes its outputs to `out`;
    /// `q̈` may be empty for routines that do not use it. Returns `false`
    /// when the program has no such routine.
    ///
    /// `registers` must come from [`Tape::registers`]; `q` and `qd` must have
    /// the program's dimension and `out` room for the outputs.
    #[allow(clippy::too_many_arguments)]
    pub fn run<I: InputFunctions + ?Sized>(
        &self,
        kind: RoutineKind,
        state: (f64, &[f64], &[f64], &[f64]),
        inputs: &I,
        registers: &mut [f64],
        out: &mut [f64],
    ) -> bool {
        let Some(routine) = self.routines.iter().find(|r| r.kind == kind) else {
            return false;
        };
        let (t, q, qd, qdd) = state;
        let n = self.dimension;
        let base = self.q_base;
        registers[base..base + n].copy_from_slice(q);
        registers[base + n..base + 2 * n].copy_from_slice(qd);
        if qdd.len() == n {
            registers[base + 2 * n..base + 3 * n].copy_from_slice(qdd);
        }
        registers[self.time_slot] = t;
        let r = registers;
        let mut buffer = [0.0f64; 8];
        for instruction in &routine.instructions {
            match *instruction {
                Instr::Add(d, a, b) => r[d as usize] = r[a as usize] + r[b as usize],
                Instr::Sub(d, a, b) => r[d as usize] = r[a as usize] - r[b as usize],
                Instr::Mul(d, a, b) => r[d as usize] = r[a as usize] * r[b as usize],
                Instr::Div(d, a, b) => r[d as usize] = r[a as usize] / r[b as usize],
                Instr::Neg(d, a) => r[d as usize] = -r[a as usize],
                Instr::Sin(d, a) => r[d as usize] = r[a as usize].sin(),
                Instr::Cos(d, a) => r[d as usize] = r[a as usize].cos(),
                Instr::Exp(d, a) => r[d as usize] = r[a as usize].exp(),
                Instr::Ln(d, a) => r[d as usize] = r[a as usize].ln(),
                Instr::Sqrt(d, a) => r[d as usize] = r[a as usize].sqrt(),
                Instr::Powi(d, a, k) => r[d as usize] = r[a as usize].powi(k),
                Instr::Powf(d, a, b) => r[d as usize] = r[a as usize].powf(r[b as usize]),
                Instr::Input {
                    dst,
                    index,
                    start,
                    count,
                } => {
                    let args = &self.arguments[start as usize..(start + count) as usize];
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
        for (slot, &o) in out.iter_mut().zip(&routine.outputs) {
            *slot = r[o as usize];
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Compiled;
    use crate::program::EvalContext;

    /// Inputs whose values depend on every argument, so wiring mistakes show.
    struct Wiggly;
    impl InputFunctions for Wiggly {
        fn value(&self, index: usize, args: &[f64]) -> f64 {
            args.iter()
                .enumerate()
                .map(|(k, a)| (a * (k + 2) as f64).sin())
                .sum::<f64>()
                + index as f64
        }
    }

    #[test]
    fn tape_and_program_agree_bit_for_bit() {
        let sources = [
            include_str!("../../specs/yaris_double_pendulum.lpm").to_string(),
            include_str!("../../specs/elastic_pendulum.lpm").to_string(),
            crate::examples::pendulum_chain(4),
            // Powf, powi, division, exp, ln, sqrt and a constant exponent.
            "model Odd; coordinates { x } parameters { a = 2.5, b = 0.5 }
             kinetic = 0.5 * a * pow(dot(x), 2) * (2 + exp(x));
             potential = pow(1 + x * x, 1/3) * b + ln(2 + x * x) + sqrt(3 + x) / (1 + pow(x, 6));"
                .to_string(),
        ];
        for source in sources {
            let compiled = Compiled::from_source(&source).unwrap();
            let program = &compiled.program;
            let n = program.dimension;
            let parameters = compiled.default_parameters();
            let tape = Tape::new(program, parameters.len());
            let mut registers = tape.registers(&parameters);
            let mut program_registers = program.registers();
            for k in 0..5 {
                let x = k as f64 * 0.37 - 0.4;
                let q: Vec<f64> = (0..n).map(|i| x + 0.1 * i as f64).collect();
                let qd: Vec<f64> = (0..n).map(|i| 0.5 - x * i as f64).collect();
                let qdd: Vec<f64> = (0..n).map(|i| x * x - i as f64).collect();
                for routine in &program.routines {
                    let ctx = EvalContext {
                        t: x,
                        q: &q,
                        qd: &qd,
                        qdd: &qdd,
                        parameters: &parameters,
                        inputs: &Wiggly,
                    };
                    let mut expected = vec![0.0; routine.outputs.len()];
                    program.run(routine, &ctx, &mut program_registers, &mut expected);
                    let mut got = vec![f64::NAN; routine.outputs.len()];
                    let state = (x, &q[..], &qd[..], &qdd[..]);
                    assert!(tape.run(routine.kind, state, &Wiggly, &mut registers, &mut got));
                    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                    assert_eq!(bits(&got), bits(&expected), "{:?}", routine.kind);
                }
            }
        }
    }

    #[test]
    fn parameters_reach_the_registers() {
        let compiled = Compiled::from_source(
            "model P; coordinates { x } parameters { k = 2 } kinetic = 0.5 * pow(dot(x), 2); potential = 0.5 * k * pow(x, 2);",
        )
        .unwrap();
        let tape = Tape::new(&compiled.program, 1);
        let mut registers = tape.registers(&[2.0]);
        let mut out = vec![0.0; tape.output_count(RoutineKind::Dynamics)];
        tape.run(
            RoutineKind::Dynamics,
            (0.0, &[0.5], &[0.0], &[]),
            &crate::NoInputs,
            &mut registers,
            &mut out,
        );
        assert_eq!(out, [1.0, -1.0]);
        tape.set_parameters(&mut registers, &[6.0]);
        tape.run(
            RoutineKind::Dynamics,
            (0.0, &[0.5], &[0.0], &[]),
            &crate::NoInputs,
            &mut registers,
            &mut out,
        );
        assert_eq!(out, [1.0, -3.0]);
    }
}
