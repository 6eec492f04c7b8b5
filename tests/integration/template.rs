//! The template workbook and the SETTINGS sheet.

use predicates::prelude::*;
use predicates::str::contains;

use crate::helpers::{read_sheet, sample, steptable, write_xlsx_sheets, xlsx_part};

#[test]
fn the_template_has_its_sheets_headers_validation_and_protection() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("plant.xlsx");
    steptable()
        .args(["template", "--branches", "3", "--steps", "12", "-o"])
        .arg(&path)
        .assert()
        .success()
        .stdout(contains("3 branches x 12 steps"));
    let workbook = calamine::open_workbook_auto(&path).unwrap();
    use calamine::Reader;
    assert_eq!(
        workbook.sheet_names(),
        [
            "SEQUENTIAL CONTROL DESCRIPTION",
            "SETTINGS",
            "ADDRESSES",
            "HELP",
            "EXAMPLE"
        ]
    );
    // The ADDRESSES sheet: notes above an empty SIGNAL | ADDRESS table.
    let addresses = read_sheet(&path, "ADDRESSES");
    assert_eq!(addresses[5][..2], ["SIGNAL", "ADDRESS"]);
    assert_eq!(addresses.len(), 6, "no pin in the template: {addresses:?}");
    let table = read_sheet(&path, "SEQUENTIAL CONTROL DESCRIPTION");
    assert_eq!(table[0][0], "SEQUENTIAL CONTROL DESCRIPTION");
    assert_eq!(table[2][1..4], ["BRANCH 1", "BRANCH 2", "BRANCH 3"]);
    assert_eq!(table[3][0], "STEP 1");
    assert_eq!(table[14][0], "STEP 12");

    let sheet1 = xlsx_part(&path, "xl/worksheets/sheet1.xml");
    assert!(sheet1.contains("<sheetProtection"), "protected");
    assert!(!sheet1.contains("password"), "without a password");
    assert!(sheet1.contains(r#"type="custom""#), "custom validation");
    assert!(
        sheet1.contains(r#"sqref="B4:D15""#),
        "on exactly the move cells"
    );
    assert!(
        sheet1.contains("promptTitle=\"Move\""),
        "with an input message"
    );
    let styles = xlsx_part(&path, "xl/styles.xml");
    assert!(styles.contains(r#"locked="0""#), "move cells unlocked");

    let settings = read_sheet(&path, "SETTINGS");
    let labels: Vec<&str> = settings.iter().map(|r| r[0].as_str()).collect();
    for label in [
        "target",
        "board",
        "mnemonic",
        "scan time",
        "safety",
        "actuator",
    ] {
        assert!(labels.contains(&label), "{label}");
    }
    // Every label the sheet reader knows is on the template, and HELP
    // explains the sheets an engineer may not know to fill.
    for label in steptable::settings::LABELS {
        assert!(labels.contains(&label), "{label} missing from the template");
    }
    let help = read_sheet(&path, "HELP");
    let topics: Vec<&str> = help.iter().map(|r| r[0].as_str()).collect();
    for topic in ["ADDRESSES", "Board", "J:7 if I:name"] {
        assert!(topics.contains(&topic), "HELP explains {topic}: {topics:?}");
    }
    let sheet2 = xlsx_part(&path, "xl/worksheets/sheet2.xml");
    assert!(
        sheet2.contains(r#"type="list""#),
        "choices as validation lists"
    );

    // The empty template says what to do; its EXAMPLE converts.
    steptable()
        .arg("check")
        .arg(&path)
        .assert()
        .code(1)
        .stderr(contains("the step table has no moves"));
    steptable()
        .arg("check")
        .arg(&path)
        .args(["--sheet", "EXAMPLE"])
        .assert()
        .success();
    // A second run does not overwrite a table someone may have filled in.
    steptable()
        .arg("template")
        .arg("-o")
        .arg(&path)
        .assert()
        .code(1)
        .stderr(contains("exists"));
}

/// The EXAMPLE sheet converts to the same files as the bundled sample (after
/// LibreOffice opened and saved it too: `tests/tools/libreoffice.rs`).
#[test]
fn the_templates_example_converts_like_the_sample() {
    let dir = tempfile::tempdir().unwrap();
    let template = dir.path().join("paper_example.xlsx");
    steptable()
        .arg("template")
        .arg("-o")
        .arg(&template)
        .assert()
        .success();
    let expected = crate::helpers::program_texts(
        &sample("paper_example.xlsx"),
        &dir.path().join("sample"),
        None,
    );
    let got = crate::helpers::program_texts(&template, &dir.path().join("t"), Some("EXAMPLE"));
    assert_eq!(got, expected);
}

/// The paper's example, as the library holds it.
fn paper_rows() -> Vec<&'static [&'static str]> {
    steptable::template_workbook::PAPER_EXAMPLE
        .iter()
        .map(|r| r.as_slice())
        .collect()
}

#[test]
fn settings_in_the_workbook_apply_and_flags_override_them() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("line.xlsx");
    write_xlsx_sheets(
        &path,
        &[
            ("SEQUENTIAL CONTROL DESCRIPTION", &paper_rows()),
            (
                "SETTINGS",
                &[
                    &["target", "iec"],
                    &["safety", "watchdog"],
                    &["actuator", "extend", "retract"],
                    &["C1", "2s", "2s"],
                ],
            ),
        ],
    );
    let io = |extra: &[&str]| {
        let out = dir.path().join(format!("out{}", extra.len()));
        steptable()
            .arg("convert")
            .arg(&path)
            .args(extra)
            .args(["--formats", "io,xlsx", "-o"])
            .arg(&out)
            .assert()
            .success();
        let csv = std::fs::read_to_string(out.join("line/line.io.csv")).unwrap();
        let simulation = read_sheet(&out.join("line/line.steptable.xlsx"), "SIMULATION");
        (csv, simulation)
    };
    let (csv, simulation) = io(&[]);
    assert!(csv.contains("%IX0.0,START"), "the sheet's target: {csv}");
    assert!(csv.contains(",alarm_wd,alarm"), "the sheet's safety: {csv}");
    // C1's 2 s stroke: step 1 takes about 2 s.
    assert_eq!(simulation[5][0], "STEP 1");
    assert!(
        simulation[5][2].parse::<f64>().unwrap() > 1.9,
        "{:?}",
        simulation[5]
    );
    let (csv, _) = io(&["--target", "siemens", "--safety", "none"]);
    assert!(csv.contains("I0.0,START"), "flags win: {csv}");
    assert!(!csv.contains("alarm"), "flags win: {csv}");
}

#[test]
fn an_invalid_setting_names_its_cell() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("line.xlsx");
    write_xlsx_sheets(
        &path,
        &[
            ("SEQUENTIAL CONTROL DESCRIPTION", &paper_rows()),
            (
                "SETTINGS",
                &[&["target", "beckhoff"], &["scan time", "fast"]],
            ),
        ],
    );
    steptable()
        .arg("convert")
        .arg(&path)
        .arg("-o")
        .arg(dir.path().join("out"))
        .assert()
        .code(1)
        .stderr(contains(
            "line.xlsx: SETTINGS!B1: error[E030]: target: \"beckhoff\" is not valid",
        ))
        .stderr(contains("SETTINGS!B2").and(contains("nothing written")));
    assert!(crate::helpers::files_below(&dir.path().join("out")).is_empty());
}

/// The template's cell validation accepts every spelling the reader accepts
/// (dashes, the minus sign, full-width and raised or lowered signs and
/// digits, Cyrillic C, spaces) and still flags what is no move at all. The
/// rule is read from the written workbook and evaluated on its own.
#[test]
fn the_templates_validation_accepts_what_the_reader_accepts() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.xlsx");
    steptable()
        .arg("template")
        .arg("-o")
        .arg(&path)
        .assert()
        .success();
    let sheet = crate::helpers::xlsx_part(&path, "xl/worksheets/sheet1.xml");
    let formula = sheet
        .split("<formula1>")
        .nth(1)
        .and_then(|f| f.split("</formula1>").next())
        .expect("a custom validation rule");
    let formula = formula
        .replace("&quot;", "\"")
        .replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&amp;", "&");
    let formula = format!("={formula}");
    let accepted = [
        "C2+1",
        "c2-1",
        "C1 + 1",
        "C2\u{2212}1",
        "C2\u{2013}1",
        "C2\u{2014}1",
        "C2\u{2010}1",
        "C2\u{FF0D}1",
        "C2\u{FF0B}1",
        "C\u{2082}\u{208B}1",
        "C\u{2082}\u{207A}1",
        "\u{0421}2-1",
        "\u{FF23}2+1",
        "C\u{FF12}-1",
        "C\u{00A0}2+1",
        "C2+",
        "C12+3",
        "T=2s",
        "I:part",
        "Y:lamp+",
        "C3+1; T=2s",
        "",
    ];
    for cell in accepted {
        if !cell.is_empty()
            && cell.starts_with(['C', 'c', '\u{0421}', '\u{FF23}'])
            && !cell.contains(';')
        {
            // The reader takes it as a move of some cylinder.
            assert!(
                steptable::cell::parse_move(cell).is_ok(),
                "the reader refuses {cell:?}"
            );
        }
        assert!(
            crate::excel_formula::evaluate(&formula, cell),
            "the template refuses {cell:?}"
        );
    }
    for cell in ["hello", "2+1", "X2+1", "C+1", "Cx-1", "C21", "K:6 if I:x"] {
        assert!(
            !crate::excel_formula::evaluate(&formula, cell),
            "the template accepts {cell:?}"
        );
    }
    assert!(
        formula.len() < 8192,
        "within Excel's formula length: {}",
        formula.len()
    );
    for cell in accepted_by_the_reader() {
        assert!(
            crate::excel_formula::evaluate(&formula, &cell),
            "the template refuses {cell:?}, which the reader accepts"
        );
    }
}

/// One sample per kind of item the reader knows: a new kind fails to
/// compile here until it has one (and so is tried against the template).
fn sample_of(item: &steptable::cell::CellItem) -> &'static str {
    use steptable::cell::CellItem;
    match item {
        CellItem::Move(_) => "C2+1",
        CellItem::Dwell { .. } => "T=2s",
        CellItem::Wait { .. } => "I:part=0",
        CellItem::Switch { .. } => "Y:lamp+",
        CellItem::Jump { .. } => "J:6 if I:reject",
    }
}

