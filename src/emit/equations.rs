//! The synthesised equations as IEC programs (`NAME.equations.st`,
//! `NAME.equations.il`): names, addresses and instruction-list code are
//! decided here, the templates `equations.st.j2` and `equations.il.j2` lay
//! them out.

use minijinja::Value;
use minijinja::value::Serde;
use serde::Serialize;

use super::templates::{TemplateError, Templates};
use crate::program::Signal;
use crate::symbols::{CONFIGURATION_NAME, RESOURCE_NAME};
use crate::synth::equations::Expr;
use crate::synth::output::{CONVENTION, equation_line};
use crate::synth::{Equation, Synthesis};

/// IEC identifiers of the program, as the sequence names them: sensors
/// `a_home`/`a_end`, state `a`, coils `ya_p`/`ya_m`, memories `x`, …
struct Names<'a> {
    s: &'a Synthesis,
}

impl Names<'_> {
    fn state(&self, v: usize) -> String {
        self.s.modified.signal_name(v)
    }

    fn output(&self, e: &Equation) -> String {
        self.s.modified.output_name(e.action)
    }
}

#[derive(Serialize)]
struct Located {
    name: String,
    address: String,
    comment: String,
}

#[derive(Serialize)]
struct State {
    name: String,
    initial: &'static str,
    comment: &'static str,
}

#[derive(Serialize)]
struct EquationModel {
    output: String,
    token: String,
    /// As Structured Text.
    expr: String,
    /// `A1  = NOT (b OR x)`, the comment of the IL block.
    line: String,
    /// The instruction-list code that leaves the value in the accumulator.
    il: Vec<String>,
    /// The coil RESET drives to bring its cylinder home.
    homes: bool,
}

#[derive(Serialize)]
struct Term {
    name: String,
    value: bool,
}

#[derive(Serialize)]
struct Model {
    title: String,
    version: &'static str,
    original: String,
    modified: String,
    convention: &'static str,
    inputs: Vec<Located>,
    coils: Vec<Located>,
    states: Vec<State>,
    /// The set and reset outputs of the memories.
    memory_outputs: Vec<String>,
    /// IL scratch variables `t1`, `t2`, … for nested operands.
    temporaries: Vec<String>,
    actuators: Vec<String>,
    memories: Vec<String>,
    /// Each memory's start value, which RESET puts back.
    memory_starts: Vec<bool>,
    /// The start state, variable by variable: the machine is home.
    home: Vec<Term>,
    equations: Vec<EquationModel>,
    program: &'static str,
    configuration: &'static str,
    resource: &'static str,
}

/// Instruction list for `e`, result in the accumulator; a nested right
/// operand goes through a temporary.
fn instructions(
    e: &Expr,
    state: &dyn Fn(usize) -> String,
    code: &mut Vec<String>,
    temps: &mut usize,
) {
    match e {
        Expr::Var(v) => code.push(format!("LD {}", state(*v))),
        Expr::Not(inner) => {
            instructions(inner, state, code, temps);
            code.push("NOT".to_string());
        }
        Expr::And(a, b) | Expr::Or(a, b) | Expr::Xor(a, b) => {
            let op = match e {
                Expr::And(..) => "AND",
                Expr::Or(..) => "OR",
                _ => "XOR",
            };
            match &**b {
                Expr::Var(v) => {
                    instructions(a, state, code, temps);
                    code.push(format!("{op} {}", state(*v)));
                }
                Expr::Not(n) if matches!(**n, Expr::Var(_)) => {
                    instructions(a, state, code, temps);
                    if let Expr::Var(v) = **n {
                        code.push(format!("{op}N {}", state(v)));
                    }
                }
                _ => {
                    *temps += 1;
                    let t = format!("t{temps}");
                    instructions(b, state, code, temps);
                    code.push(format!("ST {t}"));
                    instructions(a, state, code, temps);
                    code.push(format!("{op} {t}"));
                }
            }
        }
    }
}

/// The end sensors of every cylinder, then the operator's buttons, at
/// input bits one after the other.
fn located_inputs(s: &Synthesis) -> Vec<Located> {
    let seq = &s.modified;
    let bit = |n: usize| format!("{}.{}", n / 8, n % 8);
    let mut inputs = Vec::new();
    for v in 0..seq.actuators {
        for (name, what) in seq
            .input_names(v)
            .into_iter()
            .zip(["retracted", "extended"])
        {
            inputs.push(Located {
                name,
                address: format!("%IX{}", bit(inputs.len())),
                comment: format!("{} {what}", seq.var_name(v)),
            });
        }
    }
    // The buttons of the `convert` route's programs, by the names the
    // step program gives them (`RESET_PB`: RESET is an IL keyword).
    for (button, comment) in [
        (
            Signal::Start,
            "push button: starts cycling, the machine home",
        ),
        (
            Signal::Stop,
            "normally closed: cycling ends at the end of the cycle",
        ),
        (
            Signal::EStop,
            "emergency stop, normally closed: every coil off until RESET",
        ),
        (
            Signal::Reset,
            "push button: memories back, every cylinder home",
        ),
    ] {
        let name = button.symbol();
        inputs.push(Located {
            name,
            address: format!("%IX{}", bit(inputs.len())),
            comment: comment.to_string(),
        });
    }
    inputs
}

