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

/// `steptable faults --safety checks ARGS` on `input`, each fault's row by
/// its `fault` text; `None` when steptable refuses that program (E032).
fn faults_or_refused(
    input: &Path,
    checks: &str,
    args: &[&str],
    out: &Path,
) -> Option<BTreeMap<String, Vec<String>>> {
    let dir = out.join(checks);
    let run = steptable()
        .args(["faults"])
        .arg(input)
        .args(["--safety", checks])
        .args(args)
        .arg("-o")
        .arg(&dir)
        .output()
        .unwrap();
    if !run.status.success() {
        let said = String::from_utf8_lossy(&run.stderr);
        assert!(said.contains("E032"), "faults --safety {checks}: {said}");
        return None;
    }
    let stem = input.file_stem().unwrap().to_string_lossy().to_string();
    let rows = csv_rows(&dir.join(&stem).join(format!("{stem}.faults.csv")));
    assert_eq!(rows[0][0], "fault");
    Some(
        rows.into_iter()
            .skip(1)
            .map(|r| (r[0].clone(), r))
            .collect(),
    )
}

/// Holds every claim of the mitigation column of `input`'s report
/// (converted with `args`) to `steptable faults --safety X` with the same
/// arguments; the moment named by a "not caught" clause to the library's
/// fault table of that program, when `args` are empty.
fn check_report(input: &Path, args: &[&str], dir: &Path) {
    let stem = input.file_stem().unwrap().to_string_lossy().to_string();
    steptable()
        .arg("convert")
        .arg(input)
        .args(["--formats", "report"])
        .args(args)
        .arg("-o")
        .arg(dir.join("report"))
        .assert()
        .success();
    let page = std::fs::read_to_string(
        dir.join("report")
            .join(&stem)
            .join(format!("{stem}.report.html")),
    )
    .unwrap();
    let (header, hazards) = report_hazards(&page);
    assert_eq!(header.last().map(String::as_str), Some("mitigation"));
    assert!(!hazards.is_empty(), "{stem}");
    let checks = ["edge", "precheck", "plausibility", "watchdog", "all"];
    let runs: BTreeMap<&str, Option<BTreeMap<String, Vec<String>>>> = checks
        .iter()
        .map(|c| (*c, faults_or_refused(input, c, args, dir)))
        .collect();
    let phases: BTreeMap<&str, BTreeMap<String, Vec<String>>> = checks
        .iter()
        .filter(|c| args.is_empty() && runs[*c].is_some())
        .map(|c| (*c, hazard_phases_with(input, c)))
        .collect();
    let stays = Regex::new(r"^not caught by (.*) \(still a hazard if it appears (.*)\)$").unwrap();
    for (fault, cell) in &hazards {
        let mut caught = false;
        for check in checks {
            let option = format!("--safety {check}");
            let clause = clause_naming(cell, &option);
            // A program steptable refuses is no mitigation: not named.
            let Some(run) = &runs[check] else {
                assert!(
                    clause.is_none(),
                    "{stem}: {fault}: {option} is refused: {cell}"
                );
                continue;
            };
            let row = &run[fault];
            let (outcome, appears, detected) = (&row[3], &row[4], &row[5]);
            // All four together are tried only when none alone catches it.
            if check == "all" && caught {
                assert!(clause.is_none(), "{fault}: {cell}");
                continue;
            }
            let clause = clause.unwrap_or_else(|| panic!("{fault}: {option} missing in {cell}"));
            if outcome != "hazard" {
                caught = true;
                let alarm = if detected == "alarm" { ", alarm" } else { "" };
                assert!(
                    clause.starts_with(&format!("caught by {option} ({outcome}{alarm}")),
                    "{stem}: {fault}: {clause} (faults --safety {check}: {outcome} {detected})"
                );
            } else {
                // Not caught, at a moment at which `faults --safety X`
                // gives the hazard.
                let found = stays
                    .captures(clause)
                    .unwrap_or_else(|| panic!("{stem}: {fault}: {clause} (faults: hazard)"));
                assert!(
                    found[1].split(" or ").any(|o| o == option),
                    "{fault}: {clause}"
                );
                if let Some(phases) = phases.get(check) {
                    let left = &phases[fault];
                    assert!(
                        left.iter().any(|p| *p == found[2]),
                        "{stem}: {fault}: {option}: {clause} (faults --safety {check}: {appears}, hazards {left:?})"
                    );
                }
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

#[test]
fn the_reports_mitigations_are_what_faults_with_each_check_shows() {
    let dir = tempfile::tempdir().unwrap();
    check_report(&sample("paper_example.xlsx"), &[], dir.path());
}

/// The ways a table can lead the mitigation column astray (red team rt9),
/// each held to `faults --safety X`: a check steptable refuses to build
/// (E032, a watchdog no PLC timer holds) is never named, and a cycle too
/// long for faults at every moment is tried, as `faults` runs it, from
/// power-up only.
#[test]
fn hostile_tables_keep_the_mitigation_column_honest() {
    let dir = tempfile::tempdir().unwrap();
    let long = |n: usize| {
        let mut csv = String::from(",BRANCH 1\n");
        for i in 0..n {
            let cell = if i % 2 == 0 { "C1+1" } else { "C1-0" };
            csv.push_str(&format!("STEP {},{cell}\n", i + 1));
        }
        csv
    };
    let rows: [(&str, String, &[&str]); 4] = [
        (
            "dwell_beyond_watchdog",
            ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,T=655s\nSTEP 3,C1-0\n".to_string(),
            &["--valve", "C1=motor"],
        ),
        (
            "stroke_beyond_watchdog",
            ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C2+1\nSTEP 3,C2-0\nSTEP 4,C1-0\n".to_string(),
            &["--stroke", "C1=330s"],
        ),
        ("long_300", long(300), &[]),
        ("long_600", long(600), &[]),
    ];
    for (name, csv, args) in rows {
        let input = dir.path().join(format!("{name}.csv"));
        std::fs::write(&input, csv).unwrap();
        check_report(&input, args, &dir.path().join(name));
    }
    // The long cycle's page says that faults appeared at power-up only.
    let page = std::fs::read_to_string(
        dir.path()
            .join("long_600/report/long_600/long_600.report.html"),
    )
    .unwrap();
    assert!(page.contains("appearing at power-up only"));
    assert!(page.contains("faults from power-up only, the cycle being too long"));
}

/// The remedy named when no check catches a hazard fits the input that
/// failed (red team rt9): a push-button shorted, an emergency stop on a
/// spring-return valve, a machine input stuck at the value a wait wants, a
/// sensor shorted as its cylinder travels towards it, a heater the halt
/// would switch off but no check halts for.
#[test]
fn each_kind_of_input_gets_its_own_remedy() {
    let dir = tempfile::tempdir().unwrap();
    let one = ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C1-0\n";
    let door = ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,I:door=0\nSTEP 3,C1-0\n";
    let rows: [(&str, &str, &[&str], &str, &str); 3] = [
        (
            "step_pb",
            one,
            &["--modes", "step"],
            "STEP_PB short circuit",
            "a two-channel button",
        ),
        (
            "estop",
            one,
            &["--modes", "estop", "--valve", "C1=52mono"],
            "ESTOP open circuit",
            "5/3 closed-centre valves",
        ),
        (
            "door",
            door,
            &[],
            "door open circuit",
            "the machine input's own monitoring",
        ),
    ];
    for (name, csv, args, fault, remedy) in rows {
        let input = dir.path().join(format!("{name}.csv"));
        std::fs::write(&input, csv).unwrap();
        let out = dir.path().join(name);
        steptable()
            .arg("convert")
            .arg(&input)
            .args(["--formats", "report"])
            .args(args)
            .arg("-o")
            .arg(&out)
            .assert()
            .success();
        let page =
            std::fs::read_to_string(out.join(name).join(format!("{name}.report.html"))).unwrap();
        let (_, hazards) = report_hazards(&page);
        let cell = hazards
            .iter()
            .find(|(f, _)| f.starts_with(fault))
            .map(|(_, c)| c)
            .unwrap_or_else(|| panic!("{name}: no hazard {fault}: {hazards:?}"));
        assert!(
            cell.contains(&format!("what would (not simulated): {remedy}")),
            "{name}: {cell}"
        );
    }
    // The paper's x22 and x31 shorted read as the arrival of C2 and C3.
    let out = dir.path().join("paper");
    steptable()
        .arg("convert")
        .arg(sample("paper_example.xlsx"))
        .args(["--formats", "report", "-o"])
        .arg(&out)
        .assert()
        .success();
    let page =
        std::fs::read_to_string(out.join("paper_example/paper_example.report.html")).unwrap();
    let (_, hazards) = report_hazards(&page);
    for sensor in ["x22", "x31"] {
        let cell = &hazards[&format!("{sensor} short circuit (stuck at 1)")];
        assert!(cell.contains("a minimum travel time"), "{sensor}: {cell}");
    }
}
