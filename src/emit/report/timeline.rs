//! The report's timeline of the simulated cycle, a logic analyser's view:
//! the active step, one lane per actuator (its position), one per output
//! and per input (high or low), dwells and waits shaded, on one time axis
//! that starts at the START press, so every time on it is the step timing
//! table's. Each digital lane carries its changes in `data-edges`
//! (`0:0 1230:1 …`, milliseconds from the press and the value from then
//! on), which the page's zoom leaves alone and the tests read back.

use std::fmt::Write;

use crate::emit::diagram::{Tenths, escape};
use crate::simulate::io::IoTrace;
use crate::simulate::{SimReport, Span};

/// Pixels per second at zoom 1.
pub const PX_PER_S: f64 = 120.0;
const LANE: f64 = 22.0;
const POSITION_LANE: f64 = 40.0;
const GAP: f64 = 6.0;
const AXIS: f64 = 24.0;

/// What the timeline draws beside the digital lanes: where its time axis
/// starts, the shaded spans (dwells and waits: the proof's first cycle,
/// or a scenario's whole run), each actuator's position at every scan, and
/// the moments marked with a line across every lane (a scenario's events).
pub struct Drawn<'a> {
    /// The run's time that is 0 on the axis.
    pub press_ms: u64,
    pub spans: &'a [Span],
    /// Actuator numbers and end positions, in the order of each position vector.
    pub actuators: &'a [(u32, u32)],
    /// `(time_ms, positions)` at every scan.
    pub positions: &'a [(u64, Vec<f64>)],
    /// `(time_ms, label)` of each moment marked.
    pub marks: &'a [(u64, String)],
}

impl<'a> Drawn<'a> {
    /// The simulated cycle of `report`, from its first START press.
    pub fn of(report: &'a SimReport) -> Self {
        Drawn {
            press_ms: report.cycles.first().map_or(0, |c| c.press_ms),
            spans: &report.spans,
            actuators: &report.actuators,
            positions: &report.trace,
            marks: &[],
        }
    }
}

/// One lane: its label, what it is, and its value changes
/// `(ms from the press, value)`, the first at 0.
pub struct Lane {
    pub label: String,
    pub kind: &'static str,
    pub edges: Vec<(u64, u32)>,
}

/// The scans from `start` on at which anything may change: the first,
/// and each that reads, writes or stands in a step other than the scan
/// before it. A recorded run repeats its quiet scans, most of its scans,
/// and every lane is read at these alone.
fn changing_scans(trace: &IoTrace, start: u64) -> Vec<usize> {
    let first = trace.scans.partition_point(|s| s.time_ms < start);
    let mut out: Vec<usize> = Vec::new();
    for k in first..trace.scans.len() {
        let (before, scan) = (k.checked_sub(1).map(|b| &trace.scans[b]), &trace.scans[k]);
        let same = before.is_some_and(|b| {
            k > first && b.step == scan.step && b.outputs == scan.outputs && b.inputs == scan.inputs
        });
        if !same {
            out.push(k);
        }
    }
    out
}

/// The changes of `value(scan)` over the scans `changing` (from `start`
/// on), times taken from the press.
fn edges(
    trace: &IoTrace,
    start: u64,
    changing: &[usize],
    value: impl Fn(usize) -> u32,
) -> Vec<(u64, u32)> {
    let mut out: Vec<(u64, u32)> = Vec::new();
    for &k in changing {
        let v = value(k);
        if out.last().is_none_or(|(_, last)| *last != v) {
            out.push((trace.scans[k].time_ms - start, v));
        }
    }
    if let Some(first) = out.first_mut() {
        first.0 = 0;
    }
    out
}

