//! Step supervision with criteria analysis in the engines: the paper's
//! example converted with `--safety criteria`, x32 open circuit (step 5
//! waits for x32 and x22). The written program raises the timeout alarm
//! and lights x32's missing output, and x32's alone, in matiec (iec),
//! awlsim (siemens) and the FST interpreter (festo), and in the SCL and
//! RLL interpreters (the TIA Portal SCL, the Studio 5000 L5X), scan for
//! scan as simulated.

use steptable::convert;
use steptable::program::{Alarm, Signal};
use steptable::simulate::{Fault, Operator};

use crate::differential_native::{run_l5x, run_scl};
use crate::engines::{self, awlsim};
use crate::helpers::sample;
use crate::{Check, Tool, tool};

pub const CHECKS: &[Check] = &[Check::new(
    "supervision::the_missing_condition_is_read_in_every_engine",
    &[Tool::Shared, Tool::Awlsim],
    the_missing_condition_is_read_in_every_engine,
)];

/// START pressed from 0.5 s to 0.6 s.
fn script() -> Vec<(u64, Operator)> {
    let pressed = Operator {
        start: true,
        ..Operator::default()
    };
    vec![
        (0, Operator::default()),
        (500, pressed),
        (600, Operator::default()),
    ]
}

fn the_missing_condition_is_read_in_every_engine() {
    let dir = tempfile::tempdir().unwrap();
    let input = sample("paper_example.xlsx");
    let python = awlsim::python(&tool(Tool::Awlsim));
    let x32 = Signal::Sensor {
        actuator: 3,
        position: 2,
    };
    // Beside each engine's own file, the native programs of the two largest
    // PLC families: the TIA Portal SCL with its tag table (siemens), the
    // Studio 5000 L5X with its tags (iec), each in its interpreter.
    let runs = [
        ("iec", "st", "st,l5x,rockwell"),
        ("siemens", "awl", "awl,scl,tia"),
        ("festo", "fst", "fst"),
    ];
    for (target, format, formats) in runs {
        let args = ["--target", target, "--safety", "criteria"];
        let scenario = engines::Scenario {
            input: &input,
            out: dir.path().join(format),
            stem: "paper_example",
            args: &args,
            formats,
            script: script(),
            until_ms: 12_000,
        };
        let label = format!("paper_example {} with x32 stuck off", args.join(" "));
        let (case, report) = engines::record_scenario(&scenario, &label, |simulation| {
            simulation.faults = vec![Fault {
                signal: x32,
                stuck_at: false,
            }]
        });
        let fired = report.fired;
        // The simulation this engine must match: steps 1 to 4, then step
        // 5 waits for x32 until its watchdog runs out.
        let steps: Vec<usize> = fired.iter().map(|(_, s)| *s).collect();
        assert_eq!(steps, [1, 2, 3, 4], "{}: {fired:?}", case.label);
        let outputs = engines::run_written(&case, format, &python);
        case.check(format, outputs).unwrap();
        match target {
            "siemens" => case.check_stepped("scl", run_scl(&case)).unwrap(),
            "iec" => case.check_stepped("l5x", run_l5x(&case)).unwrap(),
            _ => {}
        }
        // The engine's outputs are the trace's: at the end the alarm and
        // x32's missing output are on, no other missing output.
        let checked = convert::check_path(&input, &engines::settings_for(&args)).unwrap();
        let program = convert::build_program(&checked.table, &checked.settings);
        let signals = &case.trace.signals.outputs;
        let last = &case.trace.scans.last().unwrap().outputs;
        let on: Vec<Signal> = signals
            .iter()
            .zip(last)
            .filter(|(s, on)| **on && matches!(s, Signal::Missing(_) | Signal::Alarm(_)))
            .map(|(s, _)| *s)
            .collect();
        let n = program
            .criteria
            .iter()
            .position(|c| c.signal == x32)
            .unwrap();
        assert_eq!(
            on,
            [Signal::Alarm(Alarm::Timeout), Signal::Missing(n as u16 + 1)],
            "{}",
            case.label
        );
    }
    eprintln!(
        "supervision: matiec, awlsim, the FST, SCL and RLL interpreters raise the timeout alarm of the paper's example with x32 stuck off and name x32, and only x32, missing, as simulated"
    );
}
