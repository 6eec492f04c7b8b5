//! The graphical bodies for CODESYS V3 (`NAME.sfc.codesys.xml`,
//! `NAME.ld.codesys.xml`, issue 39): the POUs of the SFC chart or the Ladder
//! body exactly as `NAME.sfc.xml` / `NAME.ld.xml` hold them (the text
//! proven in Beremiz's generator and matiec, taken from that file so that
//! the two cannot drift apart), wrapped as the ST program's CODESYS file
//! is: the PLCopen v2.00 namespace CODESYS reads, the I/O in the global
//! variable list `GVL_IO` and the program's own state in `GVL_steptable`
//! (the POUs name them as `VAR_EXTERNAL`, which CODESYS accepts and does
//! not need), and a `MainTask` calling the POUs in the order Beremiz's
//! task does (timers, the body, the rungs after it).

use minijinja::Value;
use minijinja::value::Serde;
use serde::Serialize;

use super::st::{self, Internal};
use super::templates::TemplateError;
use super::{EmitInput, OutputKind};

/// Renders the CODESYS file of `body` (`OutputKind::Sfc` or `Ladder`).
pub fn render(input: &EmitInput, body: OutputKind) -> Result<String, TemplateError> {
    let (iec, _) = st::parts(input, input.scan_ms)?;
    let (internals, _) = st::internals(input);
    let (template, what, file, globals) = if body == OutputKind::Ladder {
        let file = super::ladder::render(input)?;
        let globals = super::ladder::globals(input, internals).map_err(bug)?;
        ("ld.xml.j2", "the step program in Ladder", file, globals)
    } else {
        let file = super::sfc::render(input)?;
        (
            "sfc.xml.j2",
            "the sequence as an SFC chart",
            file,
            internals,
        )
    };
    let (pous, instances) = split(&file).ok_or_else(|| TemplateError {
        file: template.to_string(),
        user: true,
        line: None,
        detail: "the file has no <pous> … </pous> followed by the task's <pouInstance … typeName=\"…\"/>, which the CODESYS file takes its POUs and their calls from".to_string(),
    })?;
    // The task calls the POUs themselves: CODESYS names a program in its
    // task by the program's name (`typeName` left empty, as it exports).
    let calls: Vec<&str> = instances
        .split("typeName=\"")
        .skip(1)
        .filter_map(|rest| rest.split('"').next())
        .collect();
    #[derive(Serialize)]
    struct Context<'c> {
        iec: &'c st::Context,
        what: &'c str,
        pous: &'c str,
        calls: Vec<&'c str>,
        globals: Vec<Internal>,
        state_object_id: String,
    }
    input.templates.render(
        "codesys_body.xml.j2",
        Value::from(Serde(&Context {
            iec: &iec,
            what,
            pous,
            calls,
            globals,
            state_object_id: st::object_id(&format!("{}/GVL_steptable", input.name)),
        })),
    )
}

/// The text inside `<pous>` and the text after `</pous>` (the instances).
fn split(file: &str) -> Option<(&str, &str)> {
    let (_, rest) = file.split_once("<pous>")?;
    let (pous, instances) = rest.split_once("</pous>")?;
    instances
        .contains("<pouInstance ")
        .then_some((pous, instances))
}

fn bug(detail: String) -> TemplateError {
    TemplateError {
        file: "ld.xml.j2".to_string(),
        user: false,
        line: None,
        detail,
    }
}
