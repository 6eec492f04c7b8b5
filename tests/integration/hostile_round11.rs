//! The eleventh round of hostile input: what the red team rt21 found and
//! the last session left. An `Ä` that macOS wrote as `A` and a combining
//! mark came out as `A?` in the files Windows tools read; convert's JSON
//! E040 named no input; `simulate` and `faults` refused names for FST's
//! sake; `estop and reset` in a value cell was E030; `Ölpumpe` was said to
//! begin with no letter; `C1 0+1` brought a second error; a link to
//! nothing was "no such file". Each row goes through the binary.

use crate::helpers::steptable;
use crate::hostile_round9::workbook;

/// Runs `convert` on `bytes` saved as `name` in a new folder; the folder,
/// the exit code and what it said on stderr.
fn convert(name: &str, bytes: Vec<u8>, args: &[&str]) -> (tempfile::TempDir, Option<i32>, String) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    std::fs::write(&path, bytes).unwrap();
    let run = steptable()
        .arg("convert")
        .args(args)
        .arg("-o")
        .arg(dir.path().join("out"))
        .arg(&path)
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&run.stderr).to_string();
    (dir, run.status.code(), said)
}

/// Text is read composed: an `Ä` written as `A` and U+0308 (macOS, some
/// copy-paste) is `Ä` in the Windows-1252 files, not `A?`, with no W008; a
/// mark with no composed form is W008 by its code point, not as an
/// invisible quote (rt21 F11).
#[test]
fn decomposed_letters_are_read_composed() {
    let rows: &[&[&str]] = &[
        &["actuator", "extend"],
        &["C1 (Zylinder A\u{308})", "1s"],
        &["C2 (Hubzylinder)", "1s"],
    ];
    let (dir, code, said) = convert(
        "nfd.xlsx",
        workbook(&[], &[("SETTINGS", rows)]),
        &["--formats", "st,sdf"],
    );
    assert_eq!(code, Some(0), "{said}");
    assert!(!said.contains("W008"), "{said}");
    let sdf = std::fs::read(dir.path().join("out/nfd/nfd.sdf")).unwrap();
    assert!(sdf.contains(&0xC4) && !sdf.contains(&b'?'), "Ä is 0xC4");
    let st = std::fs::read_to_string(dir.path().join("out/nfd/nfd.st")).unwrap();
    assert!(st.contains("Zylinder \u{c4}") && !st.contains('\u{308}'));

    let csv = ",BRANCH 1\nSTEP 1 (Teil pru\u{308}fen),C1+1\nSTEP 2 (q\u{308}),C1-0\n";
    let (dir, code, said) = convert("nfd.csv", csv.into(), &["--formats", "st,sdf"]);
    assert_eq!(code, Some(0), "{said}");
    assert!(
        said.contains("warning[W008]") && said.contains("U+0308") && !said.contains('\u{308}'),
        "{said}"
    );
    let sdf = std::fs::read(dir.path().join("out/nfd/nfd.sdf")).unwrap();
    assert!(sdf.windows(3).any(|w| w == b"pr\xfc"), "ü is 0xFC");
}

/// An E040 of `convert` names the input it belongs to, in JSON too, as
/// batch's does: among several inputs the output's path alone does not
/// say which was not converted (rt21 F13).
#[test]
fn a_taken_output_place_names_its_input_in_json() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("a.csv");
    std::fs::write(&input, ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C1-0\n").unwrap();
    std::fs::create_dir_all(dir.path().join("out/a")).unwrap();
    std::fs::write(dir.path().join("out/a/a.st"), "mine").unwrap();
    let run = steptable()
        .args(["convert", "--message-format", "json", "-o"])
        .arg(dir.path().join("out"))
        .arg(&input)
        .output()
        .unwrap();
    assert_eq!(run.status.code(), Some(1));
    let said = String::from_utf8_lossy(&run.stdout);
    let line = said
        .lines()
        .find(|l| l.contains("\"E040\""))
        .unwrap_or_else(|| panic!("{said}"));
    assert!(
        line.contains("(converting ") && line.contains("a.csv)"),
        "{line}"
    );
    assert_eq!(
        std::fs::read(dir.path().join("out/a/a.st")).unwrap(),
        b"mine"
    );
}

