//! The ADDRESSES sheet: signals pinned to the wiring keep their addresses in
//! every output, the rest are laid out around them, and a wrong row is an
//! error at its cell with nothing written.

use predicates::str::contains;

use steptable::template_workbook::PAPER_EXAMPLE;

use crate::helpers::{io_rows, steptable, write_xlsx_sheets};

fn workbook(dir: &std::path::Path, pins: &[&[&str]]) -> std::path::PathBuf {
    let path = dir.join("line.xlsx");
    let paper: Vec<&[&str]> = PAPER_EXAMPLE.iter().map(|r| &r[..]).collect();
    write_xlsx_sheets(&path, &[("TABLE", &paper), ("ADDRESSES", pins)]);
    path
}

fn convert_for_siemens(
    input: &std::path::Path,
    out: &std::path::Path,
) -> assert_cmd::assert::Assert {
    steptable()
        .arg("convert")
        .arg(input)
        .args(["--target", "siemens", "-o"])
        .arg(out)
        .assert()
}

#[test]
fn pinned_signals_keep_their_addresses_in_every_output() {
    let dir = tempfile::tempdir().unwrap();
    let input = workbook(
        dir.path(),
        &[
            &["SIGNAL", "ADDRESS"],
            &["START", "I1.0"],
            &["x11", "i0.0"],
            &["y2-", "Q4.7"],
        ],
    );
    let out = dir.path().join("out");
    convert_for_siemens(&input, &out).success();
    let io = std::fs::read_to_string(out.join("line/line.io.csv")).unwrap();
    let rows = io_rows(&io);
    let at = |symbol: &str| {
        rows.iter()
            .find(|(_, s)| s == symbol)
            .map(|(a, _)| a.clone())
            .unwrap_or_else(|| panic!("{symbol} missing: {io}"))
    };
    assert_eq!(
        (at("START"), at("x11"), at("y2-")),
        ("I1.0".into(), "I0.0".into(), "Q4.7".into())
    );
    // The others keep their order around the pins: x10 takes the first free
    // bit, the sensors run on past I1.0, the coils close the gap y2- left.
    assert_eq!(at("x10"), "I0.1");
    assert_eq!(at("x32"), "I1.1");
    assert_eq!(at("x40"), "I1.2");
    assert_eq!(at("y2+"), "Q0.2");
    assert_eq!(at("y3+"), "Q0.3");
    let addresses: std::collections::BTreeSet<&String> = rows.iter().map(|(a, _)| a).collect();
    assert_eq!(addresses.len(), rows.len(), "no address twice: {io}");
    let awl = std::fs::read_to_string(out.join("line/line.awl")).unwrap();
    assert!(awl.contains("A     I 1.0;          // START"), "{awl}");
    let st = std::fs::read_to_string(out.join("line/line.st")).unwrap();
    assert!(st.contains("AT %IX1.0"), "{st}");
    assert!(st.contains("AT %QX4.7"), "{st}");
}

#[test]
fn pins_on_festo_reach_the_fst_files() {
    let dir = tempfile::tempdir().unwrap();
    let input = workbook(dir.path(), &[&["START", "I2.0"]]);
    let out = dir.path().join("out");
    steptable()
        .arg("convert")
        .arg(&input)
        .args(["--formats", "fst,fst-alloc", "-o"])
        .arg(&out)
        .assert()
        .success();
    let texts: String = crate::helpers::files_below(&out.join("line"))
        .iter()
        .map(|p| std::fs::read_to_string(p).unwrap_or_default())
        .collect();
    assert!(texts.contains("I2.0"), "{texts}");
}

#[test]
fn every_wrong_row_is_an_error_at_its_cell_and_nothing_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let input = workbook(
        dir.path(),
        &[
            &["SIGNAL", "ADDRESS"],
            &["x99", "I0.0"],
            &["x11", "%IX0.1"],
            &["x20", "I0.8"],
            &["x21", "Q0.0"],
            &["x22", "I3.3"],
            &["x23", "I3.3"],
            &["x22", "I3.4"],
            &["START", ""],
        ],
    );
    let out = dir.path().join("out");
    convert_for_siemens(&input, &out)
        .code(1)
        .stderr(contains(
            "!A2: error[E035]: \"x99\" is not an input or output of this program",
        ))
        .stderr(contains(
            "!B3: error[E035]: \"%IX0.1\" is not an input or output address of the siemens target",
        ))
        .stderr(contains(
            "!B4: error[E035]: \"I0.8\": bit 8 is out of range, a byte has bits 0 to 7",
        ))
        .stderr(contains(
            "!B5: error[E035]: x21 is an input, but \"Q0.0\" is an output address",
        ))
        .stderr(contains(
            "!B7: error[E035]: \"I3.3\" is already x22's address",
        ))
        .stderr(contains(
            "!A8: error[E035]: x22 is pinned twice (first at A6)",
        ))
        .stderr(contains(
            "!A9: error[E035]: \"START\" has no address beside it",
        ));
    assert!(!out.exists());
}

