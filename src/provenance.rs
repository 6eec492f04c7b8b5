//! How every written file records what made it. Each says "regenerate
//! rather than edit"; to regenerate, an engineer needs the command line:
//! the steptable version, the command, the options that change the output
//! and where the settings in force came from. That line ([`MadeBy`]) goes
//! into each file in the comment syntax its format allows, decided here,
//! in one place, for every file name a command writes ([`stamp`]): a
//! comment line in the programs (ST, IL, AWL, FST, CoDeSys exports), an
//! XML comment in the XML files, a `remark` in the Studio 5000 list, the
//! Comments property (`dc:description`) of a workbook. The lists whose
//! importers take no comment line (`NAME.io.csv`, `NAME.faults.csv`,
//! `NAME.fst-alloc.csv`, the STEP 7 `NAME.sdf`), the diagrams (pictures,
//! shown as they are) and synth's reports get no header; the folder's
//! `.steptable-manifest` records the line for every file (see
//! [`crate::manifest`]).
//!
//! The line is deterministic: no time, only the input's file name (not its
//! folder), the options as the command line gave them with every path cut
//! to its last part; the output folder is left out (it does not change a
//! byte).

use std::io::{Read, Write};

use crate::emit::{CommandFile, OutputFile, OutputKind};
use crate::settings::Settings;

/// The one line that says how a file was made.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MadeBy(String);

impl MadeBy {
    /// The line for outputs of the table `file` made under `settings`:
    /// `made by steptable 0.1.0 from paper.xlsx: steptable convert
    /// paper.xlsx --target siemens; settings: …`.
    pub fn of_run(settings: &Settings, file: &str) -> MadeBy {
        let name = std::path::Path::new(file)
            .file_name()
            .map(|n| n.to_string_lossy().to_string())
            .unwrap_or_else(|| file.to_string());
        MadeBy::new(
            settings.invocation.as_deref(),
            &name,
            &settings_source(settings),
        )
    }

    /// The line for outputs made from `source` (a table's file name, or a
    /// sequence), by the command line `invocation` (`None`: a library call
    /// without one), with settings from `settings`.
    pub fn new(invocation: Option<&str>, source: &str, settings: &str) -> MadeBy {
        let command = match invocation {
            Some(line) => format!("steptable {line}"),
            None => "a library call".to_string(),
        };
        MadeBy(crate::emit::one_line(&format!(
            "made by steptable {} from {source}: {command}; settings: {settings}",
            env!("CARGO_PKG_VERSION")
        )))
    }

    /// The line, without any comment syntax.
    pub fn text(&self) -> &str {
        &self.0
    }
}

/// Where the settings in force came from, for the line: the command line
/// (shown before it) or the library's caller, what a SETTINGS or ADDRESSES
/// sheet gave, and defaults.
pub fn settings_source(settings: &Settings) -> String {
    let mut sheet: Vec<String> = settings.cells.keys().map(|l| l.to_string()).collect();
    // Per actuator, what the command line did not give (by number or by
    // name) came from the sheet; an actuator is named as the engineer's
    // actuator table writes it (`C1 (clamp) stroke`).
    let naming = &settings.naming;
    let per_actuator = |what: &str, given: Vec<u32>, in_force: Vec<u32>| -> Vec<String> {
        in_force
            .into_iter()
            .filter(|n| !given.contains(n))
            .map(|n| match naming.actuators.get(&n) {
                Some(name) => format!("C{n} ({}) {what}", name.text),
                None => format!("C{n} {what}"),
            })
            .collect()
    };
    let by_line = |numbered: Vec<u32>, named: Vec<&String>| -> Vec<u32> {
        let named = named
            .into_iter()
            .filter_map(|name| naming.actuator_called(name));
        numbered.into_iter().chain(named).collect()
    };
    let sim = &settings.simulation;
    let given = &settings.given;
    sheet.extend(per_actuator(
        "valve",
        by_line(
            given.valves.keys().copied().collect(),
            given.named_valves.keys().collect(),
        ),
        sim.machine.valves.per_actuator.keys().copied().collect(),
    ));
    sheet.extend(per_actuator(
        "stroke",
        by_line(
            given.strokes.keys().copied().collect(),
            given.named_strokes.keys().collect(),
        ),
        // A kind's own times (a gripper's build-up and release) are a
        // default, not the sheet's, unless the engineer gave other ones.
        sim.machine
            .strokes
            .per_actuator
            .iter()
            .filter(|(n, stroke)| {
                let kind = sim.machine.valves.per_actuator.get(n);
                kind.and_then(|k| k.default_stroke()).as_ref() != Some(*stroke)
            })
            .map(|(n, _)| *n)
            .collect(),
    ));
    sheet.extend(per_actuator(
        "load",
        by_line(
            given.loads.keys().copied().collect(),
            given.named_loads.keys().collect(),
        ),
        sim.machine.loads.keys().copied().collect(),
    ));
    sheet.extend(
        settings
            .named
            .keys()
            .filter(|row| !given.named.contains_key(row))
            .map(|row| row.label().to_string()),
    );
    // The names of the actuator table come only from the sheet, and every
    // comment and identifier shows them.
    if !naming.actuators.is_empty() {
        sheet.push("actuator names".to_string());
    }
    sheet.sort();
    sheet.dedup();
    let first = match settings.invocation {
        Some(_) => "the command line",
        None => "the caller's",
    };
    let mut parts = vec![first.to_string()];
    if !sheet.is_empty() {
        parts.push(format!("the SETTINGS sheet ({})", sheet.join(", ")));
    }
    if !settings.pins.is_empty() {
        parts.push(format!(
            "the ADDRESSES sheet ({} pin(s))",
            settings.pins.len()
        ));
    }
    parts.push("defaults for the rest".to_string());
    parts.join(", ")
}