/// FST's 9 characters bind where an FST file is written: `simulate` and
/// `faults` write none, and `check --formats` checks as `convert
/// --formats` would; `check` alone as a default `convert` (rt21 F9).
#[test]
fn fsts_name_limit_binds_only_where_fst_is_written() {
    let rows: &[&[&str]] = &[
        &["actuator", "name"],
        &["C1", "gripper_arm"],
        &["C2", "gripper_arm2"],
    ];
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("dn.xlsx");
    std::fs::write(&path, workbook(&[], &[("SETTINGS", rows)])).unwrap();
    let run = |args: &[&str]| {
        let out = steptable()
            .args(args)
            .args(["--designations", "names"])
            .arg(&path)
            .current_dir(dir.path())
            .output()
            .unwrap();
        let said = String::from_utf8_lossy(&out.stderr).to_string()
            + &String::from_utf8_lossy(&out.stdout);
        (out.status.code(), said)
    };
    for args in [
        &["simulate"][..],
        &["faults", "-o", "f"],
        &["check", "--formats", "st,awl,sdf"],
    ] {
        let (code, said) = run(args);
        assert_eq!(code, Some(0), "{args:?}: {said}");
        assert!(!said.contains("E025"), "{args:?}: {said}");
    }
    for args in [&["check"][..], &["check", "--formats", "st,fst"]] {
        let (code, said) = run(args);
        assert_eq!(code, Some(1), "{args:?}: {said}");
        assert!(
            said.contains("error[E025]") && said.contains("9 characters"),
            "{said}"
        );
    }
}

/// `and` separates a list's items in the value cell as in one cell with
/// the label, so E046's advice (write the value right of the label) gives
/// the program asked for, not E030 (rt21 F17).
#[test]
fn and_separates_list_items_in_a_value_cell() {
    let rows: &[&[&str]] = &[
        &["modes", "estop and reset"],
        &["safety", "watchdog & edge"],
    ];
    let (dir, code, said) = convert(
        "and.xlsx",
        workbook(&[], &[("SETTINGS", rows)]),
        &["--formats", "st"],
    );
    assert_eq!(code, Some(0), "{said}");
    let st = std::fs::read_to_string(dir.path().join("out/and/and.st")).unwrap();
    assert!(
        st.contains("ESTOP") && st.contains("RESET"),
        "the modes asked for"
    );
    let rows: &[&[&str]] = &[&["modes", "estop and reset and estop"]];
    let (_, code, said) = convert("twice.xlsx", workbook(&[], &[("SETTINGS", rows)]), &[]);
    assert_eq!(code, Some(1), "{said}");
    assert!(
        said.contains("SETTINGS!B1: error[E030]") && said.contains("given twice"),
        "{said}"
    );
}

/// A name with an umlaut gives no identifier under `names`: the message
/// says why (Ö is a letter, but not A-Z) and suggests the spelling PLC
/// engineers use, which is not applied unasked (rt21 F10).
#[test]
fn a_name_with_an_umlaut_is_told_its_ascii_spelling() {
    let rows: &[&[&str]] = &[
        &["actuator", "name"],
        &["C1", "Ölpumpe"],
        &["C2", "2nd clamp"],
    ];
    let (_, code, said) = convert(
        "umlaut.xlsx",
        workbook(&[], &[("SETTINGS", rows)]),
        &["--designations", "names"],
    );
    assert_eq!(code, Some(1), "{said}");
    assert!(
        said.contains("\"Ö\" is no letter A-Z") && said.contains("write it \"Oelpumpe\""),
        "{said}"
    );
    assert!(!said.contains("begins with a letter and"), "{said}");
    let clamp = said.lines().find(|l| l.contains("2nd clamp")).unwrap();
    assert!(
        clamp.contains("begins with a letter A-Z") && clamp.contains("rename it"),
        "{clamp}"
    );
}

