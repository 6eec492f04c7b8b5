//! `NAME.report.html`: one self-contained page per machine, to open from a
//! USB stick on a shop-floor PC: the step table as the engineer wrote it,
//! the GRAFCET and the displacement diagrams (inline SVG), the I/O list
//! with its addresses, the settings used, the simulation's verdict and step
//! timing, the timeline of the simulated cycle and the fault table, hazards
//! first. No request leaves the file: the style sheet and the small script
//! (zoom, filters) are inlined, and every table and picture is there
//! without the script. It renders what the conversion already has, so it
//! costs a few milliseconds beside the fault analysis.

pub mod scenario;
pub mod timeline;

use std::fmt::Write;

use super::EmitInput;
use super::diagram::{DiagramKind, escape};
use crate::faults::Outcome;
use crate::faults::mitigation::Mitigation;

const STYLE: &str = include_str!("report.css");
const SCRIPT: &str = include_str!("report.js");

/// The most steps a table may have for the report to draw its timeline:
/// every scan of a longer cycle, every signal, would make the page (and
/// the recording) larger than a browser opens comfortably.
pub const TIMELINE_STEPS: usize = 200;

/// The most scans the timeline records and draws (200 s of a cycle at
/// 10 ms scans): a long dwell at a short scan time would otherwise make
/// the recording hundreds of megabytes and the page millions of pixels
/// wide. A longer run is recorded this far and the timeline left out.
pub const TIMELINE_SCANS: usize = 20_000;

/// The sections of the page, by id and heading, in order.
pub const SECTIONS: [(&str, &str); 8] = [
    ("table", "Step table"),
    ("grafcet", "GRAFCET"),
    ("diagrams", "Displacement diagrams"),
    ("io", "I/O list"),
    ("settings", "Settings used"),
    ("simulation", "Simulation"),
    ("timeline", "Timeline of the simulated cycle"),
    ("faults", "Sensor faults"),
];

/// The page, or why it cannot be made (a conversion that did not simulate
/// or analyse faults: a bug of the caller).
pub fn render(input: &EmitInput) -> Result<String, String> {
    let faults = input.faults.ok_or("no fault analysis")?;
    let mitigations = input.mitigations.ok_or("no mitigations of the hazards")?;
    let mut page = input.report_head()?.into_owned();
    section(&mut page, 7, &fault_table(input, faults, mitigations));
    let _ = write!(page, "<script>\n{SCRIPT}</script>\n</body>\n</html>\n");
    Ok(page)
}

/// The page up to its fault table: what needs no fault analysis, drawn
/// while it runs (see [`EmitInput::report_head`]).
pub(super) fn head(input: &EmitInput) -> Result<String, String> {
    let simulation = input.simulation.ok_or("not simulated")?;
    let name = escape(&super::one_line(input.name));
    let mut page = String::with_capacity(256 * 1024);
    let _ = write!(
        page,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>{name}: steptable report</title>\n<style>\n{STYLE}</style>\n</head>\n<body>\n<header><h1>{name}</h1><p>{}: {}</p><nav>",
        escape(&input.source()),
        escape(&input.symbols.explain(&simulation.verdict()))
    );
    for (id, heading) in SECTIONS {
        let _ = write!(page, "<a href=\"#{id}\">{heading}</a> ");
    }
    page.push_str("</nav></header>\n");
    section(&mut page, 0, &step_table(input));
    section(
        &mut page,
        1,
        &format!("<div class=\"picture\">{}</div>", input.grafcet_svg()),
    );
    section(&mut page, 2, &diagrams(input, simulation));
    section(&mut page, 3, &io_list(input));
    section(&mut page, 4, &settings(input));
    section(&mut page, 5, &step_timing(input, simulation));
    let timeline = match input.io_trace {
        Some(trace) if trace.cut => format!(
            "<p>The timeline is drawn for runs of at most {TIMELINE_SCANS} scans; this one runs longer than {} s at {} ms a scan.</p>",
            TIMELINE_SCANS as u64 * u64::from(trace.scan_ms) / 1000,
            trace.scan_ms
        ),
        Some(trace) => timeline_html(input, simulation, trace),
        None => format!(
            "<p>The timeline is drawn for tables of at most {TIMELINE_STEPS} steps; this one has {}.</p>",
            input.table.steps.len()
        ),
    };
    section(&mut page, 6, &timeline);
    Ok(page)
}

fn section(page: &mut String, index: usize, body: &str) {
    let (id, heading) = SECTIONS[index];
    let _ = write!(
        page,
        "<section id=\"{id}\">\n<h2>{heading}</h2>\n{body}\n</section>\n"
    );
}

/// An HTML table with a header row; cells are escaped.
fn table(
    class: &str,
    header: &[&str],
    rows: impl IntoIterator<Item = (String, Vec<String>)>,
) -> String {
    let mut out = format!("<table class=\"{class}\"><thead><tr>");
    for h in header {
        let _ = write!(out, "<th>{}</th>", escape(h));
    }
    out.push_str("</tr></thead><tbody>\n");
    for (attrs, cells) in rows {
        let _ = write!(out, "<tr{attrs}>");
        for c in cells {
            let _ = write!(out, "<td>{}</td>", escape(&c));
        }
        out.push_str("</tr>\n");
    }
    out.push_str("</tbody></table>");
    out
}

