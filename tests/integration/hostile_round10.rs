//! The tenth round of hostile input: what the red teams rt18 and rt19
//! found. A setting with its value after a dash (`safety — watchdog`)
//! passed in silence with the table; a note on SETTINGS (`Target: 30
//! parts/min`) was refused; valve types under no header, or with a `-`
//! among them, were lost with a W003; a Siemens engineer could not name an
//! actuator `conveyor` for FST's sake with no FST file asked for; `batch`
//! left a mistyped path out of summary.csv and named the wrong input for
//! an E040; `Ä` went as UTF-8 into the files Windows tools read as ANSI.
//! Each row goes through the binary.

use crate::helpers::{sample, steptable};
use crate::hostile_round8::refused;
use crate::hostile_round9::{check, workbook};

/// A setting and its value after a dash, or a list written with `and`, in
/// one cell with the step table: E046 as with `:` (rt18 F4).
#[test]
fn a_setting_after_a_dash_with_the_table_is_refused() {
    for text in [
        "safety — watchdog",
        "safety – watchdog",
        "safety - watchdog",
        "Modes: step and manual",
    ] {
        refused(
            "dash.xlsx",
            workbook(&[text], &[]),
            &[
                "SEQUENTIAL CONTROL DESCRIPTION!A7: error[E046]",
                "in one cell",
            ],
        );
        let csv = format!(",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C1-0\n\n{text}\n");
        refused("dash.csv", csv.into_bytes(), &["dash.csv:5:1: error[E046]"]);
    }
}

/// On SETTINGS a known label with a note after it in one cell is a note
/// (W003, exit 0), as the guide says; with a value of one word it is a
/// setting written in one cell, E046, and a wrong value is named (rt18
/// F5).
#[test]
fn a_note_after_a_settings_label_is_a_note() {
    for note in ["Target: 30 parts/min", "Safety: wear goggles"] {
        let rows: &[&[&str]] = &[&["target", "iec"], &[], &[note]];
        let (code, said) = check(workbook(&[], &[("SETTINGS", rows)]));
        assert_eq!(code, Some(0), "{note}: {said}");
        assert!(
            said.contains("SETTINGS!A3: warning[W003]") && said.contains("reads as a note"),
            "{note}: {said}"
        );
    }
    let rows: &[&[&str]] = &[&["target: codesys3"]];
    refused(
        "value.xlsx",
        workbook(&[], &[("SETTINGS", rows)]),
        &[
            "SETTINGS!A1: error[E046]",
            "\"codesys3\" is not a valid value of it",
        ],
    );
    let rows: &[&[&str]] = &[&["modes: step and manual"]];
    refused(
        "list.xlsx",
        workbook(&[], &[("SETTINGS", rows)]),
        &[
            "SETTINGS!A1: error[E046]: \"modes: step and manual\" holds the setting modes and its value in one cell;",
        ],
    );
}

/// Valve types in a column without a header, or under `Type` with a
/// placeholder among them: E046, not W003 (rt18 F6, F7).
#[test]
fn valve_types_under_no_header_or_with_a_placeholder_are_refused() {
    let headerless: &[&[&str]] = &[
        &["actuator", "extend", ""],
        &["C1", "2s", "52mono"],
        &["C2", "2s", "52bi"],
    ];
    refused(
        "headerless.xlsx",
        workbook(&[], &[("SETTINGS", headerless)]),
        &[
            "SETTINGS!C2: error[E046]",
            "in a column without a header",
            "a valve type: head it `valve`",
        ],
    );
    for placeholder in ["-", "n/a", "—"] {
        let typed: &[&[&str]] = &[
            &["actuator", "extend", "Type"],
            &["C1", "2s", "52mono"],
            &["C2", "2s", placeholder],
        ];
        refused(
            "placeholder.xlsx",
            workbook(&[], &[("SETTINGS", typed)]),
            &[
                "SETTINGS!C1: error[E046]",
                "a value under it is a valve type",
            ],
        );
    }
    // A column of notes stays one.
    let notes: &[&[&str]] = &[
        &["actuator", "extend", "Type"],
        &["C1", "2s", "clamp"],
        &["C2", "2s", "-"],
    ];
    let (code, said) = check(workbook(&[], &[("SETTINGS", notes)]));
    assert_eq!(code, Some(0), "{said}");
}

