//! Manual mode's safety promises, through the binary (red team rt7,
//! findings 1, 2, 4 and 5): STOP stops a jog; a 5/3 piston whose coil a
//! halt row holds stops at the middle position it was heading for when
//! the selector turns mid-stroke; RESET in manual homes nothing; a jog
//! button held or stuck as the selector turns moves nothing until every
//! jog button has read released.

use crate::helpers::{sample, steptable, write_xlsx_sheets};

/// The last line `simulate` prints (`ended at … ; C1 at 1.00, …; on: …`).
fn ended(path: &std::path::Path, args: &[&str]) -> String {
    let run = steptable().arg("simulate").arg(path).args(args).assert();
    let stdout = String::from_utf8_lossy(&run.get_output().stdout).into_owned();
    stdout.lines().last().unwrap_or_default().to_string()
}

/// The paper's example as a TABLE sheet with `settings`.
fn paper_with(dir: &std::path::Path, name: &str, settings: &[&[&str]]) -> std::path::PathBuf {
    let csv = std::fs::read_to_string(sample("paper_example.csv")).unwrap();
    let rows: Vec<Vec<&str>> = csv.lines().map(|l| l.split(',').collect()).collect();
    let rows: Vec<&[&str]> = rows.iter().map(|r| r.as_slice()).collect();
    let path = dir.join(name);
    write_xlsx_sheets(&path, &[("TABLE", &rows), ("SETTINGS", settings)]);
    path
}

/// STOP pressed in manual: no jog moves (C2, 5/3 closed centre, stays
/// home, or stops where it was when STOP came); released, the jog acts
/// again. A held coil a jog took over goes off with STOP too.
#[test]
fn stop_stops_a_jog() {
    let paper = sample("paper_example.csv");
    let all = ["--modes", "all", "--hold", "MAN_MODE@0.2s"];
    let jog = |extra: &[&str]| {
        let mut args = all.to_vec();
        args.extend(extra);
        ended(&paper, &args)
    };
    // Control: without STOP the jog moves C2 (3 s full stroke, 1 s held).
    let moved = jog(&["--hold", "jog2+@0.5s", "--release", "jog2+@1.5s"]);
    assert!(!moved.contains("C2 at 0.00"), "{moved}");
    let cases: [(&[&str], &str); 3] = [
        // STOP held before the jog: nothing moves.
        (
            &[
                "--hold",
                "STOP@0.4s",
                "--hold",
                "jog2+@0.5s",
                "--release",
                "jog2+@1.5s",
            ],
            "C2 at 0.00",
        ),
        // STOP during the jog: C2 stops where STOP found it (0.2 s of its
        // 1 s stroke over three positions).
        (
            &[
                "--hold",
                "jog2+@0.5s",
                "--hold",
                "STOP@0.7s",
                "--release",
                "jog2+@2.5s",
            ],
            "C2 at 0.60",
        ),
        // STOP released: the next jog moves again.
        (
            &[
                "--hold",
                "STOP@0.4s",
                "--release",
                "STOP@0.6s",
                "--hold",
                "jog2+@0.8s",
                "--release",
                "jog2+@1.8s",
            ],
            "C2 at 3.00",
        ),
    ];
    for (extra, want) in cases {
        let line = jog(extra);
        assert!(line.contains(want), "{extra:?}: {line}");
    }
    // A STOP that acts at once (`on stop`), a held coil taken over by its
    // jog (hold-safe C1, 53closed): STOP switches it off too.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("held.xlsx");
    let table: &[&[&str]] = &[&["C1+1"], &["C1-0"]];
    let settings: &[&[&str]] = &[
        &["modes", "all"],
        &["hold-safe", "C1"],
        &["on stop", "y1+ hold, y1- hold"],
        &["actuator", "valve", "extend", "retract"],
        &["C1", "53closed", "2s", "2s"],
    ];
    write_xlsx_sheets(&path, &[("TABLE", table), ("SETTINGS", settings)]);
    let line = ended(
        &path,
        &[
            "--hold",
            "MAN_MODE@0.2s",
            "--hold",
            "jog1+@0.5s",
            "--hold",
            "STOP@0.7s",
            "--release",
            "jog1+@2.5s",
        ],
    );
    assert!(
        line.contains("C1 at 0.1") && !line.contains("y1+"),
        "{line}"
    );
}

