//! OpenPLC boards: `--board` (or a SETTINGS `board` row) allocates only the
//! inputs and outputs the board wires, and a table that needs more is
//! refused with the counts.

use predicates::prelude::*;
use predicates::str::contains;

use steptable::template_workbook::PAPER_EXAMPLE;

use crate::helpers::{io_rows, steptable, write_xlsx_sheets};

fn paper_with(dir: &std::path::Path, sheets: &[(&str, &[&[&str]])]) -> std::path::PathBuf {
    let path = dir.join("line.xlsx");
    let paper: Vec<&[&str]> = PAPER_EXAMPLE.iter().map(|r| &r[..]).collect();
    let mut all: Vec<(&str, &[&[&str]])> = vec![("TABLE", &paper)];
    all.extend_from_slice(sheets);
    write_xlsx_sheets(&path, &all);
    path
}

#[test]
fn the_paper_example_fits_the_raspberry_pi() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    steptable()
        .args([
            "convert",
            "samples/paper_example.xlsx",
            "--board",
            "rpi",
            "-o",
        ])
        .arg(&out)
        .assert()
        .success()
        .stdout(contains(
            "12 inputs, 8 outputs; addresses %IX0.0 to %IX1.3, %QX0.0 to %QX0.7",
        ));
    let io = std::fs::read_to_string(out.join("paper_example/paper_example.io.csv")).unwrap();
    let rows = io_rows(&io);
    // The Pi's hardware layer reads %IX0.0 … %IX1.5 and writes %QX0.0 … %QX1.2.
    let wired = |address: &str| {
        let (area, rest) = address.split_at(3);
        let (byte, bit) = rest.split_once('.').unwrap();
        let index = byte.parse::<u32>().unwrap() * 8 + bit.parse::<u32>().unwrap();
        match area {
            "%IX" => index < 14,
            "%QX" => index < 11,
            _ => false,
        }
    };
    assert_eq!(rows.len(), 20, "{io}");
    assert!(rows.iter().all(|(a, _)| wired(a)), "{io}");
    let st = std::fs::read_to_string(out.join("paper_example/paper_example.st")).unwrap();
    assert!(st.contains("START AT %IX0.0"), "{st}");
}

#[test]
fn single_coil_valves_leave_no_gap_on_a_board() {
    // On a valve terminal (--target iec) a 5/2 single-solenoid valve keeps
    // its `-` coil's place free; a board's few pins are packed.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    steptable()
        .args(["convert", "samples/paper_example.xlsx", "--valve", "C1=52mono,C2=53closed"])
        .args(["--board", "uno", "--formats", "io", "-o"])
        .arg(&out)
        .assert()
        .failure()
        .stderr(contains("error[E036]: the program needs 7 outputs, but the uno board (Arduino Uno) wires 4 outputs (%QX0.0 … %QX0.3)"));
    steptable()
        .args([
            "convert",
            "samples/paper_example.xlsx",
            "--valve",
            "C1=52mono,C2=53closed",
        ])
        .args(["--board", "mega", "--formats", "io", "-o"])
        .arg(&out)
        .assert()
        .success();
    let io = std::fs::read_to_string(out.join("paper_example/paper_example.io.csv")).unwrap();
    let rows = io_rows(&io);
    let at = |symbol: &str| rows.iter().find(|(_, s)| s == symbol).unwrap().0.clone();
    assert_eq!(
        (at("y1").as_str(), at("y2+").as_str()),
        ("%QX0.0", "%QX0.1"),
        "{io}"
    );
    assert_eq!(at("y4-"), "%QX0.6", "{io}");
}

