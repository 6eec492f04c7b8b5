//! Studio 5000 Logix Designer program export (`NAME.L5X`): the step program
//! as ladder (RLL) in one routine, for ControlLogix and CompactLogix.
//!
//! The ladder keeps the STEP 7 statement list's structure: a BOOL step flag
//! per SFC step (`step_0` at rest, `step_k` while table step k's moves run)
//! and a `fired` bit that lets at most one transition fire per scan, one
//! rung per transition and per rung of the step program. A timer is a
//! TIMER driven by a run bit: the rung that starts it loads its preset
//! (`MOV`), sets the run bit and resets it (`RES`); `TON` runs at the top
//! of the routine (where `DN` clears the run bit, before the steps read it)
//! and again at the bottom, so that a timer started in a scan times from
//! that scan, as the step program's does.
//!
//! The inputs, outputs and memories are controller tags, named and
//! described as `NAME.rockwell.csv` has them; the step flags, `fired`, the
//! run bits and the timers are the program's own tags.

use minijinja::Value;
use minijinja::value::Serde;
use serde::Serialize;

use super::{EmitInput, one_line, templates};
use crate::program::{Action, Area, INITIAL_STEP, Literal, Signal};

/// The program and routine the file holds, as Studio 5000 names them in a
/// new project.
pub const PROGRAM: &str = crate::names::LOGIX_PROGRAM;
pub const ROUTINE: &str = crate::names::LOGIX_ROUTINE;
/// The oldest Logix Designer the file is laid out for: any newer one
/// imports it.
pub const SOFTWARE_REVISION: &str = "20.01";

#[derive(Serialize)]
struct Tag {
    name: String,
    data_type: &'static str,
    description: String,
}

#[derive(Serialize)]
struct Rung {
    comment: String,
    text: String,
}

#[derive(Serialize)]
struct Context {
    title: String,
    version: &'static str,
    source: String,
    revision: &'static str,
    program: &'static str,
    routine: &'static str,
    controller_tags: Vec<Tag>,
    program_tags: Vec<Tag>,
    rungs: Vec<Rung>,
}

/// What the rungs are written from: the names of the program's own bits.
struct Names<'a> {
    input: &'a EmitInput<'a>,
    flags: Vec<String>,
    fired: String,
}

impl Names<'_> {
    /// The bit a signal reads as: a timer reads as its run bit.
    fn bit(&self, signal: Signal) -> String {
        let symbols = self.input.symbols;
        match (signal.area(), symbols.timer(signal)) {
            (Area::Timer, Some(t)) => t.iec_run.ident.clone(),
            _ => symbols.ident(signal),
        }
    }

    fn condition(&self, literals: &[Literal]) -> String {
        literals
            .iter()
            .map(|l| {
                let op = if l.negated { "XIO" } else { "XIC" };
                format!("{op}({})", self.bit(l.signal))
            })
            .collect()
    }

    /// The output instructions of `actions`, in order.
    fn actions(&self, actions: &[Action], out: &mut Vec<String>) {
        for action in actions {
            match *action {
                Action::Reset(Signal::Sequence) => {
                    out.extend(self.flags.iter().map(|f| format!("OTU({f})")));
                    out.push(format!("OTL({})", self.flags[INITIAL_STEP]));
                }
                Action::StartTimer(timer, ms) => {
                    let t = self.input.symbols.ident(timer);
                    out.push(format!("MOV({ms},{t}.PRE)"));
                    out.push(format!("OTL({})", self.bit(timer)));
                    out.push(format!("RES({t})"));
                }
                Action::Set(s) => out.push(format!("OTL({})", self.bit(s))),
                Action::Reset(s) => {
                    out.push(format!("OTU({})", self.bit(s)));
                    if s.area() == Area::Timer {
                        out.push(format!("RES({})", self.input.symbols.ident(s)));
                    }
                }
            }
        }
    }
}

/// A rung: its conditions, then its outputs side by side in a branch.
fn rung(comment: String, condition: String, outputs: &[String]) -> Rung {
    let outputs = match outputs {
        [one] => one.clone(),
        many => format!("[{}]", many.join(",")),
    };
    Rung {
        comment: one_line(&comment),
        text: format!("{condition}{outputs};"),
    }
}

