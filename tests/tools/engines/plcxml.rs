//! The Structured Text inside a PLCopen XML file, put back together as an
//! engineering tool does when it opens the file (Beremiz generates the ST of
//! `plc.xml` this way): the program's variables with their addresses, types
//! and initial values, its ST body, and its configuration. CODESYS keeps the
//! I/O in a global variable list (`addData`) and its task in the project: the
//! list's variables become the program's own, and a 10 ms task is added.

use quick_xml::Reader;
use quick_xml::events::{BytesStart, Event};

#[derive(Default, Debug)]
struct Variable {
    name: String,
    address: Option<String>,
    data_type: String,
    initial: Option<String>,
    /// Which variable block it was declared in (matiec wants located
    /// variables in a block of their own, as the XML keeps them).
    block: usize,
}

pub fn attribute(e: &BytesStart, name: &str) -> Option<String> {
    e.attributes()
        .flatten()
        .find(|a| a.key.as_ref() == name)
        .and_then(|a| {
            a.normalized_value(quick_xml::XmlVersion::Implicit1_0)
                .ok()
                .map(|v| v.to_string())
        })
}

/// The character an entity reference (`&amp;`, `&#233;`) stands for:
/// quick-xml hands them over apart from the text around them.
pub fn entity(r: &quick_xml::events::BytesRef) -> Result<char, String> {
    let name = r.xml10_content();
    Ok(match name.as_ref() {
        "lt" => '<',
        "gt" => '>',
        "amp" => '&',
        "quot" => '"',
        "apos" => '\'',
        _ => r
            .resolve_char_ref()
            .map_err(|e| e.to_string())?
            .ok_or_else(|| format!("unknown entity &{name};"))?,
    })
}