/// A refused `C1 0+1` may have meant C1 or C10: neither's later move is a
/// second error (rt21 F7), as with `C4+1 0`.
#[test]
fn a_split_actuator_number_makes_no_second_error() {
    for (cell, later) in [("C1 0+1", "C10-0"), ("C1 0+1", "C1-0"), ("C1 2+1", "C12-0")] {
        let csv = format!(",BRANCH 1\nSTEP 1,{cell}\nSTEP 2,C2+1\nSTEP 3,C2-0\nSTEP 4,{later}\n");
        let (_, code, said) = convert("split.csv", csv.into_bytes(), &[]);
        assert_eq!(code, Some(1), "{said}");
        let errors: Vec<&str> = said.lines().filter(|l| l.contains("error[")).collect();
        assert_eq!(errors.len(), 1, "{cell} / {later}: {said}");
        assert!(errors[0].contains("split.csv:2:2: error[E010]"), "{said}");
    }
}

/// A symbolic link to nothing is called one, by convert and by batch,
/// rather than "no such file" for a name `ls` lists (rt21 F14).
#[cfg(unix)]
#[test]
fn a_dangling_link_is_called_one() {
    let dir = tempfile::tempdir().unwrap();
    let link = dir.path().join("dangling.csv");
    std::os::unix::fs::symlink(dir.path().join("nowhere.csv"), &link).unwrap();
    for command in ["convert", "batch"] {
        let run = steptable()
            .arg(command)
            .arg(&link)
            .arg("-o")
            .arg(dir.path().join(command))
            .output()
            .unwrap();
        let said = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(1), "{said}");
        assert!(
            said.contains("error[E001]: is a link to")
                && said.contains("nowhere.csv, which does not exist"),
            "{command}: {said}"
        );
    }
}

/// A setting with the table in a CSV is told the CSV's one advice, not
/// "the cell right of" a sheet's, and is said once (no W003 at its cell
/// beside the E046); a corner `STEP` over the labels is read as what it
/// is (rt21 F18).
#[test]
fn a_setting_in_a_csv_gets_the_csvs_advice_once() {
    let csv = "STEP,BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C1-0\n\nsafety — watchdog\n";
    let (_, code, said) = convert("corner.csv", csv.into(), &[]);
    assert_eq!(code, Some(1), "{said}");
    let e046 = said
        .lines()
        .find(|l| l.contains("error[E046]"))
        .unwrap_or_else(|| panic!("{said}"));
    assert!(
        e046.contains("corner.csv:5:1") && e046.contains("a CSV file holds the step table only"),
        "{e046}"
    );
    assert!(!e046.contains("cell right of"), "{e046}");
    assert!(
        !said.contains("W003"),
        "no second word on the cell, none on STEP: {said}"
    );
    let (_, code, said) = convert("corner.xlsx", workbook(&["safety: watchdog"], &[]), &[]);
    assert_eq!(code, Some(1), "{said}");
    assert!(
        said.contains(
            "move it to the SETTINGS sheet, with its value in the cell right of \"safety\""
        ),
        "{said}"
    );
}

/// A placeholder in the actuator table's valve or time cell stays refused
/// (it may stand for a value still to come), and its E030 says that an
/// empty cell gives the default; E046 over `Type` says to empty them
/// (rt21 F5).
#[test]
fn a_placeholder_in_the_actuator_table_is_told_to_be_emptied() {
    for (row, cell) in [
        (&["C2", "1s", "1s", "-"][..], "SETTINGS!D3"),
        (&["C2", "n/a", "1s", "52bi"][..], "SETTINGS!B3"),
    ] {
        let rows: &[&[&str]] = &[
            &["actuator", "extend", "retract", "valve"],
            &["C1", "1s", "1s", "52mono"],
            row,
        ];
        let (_, code, said) = convert("ph.xlsx", workbook(&[], &[("SETTINGS", rows)]), &[]);
        assert_eq!(code, Some(1), "{said}");
        let e030 = said.lines().find(|l| l.contains("error[E030]")).unwrap();
        assert!(e030.contains(&format!("{cell}: error[E030]")), "{e030}");
        assert!(
            e030.contains("leave the cell empty for the default"),
            "{e030}"
        );
    }
    let rows: &[&[&str]] = &[&["actuator", "Type"], &["C1", "52mono"], &["C2", "-"]];
    let (_, code, said) = convert("type.xlsx", workbook(&[], &[("SETTINGS", rows)]), &[]);
    assert_eq!(code, Some(1), "{said}");
    assert!(
        said.contains("head it `valve` (and empty any placeholder"),
        "{said}"
    );
}

