//! The fifth round of hostile input: what the fourth round's red teams
//! left open and the fifth found. A retry jump into its own step with a
//! dwell (every Ladder body draws it, the SFC chart refuses it: E048), a
//! jump's item said twice in the titles of the bodies that head a
//! transition with its step's cell, follow-up errors of a refused cell,
//! a RESET held as the EMERGENCY STOP is released, and a start permissive
//! whose return restarted continuous operation. Each row goes through the
//! binary: its exit code, each code at its cell, and what was written.

use crate::helpers::{convert_csv, files_below, root};

/// A retry into step 2, which only waits: the jump restarts its dwell.
const RETRY: &str = ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,T=1s; J:2 if I:r\nSTEP 3,C1-0\n";

/// Every Ladder body draws the retry (it was an internal error, exit 2):
/// the timer's restart on a rung of its own, after the one that sets
/// `fired`, with the same contacts but `fired` on (the engines prove it
/// runs as simulated: `tests/tools/ladder.rs`). The same table with the
/// jump's condition negated, and under `--modes all --safety all`.
#[test]
fn a_retry_into_a_step_with_a_dwell_is_drawn_in_ladder() {
    let tables = [RETRY.to_string(), RETRY.replace("I:r", "I:r=0")];
    let option_sets: [&[&str]; 2] = [&[], &["--modes", "all", "--safety", "all"]];
    for table in &tables {
        for options in option_sets {
            let mut args = options.to_vec();
            args.extend(["--formats", "ld,codesys-ld,beremiz-ld"]);
            let (_dir, out, _) = convert_csv(table, &args, 0);
            let written = files_below(&out);
            assert_eq!(written.len(), 4, "{table} {options:?}: {written:?}");
            let ld = std::fs::read_to_string(out.join("t/t.ld.xml")).unwrap();
            assert!(
                ld.contains("STEP 2: J:2 if I:r")
                    && ld.contains("in place of STEP 3: restarts its timer (the rung above fired)"),
                "{table} {options:?}: no restart rung"
            );
        }
    }
}

/// A jump's rung, network or comment is headed `STEP 3: J:6 if I:reject:
/// on to STEP 6 …`, not with the step's cell, which names the jump already
/// (`STEP 3: C2-0; J:6 if I:reject; J:6 if I:reject: on to …`): in AWL,
/// L5X and every Ladder body of the sorting station.
#[test]
fn a_jump_is_named_once_in_its_title() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    crate::helpers::steptable()
        .arg("convert")
        .arg(root().join("samples/sorting_station.xlsx"))
        .args(["--formats", "awl,l5x,ld,codesys-ld,beremiz-ld", "-o"])
        .arg(&out)
        .assert()
        .code(0);
    // The Beremiz project's `beremiz.xml` holds no program.
    let files: Vec<_> = files_below(&out)
        .into_iter()
        .filter(|f| !f.ends_with("beremiz.xml"))
        .collect();
    assert_eq!(files.len(), 5, "{files:?}");
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap();
        assert!(
            text.contains("STEP 3: J:6 if I:reject: on to STEP 6 in place of STEP 4"),
            "{}: no jump title",
            file.display()
        );
        assert!(
            !text.contains("J:6 if I:reject; J:6 if I:reject"),
            "{}: the jump said twice",
            file.display()
        );
    }
}