/// A stroke time that is a time, but too short, says so (rt18 F8).
#[test]
fn a_stroke_time_too_short_is_called_too_short() {
    for (header, value, says) in [
        (
            "extend",
            "0.5ms",
            "\"0.5ms\" is 0.5 ms, and a stroke time is whole milliseconds from 1ms",
        ),
        (
            "extend [ms]",
            "1,5",
            "\"1,5\" (in the header's unit) is 1.5 ms",
        ),
    ] {
        let rows: &[&[&str]] = &[&["actuator", header], &["C1", value]];
        refused(
            "short.xlsx",
            workbook(&[], &[("SETTINGS", rows)]),
            &["SETTINGS!B2: error[E030]", says],
        );
    }
}

/// `--designations names` with a name of 8 characters or more: refused
/// for FST's 9 characters only where an FST file is written (rt19 F4).
#[test]
fn fsts_name_length_binds_only_where_fst_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let rows: &[&[&str]] = &[
        &["actuator", "extend"],
        &["C1 (conveyor)", "1s"],
        &["C2 (lift)", "1s"],
    ];
    let path = dir.path().join("long.xlsx");
    std::fs::write(&path, workbook(&[], &[("SETTINGS", rows)])).unwrap();
    let convert = |formats: &str| {
        steptable()
            .args(["convert", "--designations", "names", "--target", "siemens"])
            .args(["--formats", formats, "-o"])
            .arg(dir.path().join(formats))
            .arg(&path)
            .output()
            .unwrap()
    };
    let siemens = convert("st,scl,awl,sdf");
    assert!(
        siemens.status.success(),
        "{}",
        String::from_utf8_lossy(&siemens.stderr)
    );
    let awl = std::fs::read_to_string(dir.path().join("st,scl,awl,sdf/long/long.awl")).unwrap();
    assert!(awl.contains("conveyor_end"), "{awl}");
    let fst = convert("st,fst");
    assert_eq!(fst.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&fst.stderr).contains("all Festo FST keeps of a symbol"));
}

/// `batch`: a path that names nothing has its row in summary.csv and its
/// `failed:` line (rt19 F5); an E040 names the input that failed, which
/// has no verdict, since nothing was written (rt19 F6).
#[test]
fn batch_says_every_failed_input_under_its_own_name() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(sample("oven.xlsx"), dir.path().join("oven.xlsx")).unwrap();
    let run = steptable()
        .current_dir(dir.path())
        .args(["batch", "oven.xlsx", "typo.xlsx", "-o", "out", "-q"])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert_eq!(run.status.code(), Some(1));
    assert!(stdout.contains("1 converted, 1 failed"), "{stdout}");
    assert!(
        stdout.contains("failed: typo.xlsx: error[E001]"),
        "{stdout}"
    );
    let summary = std::fs::read_to_string(dir.path().join("out/summary.csv")).unwrap();
    assert!(summary.contains("\ntypo.xlsx,failed,1,"), "{summary}");

    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(sample("paper_example.xlsx"), dir.path().join("p.xlsx")).unwrap();
    std::fs::create_dir(dir.path().join("p")).unwrap();
    std::fs::write(
        dir.path().join("p/p.io.csv"),
        std::fs::read(sample("paper_example.csv")).unwrap(),
    )
    .unwrap();
    let run = steptable()
        .current_dir(dir.path())
        .args(["batch", ".", "-o", ".", "-q", "-j", "1"])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(
        stdout.contains("error[E040]: (converting ./p.xlsx) is an input of this run"),
        "{stdout}"
    );
    let summary = std::fs::read_to_string(dir.path().join("summary.csv")).unwrap();
    let row = summary
        .lines()
        .find(|l| l.starts_with("./p.xlsx,"))
        .unwrap();
    assert!(
        row.starts_with("./p.xlsx,failed,") && !row.contains("passed"),
        "{row}"
    );
}

/// One file named twice is converted once, and said (rt19 F7).
#[test]
fn one_file_named_twice_is_converted_once() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(sample("paper_example.xlsx"), dir.path().join("p.xlsx")).unwrap();
    let run = steptable()
        .current_dir(dir.path())
        .args(["convert", "p.xlsx", "./p.xlsx", "-o", "out"])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(run.status.success(), "{stdout}");
    assert!(
        stdout.contains("note: ./p.xlsx names the file p.xlsx again; converted once"),
        "{stdout}"
    );
    let folders: Vec<_> = std::fs::read_dir(dir.path().join("out")).unwrap().collect();
    assert_eq!(folders.len(), 1);
}

