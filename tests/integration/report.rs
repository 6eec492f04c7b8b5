//! `NAME.report.html`, read back as a page on its own terms: every section
//! there, nothing that would leave the file, the timeline's lanes equal to
//! the simulation's recorded run at sampled moments, the fault rows equal
//! to `NAME.faults.csv` (hazards first), and the engineer's text escaped.
//! `tests/tools/browser.rs` opens the same pages in Chromium.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use regex::Regex;

use crate::helpers::{Build, sample, samples, steptable, write_xlsx};

/// Converts `input` with `extra` options and returns the output folder.
fn convert(input: &Path, out: &Path, extra: &[&str]) -> PathBuf {
    steptable()
        .arg("convert")
        .arg(input)
        .args(extra)
        .arg("-o")
        .arg(out)
        .assert()
        .success();
    out.join(input.file_stem().unwrap())
}

fn read(folder: &Path, suffix: &str) -> String {
    let stem = folder.file_name().unwrap().to_string_lossy().to_string();
    std::fs::read_to_string(folder.join(format!("{stem}{suffix}"))).unwrap()
}

fn unescape(text: &str) -> String {
    text.replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&quot;", "\"")
        .replace("&amp;", "&")
}

/// Nothing on the page names anything outside it.
pub fn external_references(page: &str) -> Vec<String> {
    let external = Regex::new(
        r#"(?i)(src|href|action|xlink:href)\s*=\s*"(?:[a-z][a-z0-9+.-]*:|//)[^"]*"|url\(\s*['"]?(?:[a-z]+:|//)|@import|<link\b|<iframe\b|<img\b[^>]*src"#,
    )
    .unwrap();
    external
        .find_iter(page)
        .map(|m| m.as_str().to_string())
        // The SVG namespace is a name, not a request.
        .filter(|m| !m.contains("http://www.w3.org/2000/svg\""))
        .collect()
}

/// The fault table's rows as cells.
fn fault_rows(page: &str) -> Vec<Vec<String>> {
    let body = page.split("<table class=\"faults\">").nth(1).unwrap();
    let body = body.split("</table>").next().unwrap();
    let body = body.split("<tbody>").nth(1).unwrap();
    let row = Regex::new(r"(?s)<tr[^>]*>(.*?)</tr>").unwrap();
    let cell = Regex::new(r"(?s)<td>(.*?)</td>").unwrap();
    row.captures_iter(body)
        .map(|r| cell.captures_iter(&r[1]).map(|c| unescape(&c[1])).collect())
        .collect()
}

