//! Festo FST statement list (`NAME.fst.txt`): program P0 holds the step
//! sequence, one sentence per step as in the published method; program P1
//! (no steps, processed every cycle) holds the middle stops. FST is Festo's own
//! tool, so this file always uses Festo operands (`I0.1`, `O0.1`, `F0.0`)
//! whatever `--target` chooses for the other files.

use minijinja::Value;
use minijinja::value::Serde;
use serde::Serialize;

use super::{EmitInput, action_comment, moves_text, one_line, templates};
use crate::address::{Allocation, Mnemonic, Target};
use crate::program::{Action, Literal};

#[derive(Serialize)]
struct ConditionLine {
    keyword: &'static str,
    operand: String,
    comment: String,
}

#[derive(Serialize)]
struct ActionLine {
    first: bool,
    verb: &'static str,
    operand: String,
    comment: String,
}

#[derive(Serialize)]
struct StepContext {
    number: usize,
    moves: String,
    condition: Vec<ConditionLine>,
    actions: Vec<ActionLine>,
    last: bool,
}

#[derive(Serialize)]
struct RungContext {
    comment: String,
    condition: Vec<ConditionLine>,
    actions: Vec<ActionLine>,
}

#[derive(Serialize)]
struct Context {
    title: String,
    version: &'static str,
    source: String,
    steps: Vec<StepContext>,
    rungs: Vec<RungContext>,
}

fn condition(literals: &[Literal], festo: &Allocation) -> Vec<ConditionLine> {
    literals
        .iter()
        .enumerate()
        .map(|(i, l)| {
            let operand = festo.display(l.signal);
            ConditionLine {
                keyword: if i == 0 { "IF" } else { "AND" },
                // FST negates an operand with a leading N.
                operand: if l.negated {
                    format!("N {operand}")
                } else {
                    operand
                },
                comment: l.signal.symbol(),
            }
        })
        .collect()
}

fn actions(
    list: &[Action],
    festo: &Allocation,
    comment: impl Fn(Action) -> String,
) -> Vec<ActionLine> {
    list.iter()
        .enumerate()
        .map(|(i, a)| ActionLine {
            first: i == 0,
            verb: if a.value() { "SET" } else { "RESET" },
            operand: festo.display(a.signal()),
            comment: one_line(&comment(*a)),
        })
        .collect()
}

/// Renders `NAME.fst.txt`.
pub fn render(input: &EmitInput) -> Result<String, templates::TemplateError> {
    let festo = Allocation::new(input.table, Target::Festo, Mnemonic::En);
    let count = input.program.steps.len();
    let steps = input
        .program
        .steps
        .iter()
        .enumerate()
        .map(|(i, s)| StepContext {
            number: s.number,
            moves: moves_text(&s.moves),
            condition: condition(&s.condition, &festo),
            actions: actions(&s.actions, &festo, |a| action_comment(a, &s.moves)),
            last: i + 1 == count,
        })
        .collect();
    let rungs = input
        .program
        .rungs
        .iter()
        .map(|r| RungContext {
            comment: one_line(&r.comment),
            condition: condition(&r.condition, &festo),
            actions: actions(&r.actions, &festo, |a| action_comment(a, &[])),
        })
        .collect();
    let context = Context {
        title: one_line(input.name),
        version: env!("CARGO_PKG_VERSION"),
        source: one_line(&input.source()),
        steps,
        rungs,
    };
    templates::render("program.fst.txt.j2", Value::from(Serde(&context)))
}