/// The files Windows tools read in their ANSI code page are Windows-1252:
/// `Ä` one byte, the `.sdf`'s rows of one width; a character the code
/// page lacks is W008 (rt19 F8).
#[test]
fn the_files_windows_tools_read_are_in_their_code_page() {
    let dir = tempfile::tempdir().unwrap();
    let rows: &[&[&str]] = &[
        &["actuator", "extend"],
        &["C1 (Zylinder Ä)", "1s"],
        &["C2 (Hubzylinder)", "1s"],
    ];
    let path = dir.path().join("u.xlsx");
    std::fs::write(&path, workbook(&[], &[("SETTINGS", rows)])).unwrap();
    let run = steptable()
        .args(["convert", "-o"])
        .arg(dir.path().join("out"))
        .arg(&path)
        .output()
        .unwrap();
    assert!(run.status.success());
    let sdf = std::fs::read(dir.path().join("out/u/u.sdf")).unwrap();
    assert!(sdf.contains(&0xC4), "Ä is 0xC4 in Windows-1252");
    let widths: std::collections::BTreeSet<usize> = sdf
        .split(|b| *b == b'\n')
        .filter(|l| !l.is_empty())
        .map(<[u8]>::len)
        .collect();
    assert_eq!(widths.len(), 1, "{widths:?}");
    for file in ["u.exp", "u.fst-alloc.csv"] {
        let bytes = std::fs::read(dir.path().join("out/u").join(file)).unwrap();
        assert!(
            bytes.contains(&0xC4) && std::str::from_utf8(&bytes).is_err(),
            "{file}"
        );
    }
    let st = std::fs::read_to_string(dir.path().join("out/u/u.st")).unwrap();
    assert!(st.contains("Zylinder Ä"), "the other outputs stay UTF-8");

    let rows: &[&[&str]] = &[&["actuator", "extend"], &["C1 (Ωmega)", "1s"]];
    std::fs::write(&path, workbook(&[], &[("SETTINGS", rows)])).unwrap();
    let run = steptable()
        .args(["convert", "--formats", "st,sdf", "-o"])
        .arg(dir.path().join("greek"))
        .arg(&path)
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{said}");
    assert!(
        said.contains(
            "warning[W008]: u.sdf: these files are written in the Windows-1252 code page"
        ) && said.contains("\"Ω\""),
        "{said}"
    );
}

/// A scenario time with a space before its unit is told so, not "finer
/// than a millisecond" (rt19 F2); the end of a cycle with outputs on is
/// not called "at rest" (rt19 F3).
#[test]
fn scenario_lines_say_what_happened() {
    let run = steptable()
        .args(["simulate"])
        .arg(sample("paper_example.xlsx"))
        .args(["--press", "START@1.5 s"])
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(1));
    assert!(
        said.contains("\"1.5 s\" has a space in it: write 1.5s"),
        "{said}"
    );
    let run = steptable()
        .args(["simulate"])
        .arg(sample("oven.xlsx"))
        .args(["--press", "START@1s"])
        .output()
        .unwrap();
    let table = String::from_utf8_lossy(&run.stdout);
    assert!(table.contains("step 0   end of cycle"), "{table}");
    assert!(
        !table.contains("at rest"),
        "the oven's fan and coil stay on: {table}"
    );
}

/// Settings on a sheet of another name are W015 also where the table's
/// sheet was picked among others (its sheets are read once, while
/// picking): a regression guard for that path.
#[test]
fn settings_elsewhere_are_said_where_the_table_sheet_was_picked() {
    let mut book = rust_xlsxwriter::Workbook::new();
    let table = book.add_worksheet();
    table.set_name("Table").unwrap();
    crate::hostile_round8::write_rows(
        table,
        &[&["", "BRANCH 1"], &["STEP 1", "C1+1"], &["STEP 2", "C1-0"]],
    );
    let config = book.add_worksheet();
    config.set_name("Config").unwrap();
    crate::hostile_round8::write_rows(config, &[&["modes", "all"], &["safety", "watchdog"]]);
    let (code, said) = check(book.save_to_buffer().unwrap());
    assert_eq!(code, Some(0), "{said}");
    assert!(said.contains("Config!A1: warning[W015]"), "{said}");
}

