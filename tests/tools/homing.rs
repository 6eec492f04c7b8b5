//! RESET's default homing order in the engines: a stamping station (clamp
//! C1, punch C2 with a dwell, ejector C3, feeder C4) is stopped by the
//! EMERGENCY STOP while the punch is down, then RESET: the written program
//! lifts the punch before it opens the clamp, in matiec (iec), awlsim
//! (siemens) and the FST interpreter (festo), scan for scan as simulated.
//! And homing under the watchdog: a dead home switch halts the homing and
//! cuts the drive, a guard on a range of steps halts it, and a
//! pressurised-centre valve rests home on its `-` coil; a run-on runs its
//! time out through RESET.

use steptable::simulate::Operator;

use crate::engines::{self, awlsim};
use crate::{Check, Tool, tool};

pub const CHECKS: &[Check] = &[
    Check::new(
        "homing::reset_lifts_the_punch_before_it_opens_the_clamp_in_every_engine",
        &[Tool::Shared, Tool::Awlsim],
        reset_lifts_the_punch_before_it_opens_the_clamp_in_every_engine,
    ),
    Check::new(
        "homing::a_dead_home_switch_halts_the_homing_in_every_engine",
        &[Tool::Shared, Tool::Awlsim],
        a_dead_home_switch_halts_the_homing_in_every_engine,
    ),
];

const STAMPING: &str = ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C2+1\nSTEP 3,T=2s\nSTEP 4,C2-0\nSTEP 5,C1-0\nSTEP 6,C3+1\nSTEP 7,C3-0\nSTEP 8,C4+1\nSTEP 9,C4-0\n";

/// C1 out, C2 out and back, C1 back.
const FOUR: &[&[&str]] = &[
    &["", "BRANCH 1"],
    &["STEP 1", "C1+1"],
    &["STEP 2", "C2+1"],
    &["STEP 3", "C2-0"],
    &["STEP 4", "C1-0"],
];

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

/// An input, its name, the options beyond the modes, and its events.
type Run<'a> = (
    &'a std::path::Path,
    &'a str,
    &'a [&'a str],
    &'a [(&'a str, &'a str)],
);

