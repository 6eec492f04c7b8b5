//! The displacement-step diagram: as SVG beside the outputs and as the
//! DIAGRAM sheet, both from the simulation of the generated program.

use crate::helpers::{Build, read_sheet, sample, steptable};

fn convert(dir: &std::path::Path, extra: &[&str]) -> std::path::PathBuf {
    steptable()
        .arg("convert")
        .arg(sample("paper_example.xlsx"))
        .args(extra)
        .arg("-o")
        .arg(dir)
        .assert()
        .success();
    dir.join("paper_example")
}

/// The lane of C2 climbs 0 → 3 → 1 → 2 → 1 → 2 → 0 over the step boundaries.
#[test]
fn the_papers_diagram_has_every_lane_and_position() {
    let dir = tempfile::tempdir().unwrap();
    let out = convert(dir.path(), &[]);
    let svg = std::fs::read_to_string(out.join("paper_example.diagram.svg")).unwrap();
    assert!(svg.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\""));
    assert!(svg.contains("Displacement-step diagram: paper_example"));
    for lane in ["C1", "C2", "C3", "C4"] {
        assert!(svg.contains(&format!(">{lane}</text>")), "{lane}");
    }
    assert_eq!(svg.matches("<polyline").count(), 4);
    assert!(
        svg.contains(">9=1</text>"),
        "nine boundaries, the last one is step 1 again"
    );

    let sheet = read_sheet(&out.join("paper_example.steptable.xlsx"), "DIAGRAM");
    let header = step_header(&sheet);
    assert_eq!(sheet[header][..5], ["STEP", "C1", "C2", "C3", "C4"]);
    let rows = &sheet[header + 1..header + 10];
    let steps: Vec<&str> = rows.iter().map(|r| r[0].as_str()).collect();
    assert_eq!(steps, ["1", "2", "3", "4", "5", "6", "7", "8", "9"]);
    // The levels the sensors report when each step fires, as the SVG draws
    // them: whole positions, not a piston 2 % before its end stop.
    let c2: Vec<&str> = rows.iter().map(|r| r[2].as_str()).collect();
    assert_eq!(c2, ["0", "0", "3", "1", "2", "1", "2", "0", "0"]);
    let c1: Vec<&str> = rows.iter().map(|r| r[1].as_str()).collect();
    assert_eq!(c1, ["0", "1", "1", "1", "1", "1", "1", "1", "0"]);
}

/// The row of the DIAGRAM sheet's table headers (under the charts).
fn step_header(sheet: &[Vec<String>]) -> usize {
    sheet
        .iter()
        .position(|r| r.first().is_some_and(|c| c == "STEP"))
        .expect("the STEP header")
}

#[test]
fn the_time_variant_plots_over_seconds() {
    let dir = tempfile::tempdir().unwrap();
    let out = convert(dir.path(), &["--diagram", "time"]);
    let svg = std::fs::read_to_string(out.join("paper_example.diagram.svg")).unwrap();
    assert!(svg.contains("Displacement-time diagram: paper_example"));
    assert!(svg.contains(">7 s</text>"));
    assert_eq!(svg.matches("<polyline").count(), 4);
}

/// A long cycle's time diagram stays a picture: grid lines every 10 s
/// (not 300 of them, 60 px apart) and a straight stroke drawn as one line,
/// not one point per scan. A 1,200 s stroke at a 1 ms scan wrote 67 MB.
#[test]
fn a_long_cycles_time_diagram_stays_small() {
    let dir = tempfile::tempdir().unwrap();
    let table = dir.path().join("slow.csv");
    std::fs::write(&table, "C1+1\nC1-0\n").unwrap();
    steptable()
        .args(["simulate", "--stroke", "C1=300s/300s", "--diagram"])
        .arg(dir.path())
        .arg(&table)
        .assert()
        .success();
    let svg = std::fs::read_to_string(dir.path().join("slow/slow.time.svg")).unwrap();
    let width: f64 = svg
        .split("width=\"")
        .nth(1)
        .and_then(|rest| rest.split('"').next())
        .and_then(|w| w.parse().ok())
        .unwrap();
    assert!(width < 4000.0, "{width} px wide");
    assert!(svg.contains(">600 s</text>") && !svg.contains(">5 s</text>"));
    let points = svg
        .split("<polyline points=\"")
        .nth(1)
        .and_then(|rest| rest.split('"').next())
        .unwrap()
        .split(' ')
        .count();
    // Out, back, and the corners where each stroke starts and ends.
    assert!((4..=12).contains(&points), "{points} points");
}

