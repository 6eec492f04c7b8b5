use super::*;
use crate::actuator::Valves;
use crate::cell::Sign;
use crate::names::{KEYWORDS, reserved_name, signal_problem};
use crate::program::{Alarm, ProgramOptions};
use crate::stroke::Strokes;

fn table(csv: &str) -> StepTable {
    let rows: Vec<Vec<&str>> = csv.lines().map(|l| l.split(',').collect()).collect();
    crate::table::from_rows("t.csv", &rows).expect("a valid table")
}

fn symbols(table: &StepTable, naming: &Naming) -> SymbolTable {
    let program = crate::program::build(
        table,
        &ProgramOptions::default(),
        &Valves::default(),
        &Strokes::default(),
    );
    SymbolTable::build(&program, table, naming)
}

fn named(scheme: Scheme, names: &[(u32, &str)]) -> Naming {
    Naming {
        scheme,
        actuators: names
            .iter()
            .map(|(n, text)| {
                (
                    *n,
                    ActuatorName {
                        text: text.to_string(),
                        at: crate::diag::Location {
                            file: "t.xlsx".to_string(),
                            sheet: Some("SETTINGS".to_string()),
                            cell: Some(crate::diag::CellPos::new(*n, 0)),
                        },
                    },
                )
            })
            .collect(),
    }
}

#[test]
fn paper_identifiers_are_unambiguous() {
    let a = Signal::Sensor {
        actuator: 1,
        position: 23,
    };
    let b = Signal::Sensor {
        actuator: 12,
        position: 3,
    };
    assert_ne!(paper_ident(a), paper_ident(b));
    let minus = Signal::Coil {
        actuator: 2,
        sign: Sign::Minus,
    };
    assert_eq!(paper_ident(minus), "y2m");
    assert_eq!(minus.symbol(), "y2-");
}

#[test]
fn every_generated_identifier_is_legal_in_every_target_language() {
    let signals = [
        Signal::Start,
        Signal::Sensor {
            actuator: 999,
            position: 63,
        },
        Signal::Sensor {
            actuator: 9,
            position: 9,
        },
        Signal::Coil {
            actuator: 999,
            sign: Sign::Plus,
        },
        Signal::Coil {
            actuator: 1,
            sign: Sign::Minus,
        },
        Signal::StopAt {
            actuator: 999,
            position: 62,
        },
        Signal::StartMemory,
        Signal::Halt,
        Signal::Alarm(Alarm::Sensor),
        Signal::Alarm(Alarm::Timeout),
        Signal::Alarm(Alarm::Interlock),
        Signal::Watchdog,
        Signal::WatchdogArmed,
        Signal::Dwell(255),
        Signal::DwellArmed(255),
        Signal::RunOn(255),
        Signal::RunOnArmed(255),
        Signal::InterlockZone(255),
        Signal::Continuous,
        Signal::Stop,
        Signal::EStop,
        Signal::Reset,
        Signal::StepMode,
        Signal::StepButton,
        Signal::StepPermit,
        Signal::StepMemory,
        Signal::ResetMemory,
        Signal::CycleRequest,
        Signal::Busy,
        Signal::AutoRun,
        Signal::Homing,
        Signal::HomeStage(999),
    ];
    for signal in signals {
        let id = paper_ident(signal);
        assert_eq!(check::identifier_problem(&id), None, "{id}");
        // 9 characters: FST's symbolic operands; STEP 7 allows 24.
        assert!(id.len() <= 9, "{id} is longer than 9 characters");
        assert!(
            !KEYWORDS.contains(&id.to_ascii_uppercase().as_str()),
            "{id} is a keyword"
        );
        // No table may name a machine signal like one of the program's
        // own; the mode buttons' names are taken only while their mode is
        // on, and then in any case.
        if matches!(
            signal,
            Signal::Continuous
                | Signal::Stop
                | Signal::EStop
                | Signal::Reset
                | Signal::StepMode
                | Signal::StepButton
        ) {
            let buttons: Vec<String> =
                crate::program::Modes::parse("continuous,stop,estop,reset,step")
                    .unwrap()
                    .buttons()
                    .map(|b| b.symbol().to_ascii_lowercase())
                    .collect();
            assert!(signal_problem(&id, &buttons, true).is_some(), "{id}");
            assert!(signal_problem(&id, &[], true).is_none(), "{id}");
            continue;
        }
        assert!(
            reserved_name(&id.to_ascii_lowercase()).is_some(),
            "{id} is not reserved"
        );
    }
}

