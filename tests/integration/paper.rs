//! The paper's example (Blagojević et al. 2019): the address sheets and the
//! program must be exactly those of DESIGN §3 and §4.

use std::collections::BTreeMap;

use crate::helpers::{read_sheet, sample, steptable};

const DESIGN_INPUTS: [(&str, &str); 12] = [
    ("I0.0", "START"),
    ("I0.1", "x10"),
    ("I0.2", "x11"),
    ("I0.3", "x20"),
    ("I0.4", "x21"),
    ("I0.5", "x22"),
    ("I0.6", "x23"),
    ("I0.7", "x30"),
    ("I0.8", "x31"),
    ("I0.9", "x32"),
    ("I0.10", "x40"),
    ("I0.11", "x41"),
];

const DESIGN_OUTPUTS: [(&str, &str); 8] = [
    ("O0.1", "y1+"),
    ("O0.2", "y2+"),
    ("O0.3", "y3+"),
    ("O0.4", "y4+"),
    ("O1.1", "y1-"),
    ("O1.2", "y2-"),
    ("O1.3", "y3-"),
    ("O1.4", "y4-"),
];

/// DESIGN §4's program, each sentence labelled with the step the program
/// is in while it waits (SFC numbering: 0 at rest), and the closing
/// transition back to step 0.
const DESIGN_PROGRAM: [(&str, &str); 9] = [
    (
        "STEP 0",
        "IF START AND x10 AND x20 AND x30 AND x40 THEN SET y1+ RESET y1-",
    ),
    ("STEP 1", "IF x11 THEN SET y2+ RESET y2-"),
    ("STEP 2", "IF x23 THEN SET y2- RESET y2+"),
    ("STEP 3", "IF x21 THEN SET y3+ RESET y3- SET y2+ RESET y2-"),
    (
        "STEP 4",
        "IF x32 AND x22 THEN SET y3- RESET y3+ SET y2- RESET y2+",
    ),
    (
        "STEP 5",
        "IF x30 AND x21 THEN SET y3+ RESET y3- SET y2+ RESET y2- SET y4+ RESET y4-",
    ),
    (
        "STEP 6",
        "IF x31 AND x22 AND x41 THEN SET y3- RESET y3+ SET y2- RESET y2+ SET y4- RESET y4+",
    ),
    ("STEP 7", "IF x30 AND x20 AND x40 THEN SET y1- RESET y1+"),
    ("STEP 8", "IF x10 THEN GOTO STEP 0"),
];

fn convert_paper(dir: &std::path::Path) -> std::path::PathBuf {
    steptable()
        .arg("convert")
        .arg(sample("paper_example.xlsx"))
        .arg("-o")
        .arg(dir)
        .assert()
        .success();
    dir.join("paper_example")
}

#[test]
fn address_sheets_are_exactly_the_papers() {
    let dir = tempfile::tempdir().unwrap();
    let out = convert_paper(dir.path());
    let workbook = out.join("paper_example.steptable.xlsx");

    let inputs = read_sheet(&workbook, "INPUT ADDRESSES");
    assert_eq!(inputs[0][..2], ["ADDRESS", "SYMBOL"]);
    assert_eq!(inputs.len(), 1 + DESIGN_INPUTS.len());
    for (row, (address, symbol)) in inputs[1..].iter().zip(DESIGN_INPUTS) {
        assert_eq!((row[0].as_str(), row[1].as_str()), (address, symbol));
    }

    let outputs = read_sheet(&workbook, "OUTPUT ADDRESSES");
    assert_eq!(outputs.len(), 1 + DESIGN_OUTPUTS.len());
    for (row, (address, symbol)) in outputs[1..].iter().zip(DESIGN_OUTPUTS) {
        assert_eq!((row[0].as_str(), row[1].as_str()), (address, symbol));
    }
}

#[test]
fn program_sheet_is_exactly_the_papers_with_middle_stops() {
    let dir = tempfile::tempdir().unwrap();
    let out = convert_paper(dir.path());
    let program = read_sheet(&out.join("paper_example.steptable.xlsx"), "PLC PROGRAM");
    assert_eq!(program[0][..2], ["STEP", "PROGRAM"]);
    for (row, (label, sentence)) in program[1..].iter().zip(DESIGN_PROGRAM) {
        assert_eq!((row[0].as_str(), row[1].as_str()), (label, sentence));
    }
    assert_eq!(program.len(), 10 + 3, "{program:?}");
    // Step 4 sends C2 to its middle position 2: it requests the stop there,
    // on the row of step 3, whose completion enters step 4.
    assert_eq!(program[4][2], "RESET m2_1 SET m2_2");
    let stops: Vec<&str> = program[10..]
        .iter()
        .filter(|r| r[0] == "MIDDLE STOP")
        .map(|r| r[1].as_str())
        .collect();
    assert_eq!(
        stops,
        [
            "IF m2_1 AND x21 THEN RESET y2+ RESET y2- RESET m2_1",
            "IF m2_2 AND x22 THEN RESET y2+ RESET y2- RESET m2_2",
            "IF m3_1 AND x31 THEN RESET y3+ RESET y3- RESET m3_1",
        ]
    );

    let table = read_sheet(
        &out.join("paper_example.steptable.xlsx"),
        "SEQUENTIAL CONTROL DESCRIPTION",
    );
    assert_eq!(table[2][1..4], ["BRANCH 1", "BRANCH 2", "BRANCH 3"]);
    assert_eq!(table[8][..4], ["STEP 6", "C3+1", "C2+2", "C4+1"]);
}