#[cfg(unix)]
#[test]
fn outputs_are_ordinary_readable_files() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().unwrap();
    let out = convert(dir.path(), &[]);
    let mode = |p: &std::path::Path| std::fs::metadata(p).unwrap().permissions().mode() & 0o777;
    // The same mode as any file this process creates (whatever the umask),
    // not the 0600 of a temporary file.
    let ordinary = out.join("ordinary");
    std::fs::write(&ordinary, "x").unwrap();
    assert_eq!(mode(&out.join("paper_example.st")), mode(&ordinary));
}

/// The README shows `docs/paper_example.diagram.svg`: it must be exactly what
/// the tool draws today.
#[test]
fn the_readme_diagram_is_current() {
    let dir = tempfile::tempdir().unwrap();
    let out = convert(dir.path(), &[]);
    let drawn = std::fs::read_to_string(out.join("paper_example.diagram.svg")).unwrap();
    let shown =
        std::fs::read_to_string(crate::helpers::root().join("docs/paper_example.diagram.svg"))
            .unwrap();
    assert!(
        drawn == shown,
        "regenerate docs/paper_example.diagram.svg with `steptable convert samples/paper_example.xlsx`"
    );
}

/// The DIAGRAM sheet's charts, one per cylinder, do not cover each other:
/// each starts just below the row where the one above it ends. Each is tall
/// enough to read and fits a screen, taller for more positions (C2 has
/// four, C1 two).
#[test]
fn diagram_charts_do_not_overlap() {
    let dir = tempfile::tempdir().unwrap();
    crate::helpers::steptable()
        .arg("convert")
        .arg(crate::helpers::sample("paper_example.xlsx"))
        .args(["--formats", "xlsx", "-o"])
        .arg(dir.path())
        .assert()
        .success();
    let book = dir
        .path()
        .join("paper_example/paper_example.steptable.xlsx");
    let drawing = crate::helpers::xlsx_part(&book, "xl/drawings/drawing1.xml");
    let rows = |tag: &str| -> Vec<u32> {
        drawing
            .split(&format!("<xdr:{tag}>"))
            .skip(1)
            .map(|part| {
                let row = part.split("<xdr:row>").nth(1).unwrap();
                row.split('<').next().unwrap().parse().unwrap()
            })
            .collect()
    };
    let (from, to) = (rows("from"), rows("to"));
    assert_eq!(from.len(), 4, "{drawing}");
    // Each lane tall enough to read 0, 1 and the middle positions: at
    // least 150 pixels (7 rows and a half), taller for more positions (C2 has four).
    let rows_tall: Vec<u32> = from.iter().zip(&to).map(|(f, t)| t - f).collect();
    assert!(
        rows_tall.iter().all(|r| (7..=20).contains(r)),
        "{rows_tall:?}"
    );
    assert!(rows_tall[1] > rows_tall[0], "{rows_tall:?}");
    // Stacked in the first column, one under the other, one row apart,
    // and no chart cut by a page break.
    let cols: Vec<u32> = drawing
        .split("<xdr:from><xdr:col>")
        .skip(1)
        .map(|part| part.split('<').next().unwrap().parse().unwrap())
        .collect();
    assert_eq!(cols, [0, 0, 0, 0], "{drawing}");
    let sheet = crate::helpers::xlsx_part(&book, "xl/worksheets/sheet6.xml");
    let breaks: Vec<u32> = sheet
        .split("<brk id=\"")
        .skip(1)
        .map(|part| part.split('"').next().unwrap().parse().unwrap())
        .collect();
    assert!(!breaks.is_empty(), "{sheet}");
    for (f, t) in from.iter().zip(&to) {
        assert!(
            breaks.iter().all(|b| b <= f || b > t),
            "a chart on rows {f}-{t} is cut by a page break at {breaks:?}"
        );
    }
    // Each chart plots its cylinder's column over the step numbers, the
    // table's nine rows below its header, under the charts.
    let header = step_header(&read_sheet(&book, "DIAGRAM")) + 1;
    let (first, last) = (header + 1, header + 9);
    assert!(header as u32 - 1 > to[3], "the table under the charts");
    for (k, column) in ["B", "C", "D", "E"].iter().enumerate() {
        let chart = crate::helpers::xlsx_part(&book, &format!("xl/charts/chart{}.xml", k + 1));
        assert!(
            chart.contains(&format!("<c:f>DIAGRAM!$A${first}:$A${last}</c:f>"))
                && chart.contains(&format!(
                    "<c:f>DIAGRAM!${column}${first}:${column}${last}</c:f>"
                )),
            "chart {}: {chart}",
            k + 1
        );
    }
    for k in 1..from.len() {
        assert!(
            from[k] > to[k - 1] && from[k] <= to[k - 1] + 2,
            "chart {k} starts at row {} but chart {} ends at row {} (stacked, one row apart)",
            from[k],
            k - 1,
            to[k - 1]
        );
    }
}

