//! The report's mitigation column against the tool's own fault runs: for
//! each hazard of the paper's example, what the report says each safety
//! check does is what `steptable faults --safety X` (run through the
//! binary) shows for that fault — caught (its outcome and alarm), a hazard
//! left at fewer moments (its `appears`), or not caught — and "no built-in
//! check" stands exactly where no check catches it.

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
    let without = faults_with(&input, "none", dir.path());
    for (fault, cell) in &hazards {
        let mut caught = false;
        // A check that leaves the hazard at as many moments narrows nothing.
        let before = &without[fault][4];
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
            } else if appears != before {
                assert!(clause.starts_with("under "), "{fault}: {clause}");
                assert!(
                    clause.ends_with(&format!(" it stays a hazard {appears}")),
                    "{fault}: {option}: {clause} (faults --safety {check}: {appears})"
                );
            } else {
                assert!(clause.starts_with("not caught by "), "{fault}: {clause}");
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
