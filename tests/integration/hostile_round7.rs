//! The seventh round of hostile input: what the red teams rt12 and rt13
//! left open. A formula saved without its value where a STEP label, a
//! BRANCH header or a pin goes (the table or the pin read without it, with
//! warnings only), a move between the BRANCH headers and the first step,
//! and a watchdog no PLC timer holds that `check` called ok. Each row goes
//! through the binary: its exit code, each code at its cell, and that
//! nothing was written.

use crate::helpers::steptable;
use crate::hostile_round6::uncomputed;

fn stderr(assert: &assert_cmd::assert::Assert) -> String {
    String::from_utf8_lossy(&assert.get_output().stderr).into_owned()
}

/// One workbook refused: `sheets` written, the cell `cell` of the sheet
/// part `part` made a formula without its value (when given).
struct Refused {
    name: &'static str,
    sheets: &'static [(&'static str, &'static [&'static [&'static str]])],
    formula: Option<(&'static str, &'static str, &'static str)>,
    says: &'static [&'static str],
    not: &'static [&'static str],
}

const TABLE: &str = "SEQUENTIAL CONTROL DESCRIPTION";

fn refused_cases() -> Vec<Refused> {
    vec![
        Refused {
            name: "the first STEP label a formula",
            sheets: &[(
                TABLE,
                &[
                    &["", "BRANCH 1"],
                    &["STEP 1", "I:part"],
                    &["STEP 2", "C1+1"],
                    &["STEP 3", "C1-0"],
                ],
            )],
            formula: Some(("sheet1.xml", "A2", "\"STEP \"&amp;\"1\"")),
            says: &[
                "!A2: error[E016]: the formula =\"STEP \"&\"1\" has no computed value",
                "!B2: error[E010]: \"I:part\" lies outside the table and would be lost: its row 2 has no STEP label, and it lies above the table's first step (row 3)",
            ],
            not: &["W003"],
        },
        Refused {
            name: "a middle STEP label a formula",
            sheets: &[(
                TABLE,
                &[
                    &["", "BRANCH 1"],
                    &["STEP 1", "C1+1"],
                    &["STEP 2", "C2+1"],
                    &["STEP 3", "C1-0"],
                    &["STEP 4", "C2-0"],
                ],
            )],
            formula: Some(("sheet1.xml", "A3", "\"STEP \"&amp;\"2\"")),
            says: &[
                "!A3: error[E016]: the formula",
                "!B3: error[E010]: \"C2+1\" lies outside the table and would be lost: its row's STEP label in A3 is a formula without a computed value",
            ],
            not: &["add the label"],
        },
        Refused {
            name: "a BRANCH header a formula",
            sheets: &[(
                TABLE,
                &[
                    &["", "BRANCH 1", "BRANCH 2"],
                    &["STEP 1", "C1+1", "C2+1"],
                    &["STEP 2", "C1-0", "C2-0"],
                ],
            )],
            formula: Some(("sheet1.xml", "C1", "\"BRANCH \"&amp;\"2\"")),
            says: &["!C1: error[E016]: the formula"],
            not: &["W003"],
        },
        Refused {
            name: "a move between the BRANCH headers and the first step",
            sheets: &[(
                TABLE,
                &[
                    &["", "BRANCH 1"],
                    &["", "C2+1"],
                    &["STEP 1", "C1+1"],
                    &["STEP 2", "C1-0"],
                ],
            )],
            formula: None,
            says: &["!B2: error[E010]: \"C2+1\" lies outside the table and would be lost"],
            not: &["W003"],
        },
        Refused {
            name: "a pinned signal a formula",
            sheets: &[
                (
                    TABLE,
                    &[&["", "BRANCH 1"], &["STEP 1", "C1+1"], &["STEP 2", "C1-0"]],
                ),
                ("ADDRESSES", &[&["SIGNAL", "ADDRESS"], &["START", "%IX0.5"]]),
            ],
            formula: Some(("sheet2.xml", "A2", "\"ST\"&amp;\"ART\"")),
            says: &["ADDRESSES!A2: error[E016]: the formula =\"ST\"&\"ART\" has no computed value"],
            not: &["E035"],
        },
        Refused {
            name: "a pinned address a formula",
            sheets: &[
                (
                    TABLE,
                    &[&["", "BRANCH 1"], &["STEP 1", "C1+1"], &["STEP 2", "C1-0"]],
                ),
                ("ADDRESSES", &[&["SIGNAL", "ADDRESS"], &["START", "%IX0.5"]]),
            ],
            formula: Some(("sheet2.xml", "B2", "\"%IX0.\"&amp;\"5\"")),
            says: &["ADDRESSES!B2: error[E016]: the formula"],
            not: &["E035"],
        },
        Refused {
            name: "a formula far below the table",
            sheets: &[(
                TABLE,
                &[
                    &["", "BRANCH 1"],
                    &["STEP 1", "C1+1"],
                    &["STEP 2", "C1-0"],
                    &[""],
                    &[""],
                    &[""],
                    &[""],
                    &["", "", "", "", "", "x"],
                ],
            )],
            formula: Some(("sheet1.xml", "F8", "\"C3\"&amp;\"+1\"")),
            says: &["!F8: error[E016]: the formula =\"C3\"&\"+1\" has no computed value"],
            not: &["W003"],
        },
        Refused {
            name: "a sheet of formulas only before a sheet with a table",
            sheets: &[
                ("Data", &[&[""], &["", "x"]]),
                (
                    "Old",
                    &[&["", "BRANCH 1"], &["STEP 1", "C5+1"], &["STEP 2", "C5-0"]],
                ),
            ],
            formula: Some(("sheet1.xml", "B2", "\"C1\"&amp;\"+1\"")),
            says: &[
                "Data!B2: error[E016]: the formula =\"C1\"&\"+1\" has no computed value, and its sheet holds no move or header steptable can read",
            ],
            not: &["W003"],
        },
        Refused {
            name: "a formula above the ADDRESSES header",
            sheets: &[
                (
                    TABLE,
                    &[&["", "BRANCH 1"], &["STEP 1", "C1+1"], &["STEP 2", "C1-0"]],
                ),
                (
                    "ADDRESSES",
                    &[&["x"], &[""], &["SIGNAL", "ADDRESS"], &["C1+", "%QX0.0"]],
                ),
            ],
            formula: Some(("sheet2.xml", "A1", "\"ST\"&amp;\"ART\"")),
            says: &["ADDRESSES!A1: error[E016]: the formula =\"ST\"&\"ART\" has no computed value"],
            not: &["W003"],
        },
    ]
}

