//! Lowering a [`Program`] to the runtime's interpreter [`Tape`]: constants
//! and `powf` exponents into constant registers, loads onto the parameter
//! and state registers, every other operation into a temporary, in the
//! program's order (so the tape computes bit for bit what the program does).

use crate::program::{Op, Program, Reg};
use lagrangian_runtime::tape::{Instruction, RegisterLayout, Tape, TapeRoutine};

/// The tape of `program`, a model with `parameters` parameters.
pub fn lower(program: &Program, parameters: usize) -> Tape {
    let (layout, slot, exponent_slot) = lay_out(program, parameters);
    let mut arguments = Vec::new();
    let mut translated = Vec::with_capacity(program.ops.len());
    for r in 0..program.ops.len() {
        let instruction = translate(program, r as Reg, &slot, &exponent_slot, &mut arguments);
        translated.push(instruction);
    }
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
    Tape::new(layout, routines, arguments)
        .expect("the lowering uses only the registers it lays out")
}

/// The register layout, the register of each operation's value and of each
/// `powf` exponent.
fn lay_out(program: &Program, parameters: usize) -> (RegisterLayout, Vec<u32>, Vec<u32>) {
    let ops = &program.ops;
    let mut constants = Vec::new();
    let mut slot = vec![u32::MAX; ops.len()];
    for (r, op) in ops.iter().enumerate() {
        if let Op::Const(v) = op {
            slot[r] = constants.len() as u32;
            constants.push(v.value());
        }
    }
    // Powf exponents live in registers too.
    let mut exponent_slot = vec![0u32; ops.len()];
    for (r, op) in ops.iter().enumerate() {
        if let Op::Powf(_, x) = op {
            exponent_slot[r] = constants.len() as u32;
            constants.push(x.value());
        }
    }
    let temporaries = ops.iter().filter(|op| !op.is_load()).count();
    let layout = RegisterLayout {
        constants,
        parameters,
        dimension: program.dimension,
        temporaries,
    };
    let mut next = 0;
    for (r, op) in ops.iter().enumerate() {
        slot[r] = match op {
            Op::Const(_) => slot[r],
            Op::Parameter(i) => layout.parameter(*i as usize),
            Op::Coordinate(i) => layout.coordinate(*i as usize),
            Op::Velocity(i) => layout.velocity(*i as usize),
            Op::Acceleration(i) => layout.acceleration(*i as usize),
            Op::Time => layout.time(),
            _ => {
                next += 1;
                layout.temporary(next - 1)
            }
        };
    }
    (layout, slot, exponent_slot)
}

/// The instruction of operation `r`; `None` for loads.
fn translate(
    program: &Program,
    r: Reg,
    slot: &[u32],
    exponent_slot: &[u32],
    arguments: &mut Vec<u32>,
) -> Option<Instruction> {
    let s = |a: &Reg| slot[*a as usize];
    let d = slot[r as usize];
    Some(match &program.ops[r as usize] {
        Op::Add(a, b) => Instruction::Add(d, s(a), s(b)),
        Op::Sub(a, b) => Instruction::Sub(d, s(a), s(b)),
        Op::Mul(a, b) => Instruction::Mul(d, s(a), s(b)),
        Op::Div(a, b) => Instruction::Div(d, s(a), s(b)),
        Op::Neg(a) => Instruction::Neg(d, s(a)),
        Op::Sin(a) => Instruction::Sin(d, s(a)),
        Op::Cos(a) => Instruction::Cos(d, s(a)),
        Op::Exp(a) => Instruction::Exp(d, s(a)),
        Op::Ln(a) => Instruction::Ln(d, s(a)),
        Op::Sqrt(a) => Instruction::Sqrt(d, s(a)),
        Op::Powi(a, k) => Instruction::Powi(d, s(a), *k),
        Op::Powf(a, _) => Instruction::Powf(d, s(a), exponent_slot[r as usize]),
        Op::Call(function, args) => Instruction::Call {
            function: *function,
            dst: d,
            args: [s(&args[0]), s(args.get(1).unwrap_or(&args[0]))],
        },
        Op::Input { index, args } => {
            let start = arguments.len() as u32;
            arguments.extend(args.iter().map(s));
            Instruction::Input {
                dst: d,
                index: *index,
                start,
                count: args.len() as u32,
            }
        }
        Op::Const(_)
        | Op::Parameter(_)
        | Op::Coordinate(_)
        | Op::Velocity(_)
        | Op::Acceleration(_)
        | Op::Time => return None,
    })
}
#[cfg(test)]
mod tests {
    use super::*;
    use crate::Compiled;
    use crate::program::EvalContext;
    use lagrangian_runtime::layout::RoutineKind;

    /// Inputs whose values depend on every argument, so wiring mistakes show.
    fn wiggly(index: usize, args: &[f64]) -> f64 {
        args.iter()
            .enumerate()
            .map(|(k, a)| (a * (k + 2) as f64).sin())
            .sum::<f64>()
            + index as f64
    }

    fn no_inputs(_: usize, _: &[f64]) -> f64 {
        f64::NAN
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
            let tape = lower(program, parameters.len());
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
                        inputs: &wiggly,
                    };
                    let mut expected = vec![0.0; routine.outputs.len()];
                    program.run(routine, &ctx, &mut program_registers, &mut expected);
                    let mut got = vec![f64::NAN; routine.outputs.len()];
                    let state = (x, &q[..], &qd[..], &qdd[..]);
                    assert!(tape.run(routine.kind, state, &wiggly, &mut registers, &mut got));
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
        let tape = lower(&compiled.program, 1);
        let mut registers = tape.registers(&[2.0]);
        let mut out = vec![0.0; tape.output_count(RoutineKind::Dynamics)];
        tape.run(
            RoutineKind::Dynamics,
            (0.0, &[0.5], &[0.0], &[]),
            &no_inputs,
            &mut registers,
            &mut out,
        );
        assert_eq!(out, [1.0, -1.0]);
        tape.set_parameters(&mut registers, &[6.0]);
        tape.run(
            RoutineKind::Dynamics,
            (0.0, &[0.5], &[0.0], &[]),
            &no_inputs,
            &mut registers,
            &mut out,
        );
        assert_eq!(out, [1.0, -3.0]);
    }
}
