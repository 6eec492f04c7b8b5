//! Manual mode in the engines: the paper's example converted with
//! `--modes all` runs the events of `tests/fixtures/manual_scenario.txt`
//! (each actuator jogged out and home, both buttons of C3 at once, a jog
//! under the EMERGENCY STOP, START in manual, then RESET and a cycle) in
//! matiec (iec), awlsim (siemens) and the FST interpreter (festo), scan
//! for scan as simulated.

use crate::engines::{self, awlsim};
use crate::helpers::{manual_events, sample};
use crate::{Check, Tool, tool};

pub const CHECKS: &[Check] = &[Check::new(
    "manual::jogs_run_as_simulated_in_every_engine",
    &[Tool::Shared, Tool::Awlsim],
    jogs_run_as_simulated_in_every_engine,
)];

fn jogs_run_as_simulated_in_every_engine() {
    let dir = tempfile::tempdir().unwrap();
    let python = awlsim::python(&tool(Tool::Awlsim));
    let input = sample("paper_example.xlsx");
    let written = manual_events();
    for (target, format) in [("iec", "st"), ("siemens", "awl"), ("festo", "fst")] {
        let args = ["--target", target, "--modes", "all"];
        let out = dir.path().join(format);
        let (case, report) =
            engines::convert_and_record(&input, &out, "paper_example", &args, format, &written);
        let label = &case.label;
        assert_eq!(report.happened.len(), written.len(), "{label}: every event");
        let steps: Vec<usize> = report.fired.iter().map(|(_, s)| *s).collect();
        assert_eq!(steps, (1..=9).collect::<Vec<_>>(), "{label}: one cycle");
        let outputs = engines::run_written(&case, format, &python);
        case.check(format, outputs).unwrap();
        // What the engineer sees in the engine's trace: every coil of the
        // paper's four cylinders came on in manual (before the cycle's
        // START at 19 s), y3+ and y3- never while both jogs were held.
        let scans = &case.trace.scans;
        let signals = &case.trace.signals.outputs;
        let manual = scans.iter().filter(|s| s.time_ms < 17_500);
        let mut seen = vec![false; signals.len()];
        for scan in manual {
            for (i, on) in scan.outputs.iter().enumerate() {
                seen[i] |= *on;
            }
        }
        for (i, signal) in signals.iter().enumerate() {
            if matches!(signal, steptable::program::Signal::Coil { .. }) {
                assert!(seen[i], "{label}: {} jogged in manual", signal.symbol());
            }
        }
        let both = scans.iter().filter(|s| (7_500..8_500).contains(&s.time_ms));
        let c3 = |s: &str| signals.iter().position(|x| x.symbol() == s).unwrap();
        let (y3p, y3m) = (c3("y3+"), c3("y3-"));
        assert!(
            both.clone().all(|s| !s.outputs[y3p] && !s.outputs[y3m]),
            "{label}"
        );
    }
    eprintln!(
        "manual: matiec, awlsim and the FST interpreter jog each cylinder of the paper's example, refuse both buttons and a jog under the EMERGENCY STOP, ignore START in manual and run the cycle after RESET, scan for scan as simulated"
    );
}