/// A refused cell makes no second error in the cells that are only wrong
/// because of it (docs/reference.md, E010): every actuator the refused
/// item names is left unknown from its step, not only the first (`C2+1,
/// C3+1`), whatever the spelling of the mistake (`C1~0`, `T=1s C1-0`, an
/// en dash read as Windows-1252), and so is a move in a cell outside the
/// table. Each row: its one error at its cell, and the advice it gives.
#[test]
fn a_refused_cell_makes_no_second_error() {
    let cases: [(&str, &str, &str, &str); 7] = [
        (
            "two moves split by a comma",
            ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,\"C2+1,C3+1\"\nSTEP 3,C2-0;C3-0\nSTEP 4,C1-0\n",
            "t.csv:3:2: error[E010]",
            "separate items with `;`, not `,`: C2+1; C3+1",
        ),
        (
            "two moves split by a space",
            ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C2+1 C3+1\nSTEP 3,C2-0;C3-0\nSTEP 4,C1-0\n",
            "t.csv:3:2: error[E010]",
            "separate items with `;`, not spaces: C2+1; C3+1",
        ),
        (
            "a tilde for the sign",
            ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C1~0\n",
            "t.csv:3:2: error[E010]",
            "\"C1~0\" is not a move",
        ),
        (
            "an equals sign for the sign",
            ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C1=0\n",
            "t.csv:3:2: error[E010]",
            "\"C1=0\" is not a move",
        ),
        (
            "a dwell and a move without a separator",
            ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,T=1s C1-0\n",
            "t.csv:3:2: error[E014]",
            "\"T=1s C1-0\" is not a dwell",
        ),
        (
            "an en dash read as Windows-1252",
            ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C1\u{e2}\u{20ac}\u{201c}0\n",
            "t.csv:3:2: error[E010]",
            "is not a move",
        ),
        (
            "a move below the last step, unlabelled",
            ",BRANCH 1,BRANCH 2\nSTEP 1,C1+1,\nSTEP 2,C1-0,C2+1\n,,C2-0\n",
            "t.csv:4:3: error[E010]",
            "lies outside the table and would be lost",
        ),
    ];
    for (what, table, code_at, advice) in cases {
        let (_dir, out, assert) = convert_csv(table, &[], 1);
        let stderr = String::from_utf8_lossy(&assert.get_output().stderr).into_owned();
        let errors: Vec<&str> = stderr.lines().filter(|l| l.contains(": error[")).collect();
        assert_eq!(errors.len(), 1, "{what}: {stderr}");
        assert!(
            errors[0].contains(code_at) && errors[0].contains(advice),
            "{what}: {stderr}"
        );
        assert!(!out.exists(), "{what}: refused but wrote files");
    }
}

/// RESET acts on its press, not while held (EN 60204-1: releasing the
/// EMERGENCY STOP must not start motion by itself). A RESET held through
/// the release homes nothing; released and pressed again, it homes.
#[test]
fn releasing_the_emergency_stop_with_reset_held_starts_nothing() {
    let paper = root().join("samples/paper_example.xlsx");
    let run = |extra: &[&str]| {
        let mut args = vec![
            "--modes",
            "estop,reset",
            "--press",
            "START@0.5s",
            "--hold",
            "ESTOP@step3",
            "--hold",
            "RESET@+1s",
            "--release",
            "ESTOP@+5s",
        ];
        args.extend_from_slice(extra);
        let assert = crate::helpers::steptable()
            .arg("simulate")
            .arg(&paper)
            .args(&args)
            .assert()
            .code(0);
        crate::helpers::squeezed_stdout(&assert)
    };
    let held = run(&[]);
    assert!(!held.contains("homing starts"), "{held}");
    assert!(held.contains("ended at 16.96 s in step 3"), "{held}");
    let again = run(&["--release", "RESET@+1s", "--press", "RESET@+1s"]);
    assert!(again.contains("10.48 s homing starts"), "{again}");
    assert!(again.contains("in step 0 (at rest)"), "{again}");
}

/// A start permissive that goes off ends continuous operation: the air
/// coming back a minute later starts no cycle by itself; START does.
#[test]
fn a_start_permissive_coming_back_starts_no_cycle_by_itself() {
    let table = crate::hostile_round4::FOUR;
    let settings: &[&[&str]] = &[
        &["modes", "continuous, stop"],
        &["start permissive", "air_ok"],
    ];
    let base = [
        "--hold",
        "CONT@0s",
        "--press",
        "START@0.5s",
        "--stick",
        "air_ok=0@step2",
        "--stick",
        "air_ok=1@+60s",
    ];
    let (quiet, stderr, code) = crate::helpers::simulate_sheets(table, settings, &base);
    assert_eq!(code, Some(0), "{stderr}");
    let after: Vec<&str> = quiet
        .lines()
        .skip_while(|l| !l.contains("air_ok stuck at 1"))
        .collect();
    assert!(
        after.len() > 1 && !after.iter().any(|l| l.contains("step 1")),
        "{quiet}"
    );
    let mut pressed = base.to_vec();
    pressed.extend(["--press", "START@+1s"]);
    let (started, _, _) = crate::helpers::simulate_sheets(table, settings, &pressed);
    assert!(started.contains("62.51 s step 1"), "{started}");
}

