//! What the SFC chart relies on in every tool that runs it (rt8 findings 1
//! and 12). CODESYS tests the branches of an alternative divergence from
//! left to right and ignores the `priority` attribute Beremiz and matiec
//! honour, so the branches must be drawn, and listed, in the order of their
//! priorities. CODESYS knows no `P1` and runs an IEC action once more after
//! its step (IEC 61131-3 ed. 2 too), so a step's action is a `P` whose body
//! does nothing unless the step's own flag is on.

use crate::helpers::{root, samples, steptable};
use crate::plcopen_geometry::{Node, parse};

/// The CODESYS qualifiers (its help, "Qualifiers for Actions in SFC").
const CODESYS_QUALIFIERS: [&str; 9] = ["N", "R", "S", "L", "D", "P", "SD", "DS", "SL"];

fn x_of(node: &Node) -> i64 {
    node.child("position").expect("a position").attrs["x"]
        .parse()
        .expect("an integer x")
}

fn source_of(node: &Node) -> String {
    let mut wires = Vec::new();
    node.descendants("connection", &mut wires);
    wires[0].attrs["refLocalId"].clone()
}

/// Every divergence of `body`: its branches' priorities, left to right,
/// must be 1, 2, 3 … and its outputs listed left to right. Returns how many
/// divergences were checked and the most branches one has.
fn check_branch_order(what: &str, body: &Node) -> (usize, usize) {
    let mut widest = 0;
    let mut divergences = Vec::new();
    body.descendants("selectionDivergence", &mut divergences);
    for div in &divergences {
        let id = &div.attrs["localId"];
        let mut branches: Vec<&Node> = body
            .children
            .iter()
            .filter(|c| c.name == "transition" && source_of(c) == *id)
            .collect();
        branches.sort_by_key(|t| x_of(t));
        let priorities: Vec<usize> = branches
            .iter()
            .map(|t| t.attrs["priority"].parse().expect("a priority"))
            .collect();
        let tested: Vec<usize> = (1..=branches.len()).collect();
        assert_eq!(
            priorities, tested,
            "{what}: divergence {id}: the priorities of its branches from left to right"
        );
        // Each branch leaves from its own output, and the file lists them
        // in the order they are drawn.
        let outs: Vec<i64> = div
            .children
            .iter()
            .filter(|c| c.name == "connectionPointOut")
            .map(|c| {
                c.child("relPosition").expect("relPosition").attrs["x"]
                    .parse::<i64>()
                    .unwrap()
            })
            .collect();
        assert!(
            outs.windows(2).all(|w| w[0] < w[1]),
            "{what}: divergence {id}: outputs {outs:?}"
        );
        assert_eq!(outs.len(), branches.len(), "{what}: divergence {id}");
        widest = widest.max(branches.len());
    }
    (divergences.len(), widest)
}

/// Every step's action association is a qualifier CODESYS has, and the
/// action's body tests the step's flag first.
fn check_step_actions(what: &str, text: &str, root: &Node) -> usize {
    let mut blocks = Vec::new();
    root.descendants("actionBlock", &mut blocks);
    let mut bodies = Vec::new();
    root.descendants("SFC", &mut bodies);
    let steps: Vec<&Node> = bodies
        .iter()
        .flat_map(|b| b.children.iter().filter(|c| c.name == "step"))
        .collect();
    for block in &blocks {
        let from = source_of(block);
        let step = steps
            .iter()
            .find(|s| s.attrs["localId"] == from)
            .unwrap_or_else(|| panic!("{what}: action block from {from}, not a step"));
        let flag = &step.attrs["name"];
        for action in block.children.iter().filter(|c| c.name == "action") {
            let qualifier = action.attrs["qualifier"].as_str();
            assert!(
                CODESYS_QUALIFIERS.contains(&qualifier),
                "{what}: {flag}: qualifier {qualifier}, which CODESYS does not have"
            );
            let name = &action.child("reference").expect("a named action").attrs["name"];
            let body = text
                .split(&format!("<action name=\"{name}\">"))
                .nth(1)
                .and_then(|rest| rest.split("</action>").next())
                .unwrap_or_else(|| panic!("{what}: no action {name}"));
            let code: Vec<&str> = body
                .lines()
                .map(str::trim)
                .filter(|l| !l.is_empty() && !l.starts_with('<') && !l.starts_with("(*"))
                .collect();
            let opening = format!("IF {flag}.X AND ");
            assert!(
                code.first().is_some_and(|l| l.starts_with(&opening)),
                "{what}: {name} does not start by testing {flag}: {body}"
            );
            assert_eq!(code.last().copied(), Some("END_IF;"), "{what}: {name}");
        }
    }
    blocks.len()
}