/// The table as written: one row per step with its label (and comment)
/// and each branch's cell.
fn step_table(input: &EmitInput) -> String {
    let branches = input.table.branches.max(1);
    let mut header = vec!["step".to_string()];
    header.extend((1..=branches).map(|b| format!("BRANCH {b}")));
    let header: Vec<&str> = header.iter().map(String::as_str).collect();
    let rows = input.table.steps.iter().map(|s| {
        let mut cells = vec![input.symbols.step_label(s.number)];
        cells.extend((0..branches).map(|b| s.cell_text(b)));
        (String::new(), cells)
    });
    table("steps", &header, rows)
}

fn diagrams(input: &EmitInput, simulation: &crate::simulate::SimReport) -> String {
    let step = input.diagram_svg(simulation, DiagramKind::Step);
    let time = input.diagram_svg(simulation, DiagramKind::Time);
    format!("<div class=\"picture\">{step}</div>\n<div class=\"picture\">{time}</div>")
}

fn io_list(input: &EmitInput) -> String {
    let rows = super::io_csv::rows(input)
        .into_iter()
        .map(|r| (String::new(), r.to_vec()));
    table("io", &super::io_csv::COLUMNS, rows)
}

fn settings(input: &EmitInput) -> String {
    let rows = input
        .settings
        .iter()
        .map(|(k, v)| (String::new(), vec![k.clone(), v.clone()]));
    table("settings", &["setting", "in force"], rows)
}

fn step_timing(input: &EmitInput, simulation: &crate::simulate::SimReport) -> String {
    let class = if simulation.passed {
        "passed"
    } else {
        "failed"
    };
    let mut out = format!(
        "<p class=\"verdict {class}\">{}</p>\n",
        escape(&input.symbols.explain(&simulation.verdict()))
    );
    let Some(cycle) = simulation.cycles.first() else {
        return out;
    };
    let rows = cycle.steps.iter().map(|s| {
        (
            String::new(),
            vec![
                input.symbols.step_label(s.step),
                crate::simulate::report::seconds(s.start_ms),
                crate::simulate::report::seconds(s.duration_ms),
                s.moves.clone(),
                input.symbols.explain(&s.notes),
            ],
        )
    });
    out.push_str(&table(
        "timing",
        &["step", "fires at", "lasts", "moves", "dwells and waits"],
        rows,
    ));
    out
}

fn timeline_html(
    input: &EmitInput,
    simulation: &crate::simulate::SimReport,
    trace: &crate::simulate::io::IoTrace,
) -> String {
    timeline::section(
        &timeline::Drawn::of(simulation),
        trace,
        "Time from the START press, as in the step timing above.",
        &|s| input.symbols.designation(s),
        &|n| input.symbols.actuator(n),
    )
}

/// The fault table: hazards first, then safe stalls, then the rest, each
/// in the analysis's order, coloured by outcome; filters by signal and
/// outcome work with the script, every row shows without it. Each row is
/// `NAME.faults.csv`'s with one more cell: for a hazard, its verified
/// mitigation (`crate::faults::mitigation`).
fn fault_table(
    input: &EmitInput,
    faults: &crate::faults::FaultTable,
    mitigations: &[Option<Mitigation>],
) -> String {
    let rows = super::faults_csv::rows(faults, &|s| input.symbols.designation(s), &|t| {
        input.symbols.explain(t)
    });
    let mut order: Vec<(Outcome, Vec<String>)> = faults
        .cases
        .iter()
        .zip(rows)
        .enumerate()
        .map(|(i, (case, cells))| {
            let mut cells = cells.to_vec();
            let mitigation = mitigations.get(i).and_then(Option::as_ref);
            cells.push(mitigation.map_or_else(String::new, |m| input.symbols.explain(&m.text())));
            (case.outcome, cells)
        })
        .collect();
    order.sort_by_key(|(outcome, _)| std::cmp::Reverse(*outcome as u8));
    let hazards = order.iter().filter(|(o, _)| *o == Outcome::Hazard).count();
    // A cycle too long for faults at every moment has them at power-up only
    // (`faults` says so in its summary): the page says so too.
    let (when, again) = match faults.phases_skipped {
        Some(_) => (
            "appearing at power-up only (this cycle is too long for faults at every moment)",
            "from power-up, as the table's",
        ),
        None => (
            "appearing at every moment of the cycle",
            "at the moments of the cycle until one gives the hazard (every moment, to say a check catches it)",
        ),
    };
    let mut out = format!(
        "<p>{hazards} hazard(s) among {} fault case(s): every input stuck at 1 and at 0, {when}. The mitigation of each hazard is verified: its faults are run again, {again}, with each safety check the program does not carry; a check catches the hazard when no moment gives one any more.</p>\n<div class=\"controls\" hidden><label>signal <input type=\"search\" id=\"fault-signal\" placeholder=\"e.g. x11\"></label> <label>outcome <select id=\"fault-outcome\"><option value=\"\">any</option><option>hazard</option><option>safe stall</option><option>no effect</option></select></label> <span id=\"fault-count\"></span></div>\n",
        order.len()
    );
    let rows = order.into_iter().map(|(outcome, cells)| {
        let class = outcome.label().replace(' ', "-");
        (
            format!(" class=\"{class}\" data-signals=\"{}\"", escape(&cells[1])),
            cells,
        )
    });
    let mut header = super::faults_csv::COLUMNS.to_vec();
    header.push("mitigation");
    out.push_str(&table("faults", &header, rows));
    out
}
