//! Single-step mode in the engines: the paper's example converted with
//! `--modes step`, STEP_MODE on, START, then STEP_PB presses (one while
//! C1 still moves, one held for three seconds). The written program fires
//! exactly one step per press in matiec (iec), awlsim (siemens) and the
//! FST interpreter (festo), scan for scan as simulated.

use steptable::simulate::Operator;

use crate::engines::{self, awlsim};
use crate::helpers::sample;
use crate::{Check, Tool, tool};

pub const CHECKS: &[Check] = &[Check::new(
    "single_step::one_step_per_press_in_every_engine",
    &[Tool::Shared, Tool::Awlsim],
    one_step_per_press_in_every_engine,
)];

/// The switch on, no button pressed.
const STEPPING: Operator = Operator {
    start: false,
    continuous: false,
    stop: false,
    estop: false,
    reset: false,
    step_mode: true,
    step: false,
    manual: false,
    jogs: steptable::simulate::Jogs::NONE,
};

/// START at 0.5 s; STEP_PB at 1 s (step 1: C1 out, 1 s), at 1.3 s (C1 not
/// yet at x11: nothing), held from 3 s to 6 s (step 2 only, C2 reaches
/// x23 at about 4 s and step 3 still waits).
fn script() -> Vec<(u64, Operator)> {
    let with = |at, operator| [(at, operator), (at + 100, STEPPING)];
    let step = Operator {
        step: true,
        ..STEPPING
    };
    let mut script = vec![(0, STEPPING)];
    script.extend(with(
        500,
        Operator {
            start: true,
            ..STEPPING
        },
    ));
    script.extend(with(1_000, step));
    script.extend(with(1_300, step));
    script.extend([(3_000, step), (6_000, STEPPING)]);
    script
}

fn one_step_per_press_in_every_engine() {
    let dir = tempfile::tempdir().unwrap();
    let input = sample("paper_example.xlsx");
    let python = awlsim::python(&tool(Tool::Awlsim));
    for (target, format) in [("iec", "st"), ("siemens", "awl"), ("festo", "fst")] {
        let args = ["--target", target, "--modes", "step"];
        let scenario = engines::Scenario {
            input: &input,
            out: dir.path().join(format),
            stem: "paper_example",
            args: &args,
            formats: format,
            script: script(),
            until_ms: 7_500,
        };
        let label = format!("paper_example {}", args.join(" "));
        let (case, report) = engines::record_scenario(&scenario, &label, |_| {});
        let fired = report.fired;
        // The simulation this engine must match: steps 1 and 2, each the
        // scan after its press, and nothing else.
        let steps: Vec<usize> = fired.iter().map(|(_, s)| *s).collect();
        assert_eq!(steps, [1, 2], "{}: {fired:?}", case.label);
        assert!((1_000..1_100).contains(&fired[0].0), "{fired:?}");
        assert!((3_000..3_100).contains(&fired[1].0), "{fired:?}");
        let outputs = engines::run_written(&case, format, &python);
        case.check(format, outputs).unwrap();
        // The engine's outputs are the trace's: y2- (step 3's coil) never
        // came on, though x23 was reached with STEP_PB still held.
        let at = |symbol: &str| {
            let signals = &case.trace.signals.outputs;
            let at = signals.iter().position(|s| s.symbol() == symbol);
            at.unwrap_or_else(|| panic!("{symbol} is an output"))
        };
        let (y1, y2, y2_back) = (at("y1+"), at("y2+"), at("y2-"));
        let scans = &case.trace.scans;
        assert!(scans.iter().any(|s| s.outputs[y1] && s.outputs[y2]));
        assert!(
            scans.iter().all(|s| !s.outputs[y2_back]),
            "{}: step 3 fired without a press",
            case.label
        );
    }
    eprintln!(
        "single_step: matiec, awlsim and the FST interpreter fire one step per STEP_PB press of the paper's example, none while its condition is unmet or the button is held, as simulated"
    );
}