#[test]
fn the_paper_scheme_keeps_todays_names() {
    let t = table("C1+1\nC2+3\nC2-0\nC1-0");
    let s = symbols(&t, &Naming::default());
    let x21 = Signal::Sensor {
        actuator: 2,
        position: 1,
    };
    assert_eq!(s.ident(x21), "x21");
    assert_eq!(s.designation(x21), "x21");
    assert_eq!(s.comment(x21), "cylinder 2, middle position 1");
    let y1m = Signal::Coil {
        actuator: 1,
        sign: Sign::Minus,
    };
    assert_eq!((s.ident(y1m), s.fst(y1m)), ("y1m".into(), "y1m".into()));
    assert_eq!(s.designation(y1m), "y1-");
    assert_eq!(s.role(y1m), "coil");
    assert_eq!(s.actuator(1), "C1");
}

#[test]
fn iso_designates_sensors_home_end_then_middles_and_solenoids() {
    let t = table("C1+1\nC2+3\nC2-1\nC2+2\nC2-0\nC1-0");
    let s = symbols(&t, &named(Scheme::Iso, &[(2, "punch")]));
    let sensor = |position| Signal::Sensor {
        actuator: 2,
        position,
    };
    let designations: Vec<String> = (0..=3).map(|p| s.designation(sensor(p))).collect();
    assert_eq!(designations, ["2B1", "2B3", "2B4", "2B2"]);
    let coil = |sign| Signal::Coil { actuator: 2, sign };
    assert_eq!(s.designation(coil(Sign::Plus)), "2M1");
    assert_eq!(s.designation(coil(Sign::Minus)), "2M2");
    // Identifiers may not begin with a digit: they stay the paper's, and
    // the designation leads the comment.
    assert_eq!(s.ident(sensor(0)), "x20");
    assert_eq!(
        s.comment(sensor(0)),
        "2B1: cylinder 2A1 (punch), home position 0"
    );
    assert_eq!(s.actuator(2), "2A1 (punch)");
}

#[test]
fn the_engineers_names_become_identifiers() {
    let t = table("C1+1\nC2+3\nC2-1\nC2-0\nC1-0");
    let s = symbols(
        &t,
        &named(Scheme::Names, &[(1, "Clamp"), (2, "gripper arm")]),
    );
    let sensor = |actuator, position| Signal::Sensor { actuator, position };
    assert_eq!(s.ident(sensor(1, 0)), "clamp_home");
    assert_eq!(s.ident(sensor(1, 1)), "clamp_end");
    assert_eq!(s.ident(sensor(2, 1)), "gripper_arm_pos1");
    assert_eq!(s.fst(sensor(2, 1)), "gripper_a");
    let out = Signal::Coil {
        actuator: 1,
        sign: Sign::Plus,
    };
    assert_eq!(s.ident(out), "clamp_out");
    assert_eq!(s.designation(out), "clamp_out");
    assert_eq!(s.comment(out), "cylinder 1 (Clamp), coil + (extend)");
    // Under the paper's scheme the name is only in the comments.
    let paper = symbols(&t, &named(Scheme::Paper, &[(1, "Clamp")]));
    assert_eq!(paper.ident(out), "y1p");
    assert_eq!(paper.comment(out), "cylinder 1 (Clamp), coil + (extend)");
    assert_eq!(
        paper.action_comment(crate::program::Action::Set(out), &[]),
        "y1+ on: extend C1 (Clamp)"
    );
}

