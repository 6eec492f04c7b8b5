//! Single-step mode in the engines: the paper's example and the two
//! stamping-like samples (the press station, the drilling station)
//! converted with `--modes step`, STEP_MODE on, START, then STEP_PB
//! presses (one while step 1 is not yet done, one held for three seconds).
//! The written program fires exactly one step per press in matiec (iec),
//! awlsim (siemens) and the FST interpreter (festo), scan for scan as
//! simulated.

use steptable::simulate::Operator;

use crate::engines::{self, awlsim};
use crate::helpers::sample;
use crate::{Check, Tool, tool};

pub const CHECKS: &[Check] = &[
    Check::new(
        "single_step::one_step_per_press_in_every_engine",
        &[Tool::Shared, Tool::Awlsim],
        one_step_per_press_in_every_engine,
    ),
    Check::new(
        "single_step::the_press_station_steps_one_per_press_in_every_engine",
        &[Tool::Shared, Tool::Awlsim],
        the_press_station_steps_one_per_press_in_every_engine,
    ),
    Check::new(
        "single_step::the_drilling_station_steps_one_per_press_in_every_engine",
        &[Tool::Shared, Tool::Awlsim],
        the_drilling_station_steps_one_per_press_in_every_engine,
    ),
];

/// A sample stepped by [`script`]: the outputs step 2 has on together at
/// some scan, and the output step 3 would switch on, which the held press
/// must not fire.
struct Stepped {
    stem: &'static str,
    together: &'static [&'static str],
    step_3: &'static str,
}

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

/// START at 0.5 s; STEP_PB at 1 s (step 1), at 1.3 s (step 1 not yet
/// done: the paper's C1 and the drilling station's clamp take a second to
/// go out, the press station's part comes half a second after step 1
/// starts: nothing), held from 3 s to 6 s (step 2 only: the paper's C2
/// reaches x23 at about 4 s, the samples' C2 its end at 3.6 s and 4 s,
/// and step 3 still waits).
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
    one_step_per_press(&Stepped {
        stem: "paper_example",
        together: &["y1+", "y2+"],
        step_3: "y2-",
    });
    eprintln!(
        "single_step: matiec, awlsim and the FST interpreter fire one step per STEP_PB press of the paper's example, none while its condition is unmet or the button is held, as simulated"
    );
}

/// The press station: step 1 waits for its part, step 2 lowers the
/// gripper (y2+), step 3 would switch its vacuum on.
fn the_press_station_steps_one_per_press_in_every_engine() {
    one_step_per_press(&Stepped {
        stem: "press_station",
        together: &["y2+"],
        step_3: "vacuum",
    });
    eprintln!(
        "single_step: matiec, awlsim and the FST interpreter fire one step per STEP_PB press of the press station (none before its part arrives, its vacuum never on under the held button), as simulated"
    );
}

/// The drilling station: step 1 clamps (y1+), step 2 feeds the drill
/// (y2+), step 3 would retract it (y2-).
fn the_drilling_station_steps_one_per_press_in_every_engine() {
    one_step_per_press(&Stepped {
        stem: "drilling_station",
        together: &["y1+", "y2+"],
        step_3: "y2-",
    });
    eprintln!(
        "single_step: matiec, awlsim and the FST interpreter fire one step per STEP_PB press of the drilling station (none while the clamp still moves, the drill never back under the held button), as simulated"
    );
}

/// `stepped` converted with `--modes step` runs [`script`] in every engine.
fn one_step_per_press(stepped: &Stepped) {
    let dir = tempfile::tempdir().unwrap();
    let input = sample(&format!("{}.xlsx", stepped.stem));
    let python = awlsim::python(&tool(Tool::Awlsim));
    for (target, format) in [("iec", "st"), ("siemens", "awl"), ("festo", "fst")] {
        let args = ["--target", target, "--modes", "step"];
        let scenario = engines::Scenario {
            input: &input,
            out: dir.path().join(format),
            stem: stepped.stem,
            args: &args,
            formats: format,
            script: script(),
            until_ms: 7_500,
        };
        let label = format!("{} {}", stepped.stem, args.join(" "));
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
        // The engine's outputs are the trace's: step 2's outputs on
        // together, step 3's never, though step 2 was done with STEP_PB
        // still held.
        let at = |symbol: &str| {
            let signals = &case.trace.signals.outputs;
            let at = signals.iter().position(|s| s.symbol() == symbol);
            at.unwrap_or_else(|| panic!("{symbol} is an output"))
        };
        let together: Vec<usize> = stepped.together.iter().map(|s| at(s)).collect();
        let step_3 = at(stepped.step_3);
        let scans = &case.trace.scans;
        assert!(
            scans.iter().any(|s| together.iter().all(|i| s.outputs[*i])),
            "{}: step 2's outputs on",
            case.label
        );
        assert!(
            scans.iter().all(|s| !s.outputs[step_3]),
            "{}: step 3 fired without a press",
            case.label
        );
    }
}
