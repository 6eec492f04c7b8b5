//! Scenarios from the command line in the engines: `simulate --press
//! START@0.5s --press ESTOP@step2 --press RESET@+1s --press START@step0
//! --press STOP@step1` on every bundled sample, converted with `--modes
//! stop,estop,reset`: the written program runs the very events the command
//! prints, for as long as the command runs, scan for scan as simulated, in
//! matiec (iec), awlsim (siemens) and the FST interpreter (festo).

use crate::engines::{self, awlsim};
use crate::helpers::{sample, steptable};
use crate::{Check, Tool, tool};

pub const CHECKS: &[Check] = &[Check::new(
    "scenario::stop_estop_and_reset_run_as_printed_in_every_engine",
    &[Tool::Shared, Tool::Awlsim],
    stop_estop_and_reset_run_as_printed_in_every_engine,
)];

/// Every bundled workbook: each machine's halt settings meet the buttons.
const SAMPLES: [&str; 8] = [
    "paper_example",
    "drilling_station",
    "carwash",
    "mixed_valves",
    "oven",
    "press_station",
    "sorting_station",
    "transfer_line",
];

/// START, the EMERGENCY STOP as step 2 starts (the oven has two steps), RESET a
/// second later, START once the machine is home, and STOP as step 1 of
/// that cycle starts: every button of the three modes, mid-cycle, and
/// each machine's STOP as its halt settings make it (at the cycle's end,
/// or at once).
const EVENTS: [(&str, &str); 5] = [
    ("press", "START@0.5s"),
    ("press", "ESTOP@step2"),
    ("press", "RESET@+1s"),
    ("press", "START@step0"),
    ("press", "STOP@step1"),
];

fn stop_estop_and_reset_run_as_printed_in_every_engine() {
    let dir = tempfile::tempdir().unwrap();
    let python = awlsim::python(&tool(Tool::Awlsim));
    let mut compared = 0;
    for name in SAMPLES {
        let input = sample(&format!("{name}.xlsx"));
        let printed = printed_times(&input);
        for &(target, format) in engines_for(name) {
            let args = ["--target", target, "--modes", "stop,estop,reset"];
            let out = dir.path().join(format);
            let (case, report) =
                engines::convert_and_record(&input, &out, name, &args, format, &EVENTS);
            let label = &case.label;
            // The run the engines replay is the one the command printed.
            let happened: Vec<u64> = report.happened.iter().map(|(t, _)| *t).collect();
            assert_eq!(happened, printed, "{label}: the printed event times");
            let outputs = engines::run_written(&case, format, &python);
            case.check(format, outputs).unwrap();
            // What the engineer sees: the emergency stop switches every
            // coil off, RESET homes the machine, and it stands at rest.
            let scans = &case.trace.scans;
            let estop = happened[1];
            let after = scans.iter().position(|s| s.time_ms > estop).unwrap();
            assert!(
                scans[after].outputs.iter().all(|on| !on),
                "{label}: every output off the scan after the EMERGENCY STOP"
            );
            let last = report.samples.last().unwrap();
            assert_eq!(last.step, 0, "{label}: at rest at the end");
            assert!(
                last.positions.iter().all(|p| p.abs() < 0.05),
                "{label}: home at the end: {:?}",
                last.positions
            );
            compared += 1;
        }
    }
    eprintln!(
        "scenario: {compared} runs (every sample x matiec, awlsim, FST interpreter; the oven in awlsim alone) press START, ESTOP, RESET, START and STOP as `simulate` prints them, scan for scan as simulated"
    );
}

/// The engines a sample converts for: every one, but the oven's ADDRESSES
/// sheet pins S7 addresses, so it converts for the siemens target alone.
fn engines_for(name: &str) -> &'static [(&'static str, &'static str)] {
    const EVERY: &[(&str, &str)] = &[("iec", "st"), ("siemens", "awl"), ("festo", "fst")];
    if name == "oven" { &EVERY[1..2] } else { EVERY }
}

/// The times `simulate` prints for the three events, in seconds as
/// printed, read back as milliseconds.
fn printed_times(input: &std::path::Path) -> Vec<u64> {
    let mut command = steptable();
    command
        .arg("simulate")
        .arg(input)
        .args(["--modes", "stop,estop,reset"]);
    for (option, text) in EVENTS {
        command.arg(format!("--{option}")).arg(text);
    }
    let out = command.assert().success().get_output().stdout.clone();
    let out = String::from_utf8(out).unwrap();
    EVENTS
        .iter()
        .map(|(option, text)| {
            let line = out
                .lines()
                .find(|l| l.contains(&format!("--{option} {text}:")))
                .unwrap_or_else(|| panic!("{text} printed: {out}"));
            let seconds: f64 = line.split_whitespace().next().unwrap().parse().unwrap();
            (seconds * 1000.0).round() as u64
        })
        .collect()
}
