//! Single-step mode (`--modes step`) in simulation: with the STEP_MODE
//! switch on, the paper's example fires at most one step per STEP_PB press,
//! only a step whose conditions hold at the press; off, it runs as before.
//! The hostile inputs of the mode, through the binary, are at the end.

use steptable::program::StepProgram;
use steptable::simulate::scenario::{ScenarioReport, scenario};
use steptable::simulate::{Operator, SimSettings};
use steptable::table::StepTable;

use crate::helpers::{Build, Refused, assert_refused, steptable, write_xlsx_sheets};

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

fn paper_with(modes: &str) -> (StepTable, StepProgram) {
    let build = Build::paper().modes(modes);
    let program = build.program();
    (build.table, program)
}

/// STEP_PB held from `at` for `hold_ms`, over `base`.
fn press(at: u64, hold_ms: u64, base: Operator) -> [(u64, Operator); 2] {
    [(at, Operator { step: true, ..base }), (at + hold_ms, base)]
}

fn run(table: &StepTable, program: &StepProgram, script: &[(u64, Operator)]) -> ScenarioReport {
    let mut script = script.to_vec();
    script.sort_by_key(|(t, _)| *t);
    scenario(table, program, &SimSettings::default(), &script, 22_000)
}

/// START, then nine presses: one while C1 is still moving (nothing may
/// fire, and the press is not remembered), one held for three seconds (one
/// step only), then one every two seconds.
#[test]
fn each_step_press_fires_exactly_one_step_and_only_when_its_conditions_hold() {
    let (table, program) = paper_with("step");
    let mut script = vec![(0, STEPPING)];
    script.extend([
        (
            500,
            Operator {
                start: true,
                ..STEPPING
            },
        ),
        (600, STEPPING),
    ]);
    let presses: [(u64, u64); 9] = [
        (1_000, 100),
        (1_300, 100),
        (3_000, 3_000),
        (7_000, 100),
        (9_000, 100),
        (11_000, 100),
        (13_000, 100),
        (15_000, 100),
        (17_000, 100),
    ];
    for (at, hold) in presses {
        script.extend(press(at, hold, STEPPING));
    }
    let report = run(&table, &program, &script);
    assert!(report.problems.is_empty(), "{:?}", report.problems);
    // START alone fires nothing: step 1 waits for the first press.
    let fired_in = |from: u64, to: u64| -> Vec<usize> {
        report
            .fired
            .iter()
            .filter(|(t, _)| (from..to).contains(t))
            .map(|(_, step)| *step)
            .collect()
    };
    assert_eq!(
        fired_in(0, 1_000),
        Vec::<usize>::new(),
        "{:?}",
        report.fired
    );
    assert_eq!(fired_in(1_000, 1_100), [1], "{:?}", report.fired);
    // C1 reaches x11 about 1 s after step 1: the press at 1.3 s finds step
    // 2's condition unmet and fires nothing, then or later.
    assert_eq!(
        fired_in(1_100, 3_000),
        Vec::<usize>::new(),
        "{:?}",
        report.fired
    );
    // Held for 3 s: step 2 fires, step 3's condition (x23) comes true while
    // the button is still held, and step 3 waits for the next press.
    assert_eq!(fired_in(3_000, 7_000), [2], "{:?}", report.fired);
    for (number, at) in (3..=8).zip([7_000, 9_000, 11_000, 13_000, 15_000, 17_000]) {
        assert_eq!(fired_in(at, at + 100), [number], "{:?}", report.fired);
        let later = fired_in(at + 100, at + 2_000);
        // Only the closing transition may follow step 8 without a press.
        assert!(later.iter().all(|s| *s == 9), "{:?}", report.fired);
    }
    // The closing transition moves nothing: it needs no press.
    let last = report.fired.last().unwrap();
    assert_eq!(last.1, 9, "{:?}", report.fired);
    let end = report.samples.last().unwrap();
    assert_eq!(end.step, 0);
    assert!(end.positions.iter().all(|p| p.abs() < 0.05), "{end:?}");
}

