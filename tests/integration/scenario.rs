//! Scenarios from the command line (`simulate --press/--hold/--release/
//! --stick`): what the printed step table shows of RESET mid-cycle, a
//! sensor stuck at a moment, and the three forms of time; then the hostile
//! inputs of the options, each with its code and the option named, and
//! nothing written.

use crate::helpers::{files_below, run_in, sample, steptable};

/// `simulate paper_example.xlsx ARGS`: exit code and stdout.
fn simulate(args: &[&str]) -> (i32, String) {
    let out = steptable()
        .arg("simulate")
        .arg(sample("paper_example.xlsx"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8(out.stdout).unwrap(),
    )
}

/// The time printed on the first line containing `text`, in ms.
fn time_of(table: &str, text: &str) -> u64 {
    let line = table
        .lines()
        .find(|l| l.contains(text))
        .unwrap_or_else(|| panic!("no line with {text}:\n{table}"));
    let seconds: f64 = line.split_whitespace().next().unwrap().parse().unwrap();
    (seconds * 1000.0).round() as u64
}

/// The EMERGENCY STOP as step 3 starts, RESET a second later: the cycle
/// stops short of step 4, RESET homes the machine, and it ends at rest
/// with every cylinder home.
#[test]
fn reset_mid_cycle_homes_the_paper_example_as_printed() {
    let (code, table) = simulate(&[
        "--modes",
        "estop,reset",
        "--press",
        "ESTOP@step3",
        "--press",
        "RESET@+1s",
    ]);
    assert_eq!(code, 0, "{table}");
    let step3 = time_of(&table, "step 3 ");
    let estop = time_of(&table, "--press ESTOP@step3: ESTOP pressed");
    let reset = time_of(&table, "--press RESET@+1s: RESET_PB pressed");
    assert_eq!(estop, step3 + 10, "the scan after step 3 starts:\n{table}");
    assert_eq!(reset, estop + 1_000, "{table}");
    // RESET homes the machine in the scan that reads it; the motion of
    // homing is no problem of the table's.
    assert_eq!(time_of(&table, "homing starts"), reset, "{table}");
    assert!(time_of(&table, "homing done") > reset, "{table}");
    assert!(!table.contains("problem:"), "{table}");
    assert!(
        !table.contains("step 4 "),
        "no step after the ESTOP:\n{table}"
    );
    let end = table.lines().find(|l| l.starts_with("ended at")).unwrap();
    assert!(end.contains("in step 0 (at rest)"), "{end}");
    for c in ["C1", "C2", "C3", "C4"] {
        assert!(end.contains(&format!("{c} at 0.00")), "{end}");
    }
}

/// A sensor stuck at 0 before START: the cycle waits in step 1 for ever.
#[test]
fn a_sensor_stuck_at_0_holds_the_cycle_in_its_step() {
    let (code, table) = simulate(&["--stick", "x11=0@0.2s"]);
    assert_eq!(code, 0, "{table}");
    assert_eq!(time_of(&table, "x11 stuck at 0"), 200, "{table}");
    assert!(!table.contains("step 2 "), "{table}");
    let end = table.lines().find(|l| l.starts_with("ended at")).unwrap();
    assert!(end.contains("in step 1;"), "{end}");
    assert!(end.contains("C1 at 1.00"), "{end}");
}

/// The ISO designation, the paper symbol and absolute or relative times
/// name the same event: the tables differ only in the options written.
#[test]
fn a_signal_answers_to_each_of_its_names_and_times_to_each_form() {
    let run = |args: &[&str]| {
        let (code, table) = simulate(args);
        assert_eq!(code, 0, "{table}");
        table
    };
    let paper = run(&["--designations", "iso", "--stick", "x21=0@step2"]);
    let iso = run(&["--designations", "iso", "--stick", "2B3=0@step2"]);
    assert!(paper.contains("x21 stuck at 0 (2B3)"), "{paper}");
    assert_eq!(paper.replace("x21=0", "2B3=0"), iso);
    let relative = run(&["--stick", "x21=0@1s", "--stick", "x11=0@+500ms"]);
    let absolute = run(&["--stick", "x21=0@1s", "--stick", "x11=0@1.5s"]);
    assert_eq!(relative.replace("+500ms", "1.5s"), absolute);
}

/// Events happen in the order written, across the options.
#[test]
fn events_happen_in_the_order_written_across_options() {
    let (code, table) = simulate(&[
        "--modes",
        "stop",
        "--stick",
        "x11=1@1s",
        "--hold",
        "STOP@+1s",
        "--release",
        "STOP@+1s",
    ]);
    assert_eq!(code, 0, "{table}");
    assert_eq!(time_of(&table, "STOP held"), 2_000, "{table}");
    assert_eq!(time_of(&table, "STOP released"), 3_000, "{table}");
}

/// Each hostile event: exit 1, E042 naming the option as written, nothing
/// written in the working folder.
#[test]
fn hostile_events_are_refused_with_e042_and_the_option() {
    let rows: &[(&[&str], &str, &str)] = &[
        (
            &["--press", "START@1s", "--press", "START@+0s"],
            "--press START@+0s",
            "written twice for one scan",
        ),
        (
            &["--press", "START@+1s", "--press", "START@1s"],
            "--press START@1s",
            "written twice for one scan",
        ),
        (
            &["--stick", "x21=0@1s", "--stick", "x21=1@+0s"],
            "--stick x21=1@+0s",
            "contradicts --stick x21=0@1s at the same scan",
        ),
        (
            &["--stick", "x10=0@1.001s", "--stick", "x10=1@1.002s"],
            "--stick x10=1@1.002s",
            "contradicts --stick x10=0@1.001s at the same scan",
        ),
        (
            &["--press", "START@+5s", "--press", "START@3s"],
            "--press START@3s",
            "before the event written before it (--press START@+5s, at 5 s)",
        ),
        (
            &["--press", "START@500s", "--press", "START@+200s"],
            "--press START@+200s",
            "happens after 600 s",
        ),
        (
            &[
                "--press",
                "START@step2",
                "--press",
                "START@+400s",
                "--press",
                "START@+300s",
            ],
            "--press START@+300s",
            "happens after 600 s",
        ),
        (
            &["--press", "FOO@1s"],
            "--press FOO@1s",
            "no input called \"FOO\"",
        ),
        (
            &["--press", "RESET@1s"],
            "--press RESET@1s",
            "--modes reset",
        ),
        (
            &["--press", "STOP@-1s"],
            "--press STOP@-1s",
            "before power-up",
        ),
        (
            &["--press", "STOP@step99"],
            "--press STOP@step99",
            "no step 99",
        ),
        (
            &["--press", "STOP@"],
            "--press STOP@:",
            "nothing after the @",
        ),
        // In the names the engineer chose.
        (
            &["--designations", "iso", "--stick", "1A1=0@1s"],
            "--stick 1A1=0@1s",
            "1A1 is an actuator: stick one of its sensors instead (1B1, 1B2)",
        ),
        (
            &["--designations", "iso", "--press", "FOO@1s"],
            "--press FOO@1s",
            "2B3",
        ),
        // Finding 9: events that would do nothing.
        (
            &["--release", "START@1s"],
            "--release START@1s",
            "does nothing: START is not held",
        ),
        (
            &["--hold", "START@1s", "--hold", "START@2s"],
            "--hold START@2s",
            "does nothing: START is held already (--hold START@1s)",
        ),
        (
            &[
                "--modes",
                "estop",
                "--stick",
                "ESTOP=1@0s",
                "--press",
                "ESTOP@step2",
            ],
            "--press ESTOP@step2",
            "does nothing: ESTOP reads 1 from --stick ESTOP=1@0s on",
        ),
        (
            &["--stick", "x21=0@1s", "--stick", "x21=0@2s"],
            "--stick x21=0@2s",
            "x21 is stuck at 0 already",
        ),
        // A step's event and a `+0s` after it share the scan.
        (
            &["--stick", "x21=0@step2", "--stick", "x21=1@+0s"],
            "--stick x21=1@+0s",
            "contradicts --stick x21=0@step2",
        ),
        // The messages of a malformed `@`.
        (
            &["--press", "START@1,5s"],
            "--press START@1,5s",
            "decimal comma: write 1.5s",
        ),
        (
            &["--press", "START@1s@2s"],
            "--press START@1s@2s",
            "more than one @",
        ),
        (
            &["--press", "START@+step3"],
            "--press START@+step3",
            "write step3",
        ),
        (
            &["--press", "START@0.0001s"],
            "--press START@0.0001s",
            "finer than a millisecond",
        ),
        (
            &["--stick", "=1@1s"],
            "--stick =1@1s",
            "no signal named before the =",
        ),
        (
            &["--press", "STOP@soon"],
            "--press STOP@soon",
            "is not a time",
        ),
        (
            &["--press", "STOP1s"],
            "--press STOP1s",
            "expected SIGNAL@WHEN",
        ),
        (&["--press", "STOP@4"], "--press STOP@4", "has no unit"),
        (
            &["--press", "STOP@700s"],
            "--press STOP@700s",
            "0 s to 600 s",
        ),
        (&["--press", ""], "--press :", "expected SIGNAL@WHEN"),
        (&["--press", "@1s"], "--press @1s", "no signal named"),
        (&["--press", "x21@1s"], "--press x21@1s", "stick it instead"),
        (&["--stick", "y1+=1@1s"], "--stick y1+=1@1s", "is an output"),
        (
            &["--stick", "x21@1s"],
            "--stick x21@1s",
            "SIGNAL=0 or SIGNAL=1",
        ),
        (&["--stick", "x21=2@1s"], "--stick x21=2@1s", "not 0 or 1"),
        (
            &[
                "--modes",
                "stop",
                "--hold",
                "STOP@2s",
                "--release",
                "STOP@2s",
            ],
            "--release STOP@2s",
            "contradicts --hold STOP@2s",
        ),
        (
            &[
                "--modes", "stop", "--press", "STOP@2s", "--press", "STOP@2s",
            ],
            "--press STOP@2s",
            "written twice",
        ),
        (
            &[
                "--modes", "stop", "--press", "STOP@3s", "--press", "STOP@2s",
            ],
            "--press STOP@2s",
            "before the event written before it",
        ),
    ];
    let work = tempfile::tempdir().unwrap();
    let input = sample("paper_example.xlsx").display().to_string();
    for (args, option, why) in rows {
        let (code, said) = simulate_file(work.path(), &input, args);
        assert_eq!(code, Some(1), "{args:?}: {said}");
        assert!(said.contains("error[E042]"), "{args:?}: {said}");
        assert!(said.contains(option), "{args:?} names {option}: {said}");
        assert!(said.contains(why), "{args:?} says {why}: {said}");
        assert!(!said.contains("what happened"), "{args:?} ran: {said}");
    }
    assert!(files_below(work.path()).is_empty(), "nothing written");
}

/// A repeated relative press is a second press, not a duplicate.
#[test]
fn a_relative_press_repeated_is_a_second_press() {
    let (code, table) = simulate(&[
        "--modes", "stop", "--press", "STOP@+1s", "--press", "STOP@+1s",
    ]);
    assert_eq!(code, 0, "{table}");
    assert_eq!(table.matches("STOP pressed").count(), 2, "{table}");
}

/// A sensor dying mid-cycle under the watchdog: the alarm line says when
/// the machine told its operator, and the run ends in the step it waits in.
#[test]
fn a_sensor_dying_mid_cycle_prints_the_watchdog_alarm() {
    let (code, table) = simulate(&["--safety", "all", "--stick", "x23=0@step2"]);
    assert_eq!(code, 0, "{table}");
    let stuck = time_of(&table, "x23 stuck at 0");
    let alarm = time_of(&table, "alarm_wd on");
    assert!(alarm > stuck, "{table}");
    assert!(!table.contains("step 3 "), "{table}");
    let end = table.lines().find(|l| l.starts_with("ended at")).unwrap();
    assert!(end.contains("in step 2, halted;"), "{end}");
}

/// `--report DIR`: the scenario's page holds the table as printed, a red
/// line per event at its time, and the lanes of the run: ESTOP (normally
/// closed) reads 0 from the scan of its press, RESET_PB 1, for a press's
/// 100 ms.
#[test]
fn the_report_draws_the_scenario_on_the_timeline() {
    let out = tempfile::tempdir().unwrap();
    let dir = out.path().join("r");
    let (code, table) = simulate(&[
        "--modes",
        "estop,reset",
        "--press",
        "ESTOP@step3",
        "--press",
        "RESET@+1s",
        "--report",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{table}");
    let page = dir.join("paper_example/paper_example.scenario.report.html");
    assert!(
        table.contains(&format!("report: {}", page.display())),
        "{table}"
    );
    let html = std::fs::read_to_string(&page).unwrap();
    let printed = table
        .lines()
        .skip(1)
        .take_while(|l| !l.starts_with("  report:"));
    for line in printed {
        let escaped = line
            .replace('&', "&amp;")
            .replace('<', "&lt;")
            .replace('>', "&gt;");
        assert!(html.contains(&escaped), "the page holds {line:?}");
    }
    let (estop, reset) = (
        time_of(&table, "ESTOP pressed"),
        time_of(&table, "RESET_PB pressed"),
    );
    for (at, event) in [(estop, "--press ESTOP@step3"), (reset, "--press RESET@+1s")] {
        let x = at as f64 / 1000.0 * 120.0;
        let mark = format!(r#"x1="{x:.1}""#);
        let line = html
            .lines()
            .find(|l| l.contains(&format!("<title>{event}</title>")))
            .unwrap_or_else(|| panic!("a mark for {event}"));
        assert!(line.contains(&mark), "{event} at {at} ms: {line}");
    }
    let edges = |signal: &str| {
        let key = format!(r#"data-signal="{signal}" data-edges=""#);
        let from = html.find(&key).unwrap_or_else(|| panic!("a lane {signal}")) + key.len();
        html[from..].split('"').next().unwrap().to_string()
    };
    assert!(
        edges("ESTOP").contains(&format!("{estop}:0 {}:1", estop + 100)),
        "{}",
        edges("ESTOP")
    );
    assert!(
        edges("RESET_PB").contains(&format!("{reset}:1 {}:0", reset + 100)),
        "{}",
        edges("RESET_PB")
    );
    // Self-contained: nothing loaded from elsewhere.
    assert!(
        !html.contains(" src=") && !html.contains("href=\"http"),
        "self-contained"
    );
}

/// A refused event writes no page; `--report` without an event is the
/// option parser's error.
#[test]
fn a_refused_scenario_writes_no_report() {
    let work = tempfile::tempdir().unwrap();
    let input = sample("paper_example.xlsx").display().to_string();
    for args in [
        vec!["--press", "RESET@1s", "--report", "r"],
        vec!["--report", "r"],
        vec!["--press", "START@1s", "--diagram", "r"],
    ] {
        let (code, said) = simulate_file(work.path(), &input, &args);
        assert_eq!(code, Some(1), "{args:?}: {said}");
        assert!(
            files_below(work.path()).is_empty(),
            "{args:?}: nothing written"
        );
    }
}

/// An event whose step never comes is said, after where the run ended.
#[test]
fn an_event_whose_step_never_comes_is_said() {
    let (code, table) = simulate(&["--stick", "x11=0@0.2s", "--stick", "x21=1@step3"]);
    assert_eq!(code, 0, "{table}");
    assert!(
        table
            .trim_end()
            .ends_with("never happened: --stick x21=1@step3 (the run ended first)"),
        "{table}"
    );
    assert!(!table.contains("x21 stuck"), "{table}");
}

/// `simulate FILE ARGS` in `work`: exit code and stdout.
pub(crate) fn simulate_file(
    work: &std::path::Path,
    file: &str,
    args: &[&str],
) -> (Option<i32>, String) {
    let mut line = vec!["simulate".to_string(), file.to_string()];
    line.extend(args.iter().map(|a| a.to_string()));
    run_in(work, &line)
}

/// The time of the final `ended at T s` line, in ms.
pub(crate) fn ended_at(table: &str) -> u64 {
    let line = table.lines().find(|l| l.starts_with("ended at ")).unwrap();
    let seconds: f64 = line["ended at ".len()..]
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    (seconds * 1000.0).round() as u64
}

/// An event that happens after 600 s (a step of a long cycle) is followed
/// as any other: the run goes on a healthy cycle and a second after it.
#[test]
fn the_run_goes_on_a_cycle_after_an_event_later_than_600_s() {
    let work = tempfile::tempdir().unwrap();
    let rows =
        ",BRANCH 1\nSTEP 1,\"C1+1; T=400s\"\nSTEP 2,\"C2+1; T=400s\"\nSTEP 3,C1-0\nSTEP 4,C2-0\n";
    std::fs::write(work.path().join("slow.csv"), rows).unwrap();
    let (_, proof) = simulate_file(work.path(), "slow.csv", &[]);
    assert!(proof.contains("cycle time 803.94 s"), "{proof}");
    let (code, table) = simulate_file(
        work.path(),
        "slow.csv",
        &[
            "--modes",
            "continuous",
            "--hold",
            "CONT@0s",
            "--stick",
            "x21=0@step4",
        ],
    );
    assert_eq!(code, Some(0), "{table}");
    let event = time_of(&table, "x21 stuck at 0");
    assert!(event > 600_000, "{table}");
    assert!(ended_at(&table) >= event + 803_940 + 1_000, "{table}");
    assert!(
        table.contains("in step 2;"),
        "the next cycle stalls in step 2:\n{table}"
    );
}

/// A run longer than the report's timeline draws its start, says so, and
/// the page stays as small as the report's.
#[test]
fn a_long_scenario_page_draws_the_start_of_the_run_and_says_so() {
    let work = tempfile::tempdir().unwrap();
    let input = sample("paper_example.xlsx").display().to_string();
    let args = ["--scan", "1ms", "--press", "START@15s", "--report", "r"];
    let (code, said) = simulate_file(work.path(), &input, &args);
    assert_eq!(code, Some(0), "{said}");
    let page = work
        .path()
        .join("r/paper_example/paper_example.scenario.report.html");
    let html = std::fs::read_to_string(page).unwrap();
    assert!(html.contains("The timeline is drawn for at most 20000 scans: this run went on past 20 s at 1 ms a scan"), "{said}");
    assert!(ended_at(&said) > 20_000, "{said}");
}

/// The final line names the outputs still on and says "at rest" only when
/// the machine is: the oven's fan runs on 20 s after STOP and is waited
/// for; STOP stuck before START leaves coil and fan on; a cylinder stuck
/// out is no rest.
#[test]
fn the_final_line_names_outputs_on_and_says_at_rest_only_when_true() {
    let work = tempfile::tempdir().unwrap();
    let oven = sample("oven.xlsx").display().to_string();
    let carwash = sample("carwash.xlsx").display().to_string();
    let (_, table) = simulate_file(work.path(), &oven, &["--press", "STOP@step2"]);
    let stop = time_of(&table, "STOP pressed");
    assert!(
        ended_at(&table) >= stop + 20_000,
        "the fan runs on:\n{table}"
    );
    assert!(
        table.contains("in step 0 (at rest)\n") || table.ends_with("(at rest)"),
        "{table}"
    );
    let (_, table) = simulate_file(work.path(), &oven, &["--stick", "STOP=1@1s"]);
    let end = table.lines().find(|l| l.starts_with("ended at")).unwrap();
    assert!(end.ends_with("in step 0; on: fan, coil"), "{table}");
    let (_, table) = simulate_file(work.path(), &carwash, &["--stick", "x11=0@0s"]);
    let end = table.lines().find(|l| l.starts_with("ended at")).unwrap();
    assert!(
        end.ends_with("in step 2; C1 at 1.00; on: y1+, brush, spray"),
        "{table}"
    );
}

/// Homing after RESET is what RESET asked for, also the scan that reads
/// RESET and the one that ends homing: no problem listed.
#[test]
fn homing_after_reset_is_no_problem() {
    let work = tempfile::tempdir().unwrap();
    for (file, args) in [
        (
            "paper_example.xlsx",
            ["--stick", "x23=0@step2", "--press", "RESET@+4s"],
        ),
        (
            "drilling_station.xlsx",
            ["--stick", "x21=0@0s", "--press", "RESET@5s"],
        ),
    ] {
        let input = sample(file).display().to_string();
        let mut line = vec!["--modes", "reset"];
        line.extend(args);
        let (_, table) = simulate_file(work.path(), &input, &line);
        assert!(table.contains("homing done"), "{table}");
        assert!(!table.contains("problem:"), "{file}:\n{table}");
    }
}

/// At a slow scan the scenario's own START press is held two scans, as
/// the proof's: the cycle it starts is no "start without a START press".
#[test]
fn the_scenarios_start_press_is_seen_at_a_slow_scan() {
    let work = tempfile::tempdir().unwrap();
    let input = sample("drilling_station.xlsx").display().to_string();
    let args = [
        "--scan",
        "100ms",
        "--modes",
        "estop",
        "--stick",
        "x10=1@30s",
    ];
    let (code, table) = simulate_file(work.path(), &input, &args);
    assert_eq!(code, Some(0), "{table}");
    assert!(table.contains("step 1 "), "{table}");
    assert!(!table.contains("problem:"), "{table}");
}