/// Cells the reader accepts, built from what it accepts: every kind of
/// item (alone, in any case, after another item, after an empty one), with
/// every character `cell::normalize` ignores put in at each place, and
/// every character it reads as a C, a digit or a sign in its place. Of
/// these candidates, the ones the reader parses (a space inside a name it
/// refuses).
fn accepted_by_the_reader() -> Vec<String> {
    use steptable::cell::{normalize, parse_item, parse_items};
    let kinds = [
        "C2+1",
        "T=2s",
        "I:part=0",
        "Y:lamp+",
        "J:6 if I:reject",
        "J:end if I:x",
    ];
    for kind in kinds {
        let item = parse_item(kind).expect("a sample item");
        let sample = parse_item(sample_of(&item)).expect("a sample item");
        assert_eq!(
            std::mem::discriminant(&item),
            std::mem::discriminant(&sample)
        );
    }
    let mut candidates: Vec<String> = Vec::new();
    for kind in kinds {
        candidates.extend([
            kind.to_string(),
            kind.to_lowercase(),
            format!("I:a; {kind}"),
            format!("; {kind}"),
            format!("\u{FF1B}{kind}"),
        ]);
    }
    for code in 0..=0x10FFFFu32 {
        let Some(c) = char::from_u32(code) else {
            continue;
        };
        let mapped = normalize(&c.to_string());
        if mapped.is_empty() {
            for kind in kinds {
                let chars: Vec<char> = kind.chars().collect();
                for at in 0..=chars.len() {
                    let mut cell = chars.clone();
                    cell.insert(at, c);
                    candidates.push(cell.into_iter().collect());
                }
            }
        } else if mapped == "C" {
            candidates.push(format!("{c}2+1"));
        } else if mapped == "+" || mapped == "-" {
            candidates.push(format!("C2{c}1"));
        } else if mapped.len() == 1 && mapped.as_bytes()[0].is_ascii_digit() {
            candidates.push(format!("C{c}+1"));
        }
    }
    let accepted: Vec<String> = candidates
        .into_iter()
        .filter(|cell| {
            let items = parse_items(cell);
            !items.is_empty() && items.iter().all(|i| i.is_ok())
        })
        .collect();
    // Every ignored character, at the front of each kind, is among them.
    assert!(accepted.len() > 30 * kinds.len(), "{}", accepted.len());
    accepted
}