/// Every sample (the sorting station has jumps), plain and with every mode
/// and safety function (the rungs' returns to step 0): the chart and its
/// CODESYS file.
#[test]
fn every_chart_draws_its_branches_in_the_order_they_are_tested_and_guards_its_actions() {
    let mut divergences = 0;
    let mut widest = 0;
    let mut actions = 0;
    for sample in samples() {
        for options in [&[][..], &["--modes", "all", "--safety", "all"]] {
            let dir = tempfile::tempdir().unwrap();
            let mut cmd = steptable();
            cmd.arg("convert")
                .arg(&sample)
                .args(options)
                .args(["--formats", "sfc,codesys-sfc", "-o"])
                .arg(dir.path());
            let out = cmd.output().unwrap();
            assert!(
                out.status.success(),
                "{}",
                String::from_utf8_lossy(&out.stderr)
            );
            for file in crate::helpers::files_below(dir.path()) {
                let name = file.file_name().unwrap().to_string_lossy().into_owned();
                let what = format!("{name} {options:?}");
                let text = std::fs::read_to_string(&file).unwrap();
                let doc = parse(&text);
                let mut bodies = Vec::new();
                doc.descendants("SFC", &mut bodies);
                assert_eq!(bodies.len(), 1, "{what}");
                let (checked, branches) = check_branch_order(&what, bodies[0]);
                divergences += checked;
                widest = widest.max(branches);
                actions += check_step_actions(&what, &text, &doc);
            }
        }
    }
    // The sorting station's STEP 3 with every mode: the two returns after
    // a rung, the jump `J:6 if I:reject`, the step's own transition.
    assert!(
        divergences > 50 && widest >= 4 && actions > 50,
        "{divergences} divergences, at most {widest} branches, {actions} actions"
    );
}

/// W011 (rt8 finding 4): a chart with timers for OpenPLC (`--board`,
/// `--target openplc` or `iec`) is one OpenPLC v3's upload refuses, and the
/// run says so, pointing to the ST program and the Ladder body; not for
/// another target, not for a chart without timers, not without a chart.
#[test]
fn a_chart_with_timers_for_openplc_is_said_to_be_refused_by_its_upload() {
    let press = root().join("samples/press_station.xlsx");
    let paper = root().join("samples/paper_example.csv");
    let cases: [(&std::path::Path, &[&str], bool); 7] = [
        (
            &press,
            &["--board", "rpi", "--formats", "beremiz-sfc"],
            true,
        ),
        (&press, &["--target", "openplc", "--formats", "sfc"], true),
        (&press, &["--target", "iec", "--formats", "sfc,st"], true),
        (&press, &["--target", "siemens", "--formats", "sfc"], false),
        (
            &press,
            &["--board", "rpi", "--formats", "beremiz-ld,st"],
            false,
        ),
        (
            &press,
            &["--target", "iec", "--formats", "codesys-sfc"],
            false,
        ),
        (&paper, &["--target", "iec", "--formats", "sfc"], false),
    ];
    for (input, args, warned) in cases {
        let dir = tempfile::tempdir().unwrap();
        let out = steptable()
            .arg("convert")
            .arg(input)
            .args(args)
            .arg("-o")
            .arg(dir.path())
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{args:?}: {stderr}");
        assert_eq!(
            stderr.contains("warning[W011]"),
            warned,
            "{args:?}: {stderr}"
        );
        if warned {
            for needle in [
                "OpenPLC Runtime v3",
                "3 timer(s)",
                "press_station.st",
                ".ld.beremiz/",
            ] {
                assert!(stderr.contains(needle), "{args:?}: {needle}: {stderr}");
            }
        }
    }
}