#[test]
fn a_table_with_more_inputs_than_the_board_is_refused_with_the_counts() {
    // Five cylinders (ten sensors), START and four machine inputs: 15
    // inputs, one more than the Pi wires; ten coils fit its eleven outputs.
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("big.csv");
    std::fs::write(
        &csv,
        "C1+1;C2+1;C3+1;C4+1;C5+1\nI:a;I:b;I:c;I:d;T=1s\nC1-0;C2-0;C3-0;C4-0;C5-0\n",
    )
    .unwrap();
    let out = dir.path().join("out");
    for command in [&["check"][..], &["convert", "-o", out.to_str().unwrap()]] {
        steptable()
            .args(command)
            .arg(&csv)
            .args(["--board", "rpi"])
            .assert()
            .code(1)
            .stderr(contains(
                "error[E036]: the program needs 15 inputs, but the rpi board (Raspberry Pi) wires 14 inputs (%IX0.0 … %IX1.5)",
            ))
            .stderr(contains("outputs, but").not());
    }
    assert!(!out.exists(), "nothing is written");
    // Without the board, the generic target takes it.
    steptable()
        .arg("check")
        .arg(&csv)
        .args(["--target", "openplc"])
        .assert()
        .success()
        .stdout(contains(
            "15 inputs, 10 outputs; addresses %IX0.0 to %IX1.6",
        ));
}

#[test]
fn a_board_goes_with_openplc_addresses_only() {
    steptable()
        .args(["check", "samples/paper_example.xlsx", "--board", "esp32", "--target", "festo"])
        .assert()
        .code(1)
        .stderr(contains("error[E036]: the esp32 board is OpenPLC's, whose addresses are %IX/%QX, but the target is festo"));
    // A board on the command line outweighs the sheet's target, as any
    // flag does: mixed_valves' SETTINGS sheet says festo.
    steptable()
        .args(["check", "samples/mixed_valves.xlsx", "--board", "rpi"])
        .assert()
        .success()
        .stdout(contains("%IX0.0 to %IX0.7, %QX0.0 to %QX0.4"));
}

#[test]
fn the_settings_sheet_names_the_board_and_pins_stay_on_it() {
    let dir = tempfile::tempdir().unwrap();
    let input = paper_with(
        dir.path(),
        &[
            ("SETTINGS", &[&["board", "RPI"]]),
            (
                "ADDRESSES",
                &[
                    &["SIGNAL", "ADDRESS"],
                    &["START", "%IX1.5"],
                    &["y4-", "%QX1.3"],
                ],
            ),
        ],
    );
    steptable()
        .arg("check")
        .arg(&input)
        .assert()
        .code(1)
        .stderr(contains(
            "ADDRESSES!B3: error[E035]: \"%QX1.3\" is not on the rpi board, which wires 11 outputs (%QX0.0 … %QX1.2)",
        ))
        .stderr(contains("%IX1.5").not());
    let input = paper_with(
        dir.path(),
        &[
            ("SETTINGS", &[&["board", "RPI"]]),
            ("ADDRESSES", &[&["SIGNAL", "ADDRESS"], &["START", "%IX1.5"]]),
        ],
    );
    steptable()
        .arg("check")
        .arg(&input)
        .assert()
        .success()
        .stdout(contains("addresses %IX0.0 to %IX1.5"));
    let input = paper_with(dir.path(), &[("SETTINGS", &[&["board", "beaglebone"]])]);
    steptable()
        .arg("check")
        .arg(&input)
        .assert()
        .code(1)
        .stderr(contains("SETTINGS!B1: error[E030]: board: \"beaglebone\" is not valid (expected none or one of rpi, uno,"));
}

/// A board with enough inputs but too few outputs is refused for its
/// outputs alone: three inputs fit the Uno's five, five outputs do not fit
/// its four.
#[test]
fn a_table_with_more_outputs_than_the_board_is_refused_with_the_counts() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("lamps.csv");
    std::fs::write(
        &csv,
        "C1+1; Y:lamp+; Y:horn+; Y:fan+\nC1-0; Y:lamp-; Y:horn-; Y:fan-\n",
    )
    .unwrap();
    let out = dir.path().join("out");
    steptable()
        .arg("convert")
        .arg(&csv)
        .args(["--board", "uno", "-o"])
        .arg(&out)
        .assert()
        .code(1)
        .stderr(contains(
            "error[E036]: the program needs 5 outputs, but the uno board (Arduino Uno) wires 4 outputs (%QX0.0 … %QX0.3)",
        ))
        .stderr(contains("inputs, but").not());
    assert!(!out.exists(), "nothing is written");
    steptable()
        .arg("check")
        .arg(&csv)
        .args(["--board", "nano-every"])
        .assert()
        .success()
        .stdout(contains("3 inputs, 5 outputs"));
}
