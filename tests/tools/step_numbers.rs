//! The step an engineer sees online is the SFC step (README "Step
//! numbers"): in the middle of the press station's dwells, each engine's
//! program shows the table step the dwell belongs to — `active_step` in
//! matiec, the AWL step flag in awlsim, the FST step label in the
//! interpreter. The differential checks compare the step at every scan with
//! the simulation's; these tie it to the table, so that the simulation and
//! every file agreeing on a wrong number would still fail.

use std::path::Path;

use crate::engines::{self, Case, Stepped, awlsim, fst, matiec};
use crate::{Check, Tool, shared, tool};

pub const CHECKS: &[Check] = &[
    Check::new(
        "step_numbers::inside_a_dwell_matiec_shows_the_dwells_step",
        &[Tool::Shared],
        inside_a_dwell_matiec_shows_the_dwells_step,
    ),
    Check::new(
        "step_numbers::inside_a_dwell_awlsim_shows_the_dwells_step",
        &[Tool::Awlsim],
        inside_a_dwell_awlsim_shows_the_dwells_step,
    ),
    Check::new(
        "step_numbers::inside_a_dwell_the_fst_shows_the_dwells_step",
        &[],
        inside_a_dwell_the_fst_shows_the_dwells_step,
    ),
];

/// The press station dwells in table steps 3 (T=500ms), 7 (T=300ms) and
/// 9 (T=2s, beside C3's stroke), without and with the modes and checks
/// (which add the closing transition's watchdog and `busy`).
const OPTIONS: [&[&str]; 2] = [&[], &["--modes", "all", "--safety", "all"]];

/// A case, and for each dwell of its table the scan in the middle of the
/// dwell's first run with the table step that holds the dwell.
fn cases(dir: &Path) -> Vec<(Case, Vec<(usize, usize)>)> {
    let sample = crate::helpers::sample("press_station.xlsx");
    OPTIONS
        .iter()
        .enumerate()
        .map(|(o, options)| {
            let case = engines::prepare(&sample, options, &dir.join(o.to_string()));
            let checked = steptable::convert::check_path(&sample, &engines::settings_for(options))
                .expect("valid table");
            let (table, settings) = (&checked.table, &checked.settings);
            let program = steptable::convert::build_program(table, settings);
            let report = steptable::simulate::simulate(table, &program, &settings.simulation);
            let mut moments = Vec::new();
            for step in &table.steps {
                for dwell in &step.dwells {
                    let middle = dwell_middle(&report, step.number, dwell.ms);
                    let scan = case
                        .trace
                        .scans
                        .iter()
                        .position(|s| s.time_ms >= middle)
                        .expect("the trace covers the dwell");
                    moments.push((scan, step.number));
                }
            }
            assert_eq!(
                moments.iter().map(|m| m.1).collect::<Vec<_>>(),
                [3, 7, 9],
                "the press station's dwells"
            );
            (case, moments)
        })
        .collect()
}

/// The middle of the first run of the dwell of table step `number`, from
/// the simulation's record of it (its span, within the step's time).
fn dwell_middle(report: &steptable::simulate::SimReport, number: usize, ms: u32) -> u64 {
    let cycle = &report.cycles[0];
    let timing = cycle
        .steps
        .iter()
        .find(|t| t.step == number)
        .expect("the step ran");
    let from = cycle.press_ms + timing.start_ms;
    let to = from + timing.duration_ms;
    let label = steptable::cell::dwell_text(ms);
    let span = report
        .spans
        .iter()
        .find(|s| s.label == label && s.from_ms >= from && s.from_ms < to)
        .unwrap_or_else(|| panic!("step {number}'s dwell did not run"));
    (span.from_ms + span.to_ms) / 2
}

/// Runs `engine` on every case and asserts the step it shows mid-dwell.
fn check(engine: &str, run: impl Fn(&Case) -> Result<Stepped, String>) {
    let dir = tempfile::tempdir().unwrap();
    for (case, moments) in cases(dir.path()) {
        let stepped = run(&case).unwrap_or_else(|e| panic!("{}: {engine}: {e}", case.label));
        for (scan, number) in moments {
            assert_eq!(
                case.trace.scans[scan].step, number,
                "{}: the simulation at scan {scan}",
                case.label
            );
            assert_eq!(
                stepped.steps.get(scan).copied(),
                Some(number),
                "{}: {engine} at scan {scan} ({} ms), inside step {number}'s dwell",
                case.label,
                case.trace.scans[scan].time_ms
            );
        }
    }
}

fn inside_a_dwell_matiec_shows_the_dwells_step() {
    let shared = shared();
    check("matiec", |c| {
        matiec::run_stepped(&shared, &c.file(".st"), &c.trace, &c.allocation)
    });
}

fn inside_a_dwell_awlsim_shows_the_dwells_step() {
    let python = awlsim::python(&tool(Tool::Awlsim));
    check("awlsim", |c| {
        awlsim::run_stepped(
            &python,
            &c.file(".awl"),
            c.mnemonic,
            &c.trace,
            &c.allocation,
        )
    });
}

fn inside_a_dwell_the_fst_shows_the_dwells_step() {
    check("FST interpreter", |c| {
        let text = crate::engines::read_ansi(&c.file(".fst.txt"))?;
        fst::run_stepped(&text, &c.trace, &c.festo)
    });
}
