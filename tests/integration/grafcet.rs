//! The GRAFCET picture (`NAME.grafcet.svg`): every step and transition of
//! the program is drawn, and no step box, action panel, receptivity or
//! label overlaps another, on every sample, with the modes and safety
//! checks on, and on a 30-step table. Texts are measured at 7.4 px per
//! character at 12 px (wider than the fonts a browser picks); the browser
//! check in `tests/tools/browser.rs` measures the rendered boxes.

use std::path::Path;

use regex::Regex;

use crate::helpers::{Build, sample, samples, steptable, write_xlsx};

/// `(left, top, right, bottom)`.
type Bounds = (f64, f64, f64, f64);

#[derive(Debug, Default)]
pub struct Drawn {
    /// Step ids (`0`, `3`, `4.2`) with their boxes.
    pub steps: Vec<(String, Bounds)>,
    /// Transition ids (`t3`, `t3j1`) with their receptivity texts.
    pub transitions: Vec<(String, Vec<String>)>,
    /// Action panels and the note, each with its text lines' bounds.
    pub panels: Vec<(Bounds, Vec<Bounds>)>,
    /// Receptivity lines and free labels.
    pub texts: Vec<(String, Bounds)>,
}

fn num(caps: &regex::Captures, name: &str) -> f64 {
    caps[name].parse().unwrap()
}

fn text_bounds(x: f64, y: f64, text: &str, size: f64) -> Bounds {
    let width = text.chars().count() as f64 * 7.4 * size / 12.0;
    (x, y - 0.85 * size, x + width, y + 0.3 * size)
}

fn plain(text: &str) -> String {
    let tags = Regex::new("<[^>]*>").unwrap();
    tags.replace_all(text, "")
        .replace("&amp;", "&")
        .replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&quot;", "\"")
}