/// MAN_MODE turned while C2 (5/3 closed centre) heads for its middle
/// position 2 with a coil a halt row holds: C2 stops there (x22 at 1.95),
/// as a halt would stop it, and the coil is off once it has; the same
/// with `on halt … hold` and `on stop … hold`, and with the guard open.
#[test]
fn a_held_5_3_coil_stops_at_its_middle_position_in_manual() {
    let dir = tempfile::tempdir().unwrap();
    let rows: [(&str, &[&[&str]]); 3] = [
        ("hs.xlsx", &[&["modes", "all"], &["hold-safe", "C2"]]),
        (
            "halt.xlsx",
            &[
                &["modes", "all"],
                &["safety", "watchdog"],
                &["on halt", "y2+ hold, y2- hold"],
            ],
        ),
        (
            "stop.xlsx",
            &[&["modes", "all"], &["on stop", "y2+ hold, y2- hold"]],
        ),
    ];
    for (name, settings) in rows {
        let path = paper_with(dir.path(), name, settings);
        let line = ended(
            &path,
            &["--hold", "MAN_MODE@step4", "--release", "MAN_MODE@+3s"],
        );
        assert!(
            line.contains("C2 at 1.95") && !line.contains("y2+"),
            "{name}: {line}"
        );
    }
    let path = paper_with(
        dir.path(),
        "guard.xlsx",
        &[
            &["modes", "all"],
            &["hold-safe", "C2"],
            &["interlock", "guard"],
        ],
    );
    let line = ended(
        &path,
        &["--hold", "MAN_MODE@step4", "--stick", "guard=0@+0.01s"],
    );
    assert!(line.contains("C2 at 1.95"), "{line}");
}

/// RESET pressed in manual moves nothing: a held 5/2 bistable, swivel or
/// spring-return C2 stays out (its coil on); without the hold-safe row
/// nothing moves either; and the alarm RESET is pressed for goes off.
#[test]
fn reset_in_manual_homes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("reset.xlsx");
    let table: &[&[&str]] = &[&["C1+1"], &["C2+1"], &["T=3s"], &["C2-0"], &["C1-0"]];
    let events = [
        "--hold",
        "MAN_MODE@step3",
        "--press",
        "RESET@+1s",
        "--release",
        "MAN_MODE@+3s",
    ];
    for (valve, held) in [
        ("52bi", true),
        ("swivel", true),
        ("52mono", true),
        ("52bi", false),
    ] {
        let mut settings: Vec<&[&str]> = vec![&["modes", "all"]];
        if held {
            settings.push(&["hold-safe", "C2"]);
        }
        let kind = ["C2", valve];
        settings.push(&["actuator", "valve"]);
        settings.push(&kind);
        write_xlsx_sheets(&path, &[("TABLE", table), ("SETTINGS", &settings)]);
        let line = ended(&path, &events);
        assert!(
            line.contains("C1 at 1.00") && line.contains("C2 at 1.00"),
            "{valve} held {held}: {line}"
        );
    }
    // RESET in manual still clears the watchdog's alarm and halt.
    let paper = sample("paper_example.csv");
    let alarm = |reset: bool| {
        let mut args = vec![
            "--modes",
            "all",
            "--safety",
            "watchdog",
            "--stick",
            "x32=0@0s",
            "--hold",
            "MAN_MODE@12s",
        ];
        if reset {
            args.extend(["--press", "RESET@13s"]);
        }
        ended(&paper, &args)
    };
    assert!(alarm(false).contains("alarm_wd"), "{}", alarm(false));
    assert!(!alarm(true).contains("alarm_wd"), "{}", alarm(true));
}

/// A jog button held or stuck as MAN_MODE turns on moves nothing; once
/// every button has read released, a new press moves its actuator.
#[test]
fn a_jog_held_or_stuck_as_manual_begins_moves_nothing() {
    let paper = sample("paper_example.csv");
    let cases: [(&[&str], &str); 4] = [
        (
            &["--stick", "jog1+=1@0s", "--hold", "MAN_MODE@10s"],
            "C1 at 0.00",
        ),
        (
            &["--hold", "jog1+@0s", "--hold", "MAN_MODE@10s"],
            "C1 at 0.00",
        ),
        // A stuck jog of another actuator blocks every jog.
        (
            &[
                "--stick",
                "jog3-=1@0s",
                "--hold",
                "MAN_MODE@10s",
                "--press",
                "jog1+@11s",
            ],
            "C1 at 0.00",
        ),
        // Released in manual, then pressed anew: C1 (52bi) makes its stroke.
        (
            &[
                "--hold",
                "jog1+@0s",
                "--hold",
                "MAN_MODE@10s",
                "--release",
                "jog1+@11s",
                "--press",
                "jog1+@12s",
            ],
            "C1 at 1.00",
        ),
    ];
    for (events, want) in cases {
        let mut args = vec!["--modes", "all"];
        args.extend(events);
        let line = ended(&paper, &args);
        assert!(line.contains(want), "{events:?}: {line}");
    }
}