/// A formula saved without its value where a STEP label, a BRANCH header
/// or a pin goes cannot be read: the table (or the pin) would be read
/// without it. E016 at the cell, nothing written, where it was a W003 and
/// a table of fewer steps (rt12 F2, F10; rt13 F5). A move between the
/// headers and the first step would be lost: E010, where it was a W003.
#[test]
fn what_cannot_be_read_where_the_table_goes_is_refused_at_its_cell() {
    // Every row is run, and every broken one named.
    let mut broken = Vec::new();
    for case in refused_cases() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("h.xlsx");
        let sheets: Vec<(&str, bool, &[&[&str]])> = case
            .sheets
            .iter()
            .map(|(n, rows)| (*n, false, *rows))
            .collect();
        let mut bytes = crate::messy::workbook(&sheets);
        if let Some((part, cell, formula)) = case.formula {
            bytes = uncomputed(bytes, part, cell, formula);
        }
        std::fs::write(&path, bytes).unwrap();
        for command in ["check", "convert"] {
            let out = dir.path().join("out");
            let mut run = steptable();
            run.arg(command).arg(&path);
            if command == "convert" {
                run.arg("-o").arg(&out);
            }
            let output = run.output().unwrap();
            let said = String::from_utf8_lossy(&output.stderr);
            let mut wrong = Vec::new();
            if output.status.code() != Some(1) {
                wrong.push(format!("exit {:?}", output.status.code()));
            }
            wrong.extend(
                case.says
                    .iter()
                    .filter(|l| !said.contains(*l))
                    .map(|l| format!("no {l}")),
            );
            wrong.extend(
                case.not
                    .iter()
                    .filter(|w| said.contains(*w))
                    .map(|w| format!("says {w}")),
            );
            if out.exists() {
                wrong.push("wrote files".to_string());
            }
            if !wrong.is_empty() {
                broken.push(format!(
                    "{}, {command}: {}\n{said}",
                    case.name,
                    wrong.join("; ")
                ));
            }
        }
    }
    assert!(broken.is_empty(), "{}", broken.join("\n\n"));
}