/// A hidden SETTINGS or ADDRESSES sheet is used all the same, and said so.
#[test]
fn hidden_side_sheets_are_used_and_said() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("line.xlsx");
    let mut workbook = rust_xlsxwriter::Workbook::new();
    let sheets: [(&str, Vec<Vec<&str>>); 3] = [
        ("TABLE", PAPER_EXAMPLE.iter().map(|r| r.to_vec()).collect()),
        ("SETTINGS", vec![vec!["target", "siemens"]]),
        ("ADDRESSES", vec![vec!["START", "I1.0"]]),
    ];
    for (name, rows) in &sheets {
        let sheet = workbook.add_worksheet();
        sheet.set_name(*name).unwrap();
        sheet.set_hidden(*name != "TABLE");
        for (r, row) in rows.iter().enumerate() {
            for (c, text) in row.iter().enumerate() {
                if !text.is_empty() {
                    sheet.write_string(r as u32, c as u16, *text).unwrap();
                }
            }
        }
    }
    workbook.save(&path).unwrap();
    let out = dir.path().join("out");
    steptable()
        .arg("convert")
        .arg(&path)
        .args(["--formats", "io", "-o"])
        .arg(&out)
        .assert()
        .success()
        .stderr(contains(
            "SETTINGS: warning[W004]: the SETTINGS sheet is hidden but its settings are used",
        ))
        .stderr(contains(
            "ADDRESSES: warning[W004]: the ADDRESSES sheet is hidden but its pinned addresses are used",
        ));
    let io = std::fs::read_to_string(out.join("line/line.io.csv")).unwrap();
    assert!(io.contains("I1.0,START,"), "{io}");
}

/// The header is the row with SIGNAL and ADDRESS side by side: a note above
/// it that starts with the word "signal" is the sheet's text, not the
/// header (the template's ADDRESSES sheet has such notes).
#[test]
fn the_header_is_the_row_with_both_words() {
    let dir = tempfile::tempdir().unwrap();
    let input = workbook(
        dir.path(),
        &[
            &["signal"],
            &["Pins as wired in the panel"],
            &["SIGNAL", "ADDRESS"],
            &["START", "I1.0"],
        ],
    );
    let out = dir.path().join("out");
    convert_for_siemens(&input, &out).success();
    let io = std::fs::read_to_string(out.join("line/line.io.csv")).unwrap();
    assert!(io.contains("I1.0,START,"), "{io}");
}

/// On Festo the unpinned outputs keep their order around a pinned one and
/// take the free bits from where Festo's layout starts (`O0.1`): the `+`
/// coils, then the `-` coils, packed; the pinned coil keeps its address.
#[test]
fn on_festo_the_unpinned_outputs_are_laid_out_around_a_pin() {
    let dir = tempfile::tempdir().unwrap();
    let input = workbook(dir.path(), &[&["SIGNAL", "ADDRESS"], &["y2+", "O2.0"]]);
    let out = dir.path().join("out");
    steptable()
        .arg("convert")
        .arg(&input)
        .args(["--formats", "io", "-o"])
        .arg(&out)
        .assert()
        .success();
    let io = std::fs::read_to_string(out.join("line/line.io.csv")).unwrap();
    let outputs: Vec<(String, String)> = io_rows(&io)
        .into_iter()
        .filter(|(a, _)| a.starts_with('O'))
        .collect();
    let expected = [
        ("O0.1", "y1+"),
        ("O0.2", "y3+"),
        ("O0.3", "y4+"),
        ("O0.4", "y1-"),
        ("O0.5", "y2-"),
        ("O0.6", "y3-"),
        ("O0.7", "y4-"),
        ("O2.0", "y2+"),
    ];
    let expected: Vec<(String, String)> = expected
        .iter()
        .map(|(a, s)| (a.to_string(), s.to_string()))
        .collect();
    assert_eq!(outputs, expected, "{io}");
}