/// The car wash's gantry (a drive) stopped by the EMERGENCY STOP, its home
/// switch dead, RESET: with the watchdog the homing stage runs out of
/// time, `alarm_wd` comes on and the reverse contactor goes off, in every
/// engine as simulated. The four-step table with a guard on steps 2-3 and
/// a 53pressure C1: the guard opening as RESET homes halts the homing, and
/// C1's `-` coil holds it home from power-up.
fn a_dead_home_switch_halts_the_homing_in_every_engine() {
    let dir = tempfile::tempdir().unwrap();
    let python = awlsim::python(&tool(Tool::Awlsim));
    let carwash = crate::helpers::sample("carwash.xlsx");
    let dead: [(&str, &str); 4] = [
        ("press", "START@0.5s"),
        ("press", "ESTOP@step2"),
        ("stick", "x10=0@+1s"),
        ("press", "RESET@+1s"),
    ];
    let guarded = dir.path().join("guarded.xlsx");
    crate::helpers::write_xlsx_sheets(
        &guarded,
        &[
            ("TABLE", FOUR),
            (
                "SETTINGS",
                &[
                    &["interlock", "guard in steps 2-3"],
                    &["actuator", "valve"],
                    &["C1", "53pressure"],
                    &["C2", "53closed"],
                ],
            ),
        ],
    );
    let opening: [(&str, &str); 4] = [
        ("press", "START@0.5s"),
        ("press", "ESTOP@step2"),
        ("press", "RESET@+1s"),
        ("stick", "guard=0@+0.3s"),
    ];
    let mut compared = 0;
    for (target, format) in [("iec", "st"), ("siemens", "awl"), ("festo", "fst")] {
        let runs: [Run; 2] = [
            (&carwash, "carwash", &["--safety", "watchdog"], &dead),
            (&guarded, "guarded", &["--safety", "watchdog"], &opening),
        ];
        for (input, stem, extra, events) in runs {
            let mut args = vec!["--target", target, "--modes", "estop,reset"];
            args.extend_from_slice(extra);
            let out = dir.path().join(format!("{stem}-{format}"));
            let (case, report) =
                engines::convert_and_record(input, &out, stem, &args, format, events);
            let outputs = engines::run_written(&case, format, &python);
            case.check(format, outputs).unwrap();
            let last = report.samples.last().unwrap();
            assert!(last.homing, "{}: the homing never ends", case.label);
            let on: Vec<String> = last.outputs_on.iter().map(|s| s.symbol()).collect();
            let alarm = if stem == "carwash" {
                "alarm_wd"
            } else {
                "alarm_il"
            };
            assert!(on.iter().any(|s| s == alarm), "{}: {on:?}", case.label);
            if stem == "carwash" {
                assert!(
                    !on.iter().any(|s| s == "y1-"),
                    "{}: the drive runs: {on:?}",
                    case.label
                );
            } else {
                // C1 rests home from power-up on its - coil.
                let first = &case.trace.scans[0];
                let y1m = case
                    .trace
                    .signals
                    .outputs
                    .iter()
                    .position(|s| s.symbol() == "y1-");
                assert!(
                    first.outputs[y1m.unwrap()],
                    "{}: y1- off at power-up",
                    case.label
                );
            }
            compared += 1;
        }
    }
    // A drive homed in one stage with a slower cylinder is cut at its own
    // home switch, long before the stage is done.
    let shared = dir.path().join("shared.xlsx");
    crate::helpers::write_xlsx_sheets(
        &shared,
        &[
            ("TABLE", FOUR),
            (
                "SETTINGS",
                &[
                    &["home order", "C1 C2"],
                    &["actuator", "valve", "extend", "retract"],
                    &["C1", "motor", "1s", "1s"],
                    &["C2", "53closed", "1s", "4s"],
                ],
            ),
        ],
    );
    let events: [(&str, &str); 3] = [
        ("press", "START@0.5s"),
        ("press", "ESTOP@step3"),
        ("press", "RESET@+1s"),
    ];
    for (target, format) in [("iec", "st"), ("siemens", "awl"), ("festo", "fst")] {
        let args = ["--target", target, "--modes", "estop,reset"];
        let out = dir.path().join(format!("shared-{format}"));
        let (case, _) =
            engines::convert_and_record(&shared, &out, "shared", &args, format, &events);
        let outputs = engines::run_written(&case, format, &python);
        case.check(format, outputs).unwrap();
        let signals = &case.trace.signals;
        let x10 = signals
            .inputs
            .iter()
            .position(|s| s.symbol() == "x10")
            .unwrap();
        let x20 = signals
            .inputs
            .iter()
            .position(|s| s.symbol() == "x20")
            .unwrap();
        let y1m = signals
            .outputs
            .iter()
            .position(|s| s.symbol() == "y1-")
            .unwrap();
        let driving_home = case
            .trace
            .scans
            .iter()
            .filter(|s| s.inputs[x10] && !s.inputs[x20] && s.outputs[y1m])
            .count();
        assert!(
            driving_home <= 1,
            "{}: C1 driven into its end stop for {driving_home} scans",
            case.label
        );
        compared += 1;
    }
    // The oven's fan runs its 20 s out through a RESET pressed 2 s after
    // STOP (its ADDRESSES sheet pins S7 addresses: awlsim alone).
    let oven = crate::helpers::sample("oven.xlsx");
    let events: [(&str, &str); 3] = [
        ("press", "START@0.5s"),
        ("press", "STOP@+12s"),
        ("press", "RESET@+2s"),
    ];
    let args = ["--target", "siemens", "--modes", "stop,reset"];
    let out = dir.path().join("oven-awl");
    let (case, _) = engines::convert_and_record(&oven, &out, "oven", &args, "awl", &events);
    let outputs = engines::run_written(&case, "awl", &python);
    case.check("awl", outputs).unwrap();
    let fan = case
        .trace
        .signals
        .outputs
        .iter()
        .position(|s| s.symbol() == "fan");
    let fan = fan.expect("the oven has a fan");
    let on_at = |ms: u64| {
        let scan = case.trace.scans.iter().find(|s| s.time_ms >= ms).unwrap();
        scan.outputs[fan]
    };
    assert!(
        on_at(20_000) && !on_at(33_000),
        "{}: the fan's run-on",
        case.label
    );
    eprintln!(
        "homing: {compared} runs (a dead home switch under the watchdog, a range guard opening while RESET homes; matiec, awlsim, FST interpreter) halt the homing as simulated; the oven's fan runs on through RESET in awlsim"
    );
}
