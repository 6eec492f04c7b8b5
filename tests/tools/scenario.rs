//! Scenarios from the command line in the engines: `simulate --press
//! STOP@step2 --press ESTOP@step3 --press RESET@+1s` on the paper's example
//! and the drilling station, converted with `--modes stop,estop,reset`:
//! the written program runs the very events the command prints, scan for
//! scan as simulated, in matiec (iec), awlsim (siemens) and the FST
//! interpreter (festo).

use crate::engines::{self, awlsim};
use crate::helpers::{sample, steptable};
use crate::{Check, Tool, tool};

pub const CHECKS: &[Check] = &[Check::new(
    "scenario::stop_estop_and_reset_run_as_printed_in_every_engine",
    &[Tool::Shared, Tool::Awlsim],
    stop_estop_and_reset_run_as_printed_in_every_engine,
)];

/// STOP as step 2 starts, the EMERGENCY STOP as step 3 starts, RESET a
/// second later: every button of the three modes, mid-cycle.
const EVENTS: [(&str, &str); 3] = [
    ("press", "STOP@step2"),
    ("press", "ESTOP@step3"),
    ("press", "RESET@+1s"),
];

fn stop_estop_and_reset_run_as_printed_in_every_engine() {
    let dir = tempfile::tempdir().unwrap();
    let python = awlsim::python(&tool(Tool::Awlsim));
    let mut compared = 0;
    for name in ["paper_example", "drilling_station"] {
        let input = sample(&format!("{name}.xlsx"));
        let printed = printed_times(&input);
        for (target, format) in [("iec", "st"), ("siemens", "awl"), ("festo", "fst")] {
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
        "scenario: {compared} runs (paper example, drilling station x matiec, awlsim, FST interpreter) press STOP, ESTOP and RESET as `simulate` prints them, scan for scan as simulated"
    );
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
