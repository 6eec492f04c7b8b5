//! `NAME.scenario.report.html`: a scenario of `simulate --press … --report
//! DIR` on one self-contained page, the report's style sheet, script and
//! timeline renderer reused: what happened as `simulate` prints it, and the
//! run drawn lane by lane from power-up, each event a red line across the
//! lanes.

use std::fmt::Write;

use super::timeline::{self, Drawn};
use super::{SCRIPT, STYLE};
use crate::emit::diagram::escape;
use crate::program::Signal;
use crate::simulate::io::IoTrace;

/// What the page shows.
pub struct ScenarioPage<'a> {
    /// The outputs' name (`paper_example`).
    pub name: &'a str,
    /// The table read (`paper_example.xlsx`).
    pub source: &'a str,
    /// The scenario as `simulate` prints it.
    pub printed: &'a str,
    /// The run, drawn from power-up with its events marked.
    pub drawn: Drawn<'a>,
    /// Every input and output at every scan.
    pub trace: &'a IoTrace,
    pub signal: &'a dyn Fn(Signal) -> String,
    pub actuator: &'a dyn Fn(u32) -> String,
}

/// The page.
pub fn render(page: &ScenarioPage) -> String {
    let name = escape(&crate::emit::one_line(page.name));
    let mut out = String::with_capacity(64 * 1024);
    let _ = write!(
        out,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>{name}: scenario</title>\n<style>\n{STYLE}</style>\n</head>\n<body>\n<header><h1>{name}: scenario</h1><p>{}</p></header>\n",
        escape(page.source)
    );
    let _ = write!(
        out,
        "<section id=\"happened\">\n<h2>What happened</h2>\n<pre>{}</pre>\n</section>\n",
        escape(page.printed)
    );
    let timeline = timeline::section(
        &page.drawn,
        page.trace,
        &hint(page.trace),
        page.signal,
        page.actuator,
    );
    let _ = write!(
        out,
        "<section id=\"timeline\">\n<h2>Timeline of the scenario</h2>\n{timeline}\n</section>\n"
    );
    let _ = write!(out, "<script>\n{SCRIPT}</script>\n</body>\n</html>\n");
    out
}

/// How to read the timeline, and how much of the run it draws: at most the
/// report's [`super::TIMELINE_SCANS`] scans, as the report does.
fn hint(trace: &IoTrace) -> String {
    let mut hint = String::from(
        "Time from power-up, as in the table above. Red lines: the scenario's events (hover for which).",
    );
    if trace.cut {
        let _ = write!(
            hint,
            " The timeline is drawn for at most {} scans: this run went on past {} s at {} ms a scan, and only its start is drawn.",
            super::TIMELINE_SCANS,
            super::TIMELINE_SCANS as u64 * u64::from(trace.scan_ms) / 1000,
            trace.scan_ms
        );
    }
    hint
}