/// What the template offers as a value, per SETTINGS label: the lists of
/// its cells' data validation, read from the written workbook.
pub fn template_lists(path: &std::path::Path) -> std::collections::BTreeMap<String, Vec<String>> {
    let xml = crate::helpers::xlsx_part(path, "xl/worksheets/sheet2.xml");
    let settings = read_sheet(path, "SETTINGS");
    let mut lists = std::collections::BTreeMap::new();
    for validation in xml.split("<dataValidation ").skip(1) {
        if !validation.contains(r#"type="list""#) {
            continue;
        }
        let sqref = validation
            .split(r#"sqref=""#)
            .nth(1)
            .unwrap()
            .split('"')
            .next()
            .unwrap();
        let first = sqref.split(':').next().unwrap();
        let row: usize = first
            .trim_start_matches(char::is_alphabetic)
            .parse()
            .unwrap();
        let choices = validation
            .split("<formula1>")
            .nth(1)
            .and_then(|f| f.split("</formula1>").next())
            .unwrap()
            .replace("&quot;", "")
            .replace('"', "")
            .split(',')
            .map(str::to_string)
            .collect();
        // A setting's value (column B): its label; an actuator column's
        // cells: the header above them.
        let col = (first.as_bytes()[0] - b'A') as usize;
        let label = if col == 1 {
            settings[row - 1][0].clone()
        } else {
            settings[row - 2][col].clone()
        };
        lists.insert(label, choices);
    }
    lists
}

/// The template's own choices never conflict: its target (`default`)
/// with every board of its list, and every target of its list with no
/// board, convert its EXAMPLE.
#[test]
fn the_templates_own_choices_never_conflict() {
    let dir = tempfile::tempdir().unwrap();
    let template = dir.path().join("t.xlsx");
    steptable()
        .arg("template")
        .arg("-o")
        .arg(&template)
        .assert()
        .success();
    let lists = template_lists(&template);
    let sheets: Vec<(String, Vec<Vec<String>>)> = [
        "SEQUENTIAL CONTROL DESCRIPTION",
        "SETTINGS",
        "ADDRESSES",
        "HELP",
        "EXAMPLE",
    ]
    .iter()
    .map(|name| (name.to_string(), read_sheet(&template, name)))
    .collect();
    let value_of = |rows: &[Vec<String>], label: &str| {
        rows.iter()
            .find(|r| r[0] == label)
            .map(|r| r[1].clone())
            .unwrap()
    };
    assert_eq!(value_of(&sheets[1].1, "target"), "default");
    assert_eq!(value_of(&sheets[1].1, "board"), "none");
    let mut choices: Vec<(String, String)> = lists["board"]
        .iter()
        .map(|board| ("default".to_string(), board.clone()))
        .collect();
    choices.extend(
        lists["target"]
            .iter()
            .map(|t| (t.clone(), "none".to_string())),
    );
    for (target, board) in choices {
        let path = dir.path().join("filled.xlsx");
        let mut sheets = sheets.clone();
        for row in sheets[1].1.iter_mut() {
            if row[0] == "target" {
                row[1] = target.clone();
            }
            if row[0] == "board" {
                row[1] = board.clone();
            }
        }
        let texts: Vec<Vec<Vec<&str>>> = sheets
            .iter()
            .map(|(_, rows)| {
                rows.iter()
                    .map(|r| r.iter().map(String::as_str).collect())
                    .collect()
            })
            .collect();
        let slices: Vec<Vec<&[&str]>> = texts
            .iter()
            .map(|rows| rows.iter().map(Vec::as_slice).collect())
            .collect();
        let named: Vec<(&str, &[&[&str]])> = sheets
            .iter()
            .zip(&slices)
            .map(|((name, _), rows)| (name.as_str(), rows.as_slice()))
            .collect();
        crate::helpers::write_xlsx_sheets(&path, &named);
        let check = steptable()
            .arg("check")
            .arg(&path)
            .args(["--sheet", "EXAMPLE"])
            .assert()
            .stderr(contains("OpenPLC's, whose addresses").not())
            .stderr(contains("warning").not());
        // The example needs 12 inputs and 8 outputs: a board with fewer
        // refuses it for its size, not for the target.
        let fits = board == "none"
            || steptable::address::BOARDS
                .iter()
                .any(|b| b.name == board && b.inputs >= 12 && b.outputs >= 8);
        if fits {
            check.success();
        } else {
            check
                .code(1)
                .stderr(contains("error[E036]: the program needs"));
        }
    }
}

/// `templates export` never overwrites edited templates without `--force`
/// and never writes through a symbolic link; an editor's swap file in a
/// `--templates` folder is not taken for a misnamed template; `template -o`
/// refuses a folder and a name that is not `.xlsx`.
#[cfg(unix)]
#[test]
fn template_files_are_never_clobbered() {
    let dir = tempfile::tempdir().unwrap();
    let templates = dir.path().join("t");
    steptable()
        .args(["templates", "export"])
        .arg(&templates)
        .assert()
        .success();
    let edited = templates.join("program.st.j2");
    let mut text = std::fs::read_to_string(&edited).unwrap();
    text.push_str("(* my edit *)\n");
    std::fs::write(&edited, &text).unwrap();
    steptable()
        .args(["templates", "export"])
        .arg(&templates)
        .assert()
        .code(1)
        .stderr(predicates::str::contains("--force"));
    assert_eq!(std::fs::read_to_string(&edited).unwrap(), text);
    // A link to a file elsewhere: --force replaces the link, not the file.
    let elsewhere = dir.path().join("elsewhere.txt");
    std::fs::write(&elsewhere, "keep me").unwrap();
    std::fs::remove_file(templates.join("gvl.txt.j2")).unwrap();
    std::os::unix::fs::symlink(&elsewhere, templates.join("gvl.txt.j2")).unwrap();
    steptable()
        .args(["templates", "export", "--force"])
        .arg(&templates)
        .assert()
        .success();
    assert_eq!(std::fs::read_to_string(&elsewhere).unwrap(), "keep me");
    assert!(
        !templates
            .join("gvl.txt.j2")
            .symlink_metadata()
            .unwrap()
            .is_symlink()
    );
    // An editor's swap file beside the templates does not stop a conversion.
    std::fs::write(templates.join(".program.st.j2.swp"), "binary junk").unwrap();
    std::fs::write(templates.join("program.st.j2~"), "backup").unwrap();
    steptable()
        .arg("convert")
        .arg(crate::helpers::sample("paper_example.xlsx"))
        .args(["--formats", "st", "--templates"])
        .arg(&templates)
        .arg("-o")
        .arg(dir.path().join("out"))
        .assert()
        .success();
    // template -o: a folder, or a name that is no workbook.
    steptable()
        .args(["template", "-o"])
        .arg(dir.path())
        .assert()
        .code(1)
        .stderr(predicates::str::contains("is a folder"));
    steptable()
        .args(["template", "-o"])
        .arg(dir.path().join("t.csv"))
        .assert()
        .code(1)
        .stderr(predicates::str::contains(".xlsx"));
    assert!(!dir.path().join("t.csv").exists());
}

/// The SETTINGS help texts wrap in their column; a row of the default
/// 15 points would let them run over the next row (LibreOffice) or cut
/// them (Excel): each row is at least as tall as its text's lines, counted
/// at 80 characters to a line, and the label column holds the longest label.
#[test]
fn settings_rows_are_tall_enough_for_their_help_and_labels_are_whole() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.xlsx");
    steptable()
        .args(["template", "-o"])
        .arg(&path)
        .assert()
        .success();
    let settings = read_sheet(&path, "SETTINGS");
    let xml = xlsx_part(&path, "xl/worksheets/sheet2.xml");
    let height = |row: usize| -> f64 {
        xml.split(&format!("<row r=\"{}\"", row + 1))
            .nth(1)
            .and_then(|r| r.split(" ht=\"").nth(1))
            .and_then(|h| h.split('"').next())
            .and_then(|h| h.parse().ok())
            .unwrap_or(15.0)
    };
    let mut checked = 0;
    let mut longest = 0;
    for (row, cells) in settings.iter().enumerate().skip(4) {
        let help = cells.get(3).map(String::as_str).unwrap_or("");
        if help.len() < 40 || cells[0].is_empty() {
            continue;
        }
        longest = longest.max(cells[0].chars().count());
        let lines = help.len().div_ceil(80);
        assert!(
            height(row) >= 15.0 * lines as f64,
            "SETTINGS row {} ({}): {} pt for {lines} lines",
            row + 1,
            cells[0],
            height(row)
        );
        checked += 1;
    }
    assert!(checked >= 10, "{checked} help rows");
    let width: f64 = xml
        .split("<col min=\"1\" max=\"1\" width=\"")
        .nth(1)
        .and_then(|w| w.split('"').next())
        .and_then(|w| w.parse().ok())
        .expect("column A's width");
    assert!(
        width >= longest as f64 + 1.0,
        "column A is {width} wide for a label of {longest} characters"
    );
}