/// A repeated identical action is no signal clash: synth says the state
/// is met again before the same action, and what the memories are for
/// (rt20 F7); a true clash keeps its name.
#[test]
fn a_repeated_action_is_no_signal_clash() {
    let dir = tempfile::tempdir().unwrap();
    let run = |sequence: &str| {
        let out = steptable()
            .args(["synth", "--method", "exact", "--sequence", sequence, "-o"])
            .arg(dir.path())
            .output()
            .unwrap();
        assert!(out.status.success(), "{out:?}");
        String::from_utf8_lossy(&out.stdout).to_string()
    };
    let said = run("A1 A0 A1 A0");
    assert!(!said.contains("signal clash"), "{said}");
    assert!(
        said.contains("state met again: a=0 comes before A1 (action 1) and A1 (action 3)"),
        "{said}"
    );
    assert!(run("A1 A0 B1 B0").contains("signal clash: a=0 b=0 comes before A1"));
}

/// A zero-width character or a space between two digits of any form
/// (`C1+1<ZWSP>0`, `T=1<ZWSP>5s`, `C₁ ₀+1`, `C1 ０+1`) is E010, as a space
/// between ASCII digits is: it was C1+10 and a 15 s dwell (rt22 F1, F2).
#[test]
fn any_gap_between_any_digits_is_refused() {
    for cell in [
        "C1+1\u{200b}0",
        "C1+1\u{2060}0",
        "C1+1\u{feff}0",
        "C1+1; T=1\u{200b}5s",
        "C\u{2081} \u{2080}+1",
        "C1 \u{ff10}+1",
    ] {
        let csv = format!(",BRANCH 1\nSTEP 1,\"{cell}\"\nSTEP 2,C1-0\n");
        let (_, code, said) = convert("gap.csv", csv.into_bytes(), &["--formats", "st"]);
        assert_eq!(code, Some(1), "{cell:?}: {said}");
        assert!(
            said.contains("gap.csv:2:2: error[E010]"),
            "{cell:?}: {said}"
        );
    }
}

/// Two actuators with one name that gives no identifier (`Ölpumpe`
/// twice, `Kühler` and `KÜHLER`) are E025 as ASCII names are: a row
/// naming it went to C1 without a word (rt22 F3).
#[test]
fn two_actuators_with_one_umlaut_name_are_refused() {
    for (first, second) in [("Ölpumpe", "Ölpumpe"), ("Kühler", "KÜHLER")] {
        let rows: &[&[&str]] = &[&["actuator", "name"], &["C1", first], &["C2", second]];
        let (_, code, said) = convert("dup.xlsx", workbook(&[], &[("SETTINGS", rows)]), &[]);
        assert_eq!(code, Some(1), "{first}/{second}: {said}");
        assert!(
            said.contains("SETTINGS!B3: error[E025]")
                && said.contains("too; give them different names"),
            "{said}"
        );
    }
}

/// The made-by line heads the Windows-1252 files of a German table too
/// (it was dropped once the file held an `ß`), in that code page, with a
/// file name macOS wrote decomposed composed (rt22 F4, F5).
#[test]
fn the_made_by_line_heads_the_code_page_files() {
    let csv = ",BRANCH 1\nSTEP 1 (Schließen),C1+1\nSTEP 2,C1-0\n";
    let (dir, code, said) = convert("O\u{308}l.csv", csv.into(), &["--formats", "fst,exp,st"]);
    assert_eq!(code, Some(0), "{said}");
    let folder = std::fs::read_dir(dir.path().join("out"))
        .unwrap()
        .next()
        .unwrap()
        .unwrap()
        .path();
    for suffix in [".fst.txt", ".exp"] {
        let file = std::fs::read_dir(&folder)
            .unwrap()
            .map(|e| e.unwrap().path())
            .find(|p| p.to_string_lossy().ends_with(suffix))
            .unwrap();
        let bytes = std::fs::read(&file).unwrap();
        let made = bytes
            .split(|b| *b == b'\n')
            .find(|l| l.windows(7).any(|w| w == b"made by"))
            .unwrap_or_else(|| panic!("{suffix}: no made-by line"));
        assert!(
            made.windows(2).any(|w| w == b"\xd6l"),
            "{suffix}: Ö as 0xD6"
        );
        assert!(
            bytes.contains(&0xDF) && std::str::from_utf8(&bytes).is_err(),
            "{suffix}: ß"
        );
    }
}