/// A watchdog longer than a PLC timer holds is refused by `convert` (E032,
/// arithmetic on the strokes, no run needed); `check` said ok (rt13 F4).
/// Now both say it, at the step's cell and for the homing stage.
#[test]
fn check_refuses_a_watchdog_no_timer_holds_as_convert_does() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("w.xlsx");
    let table: &[&[&str]] = &[
        &["", "BRANCH 1"],
        &["STEP 1", "C1+1"],
        &["STEP 2", "C2+1"],
        &["STEP 3", "C2-0"],
        &["STEP 4", "C1-0"],
    ];
    let settings: &[&[&str]] = &[
        &["modes", "estop, reset"],
        &["safety", "watchdog"],
        &["actuator", "valve", "extend", "retract"],
        &["C1", "motor", "1s", "1s"],
        &["C2", "52bi", "3s", "327.5s"],
        &["home order", "C1, C2"],
    ];
    std::fs::write(
        &path,
        crate::messy::workbook(&[(TABLE, false, table), ("SETTINGS", false, settings)]),
    )
    .unwrap();
    for command in ["check", "convert"] {
        let out = dir.path().join("out");
        let mut run = steptable();
        run.arg(command).arg(&path);
        if command == "convert" {
            run.arg("-o").arg(&out);
        }
        let assert = run.assert().code(1);
        let said = stderr(&assert);
        assert!(
            said.contains("!B4: error[E032]: step 3's watchdog would need"),
            "{command}: {said}"
        );
        assert!(
            said.contains("error[E032]: a homing stage's watchdog would need"),
            "{command}: {said}"
        );
        assert!(!out.exists());
    }
    // 327 s is within the timers: check passes.
    let settings: &[&[&str]] = &[
        &["modes", "estop, reset"],
        &["safety", "watchdog"],
        &["actuator", "valve", "extend", "retract"],
        &["C1", "motor", "1s", "1s"],
        &["C2", "52bi", "3s", "327s"],
        &["home order", "C1, C2"],
    ];
    std::fs::write(
        &path,
        crate::messy::workbook(&[(TABLE, false, table), ("SETTINGS", false, settings)]),
    )
    .unwrap();
    steptable().arg("check").arg(&path).assert().code(0);
}

/// A guard opening while RESET homes halts the homing; the RESET that
/// acknowledges the halt homes on. The scenario said the first homing
/// start and the end, but neither the halt nor the second start (rt12 F8):
/// the `homing` memory stays set through the halt.
#[test]
fn a_halted_homing_and_the_reset_that_homes_on_are_said() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("ic.xlsx");
    let table: &[&[&str]] = &[
        &["", "BRANCH 1"],
        &["STEP 1", "C1+1"],
        &["STEP 2", "C2+1; Y:heater+"],
        &["STEP 3", "C2-0"],
        &["STEP 4", "C1-0; Y:heater-"],
    ];
    let settings: &[&[&str]] = &[
        &["modes", "estop, reset"],
        &["interlock", "guard in steps 2-3"],
        &["actuator", "valve", "extend", "retract"],
        &["C1", "53closed", "1s", "3s"],
    ];
    std::fs::write(
        &path,
        crate::messy::workbook(&[(TABLE, false, table), ("SETTINGS", false, settings)]),
    )
    .unwrap();
    let said = crate::helpers::squeezed_stdout(
        &steptable()
            .arg("simulate")
            .arg(&path)
            .args(["--safety", "watchdog", "--press", "START@0.5s", "--press"])
            .args([
                "ESTOP@step3",
                "--press",
                "RESET@+1s",
                "--stick",
                "guard=0@+0.5s",
            ])
            .args(["--stick", "guard=1@+1s", "--press", "RESET@+1s", "--press"])
            .arg("START@step0")
            .assert()
            .code(0),
    );
    let lines: Vec<&str> = said.lines().collect();
    let at = |text: &str| {
        lines
            .iter()
            .position(|l| l.contains(text))
            .unwrap_or_else(|| panic!("no {text}:\n{said}"))
    };
    let halted = at("homing halted: RESET homes on");
    assert!(at("guard stuck at 0") < halted, "{said}");
    let starts: Vec<usize> = (0..lines.len())
        .filter(|&i| lines[i].ends_with("homing starts"))
        .collect();
    assert_eq!(starts.len(), 2, "{said}");
    assert!(starts[0] < halted && halted < starts[1], "{said}");
    assert!(starts[1] < at("homing done"), "{said}");
}