/// The digital lanes of a recorded run, from the first START press:
/// the active step, each output, each input, named by `name`.
pub fn lanes(
    trace: &IoTrace,
    press_ms: u64,
    name: &dyn Fn(crate::program::Signal) -> String,
) -> Vec<Lane> {
    let changing = changing_scans(trace, press_ms);
    let edges = |value: &dyn Fn(usize) -> u32| edges(trace, press_ms, &changing, value);
    let mut lanes = vec![Lane {
        label: "active step".to_string(),
        kind: "step",
        edges: edges(&|k| trace.scans[k].step as u32),
    }];
    for (i, signal) in trace.signals.outputs.iter().enumerate() {
        lanes.push(Lane {
            label: name(*signal),
            kind: "output",
            edges: edges(&|k| u32::from(trace.scans[k].outputs[i])),
        });
    }
    for (i, signal) in trace.signals.inputs.iter().enumerate() {
        lanes.push(Lane {
            label: name(*signal),
            kind: "input",
            edges: edges(&|k| u32::from(trace.scans[k].inputs[i])),
        });
    }
    lanes
}

fn edges_attr(edges: &[(u64, u32)]) -> String {
    edges
        .iter()
        .map(|(t, v)| format!("{t}:{v}"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// A page's timeline: how to read it (`hint`, then what the shading
/// means), the zoom buttons, the lanes' labels and the lanes, each signal
/// named by `signal`: the one builder of the report's timeline and the
/// scenario page's, so that both draw the same lanes and shading.
pub fn section(
    drawn: &Drawn,
    trace: &IoTrace,
    hint: &str,
    signal: &dyn Fn(crate::program::Signal) -> String,
    actuator: &dyn Fn(u32) -> String,
) -> String {
    let lanes = lanes(trace, drawn.press_ms, signal);
    let (svg, labels) = render(drawn, trace, &lanes, actuator);
    let hint = format!("{hint} Shaded: dwells (green) and waits for a machine input (violet).");
    timeline_box(&hint, &svg, labels)
}

/// The timeline with its zoom buttons and the lanes' labels beside it.
fn timeline_box(hint: &str, svg: &str, labels: Vec<String>) -> String {
    let mut out = format!(
        "<p class=\"hint\">{}</p>\n<div class=\"controls\" hidden><button type=\"button\" data-zoom=\"0.5\">zoom out</button> <button type=\"button\" data-zoom=\"2\">zoom in</button> <button type=\"button\" data-zoom=\"0\">fit</button></div>\n<div class=\"timeline-box\"><div class=\"lane-labels\">",
        escape(hint)
    );
    for label in labels {
        let mut parts = label.splitn(3, '|');
        let (text, kind, height) = (
            parts.next().unwrap_or(""),
            parts.next().unwrap_or(""),
            parts.next().unwrap_or("22"),
        );
        let _ = write!(
            out,
            "<div class=\"{kind}\" style=\"height:{height}px\">{}</div>",
            escape(text)
        );
    }
    let _ = write!(out, "</div><div class=\"lanes\">{svg}</div></div>");
    out
}

/// The timeline as an SVG (lanes only; their labels are the HTML beside
/// it, so that they stay put while the lanes scroll and zoom).
pub fn render(
    report: &Drawn,
    trace: &IoTrace,
    lanes: &[Lane],
    actuator: &dyn Fn(u32) -> String,
) -> (String, Vec<String>) {
    let press = report.press_ms;
    // To the end of the last scan: its outputs hold until then, and the
    // run's printed end is that time.
    let end_ms = trace
        .scans
        .last()
        .map_or(0, |s| {
            (s.time_ms + u64::from(trace.scan_ms)).saturating_sub(press)
        })
        .max(1000);
    let width = (end_ms as f64 / 1000.0 * PX_PER_S).ceil() + 20.0;
    let x = |ms: u64| ms as f64 / 1000.0 * PX_PER_S;
    let positions = report.actuators.len() as f64 * (POSITION_LANE + GAP);
    let height = AXIS + positions + lanes.len() as f64 * (LANE + GAP);
    let mut svg = String::new();
    let _ = writeln!(
        svg,
        r##"<svg xmlns="http://www.w3.org/2000/svg" class="timeline" width="{width:.0}" height="{height:.0}" viewBox="0 0 {width:.0} {height:.0}" preserveAspectRatio="none" data-px-per-s="{PX_PER_S}" data-end-ms="{end_ms}">"##
    );
    // Dwells and waits, shaded over every lane.
    for span in report.spans {
        let (a, b) = (
            x(span.from_ms.saturating_sub(press)),
            x(span.to_ms.saturating_sub(press)),
        );
        let class = if span.label.starts_with("I:") {
            "wait"
        } else {
            "dwell"
        };
        let _ = writeln!(
            svg,
            r#"<rect class="{class}" x="{a:.1}" y="{AXIS}" width="{:.1}" height="{:.1}"><title>{}</title></rect>"#,
            (b - a).max(1.0),
            height - AXIS,
            escape(&span.label)
        );
    }
    // The axis: a tick every second.
    for s in 0..=end_ms / 1000 {
        let _ = writeln!(
            svg,
            r#"<line class="tick" x1="{0:.1}" y1="{AXIS}" x2="{0:.1}" y2="{height:.0}"/><text class="axis" x="{1:.1}" y="14">{s} s</text>"#,
            x(s * 1000),
            x(s * 1000) + 2.0
        );
    }
    let mut labels = Vec::new();
    let mut top = AXIS;
    for (i, (number, pmax)) in report.actuators.iter().enumerate() {
        labels.push(format!("{}|position|{POSITION_LANE}", actuator(*number)));
        let pmax = (*pmax).max(1) as f64;
        let mut points = String::new();
        for (t, p) in report.positions.iter().filter(|(t, _)| *t >= press) {
            if let Some(p) = p.get(i) {
                let y = top + POSITION_LANE - 3.0 - p / pmax * (POSITION_LANE - 6.0);
                let _ = write!(points, "{},{} ", Tenths(x(t - press)), Tenths(y));
            }
        }
        let _ = writeln!(
            svg,
            r#"<polyline class="position" data-actuator="{number}" points="{}"/>"#,
            points.trim_end()
        );
        top += POSITION_LANE + GAP;
    }
    for lane in lanes {
        labels.push(format!("{}|{}|{LANE}", lane.label, lane.kind));
        let _ = write!(
            svg,
            r#"<g class="lane {}" data-signal="{}" data-edges="{}">"#,
            lane.kind,
            escape(&lane.label),
            edges_attr(&lane.edges)
        );
        if lane.kind == "step" {
            step_lane(&mut svg, lane, top, end_ms, &x);
        } else {
            let (high, low) = (top + 3.0, top + LANE - 3.0);
            let mut points = String::new();
            for (k, (t, v)) in lane.edges.iter().enumerate() {
                let y = if *v == 1 { high } else { low };
                if k > 0 {
                    let before = if lane.edges[k - 1].1 == 1 { high } else { low };
                    let _ = write!(points, "{},{} ", Tenths(x(*t)), Tenths(before));
                }
                let _ = write!(points, "{},{} ", Tenths(x(*t)), Tenths(y));
            }
            let last = lane
                .edges
                .last()
                .map_or(low, |(_, v)| if *v == 1 { high } else { low });
            let _ = write!(points, "{},{}", Tenths(x(end_ms)), Tenths(last));
            let _ = write!(svg, r#"<polyline points="{points}"/>"#);
        }
        svg.push_str("</g>\n");
        top += LANE + GAP;
    }
    // The marked moments over everything else, styled here: the report's
    // style sheet is the healthy cycle's, which marks none.
    for (t, label) in report.marks {
        let at = x(t.saturating_sub(press));
        let _ = writeln!(
            svg,
            r##"<line class="mark" x1="{at:.1}" y1="{AXIS}" x2="{at:.1}" y2="{height:.0}" stroke="#c0392b" stroke-width="2"><title>{}</title></line>"##,
            escape(label)
        );
    }
    svg.push_str("</svg>");
    (svg, labels)
}

/// The active step as boxes with their numbers, one per stretch.
fn step_lane(svg: &mut String, lane: &Lane, top: f64, end_ms: u64, x: &dyn Fn(u64) -> f64) {
    for (k, (t, step)) in lane.edges.iter().enumerate() {
        let until = lane.edges.get(k + 1).map_or(end_ms, |(t, _)| *t);
        let _ = write!(
            svg,
            r#"<rect x="{:.1}" y="{:.1}" width="{:.1}" height="{:.1}"/><text x="{:.1}" y="{:.1}">{step}</text>"#,
            x(*t),
            top + 2.0,
            (x(until) - x(*t)).max(0.5),
            LANE - 4.0,
            x(*t) + 3.0,
            top + LANE - 7.0
        );
    }
}