#[test]
fn a_step_comment_reaches_the_step_title() {
    let rows = [
        vec!["", "BRANCH 1"],
        vec!["STEP 1 (clamp part)", "C1+1"],
        vec!["STEP 2", "C1-0"],
    ];
    let t = crate::table::from_rows("t.csv", &rows).expect("valid");
    let s = symbols(&t, &Naming::default());
    assert_eq!(
        s.step(0).map(|n| n.title.as_str()),
        Some("C1+1 (clamp part)")
    );
    assert_eq!(s.step(1).map(|n| n.title.as_str()), Some("C1-0"));
}

#[test]
fn name_stems() {
    assert_eq!(
        scheme::stem("Gripper  arm!"),
        Some("gripper_arm".to_string())
    );
    assert_eq!(scheme::stem("2nd clamp"), None);
    assert_eq!(scheme::stem("Greifer ü"), None);
    assert_eq!(scheme::stem("  "), None);
}

#[test]
fn explanations_speak_in_the_designations() {
    let t = table("C1+1\nC1-0");
    let names = symbols(&t, &named(Scheme::Names, &[(1, "clamp")]));
    assert_eq!(
        names.designate("C1+1 waits: C1 had not reached x11; y1+ on, x10 stuck"),
        "C1+1 waits: C1 had not reached clamp_end; clamp_out on, clamp_home stuck"
    );
    let paper = symbols(&t, &Naming::default());
    assert_eq!(paper.designate("x10 (y1-)"), "x10 (y1-)");
    let iso = symbols(&t, &named(Scheme::Iso, &[]));
    assert_eq!(iso.designate("x10 (y1-), x100"), "1B1 (1M2), x100");
}

#[test]
fn findings_name_the_engineers_actuators() {
    let t = table("C1+1, C2+1\nC1-0, C2-0");
    let finding = "C1+1 waits: C1 had not reached x11; C2 ran through x21";
    // Under every scheme a named actuator is said with its name; a move
    // (`C1+1`) stays the table's notation, an unnamed actuator its label.
    let paper = symbols(&t, &named(Scheme::Paper, &[(1, "clamp")]));
    assert_eq!(
        paper.explain(finding),
        "C1+1 waits: C1 (clamp) had not reached x11; C2 ran through x21"
    );
    let iso = symbols(&t, &named(Scheme::Iso, &[(1, "clamp")]));
    assert_eq!(
        iso.explain(finding),
        "C1+1 waits: 1A1 (clamp) had not reached 1B2; 2A1 ran through 2B2"
    );
    let none = symbols(&t, &Naming::default());
    assert_eq!(none.explain(finding), finding);
}

#[test]
fn a_long_name_is_cut_in_findings_and_kept_whole_in_the_lists() {
    let t = table("C1+1\nC1-0");
    let long = format!("clamp {}", "and then some more words ".repeat(4));
    let long = long.trim_end();
    let names = symbols(&t, &named(Scheme::Paper, &[(1, long)]));
    let said = names.explain("C1 had not reached x11; C1 ran on");
    let cut = format!("{}...", &long[..FINDING_NAME - 3]);
    assert_eq!(
        said,
        format!("C1 ({cut}) had not reached x11; C1 ({cut}) ran on")
    );
    // The lists and comments keep the whole name.
    assert_eq!(names.actuator(1), format!("C1 ({long})"));
    // A name that fits is said whole.
    let short = symbols(&t, &named(Scheme::Paper, &[(1, &long[..FINDING_NAME])]));
    assert!(
        short
            .explain("C1")
            .ends_with(&format!("{})", &long[..FINDING_NAME]))
    );
}

#[test]
fn a_signal_before_a_colon_is_designated_and_a_machine_name_kept() {
    let words = |t: &str| match t {
        "x31" => Some("belt_end"),
        "I:x31" => Some("never"),
        _ => None,
    };
    assert_eq!(
        super::comment::map_words("short of x31: C3 runs, I:part", words),
        "short of belt_end: C3 runs, I:part"
    );
}
