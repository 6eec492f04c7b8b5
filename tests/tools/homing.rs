//! RESET's default homing order in the engines: a stamping station (clamp
//! C1, punch C2 with a dwell, ejector C3, feeder C4) is stopped by the
//! EMERGENCY STOP while the punch is down, then RESET: the written program
//! lifts the punch before it opens the clamp, in matiec (iec), awlsim
//! (siemens) and the FST interpreter (festo), scan for scan as simulated.

use steptable::simulate::Operator;

use crate::engines::{self, awlsim};
use crate::{Check, Tool, tool};

pub const CHECKS: &[Check] = &[Check::new(
    "homing::reset_lifts_the_punch_before_it_opens_the_clamp_in_every_engine",
    &[Tool::Shared, Tool::Awlsim],
    reset_lifts_the_punch_before_it_opens_the_clamp_in_every_engine,
)];

const STAMPING: &str = ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C2+1\nSTEP 3,T=2s\nSTEP 4,C2-0\nSTEP 5,C1-0\nSTEP 6,C3+1\nSTEP 7,C3-0\nSTEP 8,C4+1\nSTEP 9,C4-0\n";

const IDLE: Operator = Operator {
    start: false,
    continuous: false,
    stop: false,
    estop: false,
    reset: false,
    step_mode: false,
    step: false,
    manual: false,
    jogs: steptable::simulate::Jogs::NONE,
};

/// START at 0.5 s; the clamp closes (1 s), the punch goes down (1 s) and
/// dwells 2 s: at 3.5 s the punch is down. ESTOP there, RESET at 4 s.
fn script() -> Vec<(u64, Operator)> {
    let press = |at, operator| [(at, operator), (at + 100, IDLE)];
    [
        press(
            500,
            Operator {
                start: true,
                ..IDLE
            },
        ),
        press(
            3_500,
            Operator {
                estop: true,
                ..IDLE
            },
        ),
        press(
            4_000,
            Operator {
                reset: true,
                ..IDLE
            },
        ),
    ]
    .concat()
}

fn reset_lifts_the_punch_before_it_opens_the_clamp_in_every_engine() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("stamping.csv");
    std::fs::write(&input, STAMPING).unwrap();
    let python = awlsim::python(&tool(Tool::Awlsim));
    for (target, format) in [("iec", "st"), ("siemens", "awl"), ("festo", "fst")] {
        let args = ["--target", target, "--modes", "estop,reset"];
        let scenario = engines::Scenario {
            input: &input,
            out: dir.path().join(format),
            stem: "stamping",
            args: &args,
            formats: format,
            script: script(),
            until_ms: 10_000,
        };
        let label = format!("stamping {}", args.join(" "));
        let (case, _) = engines::record_scenario(&scenario, &label, |_| {});
        let outputs = engines::run_written(&case, format, &python);
        case.check(format, outputs).unwrap();
        // The engine's outputs are the trace's: read the order from it.
        let scans = &case.trace.scans;
        let input = |symbol: &str| {
            let at = case
                .trace
                .signals
                .inputs
                .iter()
                .position(|s| s.symbol() == symbol);
            let at = at.unwrap_or_else(|| panic!("{symbol} is an input"));
            move |i: usize| scans[i].inputs[at]
        };
        let output = |symbol: &str| {
            let at = case
                .trace
                .signals
                .outputs
                .iter()
                .position(|s| s.symbol() == symbol);
            let at = at.unwrap_or_else(|| panic!("{symbol} is an output"));
            move |i: usize| scans[i].outputs[at]
        };
        let after_reset = scans.iter().position(|s| s.time_ms >= 4_000).unwrap();
        let (punch_home, clamp_opens) = (input("x20"), output("y1-"));
        let lifted = (after_reset..scans.len()).find(|&i| punch_home(i));
        let opened = (after_reset..scans.len()).find(|&i| clamp_opens(i));
        let (Some(lifted), Some(opened)) = (lifted, opened) else {
            panic!(
                "{}: RESET lifts the punch ({lifted:?}) and opens the clamp ({opened:?})",
                case.label
            );
        };
        // The program reads x20 and switches y1- in the same scan.
        assert!(
            lifted <= opened,
            "{}: the clamp opens at scan {opened}, the punch is up only at scan {lifted}",
            case.label
        );
        assert!(
            (0..after_reset).any(|i| !punch_home(i)),
            "{}: the punch was down before RESET",
            case.label
        );
    }
    eprintln!(
        "homing: after an emergency stop with the punch down, matiec, awlsim and the FST interpreter lift the punch before the clamp opens on RESET, as simulated"
    );
}