/// A signal whose first 9 characters read as a reserved word or a button
/// (`start_memory`, `step_mode_sel` beside STEP_MODE) is refused only
/// where an FST file is written, and said to be FST's cut, not IEC's case
/// (rt22 F6).
#[test]
fn fsts_cut_of_a_signal_binds_only_where_fst_is_written() {
    for (cell, modes) in [
        ("C1+1; I:start_memory", "none"),
        ("C1+1; I:step_mode_sel", "step"),
    ] {
        let csv = format!(",BRANCH 1\nSTEP 1,{cell}\nSTEP 2,C1-0\n");
        let (_, code, said) = convert(
            "cut.csv",
            csv.clone().into_bytes(),
            &["--formats", "st", "--modes", modes],
        );
        assert_eq!(code, Some(0), "{cell}: {said}");
        let (_, code, said) = convert(
            "cut.csv",
            csv.into_bytes(),
            &["--formats", "st,fst", "--modes", modes],
        );
        assert_eq!(code, Some(1), "{cell}: {said}");
        assert!(
            said.contains("cut.csv:2:2: error[E015]")
                && said.contains("where a Festo FST file is written")
                && !said.contains("IEC names ignore case"),
            "{said}"
        );
    }
}

/// A move typed in the column of STEP labels below the last step would be
/// lost: E010, as beside the table (rt22 F10); `and and` in a list is an
/// empty item (rt22 F11).
#[test]
fn a_move_under_the_labels_and_an_empty_list_item_are_refused() {
    let csv = ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C1-0\nC2+1\n";
    let (_, code, said) = convert("below.csv", csv.into(), &["--formats", "st"]);
    assert_eq!(code, Some(1), "{said}");
    assert!(
        said.contains("below.csv:4:1: error[E010]") && said.contains("would be lost"),
        "{said}"
    );
    let csv = ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C1-0\n";
    let (_, code, said) = convert("list.csv", csv.into(), &["--modes", "stop and and estop"]);
    assert_eq!(code, Some(1), "{said}");
    assert!(said.contains("has an empty item"), "{said}");
}

/// `--sheet "Ablauf Ä"` finds the sheet whose name holds `A` and a
/// combining mark (rt22 F7); `???`, `default` and a load's `-` get the
/// advice to leave the cell empty as `-` does (rt22 F15).
#[test]
fn a_sheet_name_and_more_placeholders_are_read_as_meant() {
    let table: &[&[&str]] = &[&["", "BRANCH 1"], &["STEP 1", "C1+1"], &["STEP 2", "C1-0"]];
    let bytes = workbook(&[], &[("Ablauf A\u{308}", table)]);
    let (_, code, said) = convert(
        "sheet.xlsx",
        bytes,
        &["--sheet", "Ablauf \u{c4}", "--formats", "st"],
    );
    assert_eq!(code, Some(0), "{said}");
    for (valve, load) in [("???", ""), ("default", ""), ("52bi", "-")] {
        let rows: &[&[&str]] = &[
            &["actuator", "valve", "load"],
            &["C1", "52mono", ""],
            &["C2", valve, load],
        ];
        let (_, code, said) = convert("ph.xlsx", workbook(&[], &[("SETTINGS", rows)]), &[]);
        assert_eq!(code, Some(1), "{said}");
        assert!(
            said.contains("error[E030]") && said.contains("leave the cell empty for the default"),
            "{valve}/{load}: {said}"
        );
    }
}
