//! Festo FST statement list (`NAME.fst.txt`): program P0 holds the step
//! sequence, one sentence per step as in the published method; program P1
//! (no steps, processed every cycle) holds the middle stops. FST is Festo's own
//! tool, so this file always uses Festo operands (`I0.1`, `O0.1`, `F0.0`)
//! whatever `--target` chooses for the other files.

use minijinja::Value;
use minijinja::value::Serde;
use serde::Serialize;

use super::{EmitInput, one_line, templates};
use crate::address::Allocation;
use crate::program::Signal;
use crate::program::{Action, Literal};
use crate::symbols::SymbolTable;

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

/// One FST step: the SFC step the program is in (its label), the sentence
/// that waits for it to be done and runs the actions of the step it enters.
#[derive(Serialize)]
struct StepContext {
    /// The label: 0 at rest, else the table step whose moves run.
    label: usize,
    /// What that step does.
    moves: String,
    /// The step entered and what it does.
    entry: String,
    condition: Vec<ConditionLine>,
    actions: Vec<ActionLine>,
    /// The closing sentence, which jumps back to the initial step.
    closing: Option<usize>,
    /// Sentences before the step's own: each jumps away when it holds.
    jumps: Vec<JumpContext>,
}

/// A jump's sentence: its target's actions, then `JMP TO` the target's step.
#[derive(Serialize)]
struct JumpContext {
    comment: String,
    condition: Vec<ConditionLine>,
    actions: Vec<ActionLine>,
    next: usize,
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
    /// What the step labels mean, for the header.
    step_note: Vec<String>,
    /// Actions of the INIT step (start P1, initial memory values).
    init: Vec<ActionLine>,
    steps: Vec<StepContext>,
    rungs: Vec<RungContext>,
}

fn condition(
    literals: &[Literal],
    festo: &Allocation,
    symbols: &SymbolTable,
) -> Vec<ConditionLine> {
    if literals.is_empty() {
        // FST's condition that always holds.
        return vec![ConditionLine {
            keyword: "IF",
            operand: "NOP".to_string(),
            comment: "always".to_string(),
        }];
    }
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
                // The FST allocation list's symbolic operand.
                comment: symbols.fst(l.signal),
            }
        })
        .collect()
}

fn actions(
    list: &[Action],
    festo: &Allocation,
    symbols: &SymbolTable,
    moves: &[crate::table::Move],
) -> Vec<ActionLine> {
    let mut lines = Vec::new();
    for action in list {
        let operand = festo.display(action.signal());
        let comment = one_line(&symbols.action_comment(*action, moves));
        match *action {
            // FST timers count in hundredths of a second: load the preset
            // into the timer's preset register, then start it.
            Action::StartTimer(_, ms) => {
                let number = operand.trim_start_matches('T');
                let comment = match fst_ms(ms) {
                    held if held != ms => format!("{comment} (FST holds {held} ms)"),
                    _ => comment,
                };
                lines.push(("LOAD", format!("V{}", ms.div_ceil(10)), comment));
                lines.push(("TO", format!("TP{number}"), "preset in 1/100 s".to_string()));
                lines.push(("SET", operand, "timer runs".to_string()));
            }
            // P1 sends the sequence back to its start: stop P0, start it again.
            Action::Reset(Signal::Sequence) => {
                lines.push((
                    "RESET",
                    "P0".to_string(),
                    "stop the step sequence".to_string(),
                ));
                lines.push((
                    "SET",
                    "P0".to_string(),
                    format!(
                        "and start it again at STEP {}",
                        crate::program::INITIAL_STEP
                    ),
                ));
            }
            Action::Set(_) => lines.push(("SET", operand, comment)),
            Action::Reset(_) => lines.push(("RESET", operand, comment)),
        }
    }
    lines
        .into_iter()
        .enumerate()
        .map(|(i, (verb, operand, comment))| ActionLine {
            first: i == 0,
            verb,
            operand,
            comment,
        })
        .collect()
}

/// Renders `NAME.fst.txt`.
pub fn render(input: &EmitInput) -> Result<String, templates::TemplateError> {
    let program = input.program;
    let festo = input.festo;
    let symbols = input.symbols;
    let mut init = Vec::new();
    if !program.rungs.is_empty() {
        init.push(ActionLine {
            first: false,
            verb: "SET",
            operand: "P1".to_string(),
            comment: "start program P1 (logic that runs while P0 waits)".to_string(),
        });
    }
    init.extend(actions(&program.init, festo, symbols, &[]));
    for (i, line) in init.iter_mut().enumerate() {
        line.first = i == 0;
    }
    let lowered = super::lower::lower(program, symbols);
    let steps = lowered
        .steps
        .iter()
        .map(|s| {
            let own = s.own();
            StepContext {
                jumps: s
                    .jumps()
                    .iter()
                    .map(|j| JumpContext {
                        comment: one_line(j.comment),
                        condition: condition(j.condition, festo, symbols),
                        actions: actions(j.actions, festo, symbols, j.moves),
                        next: j.enters,
                    })
                    .collect(),
                label: s.active,
                moves: one_line(&s.active_title),
                entry: one_line(own.comment),
                condition: condition(own.condition, festo, symbols),
                actions: actions(own.actions, festo, symbols, own.moves),
                closing: s.closing.then_some(own.enters),
            }
        })
        .collect();
    let rungs = input
        .program
        .rungs
        .iter()
        .map(|r| RungContext {
            comment: one_line(&symbols.explain(&r.comment)),
            condition: condition(&r.condition, festo, symbols),
            actions: actions(&r.actions, festo, symbols, &[]),
        })
        .collect();
    let context = Context {
        title: one_line(input.name),
        version: env!("CARGO_PKG_VERSION"),
        source: one_line(&input.source()),
        step_note: super::step_numbering_note("the active STEP label")
            .iter()
            .map(|l| one_line(l))
            .collect(),
        init,
        steps,
        rungs,
    };
    input
        .templates
        .render("program.fst.txt.j2", Value::from(Serde(&context)))
}

/// The milliseconds an FST preset of `ms` holds: hundredths of a second,
/// rounded up.
pub fn fst_ms(ms: u32) -> u32 {
    ms.div_ceil(10) * 10
}