/// The switch off mid-cycle: the rest of the cycle runs by itself, step
/// for step as the automatic run of the same program does.
#[test]
fn switching_single_step_off_runs_the_rest_of_the_cycle() {
    let (table, program) = paper_with("step");
    let auto = Operator {
        step_mode: false,
        ..STEPPING
    };
    let mut script = vec![(0, STEPPING)];
    script.extend([
        (
            500,
            Operator {
                start: true,
                ..STEPPING
            },
        ),
        (600, STEPPING),
    ]);
    script.extend(press(1_000, 100, STEPPING));
    script.push((3_000, auto));
    let report = run(&table, &program, &script);
    assert!(report.problems.is_empty(), "{:?}", report.problems);
    let steps: Vec<usize> = report.fired.iter().map(|(_, s)| *s).collect();
    assert_eq!(steps, [1, 2, 3, 4, 5, 6, 7, 8, 9]);
    // Step 2 fires the scan after the switch goes off (x11 has long been on).
    assert!(
        (3_000..3_030).contains(&report.fired[1].0),
        "{:?}",
        report.fired
    );
}

/// With the switch off, single-step mode changes nothing: the steps fire
/// at the same scans as in the program without it.
#[test]
fn with_the_switch_off_the_cycle_is_that_of_automatic() {
    let (table, stepping) = paper_with("step,stop");
    let (_, plain) = paper_with("stop");
    let script = [
        (0, Operator::default()),
        (
            500,
            Operator {
                start: true,
                ..Operator::default()
            },
        ),
        (600, Operator::default()),
    ];
    let a = run(&table, &stepping, &script);
    let b = run(&table, &plain, &script);
    assert_eq!(a.fired.len(), 9);
    assert_eq!(a.fired, b.fired);
}

const CASES: &[Refused] = &[
    Refused {
        what: "a machine input named like the STEP button",
        table: &[&["C1+1"], &["I:step_pb"], &["C1-0"]],
        settings: &[],
        args: &["--modes", "step"],
        code_at: "TABLE!A2: error[E015]",
    },
    Refused {
        what: "a machine output named like the STEP_MODE switch, in another case",
        table: &[&["C1+1"], &["Y:Step_Mode+"], &["C1-0; Y:Step_Mode-"]],
        settings: &[],
        args: &["--modes", "step"],
        code_at: "TABLE!A2: error[E015]",
    },
    Refused {
        what: "a name Festo FST cuts to STEP_MODE (its 9 characters), an FST file written",
        table: &[&["C1+1"], &["I:step_modex"], &["C1-0"]],
        settings: &[],
        args: &["--modes", "step", "--formats", "st,fst"],
        code_at: "TABLE!A2: error[E015]",
    },
    Refused {
        what: "the STEP button's name, the mode asked for on SETTINGS",
        table: &[&["C1+1"], &["I:STEP_PB"], &["C1-0"]],
        settings: &[&["modes", "step"]],
        args: &[],
        code_at: "TABLE!A2: error[E015]",
    },
    Refused {
        what: "a machine input named like the step permit memory, in any mode",
        table: &[&["C1+1"], &["I:step_ok"], &["C1-0"]],
        settings: &[],
        args: &[],
        code_at: "TABLE!A2: error[E015]",
    },
    Refused {
        what: "a machine input named like the STEP button's edge memory",
        table: &[&["C1+1"], &["I:Step_Mem"], &["C1-0"]],
        settings: &[],
        args: &["--modes", "step"],
        code_at: "TABLE!A2: error[E015]",
    },
    Refused {
        what: "an interlock input named like the STEP button",
        table: &[&["C1+1"], &["C1-0"]],
        settings: &[&["modes", "step"], &["interlock", "step_pb"]],
        args: &[],
        code_at: "SETTINGS!B2: error[E015]",
    },
    Refused {
        what: "the mode given twice on SETTINGS",
        table: &[&["C1+1"], &["C1-0"]],
        settings: &[&["modes", "step, step"]],
        args: &[],
        code_at: "SETTINGS!B1: error[",
    },
    Refused {
        what: "the mode misspelt on SETTINGS",
        table: &[&["C1+1"], &["C1-0"]],
        settings: &[&["modes", "single step"]],
        args: &[],
        code_at: "SETTINGS!B1: error[",
    },
    Refused {
        what: "the mode beside all on SETTINGS",
        table: &[&["C1+1"], &["C1-0"]],
        settings: &[&["modes", "all, step"]],
        args: &[],
        code_at: "SETTINGS!B1: error[",
    },
    Refused {
        what: "the mode given twice on the command line",
        table: &[&["C1+1"], &["C1-0"]],
        settings: &[],
        args: &["--modes", "step,step"],
        code_at: "\"step\" is given twice",
    },
    Refused {
        what: "the mode beside all on the command line",
        table: &[&["C1+1"], &["C1-0"]],
        settings: &[],
        args: &["--modes", "all,step"],
        code_at: "\"all\" stands alone",
    },
];