/// `check` of a CSV table: exit code and what was said.
fn check_csv(text: &str) -> (Option<i32>, String) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.csv");
    std::fs::write(&path, text).unwrap();
    let output = steptable().arg("check").arg(&path).output().unwrap();
    let said = [&output.stdout, &output.stderr].map(|b| String::from_utf8_lossy(b).into_owned());
    (output.status.code(), said.concat())
}

/// The red team rt20 on the table's cells: a space between two digits is
/// no longer dropped (`C4+1 0` was C4+10, an actuator of 11 sensors); a
/// line break in a cell is shown as `\n` on the one line of its E010, with
/// the `;` hint; `STEP 2.5` is named as written and gives no comment `5`;
/// `STEP 2a` is said to be a label that is not STEP n.
#[test]
fn the_red_teams_look_at_the_tables_cells() {
    for (cell, says) in [
        (
            "C4+1 0",
            "a space splits a number: write C4+10 if that is meant",
        ),
        ("C1 +1 2", "write C1 +12 if that is meant"),
    ] {
        let (code, said) = check_csv(&format!(",BRANCH 1\nSTEP 1,{cell}\nSTEP 2,C1-0\n"));
        assert_eq!(code, Some(1), "{said}");
        assert!(
            said.contains("t.csv:2:2: error[E010]") && said.contains(says),
            "{said}"
        );
    }
    let (code, said) = check_csv(",BRANCH 1\nSTEP 1,\"C1+1\nT=2s\"\nSTEP 2,C1-0\n");
    assert_eq!(code, Some(1), "{said}");
    let line = said
        .lines()
        .find(|l| l.contains("E010"))
        .unwrap_or_default();
    assert!(
        line.contains(
            "\"C1+1\\nT=2s\" is not a move (separate items with `;`, not line breaks: C1+1; T=2s)"
        ),
        "{said}"
    );

    let decimal = ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C2+1\nSTEP 2.5,C2-0\nSTEP 3,C1-0\n";
    let (code, said) = check_csv(decimal);
    assert_eq!(code, Some(0), "{said}");
    assert!(
        said.contains("t.csv:4:1: warning[W002]: this row is labelled \"STEP 2.5\" (labels are whole numbers) but is step 3"),
        "{said}"
    );
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("d.csv");
    std::fs::write(&path, decimal).unwrap();
    steptable()
        .args(["convert", "--formats", "st", "-o"])
        .arg(dir.path().join("out"))
        .arg(&path)
        .assert()
        .success();
    let st = std::fs::read_to_string(dir.path().join("out/d/d.st")).unwrap();
    assert!(
        st.contains("STEP 3: C2-0 *)") && !st.contains("(5)"),
        "{st}"
    );

    let (code, said) = check_csv(",BRANCH 1\nSTEP 1,C1+1\nSTEP 2a,C1-0\n");
    assert_eq!(code, Some(1), "{said}");
    assert!(
        said.contains("is labelled \"STEP 2a\", which is not STEP and a whole number"),
        "{said}"
    );
}

/// A dwell finer than the AWL's and FST's 10 ms steps is W008, and the
/// comment beside the preset says what it holds (rt20 F1).
#[test]
fn a_dwell_rounded_up_in_awl_and_fst_is_said() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("d.csv");
    std::fs::write(&path, ",BRANCH 1\nSTEP 1,C1+1;T=15ms\nSTEP 2,C1-0\n").unwrap();
    let run = steptable()
        .args(["convert", "--formats", "st,awl,fst", "-o"])
        .arg(dir.path().join("out"))
        .arg(&path)
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{said}");
    assert!(
        said.contains("warning[W008]: dwell1 for 15 ms (d.awl 20 ms, d.fst.txt 20 ms)"),
        "{said}"
    );
    let awl = std::fs::read_to_string(dir.path().join("out/d/d.awl")).unwrap();
    assert!(
        awl.contains("start dwell1 for 15 ms (S5TIME holds 20 ms)"),
        "{awl}"
    );
    let fst = std::fs::read(dir.path().join("out/d/d.fst.txt")).unwrap();
    assert!(String::from_utf8_lossy(&fst).contains("(FST holds 20 ms)"));
    // Without those files, nothing to say.
    let run = steptable()
        .args(["convert", "--formats", "st", "-o"])
        .arg(dir.path().join("st"))
        .arg(&path)
        .output()
        .unwrap();
    assert!(!String::from_utf8_lossy(&run.stderr).contains("W008"));
}