/// Reading the workbook back gives the same addresses as the `.io.csv` and the
/// same program as the `.fst.txt` (whose operands are absolute addresses).
#[test]
fn workbook_agrees_with_io_csv_and_fst() {
    let dir = tempfile::tempdir().unwrap();
    let out = convert_paper(dir.path());
    let workbook = out.join("paper_example.steptable.xlsx");

    let mut csv = csv::Reader::from_path(out.join("paper_example.io.csv")).unwrap();
    let csv_rows: Vec<(String, String)> = csv
        .records()
        .map(|r| {
            let r = r.unwrap();
            (r[0].to_string(), r[1].to_string())
        })
        .collect();
    let sheet_rows: Vec<(String, String)> = ["INPUT ADDRESSES", "OUTPUT ADDRESSES"]
        .iter()
        .flat_map(|s| read_sheet(&workbook, s).into_iter().skip(1))
        .map(|r| (r[0].clone(), r[1].clone()))
        .collect();
    assert_eq!(csv_rows, sheet_rows);

    // symbol -> address, from the allocation list
    let address: BTreeMap<String, String> = csv_rows
        .iter()
        .map(|(a, s)| (s.clone(), a.clone()))
        .collect();
    let fst = std::fs::read_to_string(out.join("paper_example.fst.txt")).unwrap();
    let mut fst_steps: BTreeMap<String, Vec<String>> = BTreeMap::new();
    let mut current: Option<String> = None;
    for line in fst.lines() {
        let code = line.split('"').next().unwrap_or("").trim();
        let words: Vec<&str> = code.split_whitespace().collect();
        match words.as_slice() {
            ["STEP", label] => current = Some(format!("STEP {label}")),
            _ if line.starts_with("\" =====") => current = None,
            _ => {
                if let Some(step) = &current {
                    let entry = fst_steps.entry(step.clone()).or_default();
                    let words: Vec<&str> = words
                        .into_iter()
                        .filter(|w| !matches!(*w, "IF" | "AND" | "THEN"))
                        .collect();
                    // Flags (F…) are the middle-stop requests, kept off the
                    // sheet's PROGRAM column: drop them with their verb.
                    if words.len() == 2 && words[1].starts_with('F') {
                        continue;
                    }
                    entry.extend(words.iter().map(|w| w.to_string()));
                }
            }
        }
    }
    let program = read_sheet(&workbook, "PLC PROGRAM");
    for row in program.iter().skip(1).filter(|r| r[0].starts_with("STEP ")) {
        let expected: Vec<String> = row[1]
            .split_whitespace()
            .filter(|w| !matches!(*w, "IF" | "AND" | "THEN"))
            .map(|w| address.get(w).cloned().unwrap_or_else(|| w.to_string()))
            .collect();
        let mut expected = expected;
        let mut got = fst_steps.get(&row[0]).cloned().unwrap_or_default();
        // The closing transition: `GOTO STEP 0` on the sheet, `JMP TO 0`
        // in FST.
        if row[0] == "STEP 8" {
            assert_eq!(
                expected.split_off(expected.len() - 3),
                ["GOTO", "STEP", "0"]
            );
            assert_eq!(got.split_off(got.len() - 3), ["JMP", "TO", "0"]);
        }
        assert_eq!(got, expected, "{}", row[0]);
    }
}

#[test]
fn outputs_are_byte_stable_and_reruns_replace_them() {
    let dir = tempfile::tempdir().unwrap();
    let out = convert_paper(dir.path());
    let first: Vec<Vec<u8>> = crate::helpers::files_below(&out)
        .iter()
        .map(|p| std::fs::read(p).unwrap())
        .collect();
    // A run with other settings replaces them (its manifest vouches for
    // them), and so does the next; an output edited by hand is refused
    // instead (`output_places.rs`).
    steptable()
        .arg("convert")
        .arg(sample("paper_example.xlsx"))
        .args(["--target", "iec", "-o"])
        .arg(dir.path())
        .assert()
        .success();
    assert_ne!(
        std::fs::read(out.join("paper_example.st")).unwrap(),
        first[crate::helpers::files_below(&out)
            .iter()
            .position(|p| p.ends_with("paper_example.st"))
            .unwrap()]
    );
    convert_paper(dir.path());
    let second: Vec<Vec<u8>> = crate::helpers::files_below(&out)
        .iter()
        .map(|p| std::fs::read(p).unwrap())
        .collect();
    assert_eq!(first.len(), crate::helpers::all_files());
    assert_eq!(first, second);
}