/// The time diagram's step markers stand where the simulation's step
/// timing puts each step, counted from the START press, in every cycle:
/// read back from the picture through its own axis labels.
#[test]
fn the_time_diagrams_step_markers_are_the_simulated_step_times() {
    let dir = tempfile::tempdir().unwrap();
    let out = convert(dir.path(), &["--diagram", "time", "--formats", "diagram"]);
    let svg = std::fs::read_to_string(out.join("paper_example.diagram.svg")).unwrap();
    let number = |line: &str, attr: &str| -> f64 {
        let at = line.find(&format!("{attr}=\"")).unwrap() + attr.len() + 2;
        line[at..].split('"').next().unwrap().parse().unwrap()
    };
    // Two axis labels give the scale: x of "0 s" and of "1 s" (or the first tick).
    let ticks: Vec<(f64, f64)> = svg
        .lines()
        // The axis labels along the top (y 72), not the verdict's "7.47 s".
        .filter(|l| {
            l.starts_with("<text")
                && l.contains(r#"y="72.0" text-anchor="middle""#)
                && l.ends_with(" s</text>")
        })
        .map(|l| {
            let label = l.trim_end_matches("</text>").rsplit('>').next().unwrap();
            (
                number(l, "x"),
                label.trim_end_matches(" s").parse().unwrap(),
            )
        })
        .collect();
    let ((x0, s0), (x1, s1)) = (ticks[0], ticks[1]);
    let seconds_at = |x: f64| s0 + (x - x0) / (x1 - x0) * (s1 - s0);
    let markers: Vec<f64> = svg
        .lines()
        .filter(|l| l.contains("stroke=\"#e67e22\""))
        .map(|l| seconds_at(number(l, "x1")))
        .collect();
    let report = steptable::simulate::simulate(
        &Build::path(&sample("paper_example.xlsx")).table,
        &Build::path(&sample("paper_example.xlsx")).program(),
        &Default::default(),
    );
    let press = report.cycles[0].press_ms;
    let expected: Vec<f64> = report
        .cycles
        .iter()
        .flat_map(|c| {
            c.steps
                .iter()
                .map(move |s| (c.press_ms - press + s.start_ms) as f64 / 1000.0)
        })
        .collect();
    assert!(
        report.cycles.len() > 1 && expected.len() > 8,
        "{expected:?}"
    );
    assert_eq!(markers.len(), expected.len(), "{markers:?}");
    for (m, e) in markers.iter().zip(&expected) {
        assert!(
            (m - e).abs() < 0.01,
            "a marker at {m} s, the step fired at {e} s"
        );
    }
    // Step 4 of the paper's example fires 2.59 s after START, as the table says.
    assert!((expected[3] - 2.59).abs() < 0.005, "{expected:?}");
}

/// The legend says what a rising lane means in the words of the kinds the
/// table has: the paper's cylinders extend, the car wash's drive runs
/// forward (it once read "one lane per cylinder … extends" there too).
#[test]
fn the_legend_speaks_of_the_tables_own_kinds() {
    let dir = tempfile::tempdir().unwrap();
    let legend = |name: &str| {
        steptable()
            .arg("convert")
            .arg(sample(&format!("{name}.xlsx")))
            .args(["--formats", "diagram", "-o"])
            .arg(dir.path())
            .assert()
            .success();
        let svg = dir.path().join(name).join(format!("{name}.diagram.svg"));
        let svg = std::fs::read_to_string(svg).unwrap();
        let at = svg.find("one lane per").expect("a legend");
        svg[at..at + svg[at..].find('<').unwrap()].to_string()
    };
    let paper = legend("paper_example");
    assert!(
        paper.contains("one lane per cylinder") && paper.contains("extends (+)"),
        "{paper}"
    );
    let carwash = legend("carwash");
    assert!(carwash.contains("one lane per actuator"), "{carwash}");
    assert!(
        carwash.contains("runs forward") && !carwash.contains("extends"),
        "{carwash}"
    );
}