/// How a file of a given name takes the line.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Syntax {
    /// `(* … *)` as the first line: ST, IL, a global variable list.
    Iec,
    /// `(* … *)` after the leading `(* @…*)` pragmas CoDeSys V2.3 reads
    /// first.
    IecAfterPragmas,
    /// `// …` (STEP 7 AWL and TIA Portal SCL sources).
    Awl,
    /// `" …` (Festo FST statement list).
    Fst,
    /// `<!-- … -->` after the XML declaration (PLCopen, CODESYS, Beremiz,
    /// Studio 5000's L5X).
    Xml,
    /// `<!-- … -->` after the HTML doctype (the report).
    Html,
    /// `remark,"…"` after Studio 5000's first line.
    Remark,
    /// The workbook's Comments property.
    Workbook,
    /// No comment its readers accept: the manifest holds the line.
    None,
}

fn syntax(name: &str) -> Syntax {
    let ends = |suffix: &str| name.ends_with(suffix);
    if ends(OutputKind::CodesysV2.suffix()) {
        Syntax::IecAfterPragmas
    } else if ends(OutputKind::StructuredText.suffix())
        || ends(OutputKind::Gvl.suffix())
        || ends(CommandFile::EquationsIl.suffix())
    {
        Syntax::Iec
    } else if ends(OutputKind::Awl.suffix()) || ends(OutputKind::Scl.suffix()) {
        Syntax::Awl
    } else if ends(OutputKind::Fst.suffix()) {
        Syntax::Fst
    } else if ends(".xml") || ends(OutputKind::L5x.suffix()) {
        Syntax::Xml
    } else if ends(OutputKind::Report.suffix()) {
        Syntax::Html
    } else if ends(OutputKind::Rockwell.suffix()) {
        Syntax::Remark
    } else if ends(".xlsx") {
        Syntax::Workbook
    } else {
        Syntax::None
    }
}