/// Each row through the binary: exit 1, its code at its cell, nothing
/// written.
#[test]
fn hostile_single_step_inputs_are_refused_with_their_cell() {
    assert_refused(CASES);
}

/// The buttons' names are free for a machine signal without the mode.
#[test]
fn the_step_buttons_names_are_taken_only_with_the_mode() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("free.xlsx");
    let table: &[&[&str]] = &[&["C1+1"], &["I:step_pb"], &["C1-0"]];
    write_xlsx_sheets(&path, &[("TABLE", table)]);
    steptable().arg("check").arg(&path).assert().success();
}

/// The fault table classifies the mode's inputs: a STEP_MODE stuck at 1
/// stalls safely (no step without a press); the other three show no
/// effect in automatic, the broken switch wire (stuck at 0) among them,
/// which the guide says no check can catch.
#[test]
fn the_fault_table_classifies_the_step_inputs() {
    use steptable::faults::Outcome;
    use steptable::program::Signal;
    let table = Build::paper().modes("step").faults();
    let outcome = |signal: Signal, stuck_at: bool| {
        let case = table.cases.iter().find(|c| {
            c.faults.len() == 1 && c.faults[0].signal == signal && c.faults[0].stuck_at == stuck_at
        });
        case.unwrap_or_else(|| panic!("{signal:?} stuck at {stuck_at} is a case"))
            .outcome
    };
    assert_eq!(outcome(Signal::StepMode, true), Outcome::SafeStall);
    assert_eq!(outcome(Signal::StepMode, false), Outcome::NoEffect);
    // A shorted STEP_PB reads as one press in single step: the step the
    // sequence waits at fires without the operator's press.
    assert_eq!(outcome(Signal::StepButton, true), Outcome::Hazard);
    let short = table.cases.iter().find(|c| {
        c.faults.len() == 1 && c.faults[0].signal == Signal::StepButton && c.faults[0].stuck_at
    });
    let explanation = &short.unwrap().explanation;
    assert!(
        explanation.contains("step 1 fired in single step without a STEP_PB press"),
        "{explanation}"
    );
    assert_eq!(outcome(Signal::StepButton, false), Outcome::NoEffect);
}

/// Every path of the sorting station (its jumps on `I:reject` and
/// `I:no_label`) still runs with the mode, the switch off: the proof of
/// `simulate` passes.
#[test]
fn the_sorting_stations_paths_run_with_the_mode() {
    steptable()
        .arg("simulate")
        .arg(crate::helpers::sample("sorting_station.xlsx"))
        .args(["--modes", "step"])
        .assert()
        .success();
}

/// The guide's worked examples of the operating modes (continuous with
/// the buttons, single step, manual) are what `simulate` prints, line for
/// line (each command as the guide writes it, on the sample).
#[test]
fn the_guides_worked_examples_are_what_simulate_prints() {
    let guide = std::fs::read_to_string(crate::helpers::root().join("docs/guide.md")).unwrap();
    let start = "$ steptable simulate paper_example.xlsx --modes ";
    let mut examples = 0;
    for (at, _) in guide.match_indices(start) {
        let block: Vec<&str> = guide[at..]
            .lines()
            .take_while(|l| !l.starts_with("```"))
            .collect();
        let command_lines = block.iter().take_while(|l| l.ends_with('\\')).count() + 1;
        let command: String = block[..command_lines]
            .iter()
            .map(|l| l.trim_end_matches('\\'))
            .collect::<Vec<_>>()
            .join(" ");
        let args: Vec<&str> = command.split_whitespace().skip(4).collect();
        let run = steptable()
            .arg("simulate")
            .arg(crate::helpers::sample("paper_example.xlsx"))
            .args(&args)
            .assert()
            .success();
        let out = String::from_utf8_lossy(&run.get_output().stdout).into_owned();
        let printed: Vec<&str> = out.lines().skip(1).collect();
        assert!(
            elided_match(&block[command_lines..], &printed),
            "{command}: the guide says\n{}\nsimulate prints\n{out}",
            block[command_lines..].join("\n")
        );
        examples += 1;
    }
    assert_eq!(
        examples, 3,
        "continuous with the buttons, single step, manual"
    );
}