/// Each digital lane's changes: label → `(ms from the press, value)`.
pub fn lanes(page: &str) -> BTreeMap<String, Vec<(u64, u32)>> {
    let lane =
        Regex::new(r#"<g class="lane (\w+)" data-signal="([^"]*)" data-edges="([^"]*)">"#).unwrap();
    lane.captures_iter(page)
        .map(|c| {
            let edges = c[3]
                .split(' ')
                .map(|e| {
                    let (t, v) = e.split_once(':').unwrap();
                    (t.parse().unwrap(), v.parse().unwrap())
                })
                .collect();
            (unescape(&c[2]), edges)
        })
        .collect()
}

fn value_at(edges: &[(u64, u32)], ms: u64) -> u32 {
    edges.iter().take_while(|(t, _)| *t <= ms).last().unwrap().1
}

fn check_page(folder: &Path, build: &Build) {
    let page = read(folder, ".report.html");
    let what = folder.display();
    for (id, heading) in steptable::emit::report::SECTIONS {
        assert!(
            page.contains(&format!("<section id=\"{id}\">\n<h2>{heading}</h2>")),
            "{what}: {id}"
        );
    }
    assert_eq!(external_references(&page), Vec::<String>::new(), "{what}");
    assert!(page.contains("<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"grafcet\""));
    for diagram in ["Displacement-step diagram: ", "Displacement-time diagram: "] {
        assert!(page.contains(diagram), "{what}: {diagram}");
    }

    // The fault rows are NAME.faults.csv's, hazards first.
    let csv = read(folder, ".faults.csv");
    let mut reader = csv::Reader::from_reader(csv.as_bytes());
    let mut expected: Vec<Vec<String>> = reader
        .records()
        .map(|r| r.unwrap().iter().map(String::from).collect())
        .collect();
    let rank = |r: &Vec<String>| match r[3].as_str() {
        "hazard" => 0,
        "safe stall" => 1,
        _ => 2,
    };
    expected.sort_by_key(rank);
    // Each row is the CSV's with the mitigation after it: filled for a
    // hazard (tests/integration/mitigation.rs checks what it says), empty
    // for the rest.
    let rows = fault_rows(&page);
    for row in &rows {
        let mitigation = row.last().unwrap();
        assert_eq!(
            row[3] == "hazard",
            !mitigation.is_empty(),
            "{what}: {row:?}"
        );
    }
    let rows: Vec<Vec<String>> = rows
        .into_iter()
        .map(|r| r[..r.len() - 1].to_vec())
        .collect();
    assert_eq!(rows, expected, "{what}");

    // The timeline is the simulated run, scan for scan at sampled moments.
    let program = build.program();
    let signals = steptable::simulate::io::IoSignals::every(&program);
    let (report, trace) = steptable::simulate::simulate_recording(
        &build.table,
        &program,
        &build.settings.simulation,
        signals,
    );
    let press = report.cycles[0].press_ms;
    let lanes = lanes(&page);
    let symbols =
        steptable::symbols::SymbolTable::build(&program, &build.table, &build.settings.naming);
    assert_eq!(
        lanes.len(),
        1 + trace.signals.inputs.len() + trace.signals.outputs.len(),
        "{what}"
    );
    for scan in trace.scans.iter().filter(|s| s.time_ms >= press).step_by(7) {
        let at = scan.time_ms - press;
        assert_eq!(
            value_at(&lanes["active step"], at),
            scan.step as u32,
            "{what}: step at {at} ms"
        );
        for (signals, values) in [
            (&trace.signals.inputs, &scan.inputs),
            (&trace.signals.outputs, &scan.outputs),
        ] {
            for (signal, value) in signals.iter().zip(values) {
                let name = symbols.designation(*signal);
                assert_eq!(
                    value_at(&lanes[&name], at),
                    u32::from(*value),
                    "{what}: {name} at {at} ms"
                );
            }
        }
    }
}

#[test]
fn every_samples_report_has_every_section_the_faults_and_the_simulated_run() {
    let dir = tempfile::tempdir().unwrap();
    for path in samples() {
        let folder = convert(&path, dir.path(), &["--formats", "report,faults"]);
        check_page(&folder, &Build::path(&path));
    }
    // With modes and safety checks, and ISO designations.
    let path = sample("paper_example.xlsx");
    let out = dir.path().join("modes");
    let folder = convert(
        &path,
        &out,
        &[
            "--formats",
            "report,faults",
            "--modes",
            "all",
            "--designations",
            "iso",
        ],
    );
    let mut build = Build::path(&path).modes("all");
    build.settings.naming.scheme = "iso".parse().unwrap();
    check_page(&folder, &build);
    assert!(read(&folder, ".report.html").contains("data-signal=\"1B2\""));
}

#[test]
fn the_report_is_written_by_default_and_left_out_by_formats() {
    let dir = tempfile::tempdir().unwrap();
    let folder = convert(&sample("paper_example.xlsx"), dir.path(), &[]);
    let page = read(&folder, ".report.html");
    assert!(
        page.starts_with("<!DOCTYPE html>\n<!-- made by steptable "),
        "{}",
        &page[..200]
    );
    assert!(page.contains("<td>scan time</td><td>10ms</td>"));
    assert!(page.contains("<p class=\"verdict passed\">passed: cycle time 7.47 s</p>"));
    let without = convert(
        &sample("paper_example.xlsx"),
        &dir.path().join("w"),
        &["--formats", "st,xlsx"],
    );
    assert!(!without.join("paper_example.report.html").exists());
}

/// Hostile text in the table reaches the page as text, never as markup.
#[test]
fn the_engineers_text_is_escaped() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("hostile.xlsx");
    let rows: &[&[&str]] = &[
        &["", "BRANCH 1"],
        &["STEP 1 (</td><script>alert(1)</script> & <b>)", "C1+1"],
        &["STEP 2 (\"><img src=x onerror=alert(2)>)", "C1-0"],
    ];
    write_xlsx(&path, "SEQUENTIAL CONTROL DESCRIPTION", rows);
    let folder = convert(&path, dir.path(), &["--formats", "report,faults"]);
    let page = read(&folder, ".report.html");
    assert!(!page.contains("<script>alert"), "a script from a cell");
    assert!(!page.contains("<img"), "an image from a cell");
    assert!(page.contains("&lt;/td&gt;&lt;script&gt;alert(1)&lt;/script&gt; &amp; &lt;b&gt;"));
    assert_eq!(
        page.matches("<script>").count(),
        1,
        "only the page's own script"
    );
    assert_eq!(external_references(&page), Vec::<String>::new());
}

/// A long dwell at a short scan time: the recording stops at the
/// timeline's scan budget and the page says so, instead of recording
/// every scan (the red team saw 341 MB and an abort under a memory cap).
#[test]
fn a_run_longer_than_the_timeline_budget_is_said_not_drawn() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("long.xlsx");
    let rows: &[&[&str]] = &[
        &["", "BRANCH 1"],
        &["STEP 1", "C1+1; T=30s"],
        &["STEP 2", "C1-0"],
    ];
    write_xlsx(&input, "SEQUENTIAL CONTROL DESCRIPTION", rows);
    let folder = convert(
        &input,
        dir.path(),
        &["--scan", "1ms", "--formats", "report"],
    );
    let page = read(&folder, ".report.html");
    assert!(
        page.contains("The timeline is drawn for runs of at most 20000 scans"),
        "{page}"
    );
    assert!(!page.contains("class=\"timeline\""), "no timeline drawn");
    // A short run still gets its timeline.
    let short = dir.path().join("short");
    let folder = convert(&input, &short, &["--scan", "10ms", "--formats", "report"]);
    let page = read(&folder, ".report.html");
    assert!(!page.contains("at most 20000 scans"), "drawn at 10 ms");
}