/// `file` with the line `made` in the comment syntax of its format (see
/// the module's doc); a file that takes no comment, unchanged.
pub fn stamp(file: OutputFile, made: &MadeBy) -> Result<OutputFile, String> {
    let line = made.text();
    let syntax = syntax(&file.name);
    if syntax == Syntax::Workbook {
        let bytes = workbook_comment(&file.bytes, line)
            .map_err(|e| format!("{}: cannot record how it was made: {e}", file.name))?;
        return Ok(OutputFile { bytes, ..file });
    }
    // The files Windows tools read in their ANSI code page are
    // Windows-1252 already: read, stamped and written back in it.
    let ansi = OutputKind::ALL
        .iter()
        .any(|k| k.windows_ansi() && file.name.ends_with(k.suffix()));
    let text = match ansi {
        true => encoding_rs::WINDOWS_1252
            .decode_without_bom_handling(&file.bytes)
            .0
            .into_owned(),
        false => match String::from_utf8(file.bytes.clone()) {
            Ok(text) => text,
            Err(_) => return Ok(file),
        },
    };
    // The lists Windows tools import end their lines in CRLF; the line
    // added ends as the file's first line does.
    let eol = if text.split('\n').next().is_some_and(|l| l.ends_with('\r')) {
        "\r\n"
    } else {
        "\n"
    };
    let (at, comment) = match syntax {
        Syntax::Iec => (0, format!("(* {} *)", iec_comment(line))),
        Syntax::IecAfterPragmas => (
            after_lines(&text, |l| l.starts_with("(* @")),
            format!("(* {} *)", iec_comment(line)),
        ),
        Syntax::Awl => (0, format!("// {line}")),
        Syntax::Fst => (0, format!("\" {line}")),
        Syntax::Xml => (
            after_lines(&text, |l| l.starts_with("<?xml")),
            format!("<!-- {} -->", xml_comment(line)),
        ),
        // HTML, unlike XML, allows `--` inside a comment; only its end may
        // not appear there.
        Syntax::Html => (
            after_lines(&text, |l| l.starts_with("<!DOCTYPE")),
            format!("<!-- {} -->", line.replace("-->", "- ->")),
        ),
        Syntax::Remark => (
            first_line_end(&text),
            format!("remark,\"{}\"", line.replace('"', "\"\"")),
        ),
        Syntax::Workbook | Syntax::None => return Ok(file),
    };
    let mut out = String::with_capacity(text.len() + comment.len() + 2);
    out.push_str(&text[..at]);
    out.push_str(&comment);
    out.push_str(eol);
    out.push_str(&text[at..]);
    let bytes = match ansi {
        true => crate::emit::windows_1252(&out),
        false => out.into_bytes(),
    };
    Ok(OutputFile { bytes, ..file })
}

/// Every file of `files`, stamped.
pub fn stamp_all(files: Vec<OutputFile>, made: &MadeBy) -> Result<Vec<OutputFile>, String> {
    // Each file is copied whole behind its new first lines (the workbook
    // zipped again): on both cores.
    use rayon::prelude::*;
    files.into_par_iter().map(|f| stamp(f, made)).collect()
}

/// The byte offset after the leading lines that `leading` accepts.
fn after_lines(text: &str, leading: impl Fn(&str) -> bool) -> usize {
    let mut at = 0;
    for line in text.split_inclusive('\n') {
        if !leading(line) {
            break;
        }
        at += line.len();
    }
    at
}

/// The byte offset after the first line.
fn first_line_end(text: &str) -> usize {
    text.find('\n').map_or(text.len(), |i| i + 1)
}

/// Text inside `(* … *)`: a file name holding `*)` must not end the
/// comment, nor `(*` open a nested one (CoDeSys nests them).
fn iec_comment(text: &str) -> String {
    text.replace("(*", "( *").replace("*)", "* )")
}

/// Text inside `<!-- … -->`, where XML forbids `--`: the options' double
/// dashes are written `- -` there.
fn xml_comment(text: &str) -> String {
    let mut out = text.to_string();
    while out.contains("--") {
        out = out.replace("--", "- -");
    }
    out
}

/// A workbook (a zip of XML parts) with `line` as its Comments property
/// (`dc:description` in `docProps/core.xml`, what Excel and LibreOffice
/// show under File > Properties). Every other part is copied as it was.
fn workbook_comment(bytes: &[u8], line: &str) -> Result<Vec<u8>, zip::result::ZipError> {
    const CORE: &str = "docProps/core.xml";
    const END: &str = "</cp:coreProperties>";
    let mut archive = zip::ZipArchive::new(std::io::Cursor::new(bytes))?;
    let mut writer =
        zip::ZipWriter::new(std::io::Cursor::new(Vec::with_capacity(bytes.len() + 512)));
    for i in 0..archive.len() {
        let entry = archive.by_index_raw(i)?;
        if entry.name()? != CORE {
            writer.raw_copy_file(entry)?;
            continue;
        }
        drop(entry);
        let mut core = String::new();
        archive.by_index(i)?.read_to_string(&mut core)?;
        let description = format!("<dc:description>{}</dc:description>", xml_text(line));
        let core = match core.rfind(END) {
            Some(at) if !core.contains("<dc:description>") => {
                format!("{}{description}{}", &core[..at], &core[at..])
            }
            _ => core,
        };
        // The fixed time rust_xlsxwriter gives its parts: byte-stable.
        let options = zip::write::SimpleFileOptions::default()
            .compression_method(zip::CompressionMethod::Deflated)
            .last_modified_time(zip::DateTime::default());
        writer.start_file(CORE, options)?;
        writer.write_all(core.as_bytes())?;
    }
    Ok(writer.finish()?.into_inner())
}

