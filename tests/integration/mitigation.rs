//! The report's mitigation column against the tool's own fault runs: for
//! each hazard of the paper's example, what the report says each safety
//! check does is what `steptable faults --safety X` (run through the
//! binary) shows for that fault — caught (its outcome and alarm), or not
//! caught, named with a moment at which that fault table gives the hazard
//! — and "no built-in check" stands exactly where no check catches it.

use std::collections::BTreeMap;
use std::path::Path;

use regex::Regex;

use crate::helpers::{sample, steptable};

/// `NAME.faults.csv` as rows of cells, header first.
fn csv_rows(path: &Path) -> Vec<Vec<String>> {
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .from_path(path)
        .unwrap();
    reader
        .records()
        .map(|r| r.unwrap().iter().map(String::from).collect())
        .collect()
}

/// `steptable faults --safety checks` on `input`: each fault's row by its
/// `fault` text.
fn faults_with(input: &Path, checks: &str, out: &Path) -> BTreeMap<String, Vec<String>> {
    let dir = out.join(checks);
    steptable()
        .args(["faults"])
        .arg(input)
        .args(["--safety", checks, "-o"])
        .arg(&dir)
        .assert()
        .success();
    let stem = input.file_stem().unwrap().to_string_lossy().to_string();
    let rows = csv_rows(&dir.join(&stem).join(format!("{stem}.faults.csv")));
    assert_eq!(rows[0][0], "fault");
    rows.into_iter()
        .skip(1)
        .map(|r| (r[0].clone(), r))
        .collect()
}

/// Per fault text, the phases (as the fault table labels them) at which
/// the fault gives a hazard on the program of `input` with `check`.
fn hazard_phases_with(input: &Path, check: &str) -> BTreeMap<String, Vec<String>> {
    use steptable::faults::Outcome;
    let mut settings = steptable::settings::Settings::new();
    settings.program.safety = match check {
        "all" => steptable::program::Safety::all(),
        _ => steptable::program::Safety {
            edge: check == "edge",
            precheck: check == "precheck",
            plausibility: check == "plausibility",
            watchdog: check == "watchdog",
            ..Default::default()
        },
    };
    let checked = steptable::convert::check_path(input, &settings).unwrap();
    let program = steptable::convert::build_program(&checked.table, &settings);
    let table = steptable::faults::analyse(&checked.table, &program, &settings.simulation, 1);
    table
        .cases
        .iter()
        .map(|c| {
            let phases = table
                .moments
                .iter()
                .zip(&c.outcomes)
                .filter(|(_, o)| **o == Outcome::Hazard)
                .map(|(m, _)| m.phase.label())
                .collect();
            (c.fault_text(), phases)
        })
        .collect()
}

/// The report's hazard rows: fault text → mitigation cell; and its header.
fn report_hazards(page: &str) -> (Vec<String>, BTreeMap<String, String>) {
    let body = page.split("<table class=\"faults\">").nth(1).unwrap();
    let body = body.split("</table>").next().unwrap();
    let head = Regex::new(r"<th>(.*?)</th>").unwrap();
    let header = head.captures_iter(body).map(|c| c[1].to_string()).collect();
    let row = Regex::new(r#"(?s)<tr class="hazard"[^>]*>(.*?)</tr>"#).unwrap();
    let cell = Regex::new(r"(?s)<td>(.*?)</td>").unwrap();
    let unescape = |t: &str| {
        t.replace("&lt;", "<")
            .replace("&gt;", ">")
            .replace("&amp;", "&")
    };
    let hazards = row
        .captures_iter(body)
        .map(|r| {
            let cells: Vec<String> = cell.captures_iter(&r[1]).map(|c| unescape(&c[1])).collect();
            (cells[0].clone(), cells.last().unwrap().clone())
        })
        .collect();
    (header, hazards)
}

/// The clause of `cell` (split at `; `) that mentions `option` as a word.
fn clause_naming<'c>(cell: &'c str, option: &str) -> Option<&'c str> {
    let word = Regex::new(&format!(r"{}(\W|$)", regex::escape(option))).unwrap();
    cell.split("; ").find(|c| word.is_match(c))
}

#[test]
fn the_reports_mitigations_are_what_faults_with_each_check_shows() {
    let dir = tempfile::tempdir().unwrap();
    let input = sample("paper_example.xlsx");
    steptable()
        .arg("convert")
        .arg(&input)
        .args(["--formats", "report", "-o"])
        .arg(dir.path().join("report"))
        .assert()
        .success();
    let page = std::fs::read_to_string(
        dir.path()
            .join("report/paper_example/paper_example.report.html"),
    )
    .unwrap();
    let (header, hazards) = report_hazards(&page);
    assert_eq!(header.last().map(String::as_str), Some("mitigation"));
    assert!(!hazards.is_empty());
    let checks = ["edge", "precheck", "plausibility", "watchdog", "all"];
    let runs: BTreeMap<&str, BTreeMap<String, Vec<String>>> = checks
        .iter()
        .map(|c| (*c, faults_with(&input, c, dir.path())))
        .collect();
    let phases: BTreeMap<&str, BTreeMap<String, Vec<String>>> = checks
        .iter()
        .map(|c| (*c, hazard_phases_with(&input, c)))
        .collect();
    let stays = Regex::new(r"^not caught by (.*) \(still a hazard if it appears (.*)\)$").unwrap();
    for (fault, cell) in &hazards {
        let mut caught = false;
        for check in checks {
            let option = format!("--safety {check}");
            let row = &runs[check][fault];
            let (outcome, appears, detected) = (&row[3], &row[4], &row[5]);
            let clause = clause_naming(cell, &option);
            // All four together are tried only when none alone catches it.
            if check == "all" && caught {
                assert!(clause.is_none(), "{fault}: {cell}");
                continue;
            }
            let clause = clause.unwrap_or_else(|| panic!("{fault}: {option} missing in {cell}"));
            if outcome != "hazard" {
                caught = true;
                let alarm = if detected == "alarm" { ", alarm" } else { "" };
                assert_eq!(
                    clause,
                    format!("caught by {option} ({outcome}{alarm})"),
                    "{fault}"
                );
            } else {
                // Not caught, at a moment at which `faults --safety X`
                // gives the hazard.
                let found = stays
                    .captures(clause)
                    .unwrap_or_else(|| panic!("{fault}: {clause}"));
                assert!(
                    found[1].split(" or ").any(|o| o == option),
                    "{fault}: {clause}"
                );
                let left = &phases[check][fault];
                assert!(
                    left.iter().any(|p| *p == found[2]),
                    "{fault}: {option}: {clause} (faults --safety {check}: {appears}, hazards {left:?})"
                );
            }
        }
        assert_eq!(
            cell.contains(
                "no built-in check catches it at every moment; what would (not simulated): "
            ),
            !caught,
            "{fault}: {cell}"
        );
    }
}
