//! Exports checked by other tools: xmllint against the official PLCopen
//! schema, blark (an IEC 61131-3 parser) on the ST. The programs themselves
//! run in their engines in `differential.rs`.

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::helpers::{files_below, sample, samples, steptable};
use crate::{Check, Tool, shared, tool};

pub const CHECKS: &[Check] = &[
    Check::new(
        "exports::plcopen_and_codesys_xml_validate_against_the_official_schema",
        &[Tool::Xmllint, Tool::Shared],
        plcopen_and_codesys_xml_validate_against_the_official_schema,
    ),
    Check::new(
        "exports::structured_text_parses_with_blark",
        &[Tool::Blark],
        structured_text_parses_with_blark,
    ),
];

/// Converts every sample (and the paper's example with every safety check)
/// with `extra` arguments, returning the output folder.
fn convert_all(dir: &Path, extra: &[&str]) -> Vec<PathBuf> {
    steptable()
        .arg("convert")
        .args(samples())
        .args(extra)
        .arg("-o")
        .arg(dir.join("plain"))
        .assert()
        .success();
    steptable()
        .arg("convert")
        .arg(sample("paper_example.xlsx"))
        .args(extra)
        .args(["--safety", "all", "-o"])
        .arg(dir.join("safety"))
        .assert()
        .success();
    // Every operating mode, with dwells, waits and machine outputs.
    steptable()
        .arg("convert")
        .arg(sample("paper_example.xlsx"))
        .arg(sample("press_station.xlsx"))
        .args(extra)
        .args(["--modes", "all", "--safety", "all", "-o"])
        .arg(dir.join("modes"))
        .assert()
        .success();
    // The engineer's names and step comments, under ISO 1219 designations
    // and as identifiers (issue 38).
    for scheme in ["iso", "names"] {
        steptable()
            .arg("convert")
            .arg(crate::helpers::root().join("tests/fixtures/named_station.xlsx"))
            .args(extra)
            .args(["--modes", "all", "--designations", scheme, "-o"])
            .arg(dir.join(scheme))
            .assert()
            .success();
    }
    files_below(dir)
}

fn plcopen_and_codesys_xml_validate_against_the_official_schema() {
    let xmllint = tool(Tool::Xmllint);
    let dir = tempfile::tempdir().unwrap();
    let files = convert_all(dir.path(), &["--formats", "plcopen,codesys"]);
    let shared = shared();
    let schema = shared.join("reference/tc6_xml_v201.xsd");
    assert!(schema.exists(), "{} is missing", schema.display());
    let mut checked = 0;
    for file in files
        .iter()
        .filter(|f| f.to_string_lossy().ends_with(".xml"))
    {
        // The CODESYS flavour uses the v2.00 namespace, whose structure is the
        // same: validate it against v2.01 with the namespace swapped.
        let path = if file.to_string_lossy().ends_with(".codesys.xml") {
            let text = std::fs::read_to_string(file).unwrap();
            assert!(text.contains("xmlns=\"http://www.plcopen.org/xml/tc6_0200\""));
            // Not PLC_PRG: every CODESYS Standard project has one already.
            assert!(text.contains("<pou name=\"steptable_main\" pouType=\"program\">"));
            assert!(!text.contains("PLC_PRG"));
            assert!(text.contains("<task name=\"MainTask\" interval=\"PT0.01S\""));
            assert_eq!(text.matches("<ObjectId>").count(), 2);
            assert!(text.contains("<globalVars name=\"GVL_IO\">"));
            let swapped = file.with_extension("v201.xml");
            std::fs::write(&swapped, text.replace("tc6_0200", "tc6_0201")).unwrap();
            swapped
        } else {
            file.clone()
        };
        let output = Command::new(&xmllint)
            .arg("--noout")
            .arg("--schema")
            .arg(&schema)
            .arg(&path)
            .output()
            .unwrap();
        assert!(
            output.status.success(),
            "{}: {}",
            file.display(),
            String::from_utf8_lossy(&output.stderr)
        );
        checked += 1;
    }
    assert_eq!(checked, 2 * (samples().len() + 5));
}

fn structured_text_parses_with_blark() {
    let blark = tool(Tool::Blark);
    let dir = tempfile::tempdir().unwrap();
    let mut files = convert_all(dir.path(), &["--formats", "st"]);
    // The synthesised equations' program too.
    steptable()
        .args(["synth", "--sequence", "A1 A0 A1 A0 A1 A0 B1 B0 C1 C0", "-o"])
        .arg(dir.path().join("synth"))
        .assert()
        .success();
    files.push(crate::helpers::synthesised(
        &dir.path().join("synth"),
        "A1 A0 A1 A0 A1 A0 B1 B0 C1 C0",
        ".equations.st",
    ));
    for file in files {
        // blark's grammar has no CONFIGURATION (matiec and OpenPLC's upload
        // compile the whole file in differential.rs): cut it off, and make
        // sure that what is cut is one configuration and nothing else.
        let text = std::fs::read_to_string(&file).unwrap();
        let (program, configuration) = match text.find("\nCONFIGURATION ") {
            Some(at) => text.split_at(at),
            None => (text.as_str(), ""),
        };
        let configuration = configuration.trim();
        assert!(
            configuration.is_empty()
                || (configuration.matches("CONFIGURATION ").count() == 1
                    && configuration.ends_with("END_CONFIGURATION")),
            "{}: more than a configuration after the program",
            file.display()
        );
        assert!(
            program.contains("END_PROGRAM"),
            "{}: no program before the configuration",
            file.display()
        );
        let cut = file.with_extension("program.st");
        std::fs::write(&cut, program).unwrap();
        let output = Command::new(&blark)
            .arg("parse")
            .arg(&cut)
            .output()
            .unwrap();
        assert!(
            output.status.success(),
            "{}: {}",
            file.display(),
            String::from_utf8_lossy(&output.stdout)
        );
    }
}