/// Text as XML character data.
fn xml_text(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn made() -> MadeBy {
        let mut settings = Settings::new();
        settings.invocation = Some("convert x*)(*--y.xlsx --target siemens".to_string());
        MadeBy::of_run(&settings, "/tmp/abc/x*)(*--y.xlsx")
    }

    fn stamped(name: &str, text: &str) -> String {
        let file = OutputFile {
            name: name.to_string(),
            bytes: text.as_bytes().to_vec(),
        };
        String::from_utf8(stamp(file, &made()).unwrap().bytes).unwrap()
    }

    #[test]
    fn the_line_names_the_file_not_its_folder_and_no_time() {
        let text = made().text().to_string();
        assert!(
            text.starts_with(&format!(
                "made by steptable {} from x*)(*--y.xlsx: steptable convert",
                env!("CARGO_PKG_VERSION")
            )),
            "{text}"
        );
        assert!(!text.contains("/tmp"), "{text}");
    }

    #[test]
    fn each_format_gets_the_line_in_its_own_comment_syntax() {
        let st = stamped("p.st", "PROGRAM p\nEND_PROGRAM\n");
        assert!(st.starts_with("(* made by"), "{st}");
        // The comment ends once, at its end.
        let first = st.lines().next().unwrap();
        assert_eq!(first.matches("*)").count(), 1, "{first}");
        assert_eq!(first.matches("(*").count(), 1, "{first}");
        let exp = stamped(
            "p.exp",
            "(* @NESTEDCOMMENTS := 'Yes' *)\r\n(* @PATH := '' *)\r\nVAR_GLOBAL\r\n",
        );
        let lines: Vec<&str> = exp.split("\r\n").collect();
        assert!(lines[2].starts_with("(* made by"), "{exp}");
        assert_eq!(lines[3], "VAR_GLOBAL");
        let xml = stamped("p.plcopen.xml", "<?xml version=\"1.0\"?>\n<project/>\n");
        let comment = xml.lines().nth(1).unwrap();
        assert!(comment.starts_with("<!-- made by"), "{xml}");
        assert!(!comment[4..comment.len() - 3].contains("--"), "{comment}");
        assert!(stamped("p.awl", "ORGANIZATION_BLOCK\n").starts_with("// made by"));
        assert!(stamped("p.fst.txt", "STEP INIT\n").starts_with("\" made by"));
        let rockwell = stamped("p.rockwell.csv", "remark,\"CSV-Import-Export\"\r\n0.3\r\n");
        let lines: Vec<&str> = rockwell.split("\r\n").collect();
        assert_eq!(lines[0], "remark,\"CSV-Import-Export\"");
        assert!(lines[1].starts_with("remark,\"made by"), "{rockwell}");
        for list in [
            "p.io.csv",
            "p.faults.csv",
            "p.fst-alloc.csv",
            "p.sdf",
            "p.synth.json",
            "p.diagram.svg",
        ] {
            assert_eq!(stamped(list, "a,b\n"), "a,b\n", "{list}");
        }
    }

    #[test]
    fn a_workbook_gets_the_line_as_its_comments_property() {
        let mut workbook = rust_xlsxwriter::Workbook::new();
        workbook.add_worksheet();
        let bytes = workbook.save_to_buffer().unwrap();
        let file = OutputFile {
            name: "p.xlsx".to_string(),
            bytes,
        };
        let stamped = stamp(file, &made()).unwrap();
        let mut archive = zip::ZipArchive::new(std::io::Cursor::new(stamped.bytes)).unwrap();
        let mut core = String::new();
        archive
            .by_name("docProps/core.xml")
            .unwrap()
            .read_to_string(&mut core)
            .unwrap();
        assert!(core.contains("<dc:description>made by steptable"), "{core}");
        // The rest of the workbook still reads.
        assert!(archive.by_name("xl/workbook.xml").is_ok());
    }
}
