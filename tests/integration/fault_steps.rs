//! The fault table's `step` column is the SFC step the machine is in (0 at
//! rest, k while table step k's moves run) when the finding the explanation
//! names first happens, and every output shows that one number: the CSV,
//! the workbook's FAULTS sheet, the report and the `faults` console table.

use crate::helpers::{read_sheet, sample, steptable};

/// Pinned on the paper's example: a stall at rest, a stall in a step, an
/// early start, an early start with a collision, a stall with a collision.
const PINNED: [(&str, &str); 5] = [
    ("x10 open circuit (stuck at 0)", "0"),
    ("x11 open circuit (stuck at 0)", "1"),
    ("x11 short circuit (stuck at 1)", "2"),
    ("x22 short circuit (stuck at 1)", "5"),
    ("x21 open circuit (stuck at 0)", "5"),
];

#[test]
fn every_output_shows_the_step_the_machine_is_in() {
    let dir = tempfile::tempdir().unwrap();
    steptable()
        .args(["convert", "--formats", "faults,xlsx,report", "-o"])
        .arg(dir.path())
        .arg(sample("paper_example.xlsx"))
        .assert()
        .success();
    let out = dir.path().join("paper_example");
    let csv = std::fs::read_to_string(out.join("paper_example.faults.csv")).unwrap();
    let mut reader = csv::Reader::from_reader(csv.as_bytes());
    let csv_rows: Vec<Vec<String>> = reader
        .records()
        .map(|r| r.unwrap().iter().map(str::to_string).collect())
        .collect();
    let sheet = read_sheet(&out.join("paper_example.steptable.xlsx"), "FAULTS");
    let html = std::fs::read_to_string(out.join("paper_example.report.html")).unwrap();
    let console = steptable()
        .args(["faults", "-o"])
        .arg(dir.path().join("again"))
        .arg(sample("paper_example.xlsx"))
        .assert()
        .success();
    let console = String::from_utf8_lossy(&console.get_output().stdout).to_string();
    for (fault, step) in PINNED {
        let in_csv = csv_rows.iter().find(|r| r[0] == fault).expect(fault);
        assert_eq!(in_csv[6], step, "CSV {fault}");
        let in_sheet = sheet.iter().find(|r| r[0] == fault).expect(fault);
        assert_eq!(in_sheet[4], step, "FAULTS sheet {fault}");
        let row = html
            .split("<tr")
            .find(|r| r.contains(&format!("<td>{fault}</td>")))
            .expect(fault);
        let cells: Vec<&str> = row.split("<td>").skip(1).collect();
        assert_eq!(cells[6], format!("{step}</td>"), "report {fault}");
        let line = console
            .lines()
            .find(|l| l.trim_start().starts_with(fault))
            .expect(fault);
        // The step column stands right before the explanation.
        assert!(
            line.contains(&format!(" {step}  {}", in_csv[7])),
            "console {fault}: {line}"
        );
    }
}