/// Every equation as the templates lay it out, and the most scratch
/// variables one needs in IL.
fn equation_models(s: &Synthesis, names: &Names) -> (Vec<EquationModel>, usize) {
    let seq = &s.modified;
    let initial = seq.initial_state();
    let mut most_temps = 0;
    let equations = s
        .equations
        .iter()
        .map(|e| {
            let mut il = Vec::new();
            let mut temps = 0;
            instructions(&e.expr, &|v| names.state(v), &mut il, &mut temps);
            most_temps = most_temps.max(temps);
            EquationModel {
                output: names.output(e),
                token: seq.token(e.action),
                expr: e.expr.text(&|v| names.state(v)),
                line: equation_line(s, e),
                il,
                homes: !seq.is_memory(e.action.var)
                    && ((initial >> e.action.var) & 1 == 1) == e.action.value,
            }
        })
        .collect();
    (equations, most_temps)
}

/// `temporaries`: whether the language needs scratch variables (IL does).
fn model(s: &Synthesis, title: &str, program: &'static str, temporaries: bool) -> Model {
    let seq = &s.modified;
    let names = Names { s };
    let bit = |n: usize| format!("{}.{}", n / 8, n % 8);
    let inputs = located_inputs(s);
    let coils = s
        .equations
        .iter()
        .filter(|e| !seq.is_memory(e.action.var))
        .enumerate()
        .map(|(n, e)| Located {
            name: names.output(e),
            address: format!("%QX{}", bit(n)),
            comment: seq.token(e.action),
        })
        .collect();
    let initial = seq.initial_state();
    let states = (0..seq.variables())
        .map(|v| State {
            name: names.state(v),
            initial: if (initial >> v) & 1 == 1 {
                "TRUE"
            } else {
                "FALSE"
            },
            comment: if seq.is_memory(v) {
                "memory"
            } else {
                "sensor state"
            },
        })
        .collect();
    let (equations, most_temps) = equation_models(s, &names);
    Model {
        title: title.to_string(),
        version: env!("CARGO_PKG_VERSION"),
        original: s.original.text(),
        modified: seq.text(),
        convention: CONVENTION,
        inputs,
        coils,
        states,
        memory_outputs: s
            .equations
            .iter()
            .filter(|e| seq.is_memory(e.action.var))
            .map(|e| names.output(e))
            .collect(),
        temporaries: (1..=if temporaries { most_temps } else { 0 })
            .map(|t| format!("t{t}"))
            .collect(),
        actuators: (0..seq.actuators).map(|v| names.state(v)).collect(),
        memories: (seq.actuators..seq.variables())
            .map(|v| names.state(v))
            .collect(),
        memory_starts: (seq.actuators..seq.variables())
            .map(|v| (initial >> v) & 1 == 1)
            .collect(),
        home: (0..seq.variables())
            .map(|v| Term {
                name: names.state(v),
                value: (initial >> v) & 1 == 1,
            })
            .collect(),
        equations,
        program,
        configuration: CONFIGURATION_NAME,
        resource: RESOURCE_NAME,
    }
}

/// `NAME.equations.st`: a complete program with a configuration, that reads
/// the end sensors, evaluates every equation on the scan's state, drives the
/// coils and sets/resets the memories.
pub fn structured_text(
    templates: &Templates,
    s: &Synthesis,
    title: &str,
) -> Result<String, TemplateError> {
    let model = model(s, title, "synth_main", false);
    templates.render("equations.st.j2", Value::from(Serde(&model)))
}

/// `NAME.equations.il`: the same equations in IEC instruction list, one
/// block per output, with temporaries for nested operands. Each latch is
/// one load-or-and-store, not an S/R pair: matiec fails (an internal error
/// or a crash) on programs with many S/R pairs.
pub fn instruction_list(
    templates: &Templates,
    s: &Synthesis,
    title: &str,
) -> Result<String, TemplateError> {
    let model = model(s, title, "synth_il", true);
    templates.render("equations.il.j2", Value::from(Serde(&model)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn il(e: &Expr) -> Vec<String> {
        let (mut code, mut temps) = (Vec::new(), 0);
        instructions(
            e,
            &|v| ["a", "b", "c"][v].to_string(),
            &mut code,
            &mut temps,
        );
        code
    }

    #[test]
    fn a_negated_operand_is_one_instruction_only_when_it_is_a_variable() {
        let var = |v| Box::new(Expr::Var(v));
        let and_not_b = Expr::And(var(0), Box::new(Expr::Not(var(1))));
        assert_eq!(il(&and_not_b), ["LD a", "ANDN b"]);
        // NOT (b OR c) needs its own accumulator: through a temporary.
        let and_not_b_or_c = Expr::And(
            var(0),
            Box::new(Expr::Not(Box::new(Expr::Or(var(1), var(2))))),
        );
        assert_eq!(
            il(&and_not_b_or_c),
            ["LD b", "OR c", "NOT", "ST t1", "LD a", "AND t1"]
        );
    }
}
