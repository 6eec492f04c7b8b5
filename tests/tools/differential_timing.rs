//! Dwells never shorter than the table asks, in every output language, for
//! awkward durations: the `.st` and `.fst.txt` give the simulation's trace
//! exactly; the `.awl` (whose S5 timers count in steps of 10 ms, 100 ms, 1 s
//! or 10 s) may end a dwell later by at most one step of its time base, and
//! English and German sources time alike.

use std::path::Path;

use steptable::address::Mnemonic;
use steptable::cell::Sign;
use steptable::program::Signal;
use steptable::simulate::io::IoTrace;

use crate::engines::{self, Case, Engine, awlsim, fst, matiec};
use crate::{Check, Tool, shared, tool};

pub const CHECKS: &[Check] = &[
    Check::new(
        "differential_timing::dwells_are_never_shorter_than_asked_in_the_simulation_and_fst",
        &[],
        || dwells_are_never_shorter_than_asked(Engine::Fst),
    ),
    Check::new(
        "differential_timing::dwells_are_never_shorter_than_asked_in_matiec",
        &[Tool::Shared],
        || dwells_are_never_shorter_than_asked(Engine::Matiec),
    ),
    Check::new(
        "differential_timing::dwells_are_never_shorter_than_asked_in_awlsim",
        &[Tool::Awlsim],
        || dwells_are_never_shorter_than_asked(Engine::Awlsim),
    ),
];

const DURATIONS: [(&str, u64); 6] = [
    ("10ms", 10),
    ("15ms", 15),
    ("1.005s", 1005),
    ("9.99s", 9990),
    ("10.01s", 10_010),
    ("655s", 655_000),
];

/// C1 out, dwell, C1 back: the dwell's end is when y1- comes on.
fn case(dir: &Path, text: &str, extra: &[&str]) -> Case {
    let input = dir.join(format!("dwell_{}.csv", text.replace('.', "_")));
    std::fs::write(&input, format!("C1+1\nT={text}\nC1-0\n")).unwrap();
    let mut args = vec!["--formats", "st,awl,fst"];
    args.extend_from_slice(extra);
    engines::prepare(
        &input,
        &args,
        &dir.join(format!("out-{text}-{}", extra.join(""))),
    )
}

fn y1_minus() -> Signal {
    Signal::Coil {
        actuator: 1,
        sign: Sign::Minus,
    }
}

/// The first scan at which `signal` is on in `outputs`.
fn first_on(trace: &IoTrace, outputs: &[Vec<bool>], signal: Signal) -> Option<usize> {
    let k = trace.signals.outputs.iter().position(|s| *s == signal)?;
    outputs.iter().position(|o| o[k])
}

/// The first scan at which input `signal` reads 1.
fn first_input(trace: &IoTrace, signal: Signal) -> usize {
    let k = trace
        .signals
        .inputs
        .iter()
        .position(|s| *s == signal)
        .unwrap();
    trace.scans.iter().position(|s| s.inputs[k]).unwrap()
}

fn dwells_are_never_shorter_than_asked(engine: Engine) {
    let dir = tempfile::tempdir().unwrap();
    let shared = (engine == Engine::Matiec).then(shared);
    let python = (engine == Engine::Awlsim).then(|| awlsim::python(&tool(Tool::Awlsim)));
    for (text, ms) in DURATIONS {
        let case = case(dir.path(), text, &[]);
        let trace = &case.trace;
        let scan = trace.scan_ms as u64;
        let sim: Vec<Vec<bool>> = trace.scans.iter().map(|s| s.outputs.clone()).collect();
        let started = first_input(
            trace,
            Signal::Sensor {
                actuator: 1,
                position: 1,
            },
        );
        let ended = first_on(trace, &sim, y1_minus()).unwrap();
        // The simulation itself: at least the dwell, at most one scan more.
        let lasted = (ended - started) as u64 * scan;
        assert!(
            lasted >= ms && lasted < ms + scan,
            "{text}: simulation {lasted} ms"
        );
        if engine == Engine::Fst {
            let fst_text = crate::engines::read_ansi(&case.file(".fst.txt")).unwrap();
            case.check("FST", fst::run(&fst_text, trace, &case.festo))
                .unwrap();
        }
        if let Some(shared) = &shared {
            case.check(
                "matiec",
                matiec::run(shared, &case.file(".st"), trace, &case.allocation),
            )
            .unwrap();
        }
        let Some(python) = &python else { continue };
        // AWL: the first cycle up to a little after the dwell is enough.
        let mut first = trace.clone();
        first.scans.truncate(ended + 1100);
        let mut ends = Vec::new();
        for mnemonic in [Mnemonic::En, Mnemonic::De] {
            let awl_case = if mnemonic == Mnemonic::En {
                None
            } else {
                Some(case_de(dir.path(), text))
            };
            let c = awl_case.as_ref().unwrap_or(&case);
            let outputs =
                awlsim::run(python, &c.file(".awl"), mnemonic, &first, &c.allocation).unwrap();
            let end = first_on(&first, &outputs, y1_minus())
                .unwrap_or_else(|| panic!("{text} ({mnemonic:?}): y1- never came on in awlsim"));
            let lasted = (end - started) as u64 * scan;
            let base = [10, 100, 1000, 10_000]
                .into_iter()
                .find(|b| ms.div_ceil(*b) <= 999)
                .unwrap();
            assert!(
                lasted >= ms && lasted <= ms + scan + base,
                "{text} ({mnemonic:?}): the AWL dwell lasted {lasted} ms"
            );
            // Up to there the AWL did what the simulation did.
            let before: Vec<Vec<bool>> = outputs[..end.min(ended)].to_vec();
            let mut head = first.clone();
            head.scans.truncate(before.len());
            head.compare(&before)
                .unwrap_or_else(|m| panic!("{text} ({mnemonic:?}): {m}"));
            ends.push(end);
        }
        assert_eq!(ends[0], ends[1], "{text}: English and German AWL differ");
    }
}

fn case_de(dir: &Path, text: &str) -> Case {
    case(dir, text, &["--mnemonic", "de"])
}