/// The `.st` a tool would compile from this PLCopen XML.
pub fn structured_text(xml: &str) -> Result<String, String> {
    let mut reader = Reader::from_str(xml);
    let mut stack: Vec<String> = Vec::new();
    let mut program = None;
    let mut variables: Vec<Variable> = Vec::new();
    let mut blocks = 0;
    let mut body = String::new();
    let mut configuration = None;
    let mut resource = None;
    let mut task: Option<(String, String, String)> = None;
    let mut instance: Option<(String, String)> = None;
    let in_body = |stack: &[String]| stack.iter().any(|s| s == "ST");
    loop {
        let event = reader.read_event().map_err(|e| format!("XML: {e}"))?;
        match &event {
            Event::Start(e) | Event::Empty(e) => {
                let name = e.name().as_ref().to_string();
                match name.as_str() {
                    "pou" if attribute(e, "pouType").as_deref() == Some("program") => {
                        program = attribute(e, "name");
                    }
                    "localVars" | "globalVars" => blocks += 1,
                    "variable" => variables.push(Variable {
                        name: attribute(e, "name").unwrap_or_default(),
                        address: attribute(e, "address"),
                        block: blocks,
                        ..Variable::default()
                    }),
                    "derived" if stack.last().is_some_and(|s| s == "type") => {
                        if let Some(v) = variables.last_mut() {
                            v.data_type = attribute(e, "name").unwrap_or_default();
                        }
                    }
                    "simpleValue" => {
                        if let Some(v) = variables.last_mut() {
                            v.initial = attribute(e, "value");
                        }
                    }
                    "configuration" => configuration = attribute(e, "name"),
                    "resource" => resource = attribute(e, "name"),
                    "task" => {
                        task = Some((
                            attribute(e, "name").unwrap_or_default(),
                            attribute(e, "interval").unwrap_or_default(),
                            attribute(e, "priority").unwrap_or_default(),
                        ))
                    }
                    "pouInstance" => {
                        instance = Some((
                            attribute(e, "name").unwrap_or_default(),
                            attribute(e, "typeName").unwrap_or_default(),
                        ))
                    }
                    other if stack.last().is_some_and(|s| s == "type") => {
                        if let Some(v) = variables.last_mut() {
                            v.data_type = other.to_string();
                        }
                    }
                    _ => {}
                }
                if matches!(event, Event::Start(_)) {
                    stack.push(name);
                }
            }
            Event::End(_) => {
                stack.pop();
            }
            Event::Text(t) if in_body(&stack) => {
                body.push_str(&t.xml10_content());
            }
            Event::CData(t) if in_body(&stack) => {
                body.push_str(&t.xml10_content());
            }
            Event::GeneralRef(r) if in_body(&stack) => body.push(entity(r)?),
            Event::Eof => break,
            _ => {}
        }
    }
    let program = program.ok_or("no program POU")?;
    let mut st = format!("PROGRAM {program}\n");
    for block in 1..=blocks {
        let inside: Vec<&Variable> = variables.iter().filter(|v| v.block == block).collect();
        if inside.is_empty() {
            continue;
        }
        st.push_str("  VAR\n");
        for v in inside {
            let at = v
                .address
                .as_ref()
                .map(|a| format!(" AT {a}"))
                .unwrap_or_default();
            let init = v
                .initial
                .as_ref()
                .map(|i| format!(" := {i}"))
                .unwrap_or_default();
            st.push_str(&format!("    {}{at} : {}{init};\n", v.name, v.data_type));
        }
        st.push_str("  END_VAR\n");
    }
    st.push_str(&body);
    st.push_str("\nEND_PROGRAM\n\n");
    let (task, interval, priority) =
        task.unwrap_or(("cyclic_task".into(), "T#10ms".into(), "0".into()));
    let (instance, type_name) = match instance {
        // CODESYS calls the program by its own name, with no type; IEC
        // needs an instance name of its own.
        Some((_, t)) if t.is_empty() => ("main_instance".into(), program),
        Some(pair) => pair,
        None => ("main_instance".into(), program),
    };
    // CODESYS writes the interval as an XML duration (PT0.01S).
    let interval = match interval
        .strip_prefix("PT")
        .and_then(|t| t.strip_suffix('S'))
    {
        Some(seconds) => format!("T#{seconds}s"),
        None => interval,
    };
    st.push_str(&format!(
        "CONFIGURATION {}\n  RESOURCE {} ON PLC\n    TASK {task}(INTERVAL := {interval}, PRIORITY := {priority});\n    PROGRAM {instance} WITH {task} : {type_name};\n  END_RESOURCE\nEND_CONFIGURATION\n",
        configuration.unwrap_or_else(|| "Config0".into()),
        resource.unwrap_or_else(|| "Res0".into()),
    ));
    Ok(st)
}

/// The `.st` matiec would compile from a CoDeSys V2.3 export: its global
/// variable list becomes the program's own I/O block (CoDeSys links the two
/// by name), its program as written, and a configuration to run it.
pub fn from_codesys_v2(exp: &str) -> Result<String, String> {
    let text = exp.replace("\r\n", "\n");
    let globals = text
        .split_once("VAR_GLOBAL\n")
        .and_then(|(_, rest)| rest.split_once("END_VAR"))
        .map(|(vars, _)| vars)
        .ok_or("no VAR_GLOBAL block")?;
    let start = text.find("\nPROGRAM ").ok_or("no PROGRAM")? + 1;
    let end = text.rfind("END_PROGRAM").ok_or("no END_PROGRAM")?;
    let program = &text[start..end];
    let (head, rest) = program.split_once('\n').ok_or("empty PROGRAM")?;
    let name = head.trim_start_matches("PROGRAM").trim();
    Ok(format!(
        "{head}\n  VAR\n{globals}  END_VAR\n{rest}END_PROGRAM\n\nCONFIGURATION Config0\n  RESOURCE Res0 ON PLC\n    TASK cyclic_task(INTERVAL := T#10ms, PRIORITY := 0);\n    PROGRAM main_instance WITH cyclic_task : {name};\n  END_RESOURCE\nEND_CONFIGURATION\n"
    ))
}