/// `synth --sequence … --sheet X`: a sequence has no sheet, refused rather
/// than dropped (rt20 F8).
#[test]
fn synth_refuses_a_sheet_beside_a_sequence() {
    let dir = tempfile::tempdir().unwrap();
    let run = steptable()
        .args(["synth", "--sequence", "A1 A0", "--sheet", "X", "-o"])
        .arg(dir.path())
        .output()
        .unwrap();
    assert_eq!(run.status.code(), Some(1));
    let said = String::from_utf8_lossy(&run.stderr);
    assert!(
        said.contains("cannot be used with '--sheet <NAME>'"),
        "{said}"
    );
}

/// The red team rt21 on this round's rules. On SETTINGS, a value among
/// other words in one cell (`modes: estop, required by CE`, `modes: stop
/// and estp`, `target: siemens S7-1500`) is E046, not a note lost with
/// exit 0; a number or a placeholder after a label (`Target: 30`, `Modes:
/// n/a`) stays a note. A valve type beside `default` under `Type` is E046.
/// A space between digits of a dwell or a jump is E010 (`T = 1 5 s` was
/// 15 s). Under `names`, a symbol longer than STEP 7's 24 characters is
/// E015 where the `.sdf` or `.awl` is written. `batch` says a file named
/// twice; a tab in a message is shown as `\t`.
#[test]
fn the_red_teams_look_at_this_rounds_rules() {
    for text in [
        "modes: estop, required by CE",
        "modes: stop and estp",
        "modes: estop - required by CE",
        "safety: watchdog plausibility",
        "target: siemens S7-1500",
    ] {
        let rows: &[&[&str]] = &[&[text]];
        refused(
            "among.xlsx",
            workbook(&[], &[("SETTINGS", rows)]),
            &["SETTINGS!A1: error[E046]"],
        );
    }
    for note in ["Target: 30", "Target: 30/min", "Modes: n/a", "Safety — TBD"] {
        let rows: &[&[&str]] = &[&["target", "iec"], &[], &[note]];
        let (code, said) = check(workbook(&[], &[("SETTINGS", rows)]));
        assert_eq!(code, Some(0), "{note}: {said}");
    }
    let typed: &[&[&str]] = &[
        &["actuator", "extend", "Type"],
        &["C1", "2s", "52mono"],
        &["C2", "2s", "default"],
    ];
    refused(
        "default.xlsx",
        workbook(&[], &[("SETTINGS", typed)]),
        &[
            "SETTINGS!C1: error[E046]",
            "a value under it is a valve type",
        ],
    );
    for (item, says) in [
        ("T = 1 5 s", "write T = 15 s if that is meant"),
        ("J:1 0 if I:rej", "write J:10 if I:rej if that is meant"),
    ] {
        let (code, said) = check_csv(&format!(",BRANCH 1\nSTEP 1,C1+1; {item}\nSTEP 2,C1-0\n"));
        assert_eq!(code, Some(1), "{said}");
        assert!(said.contains(says), "{said}");
    }
    let (_, said) = check_csv(",BRANCH 1\nSTEP 1,C1+1\tC2+1\nSTEP 2,C1-0\n");
    assert!(said.contains("\"C1+1\\tC2+1\""), "{said}");

    let dir = tempfile::tempdir().unwrap();
    let rows: &[&[&str]] = &[
        &["actuator", "extend"],
        &["C1 (main_transfer_gripper_arm)", "1s"],
    ];
    let path = dir.path().join("long.xlsx");
    std::fs::write(&path, workbook(&[], &[("SETTINGS", rows)])).unwrap();
    let convert = |formats: &str| {
        steptable()
            .args([
                "convert",
                "--designations",
                "names",
                "--formats",
                formats,
                "-o",
            ])
            .arg(dir.path().join(formats))
            .arg(&path)
            .output()
            .unwrap()
    };
    let sdf = convert("st,sdf");
    assert_eq!(sdf.status.code(), Some(1));
    let said = String::from_utf8_lossy(&sdf.stderr);
    assert!(
        said.contains("error[E015]") && said.contains("more than the 24 characters"),
        "{said}"
    );
    assert!(convert("st,scl").status.success());

    std::fs::copy(sample("oven.xlsx"), dir.path().join("oven.xlsx")).unwrap();
    let run = steptable()
        .current_dir(dir.path())
        .args(["batch", "oven.xlsx", "./oven.xlsx", "-o", "out", "-q"])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(
        stdout.contains("note: ./oven.xlsx names the file oven.xlsx again; converted once"),
        "{stdout}"
    );
}