/// With `--message-format json` a scenario printed its table on stderr and
/// nothing on stdout, even when the run found a problem (rt13 F7): a script
/// could not see it. Each problem is a W014 object now, with its time and
/// step; the human output lists them in the table only.
#[test]
fn a_scenarios_problems_are_said_in_json() {
    let paper = crate::helpers::sample("paper_example.xlsx");
    let run = |format: &str| {
        steptable()
            .arg("simulate")
            .arg(&paper)
            .args(["--press", "START@0s", "--stick", "x21=1@1.2s"])
            .args(["--message-format", format])
            .output()
            .unwrap()
    };
    let json = run("json");
    assert_eq!(json.status.code(), Some(0));
    let objects: Vec<serde_json::Value> = String::from_utf8_lossy(&json.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).expect("one JSON object per line"))
        .collect();
    let messages: Vec<&str> = objects
        .iter()
        .inspect(|o| assert_eq!(o["code"], "W014", "{o}"))
        .map(|o| o["message"].as_str().unwrap())
        .collect();
    assert_eq!(
        messages,
        [
            "at 1.97 s in step 4: step 4 started before step 3 finished (C2 had not reached x21)",
            "at 1.97 s in step 4: C2 ran through x22 in step 4"
        ]
    );
    let table = String::from_utf8_lossy(&json.stderr);
    assert!(
        table.contains("problem: C2 ran through x22 in step 4"),
        "{table}"
    );
    let human = run("human");
    let said = String::from_utf8_lossy(&human.stdout);
    assert!(said.contains("problem: C2 ran through x22"), "{said}");
    assert!(!said.contains("W014") && !String::from_utf8_lossy(&human.stderr).contains("W014"));
}

/// One `.ods` workbook or `.xlsx` workbook refused: E016 at `cell`.
fn refused_bytes(name: &str, bytes: Vec<u8>, cell: &str) {
    let says = format!("!{cell}: error[E016]: the formula");
    crate::hostile_round8::refused(name, bytes, &[&says]);
}

/// A formula an `.ods` saved without its value read as an empty cell
/// (calamine's values hold nothing there), so a step's move vanished with
/// exit 0 (rt14 F13). It is E016 at its cell, as in an `.xlsx`.
#[test]
fn an_ods_formula_without_its_value_is_e016() {
    let cell = |text: &str| {
        format!(
            "<table:table-cell office:value-type=\"string\"><text:p>{text}</text:p></table:table-cell>"
        )
    };
    let row = |cells: &[String]| format!("<table:table-row>{}</table:table-row>", cells.concat());
    let formula =
        "<table:table-cell table:formula=\"of:=&quot;C1&quot;&amp;&quot;-0&quot;\"/>".to_string();
    let table = [
        row(&[cell(""), cell("BRANCH 1")]),
        row(&[cell("STEP 1"), cell("C1+1")]),
        row(&[cell("STEP 2"), cell("C2+1")]),
        row(&[cell("STEP 3"), formula]),
        row(&[cell("STEP 4"), cell("C2-0")]),
    ]
    .concat();
    refused_bytes("f.ods", crate::hostile::ods_of(&table), "B4");
}

/// A program that does not calculate (XlsxWriter, rust_xlsxwriter) saves
/// 0 as a formula's value and asks Excel to calculate on opening
/// (`fullCalcOnLoad`): Excel shows the move, steptable read the 0 and
/// refused or dropped it elsewhere (rt14 F14). The placeholder is no value.
#[test]
fn a_placeholder_zero_in_a_workbook_to_be_calculated_is_e016() {
    let mut workbook = rust_xlsxwriter::Workbook::new();
    let sheet = workbook.add_worksheet();
    let rows: &[&[&str]] = &[
        &["", "BRANCH 1"],
        &["STEP 1", "C1+1"],
        &["STEP 2", "C2+1"],
        &["STEP 3", ""],
        &["STEP 4", "C2-0"],
    ];
    for (r, row) in rows.iter().enumerate() {
        for (c, text) in row.iter().enumerate().filter(|(_, t)| !t.is_empty()) {
            sheet.write_string(r as u32, c as u16, *text).unwrap();
        }
    }
    sheet.write_formula(3, 1, "=\"C1\"&\"-0\"").unwrap();
    refused_bytes("x.xlsx", workbook.save_to_buffer().unwrap(), "B4");
}