#[test]
fn csv_sample_gives_the_same_program_as_the_workbook() {
    let dir = tempfile::tempdir().unwrap();
    steptable()
        .args(["convert", "-o"])
        .arg(dir.path())
        .arg(sample("paper_example.csv"))
        .assert()
        .success();
    convert_paper(&dir.path().join("xlsx"));
    let from_csv =
        std::fs::read_to_string(dir.path().join("paper_example/paper_example.io.csv")).unwrap();
    let from_xlsx =
        std::fs::read_to_string(dir.path().join("xlsx/paper_example/paper_example.io.csv"))
            .unwrap();
    assert_eq!(from_csv, from_xlsx);
    // Each names its input, in its source line and the line that says how
    // it was made.
    let strip_source = |text: String| -> String {
        text.lines()
            .filter(|l| !l.contains("Source:") && !l.contains("made by steptable"))
            .collect::<Vec<_>>()
            .join("\n")
    };
    for ext in ["st", "fst.txt"] {
        let a = std::fs::read_to_string(
            dir.path()
                .join(format!("paper_example/paper_example.{ext}")),
        )
        .unwrap();
        let b = std::fs::read_to_string(
            dir.path()
                .join(format!("xlsx/paper_example/paper_example.{ext}")),
        )
        .unwrap();
        assert_eq!(strip_source(a), strip_source(b), "{ext}");
    }
}

/// The same table as legacy `.xls` (offset on a second sheet) and as an `.ods`
/// bare grid without headers gives the same allocation list and PLC PROGRAM.
#[test]
fn xls_and_ods_read_the_same_table() {
    let dir = tempfile::tempdir().unwrap();
    let reference = convert_paper(&dir.path().join("ref"));
    let expected_csv = std::fs::read(reference.join("paper_example.io.csv")).unwrap();
    let expected_program = read_sheet(
        &reference.join("paper_example.steptable.xlsx"),
        "PLC PROGRAM",
    );
    for fixture in ["paper_example.xls", "paper_example_grid.ods"] {
        let input = crate::helpers::root().join("tests/fixtures").join(fixture);
        steptable()
            .arg("convert")
            .arg(&input)
            .arg("-o")
            .arg(dir.path())
            .assert()
            .success();
        let stem = fixture.split('.').next().unwrap();
        let out = dir.path().join(stem);
        assert_eq!(
            std::fs::read(out.join(format!("{stem}.io.csv"))).unwrap(),
            expected_csv,
            "{fixture}"
        );
        assert_eq!(
            read_sheet(&out.join(format!("{stem}.steptable.xlsx")), "PLC PROGRAM"),
            expected_program,
            "{fixture}"
        );
    }
}

#[test]
fn the_binary_converts_every_sample_for_every_target() {
    let samples = crate::helpers::samples();
    for target in ["festo", "iec", "siemens"] {
        // A sample whose ADDRESSES sheet pins one target's addresses
        // converts for that target only (the oven: STEP 7).
        let fitting: Vec<&std::path::PathBuf> = samples
            .iter()
            .filter(|s| crate::helpers::targets_of(s).contains(&target))
            .collect();
        let dir = tempfile::tempdir().unwrap();
        steptable()
            .arg("convert")
            .args(&fitting)
            .args(["--target", target, "-o"])
            .arg(dir.path())
            .assert()
            .success();
        // paper_example.csv and paper_example.xlsx share a stem: two folders.
        let files = crate::helpers::files_below(dir.path());
        assert_eq!(
            files.len(),
            crate::helpers::all_files() * fitting.len(),
            "{target}: {files:?}"
        );
    }
    // The pinned oven for another target is an error at its cells.
    steptable()
        .arg("check")
        .arg(crate::helpers::sample("oven.xlsx"))
        .args(["--target", "festo"])
        .assert()
        .failure()
        .stderr(predicates::str::contains("ADDRESSES!B6: error[E035]"));
}

/// Each sheet of the written workbook keeps its header on screen when
/// scrolled: the table below its BRANCH row and right of its STEP labels,
/// the lists below their header rows, the fault table below its column
/// titles.
#[test]
fn the_workbook_freezes_every_header() {
    let dir = tempfile::tempdir().unwrap();
    steptable()
        .arg("convert")
        .arg(sample("paper_example.xlsx"))
        .args(["--formats", "xlsx", "-o"])
        .arg(dir.path())
        .assert()
        .success();
    let workbook = dir
        .path()
        .join("paper_example/paper_example.steptable.xlsx");
    for (sheet, top_left) in [
        (1, "B4"),
        (2, "A2"),
        (3, "A2"),
        (4, "A2"),
        (5, "A6"),
        (7, "A5"),
    ] {
        let xml = crate::helpers::xlsx_part(&workbook, &format!("xl/worksheets/sheet{sheet}.xml"));
        assert!(
            xml.contains(&format!(r#"topLeftCell="{top_left}""#))
                && xml.contains(r#"state="frozen""#),
            "sheet {sheet}: {}",
            xml.split("<pane")
                .nth(1)
                .unwrap_or("no pane")
                .split('>')
                .next()
                .unwrap_or("")
        );
    }
}