/// The SFC chart of a retry into a step with a dwell would not restart
/// the dwell (its step stays active through the jump: the engine proof
/// found it), so any chart asked for is E048 at the jump's cell, and
/// nothing is written; a retry whose re-entry does nothing (the step only
/// waits) is drawn.
#[test]
fn a_chart_refuses_a_retry_that_restarts_its_step() {
    for formats in ["sfc", "beremiz-sfc", "codesys-sfc", "st,sfc", "all"] {
        let (_dir, out, assert) = convert_csv(RETRY, &["--formats", formats], 1);
        let stderr = String::from_utf8_lossy(&assert.get_output().stderr).into_owned();
        assert!(
            stderr.contains("t.csv:3:2: error[E048]: \"J:2 if I:r\" jumps back into its own step"),
            "{formats}: {stderr}"
        );
        assert!(!out.exists(), "{formats}: refused but wrote files");
    }
    // Without a chart, the same table converts.
    convert_csv(RETRY, &["--formats", "st,ld"], 0);
    let waits = ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,I:x; J:2 if I:r\nSTEP 3,C1-0\n";
    let (_dir, out, _) = convert_csv(waits, &["--formats", "sfc"], 0);
    assert!(out.join("t/t.sfc.xml").exists());
}

/// RESET homes in its order whatever the valve: a clamp on a
/// spring-return valve (`52mono`) homed after the drill keeps its coil on
/// until its stage, so the part is not released under the tool (its coil
/// cut by RESET itself was its move home, out of the order). The drilling
/// station homes C2, then C1, then C3 in the same time with either valve.
#[test]
fn reset_keeps_a_spring_return_clamp_closed_until_its_stage() {
    let drilling = root().join("samples/drilling_station.xlsx");
    let run = |extra: &[&str]| {
        let assert = crate::helpers::steptable()
            .arg("simulate")
            .arg(&drilling)
            .args(["--modes", "estop,reset", "--press", "START@0.5s"])
            .args(["--press", "RESET@2.3s"])
            .args(extra)
            .assert()
            .code(0);
        crate::helpers::squeezed_stdout(&assert)
    };
    let done = |said: &str| {
        said.lines()
            .find(|l| l.contains("homing done"))
            .map(str::to_string)
            .unwrap_or_else(|| panic!("{said}"))
    };
    let bistable = run(&[]);
    let spring = run(&["--valve", "C1=52mono"]);
    assert_eq!(done(&spring), done(&bistable), "{spring}");
    assert_eq!(done(&spring).trim(), "4.08 s homing done");
}

/// A guard that opens while RESET homes stops the homing drives, as the
/// guide says: the stage's `-` coil goes off and the closed-centre piston
/// stays where it was, rather than driving home behind the open guard.
#[test]
fn a_guard_opening_during_homing_stops_the_homing_drives() {
    let table = crate::hostile_round4::FOUR;
    let settings: &[&[&str]] = &[
        &["modes", "estop, reset"],
        &["interlock", "guard"],
        &["actuator", "valve"],
        &["C1", "53closed"],
        &["C2", "53closed"],
    ];
    let args = [
        "--press",
        "START@0.5s",
        "--press",
        "ESTOP@step3",
        "--press",
        "RESET@+0.5s",
        "--stick",
        "guard=0@+0.2s",
    ];
    let (said, stderr, code) = crate::helpers::simulate_sheets(table, settings, &args);
    assert_eq!(code, Some(0), "{stderr}");
    assert!(
        said.contains("homing starts") && !said.contains("homing done"),
        "{said}"
    );
    let end = crate::helpers::line_with(&said, "ended at");
    let c2: f64 = end
        .split("C2 at ")
        .nth(1)
        .and_then(|r| r.split([',', ';']).next())
        .and_then(|v| v.trim().parse().ok())
        .unwrap_or_else(|| panic!("{end}"));
    assert!(c2 > 0.5, "C2 drove home behind the open guard: {end}");
}