/// Reads the picture back from its SVG text, on its own terms.
pub fn drawn(svg: &str) -> Drawn {
    let rect = r#"<rect x="(?P<x>[-\d.]+)" y="(?P<y>[-\d.]+)" width="(?P<w>[\d.]+)" height="(?P<h>[\d.]+)""#;
    let step = Regex::new(&format!(
        r#"<g class="step" data-step="(?P<id>[^"]+)">{rect}"#
    ))
    .unwrap();
    let panel = Regex::new(&format!(
        r#"<g class="(actions|note)">{rect}[^>]*>(?P<body>.*?)</g>"#
    ))
    .unwrap();
    let text = Regex::new(r#"<text (?:class="label" )?x="(?P<x>[-\d.]+)" y="(?P<y>[-\d.]+)"(?: font-size="(?P<s>[\d.]+)")?[^>]*>(?P<t>.*?)</text>"#).unwrap();
    let transition =
        Regex::new(r#"<g class="transition" data-transition="(?P<id>[^"]+)">(?P<body>.*?)</g>"#)
            .unwrap();
    let label = Regex::new(r#"<text class="label" [^\n]*"#).unwrap();
    let mut out = Drawn::default();
    for c in step.captures_iter(svg) {
        let (x, y) = (num(&c, "x"), num(&c, "y"));
        out.steps.push((
            c["id"].to_string(),
            (x, y, x + num(&c, "w"), y + num(&c, "h")),
        ));
    }
    for c in panel.captures_iter(svg) {
        let (x, y) = (num(&c, "x"), num(&c, "y"));
        let lines = text
            .captures_iter(&c["body"])
            .map(|t| text_bounds(num(&t, "x"), num(&t, "y"), &plain(&t["t"]), 12.0))
            .collect();
        out.panels
            .push(((x, y, x + num(&c, "w"), y + num(&c, "h")), lines));
    }
    for c in transition.captures_iter(svg) {
        let mut lines = Vec::new();
        for t in text.captures_iter(&c["body"]) {
            let words = plain(&t["t"]);
            out.texts.push((
                words.clone(),
                text_bounds(num(&t, "x"), num(&t, "y"), &words, 12.0),
            ));
            lines.push(words);
        }
        out.transitions.push((c["id"].to_string(), lines));
    }
    for l in label.find_iter(svg) {
        let t = text.captures(l.as_str()).unwrap();
        let size = t.name("s").map_or(12.0, |s| s.as_str().parse().unwrap());
        let words = plain(&t["t"]);
        out.texts.push((
            words.clone(),
            text_bounds(num(&t, "x"), num(&t, "y"), &words, size),
        ));
    }
    out
}

fn overlap(a: Bounds, b: Bounds) -> bool {
    a.0 < b.2 && b.0 < a.2 && a.1 < b.3 && b.1 < a.3
}

fn inside(a: Bounds, b: Bounds) -> bool {
    a.0 >= b.0 && a.2 <= b.2 && a.1 >= b.1 && a.3 <= b.3
}

/// Every overlap of two boxes or labels, and every panel line outside its
/// panel, named.
pub fn overlaps(d: &Drawn) -> Vec<String> {
    let mut boxes: Vec<(String, Bounds)> = d
        .steps
        .iter()
        .map(|(id, b)| (format!("step {id}"), *b))
        .collect();
    boxes.extend(
        d.panels
            .iter()
            .enumerate()
            .map(|(k, (b, _))| (format!("panel {k}"), *b)),
    );
    boxes.extend(d.texts.iter().map(|(t, b)| (format!("text {t:?}"), *b)));
    let mut found = Vec::new();
    for (i, (a, ab)) in boxes.iter().enumerate() {
        for (b, bb) in &boxes[i + 1..] {
            if overlap(*ab, *bb) {
                found.push(format!("{a} {ab:?} overlaps {b} {bb:?}"));
            }
        }
    }
    for (k, (b, lines)) in d.panels.iter().enumerate() {
        for line in lines {
            if !inside(*line, *b) {
                found.push(format!("a line of panel {k} {line:?} is outside it {b:?}"));
            }
        }
    }
    found
}

fn convert(input: &Path, out: &Path, extra: &[&str]) -> String {
    steptable()
        .arg("convert")
        .arg(input)
        .args(["--formats", "grafcet"])
        .args(extra)
        .arg("-o")
        .arg(out)
        .assert()
        .success();
    let stem = input.file_stem().unwrap().to_string_lossy().to_string();
    std::fs::read_to_string(out.join(&stem).join(format!("{stem}.grafcet.svg"))).unwrap()
}

/// The steps and transitions the program has: `(step number, boxes)` and
/// transition ids.
fn expected(build: &Build) -> (Vec<usize>, Vec<String>) {
    let program = build.program();
    let mut steps = vec![0];
    let mut transitions = Vec::new();
    for (i, s) in program.steps.iter().enumerate() {
        transitions.push(format!("t{i}"));
        transitions.extend((1..=s.jumps.len()).map(|k| format!("t{i}j{k}")));
        if s.kind == steptable::program::StepKind::Table {
            steps.push(program.step_entered(i));
        }
    }
    (steps, transitions)
}

fn check(svg: &str, build: &Build, what: &str) {
    let d = drawn(svg);
    let problems = overlaps(&d);
    assert!(problems.is_empty(), "{what}:\n{}", problems.join("\n"));
    let (steps, transitions) = expected(build);
    let mut numbers: Vec<usize> = d
        .steps
        .iter()
        .map(|(id, _)| id.split('.').next().unwrap().parse().unwrap())
        .collect();
    numbers.dedup();
    assert_eq!(numbers, steps, "{what}: steps drawn");
    let ids: Vec<String> = d.transitions.iter().map(|(id, _)| id.clone()).collect();
    assert_eq!(ids, transitions, "{what}: transitions drawn");
    // Step 0 is the initial step, in a double box.
    assert!(svg.contains(r#"data-step="0"><rect"#) && svg.matches("<rect").count() > d.steps.len());
}

#[test]
fn every_samples_grafcet_has_every_step_and_transition_and_no_overlap() {
    let dir = tempfile::tempdir().unwrap();
    for path in samples() {
        for (k, extra) in [&[][..], &["--modes", "all", "--safety", "all"][..]]
            .iter()
            .enumerate()
        {
            let out = dir.path().join(format!("{k}"));
            let svg = convert(&path, &out, extra);
            let mut build = Build::path(&path);
            if k == 1 {
                build = build.modes("all").safety("all".parse().unwrap());
            }
            check(&svg, &build, &format!("{} {extra:?}", path.display()));
            if k == 1 {
                assert!(
                    svg.contains("Modes and safety"),
                    "{}: the note",
                    path.display()
                );
            }
        }
    }
}

#[test]
fn the_papers_grafcet_reads_as_the_engineer_draws_it() {
    let dir = tempfile::tempdir().unwrap();
    let svg = convert(&sample("paper_example.xlsx"), dir.path(), &[]);
    let d = drawn(&svg);
    let ids: Vec<&str> = d.steps.iter().map(|(id, _)| id.as_str()).collect();
    assert_eq!(
        ids,
        [
            "0", "1", "2", "3", "4.1", "4.2", "5.1", "5.2", "6.1", "6.2", "6.3", "7.1", "7.2",
            "7.3", "8"
        ]
    );
    let receptivity: Vec<String> = d.transitions.iter().map(|(_, l)| l.join(" ")).collect();
    assert_eq!(
        receptivity,
        [
            "START · x10 · x20 · x30 · x40",
            "x11",
            "x23",
            "x21",
            "x32 · x22",
            "x30 · x21",
            "x31 · x22 · x41",
            "x30 · x20 · x40",
            "x10"
        ]
    );
    // Four AND divergences and four convergences, as double lines.
    assert_eq!(svg.matches(r#"<g class="and">"#).count(), 8);
    assert!(svg.contains(">S y2+</text><text x=") && svg.contains(">R y2-</text>"));
    // ISO designations reach the chart.
    let iso = convert(
        &sample("paper_example.xlsx"),
        &dir.path().join("iso"),
        &["--designations", "iso"],
    );
    assert!(iso.contains(">1B2</text>"), "x11 is 1B2 under ISO");
}

#[test]
fn the_sorting_stations_jumps_are_a_selection_with_their_targets() {
    let dir = tempfile::tempdir().unwrap();
    let svg = convert(&sample("sorting_station.xlsx"), dir.path(), &[]);
    let d = drawn(&svg);
    let jumps: Vec<(String, String)> = d
        .transitions
        .iter()
        .filter(|(id, _)| id.contains('j'))
        .map(|(id, l)| (id.clone(), l.join(" ")))
        .collect();
    assert_eq!(
        jumps,
        [
            ("t3j1".into(), "x20 · reject".into()),
            ("t6j1".into(), "x10 · no_label".into())
        ]
    );
    assert!(svg.contains(">→ step 6</text>") && svg.contains(">→ step 0</text>"));
    // The sequence goes on only when the jump is not taken.
    assert!(
        svg.contains(r#"x20 · <tspan text-decoration="overline">reject</tspan>"#),
        "{svg}"
    );
    // The dwell starts once x41 is on, as the program's timer does.
    assert!(svg.contains("t/x41/500ms"), "the dwell as a GRAFCET time");
}

/// Two jumps from one step: the program tests them in turn (`IF … ELSIF`),
/// so the second is drawn with the first one's input negated: the
/// alternatives stay exclusive, as IEC 60848 needs of a selection. A dwell
/// after a move starts when its sensor comes on, not with the step.
#[test]
fn a_second_jump_and_a_dwell_read_as_the_program_runs_them() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("two.xlsx");
    let rows: &[&[&str]] = &[
        &["", "BRANCH 1"],
        &["STEP 1", "C1+1"],
        &["STEP 2", "C2+1; T=2s"],
        &["STEP 3", "C2-0; J:5 if I:jmpa; J:6 if I:jmpb"],
        &["STEP 4", "T=1s"],
        &["STEP 5", "T=200ms"],
        &["STEP 6", "C1-0"],
    ];
    write_xlsx(&path, "SEQUENTIAL CONTROL DESCRIPTION", rows);
    let svg = convert(&path, dir.path(), &[]);
    let d = drawn(&svg);
    let jumps: Vec<String> = d
        .transitions
        .iter()
        .filter(|(id, _)| id.contains('j'))
        .map(|(_, l)| l.join(" "))
        .collect();
    assert_eq!(jumps, ["x20 · jmpa", "x20 · jmpb · jmpa"]);
    assert!(
        svg.contains(r#"jmpb · <tspan text-decoration="overline">jmpa</tspan>"#),
        "{svg}"
    );
    // The dwell after C2's move runs from x21 on; the dwell alone in its
    // step runs with the step.
    assert!(svg.contains("t/x21/2s"), "{svg}");
    assert!(svg.contains("t/X4/1s"), "{svg}");
}

#[test]
fn a_thirty_step_table_stays_legible() {
    use steptable::random_table::{Shape, add_jumps, random_rows};
    let dir = tempfile::tempdir().unwrap();
    let wide = Regex::new(r#"width="(\d+)""#).unwrap();
    for seed in [3, 30, 300] {
        let shape = Shape {
            actuators: 6,
            max_position: 3,
            branches: 3,
            steps: 30,
        };
        let mut rows = random_rows(seed, shape);
        add_jumps(seed, &mut rows);
        let rows: Vec<Vec<&str>> = rows
            .iter()
            .map(|r| r.iter().map(String::as_str).collect())
            .collect();
        let rows: Vec<&[&str]> = rows.iter().map(Vec::as_slice).collect();
        let path = dir.path().join(format!("thirty{seed}.xlsx"));
        write_xlsx(&path, "SEQUENTIAL CONTROL DESCRIPTION", &rows);
        let svg = convert(&path, &dir.path().join(format!("o{seed}")), &[]);
        let build = Build::path(&path);
        assert!(build.table.steps.len() >= 29, "{}", build.table.steps.len());
        check(&svg, &build, &format!("seed {seed}"));
        let width: f64 = wide.captures(&svg).unwrap()[1].parse().unwrap();
        assert!(width < 1400.0, "seed {seed}: {width} px wide");
    }
}
