//! IEC 61131-3 Structured Text (`NAME.st`) that matiec — the compiler behind
//! OpenPLC and Beremiz — accepts as it is: located variables in their own VAR
//! block, `(* *)` comments only, and a CONFIGURATION with a cyclic task.

use minijinja::Value;
use minijinja::value::Serde;
use serde::Serialize;

use super::{EmitInput, action_comment, moves_text, templates};
use crate::address::{Allocation, Assigned, Signal};
use crate::program::{Action, condition_text};

/// Identifiers of the program's own parts. `step` is an IEC keyword, so the
/// step counter is called `active_step`.
pub const PROGRAM_NAME: &str = "steptable_main";
pub const STEP_VAR: &str = "active_step";

#[derive(Serialize)]
struct Var {
    ident: String,
    iec_address: String,
    address: String,
    comment: String,
}

#[derive(Serialize)]
struct Assignment {
    ident: String,
    value: &'static str,
    comment: String,
}

#[derive(Serialize)]
struct StepContext {
    number: usize,
    moves: String,
    condition: String,
    actions: Vec<Assignment>,
    next: usize,
    last: bool,
}

#[derive(Serialize)]
struct RungContext {
    comment: String,
    condition: String,
    actions: Vec<Assignment>,
}

#[derive(Serialize)]
struct Context {
    title: String,
    version: &'static str,
    source: String,
    target: String,
    program_name: &'static str,
    step_var: &'static str,
    inputs: Vec<Var>,
    outputs: Vec<Var>,
    memories: Vec<Var>,
    steps: Vec<StepContext>,
    rungs: Vec<RungContext>,
    configuration_name: &'static str,
    resource_name: &'static str,
    task_name: &'static str,
    instance_name: &'static str,
    task_interval: String,
}

fn vars(list: &[Assigned], alloc: &Allocation, input: &EmitInput) -> Vec<Var> {
    list.iter()
        .map(|a| Var {
            ident: a.signal.ident(),
            iec_address: a.address.iec(),
            address: a.address.display(alloc.mnemonic),
            comment: comment_text(&a.signal.comment(input.table)),
        })
        .collect()
}

fn assignments(actions: &[Action], comment: impl Fn(Action) -> String) -> Vec<Assignment> {
    actions
        .iter()
        .map(|a| Assignment {
            ident: a.signal().ident(),
            value: if a.value() { "TRUE" } else { "FALSE" },
            comment: comment_text(&comment(*a)),
        })
        .collect()
}

/// Text made safe inside `(* … *)`: ST comments do not nest.
fn comment_text(text: &str) -> String {
    super::one_line(text)
        .replace("(*", "( *")
        .replace("*)", "* )")
}

/// Renders `NAME.st`.
pub fn render(input: &EmitInput, scan_millis: u32) -> Result<String, templates::TemplateError> {
    let alloc = input.allocation;
    let count = input.program.steps.len();
    let steps = input
        .program
        .steps
        .iter()
        .enumerate()
        .map(|(i, s)| StepContext {
            number: s.number,
            moves: comment_text(&moves_text(&s.moves)),
            condition: condition_text(&s.condition, Signal::ident, "AND", "NOT "),
            actions: assignments(&s.actions, |a| action_comment(a, &s.moves)),
            next: if i + 1 == count { 1 } else { s.number + 1 },
            last: i + 1 == count,
        })
        .collect();
    let rungs = input
        .program
        .rungs
        .iter()
        .map(|r| RungContext {
            comment: comment_text(&r.comment),
            condition: condition_text(&r.condition, Signal::ident, "AND", "NOT "),
            actions: assignments(&r.actions, |a| action_comment(a, &[])),
        })
        .collect();
    let context = Context {
        title: input.name.to_string(),
        version: env!("CARGO_PKG_VERSION"),
        source: comment_text(&input.source()),
        target: alloc.target.name().to_string(),
        program_name: PROGRAM_NAME,
        step_var: STEP_VAR,
        inputs: vars(&alloc.inputs, alloc, input),
        outputs: vars(&alloc.outputs, alloc, input),
        memories: vars(&alloc.memories, alloc, input),
        steps,
        rungs,
        configuration_name: "config0",
        resource_name: "resource0",
        task_name: "cyclic_task",
        instance_name: "main_instance",
        task_interval: format!("T#{scan_millis}ms"),
    };
    templates::render("program.st.j2", Value::from(Serde(&context)))
}