/// Whether `printed` is `written` where a line `…` of the guide stands for
/// any number of printed lines.
fn elided_match(written: &[&str], printed: &[&str]) -> bool {
    match written.split_first() {
        None => printed.is_empty(),
        Some((line, rest)) if line.trim() == "…" => {
            (0..=printed.len()).any(|skip| elided_match(rest, &printed[skip..]))
        }
        Some((line, rest)) => printed.first() == Some(line) && elided_match(rest, &printed[1..]),
    }
}

/// The last line and every `problem:` line `simulate` prints.
fn simulated(args: &[&str]) -> (String, Vec<String>) {
    let paper = crate::helpers::sample("paper_example.csv");
    let run = steptable().arg("simulate").arg(&paper).args(args).assert();
    let stdout = String::from_utf8_lossy(&run.get_output().stdout).into_owned();
    let problems = stdout
        .lines()
        .filter(|l| l.contains("problem:"))
        .map(str::to_string)
        .collect();
    (
        stdout.lines().last().unwrap_or_default().to_string(),
        problems,
    )
}

/// A START that cannot start the cycle now is forgotten (red team rt7,
/// finding 3): pressed in single step, it does not start the cycle when
/// the switch goes off a minute later; refused by the precheck, it does
/// not start it when the sensor is repaired. In single step it still waits
/// for the first STEP_PB press, and START held through the refusal asks
/// again.
#[test]
fn a_start_that_cannot_start_the_cycle_is_forgotten() {
    let forgotten: [&[&str]; 3] = [
        &[
            "--modes",
            "all",
            "--hold",
            "STEP_MODE@0s",
            "--press",
            "START@0.5s",
            "--release",
            "STEP_MODE@60s",
        ],
        &[
            "--modes",
            "stop",
            "--safety",
            "precheck",
            "--stick",
            "x11=1@0s",
            "--press",
            "START@0.5s",
            "--stick",
            "x11=0@60s",
        ],
        // Single step and a press the precheck refuses: forgotten too.
        &[
            "--modes",
            "step",
            "--safety",
            "precheck",
            "--hold",
            "STEP_MODE@0s",
            "--stick",
            "x11=1@0s",
            "--press",
            "START@0.5s",
            "--press",
            "STEP@1s",
            "--stick",
            "x11=0@30s",
            "--press",
            "STEP@31s",
        ],
    ];
    for args in forgotten {
        let (end, problems) = simulated(args);
        assert!(
            end.contains("in step 0") && end.contains("C1 at 0.00") && problems.is_empty(),
            "{args:?}: {end} {problems:?}"
        );
    }
    let started: [&[&str]; 2] = [
        &[
            "--modes",
            "step",
            "--hold",
            "STEP_MODE@0s",
            "--press",
            "START@0.5s",
            "--press",
            "STEP@20s",
        ],
        &[
            "--modes",
            "stop",
            "--safety",
            "precheck",
            "--stick",
            "x11=1@0s",
            "--hold",
            "START@0.5s",
            "--stick",
            "x11=0@3s",
            "--release",
            "START@4s",
        ],
    ];
    for args in started {
        let (end, problems) = simulated(args);
        assert!(
            end.contains("C1 at 1.00") && problems.is_empty(),
            "{args:?}: {end} {problems:?}"
        );
    }
}

/// A shorted STEP_PB in single step fires one step, no more, and the run
/// says so as the hazard it is (red team rt7, finding 6): not "no START".
#[test]
fn a_shorted_step_button_fires_one_step_and_is_a_problem() {
    let (end, problems) = simulated(&[
        "--modes",
        "step",
        "--hold",
        "STEP_MODE@0s",
        "--press",
        "START@0.5s",
        "--press",
        "STEP@1s",
        "--press",
        "STEP@2.5s",
        "--press",
        "STEP@4s",
        "--stick",
        "STEP_PB=1@6s",
    ]);
    assert!(end.contains("in step 4"), "{end}");
    assert_eq!(problems.len(), 1, "{problems:?}");
    assert!(
        problems[0].contains("step 4 fired in single step without a STEP_PB press"),
        "{problems:?}"
    );
    let (_, problems) = simulated(&[
        "--modes",
        "step",
        "--hold",
        "STEP_MODE@0s",
        "--press",
        "START@0.5s",
        "--stick",
        "STEP_PB=1@1s",
    ]);
    assert!(
        problems.len() == 1
            && problems[0].contains("step 1 fired in single step without a STEP_PB press"),
        "{problems:?}"
    );
}
