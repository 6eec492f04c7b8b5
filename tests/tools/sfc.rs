//! The SFC chart (`NAME.sfc.xml`, issue 39) proven as a user's tools take
//! it: valid against the PLCopen XSD, turned into textual SFC by Beremiz's
//! own generator (`plcopen2st.py`), compiled by matiec and run on the inputs
//! steptable's simulation recorded, with the simulation's outputs at every
//! scan over the whole matrix, and so does every chart with its priorities
//! renumbered by the branches' places from left to right, the order
//! CODESYS tests them in (rt8 finding 1), and the chart whose entry actions
//! are held by N (run every scan and once more after, which their guard
//! makes one run: rt8 finding 12). Two deliberately wrong charts (no
//! transition priorities; N-held actions without their guard) must be
//! caught with their scan and signal.

use std::path::Path;
use std::process::Command;

use crate::differential::{matrix, run_all};
use crate::engines::{self, Case, matiec};
use crate::{Check, Tool, shared, tool};

pub const CHECKS: &[Check] = &[
    Check::new(
        "sfc::the_chart_runs_in_matiec_as_simulated",
        &[Tool::Shared, Tool::Xmllint, Tool::BeremizPython],
        the_chart_runs_in_matiec_as_simulated,
    ),
    Check::new(
        "sfc::a_wrong_chart_is_caught_with_its_scan_and_signal",
        &[Tool::Shared, Tool::BeremizPython],
        a_wrong_chart_is_caught_with_its_scan_and_signal,
    ),
];

/// Beremiz's generator on `xml`: the ST (with textual SFC) it writes.
fn beremiz_text(python: &Path, shared: &Path, xml: &Path) -> Result<std::path::PathBuf, String> {
    let out = xml.with_extension("beremiz.st");
    let output = Command::new(python)
        .arg(shared.join("tools/plcopen2st.py"))
        .arg(xml)
        .arg(&out)
        .output()
        .map_err(|e| e.to_string())?;
    if !output.status.success() {
        return Err(format!(
            "Beremiz's generator refuses {}: {}{}",
            xml.display(),
            String::from_utf8_lossy(&output.stdout),
            String::from_utf8_lossy(&output.stderr)
        ));
    }
    Ok(out)
}

pub(crate) fn xsd_valid(xmllint: &Path, shared: &Path, xml: &Path) -> Result<(), String> {
    let output = Command::new(xmllint)
        .arg("--noout")
        .arg("--schema")
        .arg(shared.join("reference/tc6_xml_v201.xsd"))
        .arg(xml)
        .output()
        .map_err(|e| e.to_string())?;
    if output.status.success() {
        Ok(())
    } else {
        Err(String::from_utf8_lossy(&output.stderr).into_owned())
    }
}

/// The chart of `case`, through Beremiz and matiec, against the simulation.
pub(crate) fn run_chart(
    python: &Path,
    shared: &Path,
    case: &Case,
    xml: &Path,
) -> Result<(), String> {
    run_beremiz(python, shared, case, xml, "Beremiz + matiec .sfc.xml")
}

/// A PLCopen body of `case` (chart or ladder), turned into ST by Beremiz's
/// generator, compiled and run by matiec against the simulation.
pub(crate) fn run_beremiz(
    python: &Path,
    shared: &Path,
    case: &Case,
    xml: &Path,
    label: &str,
) -> Result<(), String> {
    let st = beremiz_text(python, shared, xml).map_err(|e| format!("{}: {e}", case.label))?;
    case.check(
        label,
        matiec::run(shared, &st, &case.trace, &case.allocation),
    )
}

fn the_chart_runs_in_matiec_as_simulated() {
    let shared = shared();
    let python = tool(Tool::BeremizPython);
    let xmllint = tool(Tool::Xmllint);
    let dir = tempfile::tempdir().unwrap();
    let cases = matrix(dir.path(), &["--formats", "sfc"]);
    let uploads = std::sync::atomic::AtomicUsize::new(0);
    run_all(&cases, |c| {
        let xml = c.file(".sfc.xml");
        xsd_valid(&xmllint, &shared, &xml).map_err(|e| format!("{}: XSD: {e}", c.label))?;
        run_chart(&python, &shared, c, &xml)?;
        // CODESYS's rule, left to right: the same chart, the same run.
        let text = std::fs::read_to_string(&xml).unwrap();
        let left_to_right = by_position(&text);
        if left_to_right != text {
            let lr = xml.with_extension("left-to-right.xml");
            std::fs::write(&lr, left_to_right).unwrap();
            run_beremiz(&python, &shared, c, &lr, "the chart tested left to right")?;
        }
        // OpenPLC v3's older runtime headers cannot build a TON declared
        // as a global (docs/outputs.md says so): a chart without timers
        // must pass its upload.
        if !text.contains("<derived name=\"TON\"/>") {
            let st = xml.with_extension("beremiz.st");
            crate::differential::openplc_accepts(&shared, &st)
                .map_err(|e| format!("{}: OpenPLC upload: {e}", c.label))?;
            uploads.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        }
        Ok(())
    });
    let uploads = uploads.load(std::sync::atomic::Ordering::Relaxed);
    assert!(
        uploads > 0,
        "no chart without timers went through the upload"
    );
    eprintln!("sfc: {uploads} charts without timers accepted by OpenPLC v3's upload");
    eprintln!(
        "sfc: {} charts XSD-valid, generated by Beremiz, run in matiec, traces equal",
        cases.len()
    );
}