fn rungs(names: &Names) -> Vec<Rung> {
    let input = names.input;
    let program = input.program;
    let symbols = input.symbols;
    let timers: Vec<(String, String)> = program
        .timers
        .iter()
        .map(|&t| (symbols.ident(t), names.bit(t)))
        .collect();
    let mut rungs = Vec::new();
    // First scan: as at power-up, everything off and the sequence at rest.
    let mut first = Vec::new();
    let allocation = input.allocation;
    for a in allocation.outputs.iter().chain(&allocation.memories) {
        first.push(format!("OTU({})", symbols.ident(a.signal)));
    }
    for (timer, run) in &timers {
        first.push(format!("OTU({run})"));
        first.push(format!("RES({timer})"));
    }
    first.extend(names.flags.iter().map(|f| format!("OTU({f})")));
    first.push(format!("OTL({})", names.flags[INITIAL_STEP]));
    names.actions(&program.init, &mut first);
    rungs.push(rung(
        format!("first scan: every output off, the sequence in STEP {INITIAL_STEP}"),
        "XIC(S:FS)".to_string(),
        &first,
    ));
    rungs.push(rung(
        "no step has fired yet in this scan".to_string(),
        String::new(),
        &[format!("OTU({})", names.fired)],
    ));
    for (timer, run) in &timers {
        rungs.push(rung(
            format!("{timer} times while {run} is set; when it is done, {run} goes off"),
            String::new(),
            &[format!(
                "XIC({run})TON({timer},?,?)XIC({timer}.DN)OTU({run})"
            )],
        ));
    }
    let count = program.steps.len();
    for (k, step) in program.steps.iter().enumerate() {
        let active = program.step_in(k);
        let in_step = format!(
            "STEP {active}: {}",
            symbols
                .step(k)
                .map_or_else(|| program.title_in(k), |n| n.active_title.clone())
        );
        // A jump's rung: the step's title names its jumps already.
        let transitions = step
            .jumps
            .iter()
            .map(|j| {
                let comment = format!("STEP {active}: {}", super::jump_comment(program, k, j));
                (comment, &j.condition, &j.actions, j.next)
            })
            .chain([(
                format!("{in_step}; {}", super::entry_comment(program, symbols, k)),
                &step.condition,
                &step.actions,
                (k + 1) % count,
            )]);
        for (comment, condition, actions, next) in transitions {
            let mut outputs = Vec::new();
            names.actions(actions, &mut outputs);
            outputs.push(format!("OTU({})", names.flags[k]));
            outputs.push(format!("OTL({})", names.flags[next]));
            outputs.push(format!("OTL({})", names.fired));
            let condition = format!(
                "XIC({})XIO({}){}",
                names.flags[k],
                names.fired,
                names.condition(condition)
            );
            rungs.push(rung(comment, condition, &outputs));
        }
    }
    for r in &program.rungs {
        let mut outputs = Vec::new();
        names.actions(&r.actions, &mut outputs);
        rungs.push(rung(
            symbols.explain(&r.comment),
            names.condition(&r.condition),
            &outputs,
        ));
    }
    for (timer, run) in &timers {
        rungs.push(rung(
            format!("{timer} starts timing in the scan that set {run}"),
            format!("XIC({run})"),
            &[format!("TON({timer},?,?)")],
        ));
    }
    rungs
}

fn bool_tag(name: String, description: String) -> Tag {
    Tag {
        name,
        data_type: "BOOL",
        description: one_line(&description),
    }
}

/// The program's own tags: step flags, `fired`, and each timer's run bit
/// and TIMER.
fn program_tags(names: &Names) -> Vec<Tag> {
    let input = names.input;
    let symbols = input.symbols;
    let mut tags: Vec<Tag> = names
        .flags
        .iter()
        .enumerate()
        .map(|(k, flag)| {
            let comment = symbols.step(k).map(|s| s.flag.comment.clone());
            bool_tag(flag.clone(), comment.unwrap_or_default())
        })
        .collect();
    tags.push(bool_tag(names.fired.clone(), symbols.fired.comment.clone()));
    for &timer in &input.program.timers {
        if let Some(t) = symbols.timer(timer) {
            tags.push(bool_tag(t.iec_run.ident.clone(), t.iec_run.comment.clone()));
        }
        tags.push(Tag {
            name: symbols.ident(timer),
            data_type: "TIMER",
            description: one_line(&symbols.comment(timer)),
        });
    }
    tags
}

/// Renders `NAME.L5X`.
pub fn render(input: &EmitInput) -> Result<String, templates::TemplateError> {
    let program = input.program;
    let symbols = input.symbols;
    let names = Names {
        input,
        flags: (0..program.steps.len())
            .map(|k| {
                symbols.step(k).map_or_else(
                    || format!("step_{}", program.step_in(k)),
                    |s| s.flag.ident.clone(),
                )
            })
            .collect(),
        fired: symbols.fired.ident.clone(),
    };
    let alloc = input.allocation;
    // As NAME.rockwell.csv describes them: the address, then the comment.
    let controller_tags = alloc
        .inputs
        .iter()
        .chain(&alloc.outputs)
        .chain(&alloc.memories)
        .map(|a| {
            let description = format!(
                "{} {}",
                a.address.display(alloc.mnemonic),
                symbols.comment(a.signal)
            );
            bool_tag(symbols.ident(a.signal), description)
        })
        .collect();
    let context = Context {
        title: one_line(input.name),
        version: env!("CARGO_PKG_VERSION"),
        source: one_line(&input.source()),
        revision: SOFTWARE_REVISION,
        program: PROGRAM,
        routine: ROUTINE,
        controller_tags,
        program_tags: program_tags(&names),
        rungs: rungs(&names),
    };
    input
        .templates
        .render("program.l5x.xml.j2", Value::from(Serde(&context)))
}
