//! TIA Portal SCL external source (`NAME.scl`) for the S7-1200 and S7-1500,
//! which run no statement list: a FUNCTION_BLOCK holding the step program,
//! its instance DB and the cyclic OB `"Main"` that calls it, imported
//! through "External source files → Generate blocks from source".
//!
//! The program is the Structured Text one (the same `CASE` over the SFC
//! step, the same TON restarts), spelled as SCL spells names: the inputs
//! and outputs are the tags of `NAME.tags.xlsx` in double quotes, the
//! step counter, memories and timers the block's own statics with `#`,
//! the timers IEC `TON_TIME` multi-instances.

use minijinja::Value;
use minijinja::value::Serde;
use serde::Serialize;

use super::st::{Internal, RungContext, Spelling, StepContext, Timer};
use super::{EmitInput, one_line, templates};

/// The function block, its instance data block and the OB that calls it.
pub const BLOCK_NAME: &str = crate::symbols::PROGRAM_NAME;
pub const INSTANCE_DB: &str = crate::names::TIA_INSTANCE_DB;
pub const CYCLIC_OB: &str = crate::names::TIA_CYCLIC_OB;

#[derive(Serialize)]
struct Static {
    ident: String,
    data_type: &'static str,
    initial: Option<String>,
    comment: String,
}

#[derive(Serialize)]
struct Context {
    title: String,
    version: &'static str,
    source: String,
    target: String,
    step_note: Vec<String>,
    block: &'static str,
    instance: &'static str,
    ob: &'static str,
    statics: Vec<Static>,
    timers: Vec<Timer>,
    step_var: String,
    steps: Vec<StepContext>,
    rungs: Vec<RungContext>,
}

/// An IEC type as TIA Portal names it: the IEC on-delay is `TON_TIME`.
fn tia_type(iec: &str) -> &'static str {
    match iec {
        "INT" => "Int",
        "TIME" => "Time",
        "TON" => "TON_TIME",
        _ => "Bool",
    }
}

fn statics(internals: Vec<Internal>) -> Vec<Static> {
    internals
        .into_iter()
        .map(|v| Static {
            data_type: tia_type(v.data_type),
            initial: v.initial,
            ident: v.ident,
            comment: v.comment,
        })
        .collect()
}

/// Renders `NAME.scl`.
pub fn render(input: &EmitInput) -> Result<String, templates::TemplateError> {
    let sp = Spelling::Scl;
    let (steps, rungs) = super::st::sequence(input, sp);
    let (internals, timers) = super::st::internals(input);
    let timers = timers
        .into_iter()
        .map(|t| Timer {
            ident: sp.own(&t.ident),
            run: sp.own(&t.run),
            preset: sp.own(&t.preset),
        })
        .collect();
    let symbols = input.symbols;
    let context = Context {
        title: one_line(input.name),
        version: env!("CARGO_PKG_VERSION"),
        source: one_line(&input.source()),
        target: input.allocation.target.name().to_string(),
        step_note: super::step_numbering_note(&sp.own(&symbols.step_counter.ident))
            .iter()
            .map(|l| one_line(l))
            .collect(),
        block: BLOCK_NAME,
        instance: INSTANCE_DB,
        ob: CYCLIC_OB,
        statics: statics(internals),
        timers,
        step_var: sp.own(&symbols.step_counter.ident),
        steps,
        rungs,
    };
    input
        .templates
        .render("program.scl.j2", Value::from(Serde(&context)))
}