/// The sorting station's chart made wrong as the traps say: the
/// layer must name the scan and the signal where it parts from the
/// simulation.
fn a_wrong_chart_is_caught_with_its_scan_and_signal() {
    let shared = shared();
    let python = tool(Tool::BeremizPython);
    let dir = tempfile::tempdir().unwrap();
    let sample = crate::helpers::root().join("samples/sorting_station.xlsx");
    let case = engines::prepare(
        &sample,
        &["--target", "iec", "--formats", "sfc"],
        dir.path(),
    );
    let xml = case.file(".sfc.xml");
    let right = std::fs::read_to_string(&xml).unwrap();
    run_chart(&python, &shared, &case, &xml).expect("the chart as written runs as simulated");
    // The transitions' priorities only (the task keeps its own).
    let no_priority: String = right
        .lines()
        .map(|l| {
            if l.trim_start().starts_with("<transition ") {
                strip_attribute(l, " priority=\"")
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n");
    assert_ne!(no_priority, right);
    // Held by N, the entry actions run on every scan of their step and
    // once more after it (as CODESYS runs an IEC action): their guard
    // (the step's flag, `active_step` not yet k) keeps them to one run
    // per entry, so the chart still runs as simulated (rt8 finding 12) …
    let held = right.replace("qualifier=\"P\"", "qualifier=\"N\"");
    assert_ne!(held, right);
    let held_xml = dir.path().join("held.sfc.xml");
    std::fs::write(&held_xml, &held).unwrap();
    run_chart(&python, &shared, &case, &held_xml)
        .expect("N-held actions with their guard run as simulated");
    // … and without the guard they do not.
    let unguarded: String = held
        .lines()
        .map(|l| {
            if l.starts_with("IF ") && l.contains(".X AND ") {
                "IF TRUE THEN".to_string()
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n");
    assert_ne!(unguarded, held);
    for (what, text) in [
        ("no priorities", no_priority),
        ("N-held actions without their guard", unguarded),
    ] {
        let wrong = dir
            .path()
            .join(format!("wrong-{}.sfc.xml", what.replace(' ', "-")));
        std::fs::write(&wrong, text).unwrap();
        let err = run_chart(&python, &shared, &case, &wrong).expect_err(&format!(
            "a chart with {what} must differ from the simulation"
        ));
        assert!(err.contains("scan"), "{what}: {err}");
        eprintln!("sfc: {what} caught: {err}");
    }
}

/// The chart `text` with the priorities of the transitions leaving one
/// element renumbered 1, 2, 3 … by their places from left to right, as
/// CODESYS tests an alternative branch (rt8's `cases/codesys_order.py`).
/// Reads the file as `sfc.xml.j2` writes it: a transition's position on the
/// line after its start, its source in its first `refLocalId`.
pub(crate) fn by_position(text: &str) -> String {
    let lines: Vec<&str> = text.lines().collect();
    let number = |line: &str, key: &str| -> Option<i64> {
        let rest = line.split(key).nth(1)?;
        rest.split('"').next()?.parse().ok()
    };
    // (source, x, line of the transition's start)
    let mut branches: Vec<(i64, i64, usize)> = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        if !line.trim_start().starts_with("<transition ") {
            continue;
        }
        let x = number(lines[i + 1], " x=\"").expect("a transition's position");
        let source = lines[i..]
            .iter()
            .find_map(|l| number(l, "refLocalId=\""))
            .expect("a transition's source");
        branches.push((source, x, i));
    }
    branches.sort();
    let mut renumbered: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
    let mut previous = None;
    let mut priority = 0;
    for (source, _, i) in branches {
        priority = if previous == Some(source) {
            priority + 1
        } else {
            1
        };
        previous = Some(source);
        let line = strip_attribute(lines[i], " priority=\"");
        let line = line.trim_end_matches('>');
        renumbered[i] = format!("{line} priority=\"{priority}\">");
    }
    let mut out = renumbered.join("\n");
    if text.ends_with('\n') {
        out.push('\n');
    }
    out
}

/// `text` without every attribute that starts with `attribute` (its quoted value too).
fn strip_attribute(text: &str, attribute: &str) -> String {
    let mut out = String::new();
    let mut rest = text;
    while let Some(at) = rest.find(attribute) {
        out.push_str(&rest[..at]);
        let value = &rest[at + attribute.len()..];
        rest = value.split_once('"').map_or("", |(_, after)| after);
    }
    out.push_str(rest);
    out
}