/// Every output of the allocation list can be pinned: an alarm lamp too.
#[test]
fn an_alarm_output_can_be_pinned() {
    let dir = tempfile::tempdir().unwrap();
    let input = workbook(
        dir.path(),
        &[
            &["SIGNAL", "ADDRESS"],
            &["alarm_wd", "Q3.7"],
            &["alarm_pl", "Q3.6"],
        ],
    );
    let out = dir.path().join("out");
    steptable()
        .arg("convert")
        .arg(&input)
        .args([
            "--target",
            "siemens",
            "--safety",
            "all",
            "--formats",
            "io,st",
            "-o",
        ])
        .arg(&out)
        .assert()
        .success();
    let io = std::fs::read_to_string(out.join("line/line.io.csv")).unwrap();
    assert!(io.contains("Q3.7,alarm_wd,alarm"), "{io}");
    assert!(io.contains("Q3.6,alarm_pl,alarm"), "{io}");
    let st = std::fs::read_to_string(out.join("line/line.st")).unwrap();
    assert!(st.contains("AT %QX3.7"), "{st}");
}

/// The criteria analysis reads as whole words: its outputs start a 16-bit
/// word of their own on every target (red team rt7 F8: they began mid-word
/// and straddled two words, while the allocation list labelled each "bit
/// k" of a word that matched no address), and they can be pinned like the
/// alarm lamps (F9: "miss1 is not an input or output of this program").
#[test]
fn the_criteria_outputs_start_a_word_and_can_be_pinned() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("paper.csv");
    let rows: Vec<String> = PAPER_EXAMPLE.iter().map(|r| r.join(",")).collect();
    std::fs::write(&csv, rows.join("\n")).unwrap();
    for (target, alarm, first, last) in [
        ("festo", "O1.5", "O2.0", "O2.10"),
        ("iec", "%QX1.0", "%QX2.0", "%QX3.2"),
        ("siemens", "Q1.0", "Q2.0", "Q3.2"),
    ] {
        let out = dir.path().join(target);
        steptable()
            .arg("convert")
            .arg(&csv)
            .args(["--safety", "criteria", "--target", target, "-o"])
            .arg(&out)
            .args(["--formats", "io"])
            .assert()
            .success();
        let io = std::fs::read_to_string(out.join("paper/paper.io.csv")).unwrap();
        let rows = io_rows(&io);
        let at = |symbol: &str| rows.iter().find(|(_, s)| s == symbol).unwrap().0.clone();
        assert_eq!(
            (at("alarm_wd"), at("miss1"), at("miss11")),
            (alarm.into(), first.into(), last.into()),
            "{target}"
        );
        assert!(
            !io.contains(" bit "),
            "no word bit the address contradicts: {io}"
        );
        assert!(io.contains("criterion 9 missing: the step ran out of time and x32 on is not met"));
    }
    let mut pins: Vec<Vec<String>> = vec![vec!["SIGNAL".into(), "ADDRESS".into()]];
    // miss1 … miss8 at Q8.0 … Q8.7, miss9 … miss11 at Q9.0 … Q9.2.
    pins.extend((0..11).map(|k| {
        vec![
            format!("miss{}", k + 1),
            format!("Q{}.{}", 8 + k / 8, k % 8),
        ]
    }));
    let pins: Vec<Vec<&str>> = pins
        .iter()
        .map(|r| r.iter().map(String::as_str).collect())
        .collect();
    let pins: Vec<&[&str]> = pins.iter().map(|r| &r[..]).collect();
    let input = workbook(dir.path(), &pins);
    let out = dir.path().join("pinned");
    steptable()
        .arg("convert")
        .arg(&input)
        .args(["--safety", "criteria", "--target", "siemens", "-o"])
        .arg(&out)
        .assert()
        .success();
    let io = std::fs::read_to_string(out.join("line/line.io.csv")).unwrap();
    let rows = io_rows(&io);
    let at = |symbol: &str| rows.iter().find(|(_, s)| s == symbol).unwrap().0.clone();
    assert_eq!(
        (at("miss1"), at("miss8"), at("miss11")),
        ("Q8.0".into(), "Q8.7".into(), "Q9.2".into())
    );
}
