//! The scenario's promises a red team found broken (issue 40, findings 5,
//! 6, 10, 11, 12 and the messages), each through the binary where the
//! engineer sees it: a `stepK` event waits for the step entered anew, the
//! step numbers printed are the ones `@stepK` takes, a button's alias is
//! no machine signal's name, the timeline has every output's lane and the
//! shading on both pages, a scenario's page and a conversion leave each
//! other's files, and the advice names the options the command has.

use crate::helpers::{convert_csv, files_with_bytes, run_in, sample};
use crate::scenario::{ended_at, simulate_file};

/// The times (ms) of the lines containing `text`, in order.
fn times_of(table: &str, text: &str) -> Vec<u64> {
    table
        .lines()
        .filter(|l| l.contains(text))
        .map(|l| {
            let seconds: f64 = l.split_whitespace().next().unwrap().parse().unwrap();
            (seconds * 1000.0).round() as u64
        })
        .collect()
}

fn paper(work: &std::path::Path, args: &[&str]) -> (Option<i32>, String) {
    simulate_file(
        work,
        &sample("paper_example.xlsx").display().to_string(),
        args,
    )
}

/// Finding 6: an event at `stepK` after another waits for the program to
/// enter step K anew: three at `step2` are three passes, a cycle apart,
/// never the scan of the event before.
#[test]
fn events_at_one_step_happen_at_successive_passes() {
    let work = tempfile::tempdir().unwrap();
    let (code, table) = paper(
        work.path(),
        &[
            "--modes",
            "continuous,stop",
            "--hold",
            "CONT@0s",
            "--press",
            "START@0.5s",
            "--press",
            "START@step2",
            "--press",
            "START@step2",
            "--press",
            "STOP@step2",
        ],
    );
    assert_eq!(code, Some(0), "{table}");
    let mut events = times_of(&table, "@step2: ");
    assert_eq!(events.len(), 3, "{table}");
    let entered = times_of(&table, "step 2   ");
    assert_eq!(entered.len(), 3, "one pass each: {table}");
    for (event, step) in events.iter().zip(&entered) {
        assert!(event > step && event - step <= 10, "{table}");
    }
    events.dedup();
    assert_eq!(events.len(), 3, "three scans: {table}");
    assert!(events[1] - events[0] > 5_000, "a cycle apart: {table}");
}

/// Finding 12: the closing transition prints as the step it enters, 0, the
/// number `@step0` takes (no `step 9` that `@step9` refuses); and the
/// page's timeline ends where the printed run ends.
#[test]
fn the_printed_step_numbers_are_the_ones_at_step_takes() {
    let work = tempfile::tempdir().unwrap();
    let (code, table) = paper(
        work.path(),
        &[
            "--press",
            "START@1s",
            "--press",
            "START@step0",
            "--report",
            "r",
        ],
    );
    assert_eq!(code, Some(0), "{table}");
    assert!(!table.contains("step 9"), "{table}");
    let ends = times_of(&table, "step 0   end of cycle");
    assert_eq!(ends.len(), 2, "two cycles: {table}");
    let press = times_of(&table, "--press START@step0: START pressed");
    assert_eq!(press.len(), 1, "{table}");
    assert!(press[0] > ends[0] && press[0] - ends[0] <= 10, "{table}");
    let page = std::fs::read_to_string(
        work.path()
            .join("r/paper_example/paper_example.scenario.report.html"),
    )
    .unwrap();
    let end = page
        .split("data-end-ms=\"")
        .nth(1)
        .and_then(|r| r.split('"').next())
        .unwrap();
    assert_eq!(end.parse::<u64>().unwrap(), ended_at(&table), "{table}");
}

/// Finding 5: a machine input may not take a button's alias while the
/// program has that button: E015 at its cell, through convert and through
/// a scenario.
#[test]
fn a_buttons_alias_is_no_machine_signals_name() {
    let table = ",BRANCH 1\nSTEP 1,I:emergency_stop\nSTEP 2,C1+1\nSTEP 3,C1-0\n";
    let (_dir, out, assert) = convert_csv(table, &["--modes", "estop"], 1);
    let said = String::from_utf8_lossy(&assert.get_output().stderr).into_owned();
    assert!(said.contains("t.csv:2:2: error[E015]"), "{said}");
    assert!(said.contains("EMERGENCY_STOP"), "{said}");
    assert!(!out.exists(), "nothing written");
    // Without the button the name is free.
    convert_csv(table, &[], 0);
    let work = tempfile::tempdir().unwrap();
    std::fs::write(work.path().join("t.csv"), table).unwrap();
    let (code, said) = simulate_file(
        work.path(),
        "t.csv",
        &["--modes", "estop", "--stick", "EMERGENCY_STOP=1@1s"],
    );
    assert_eq!(code, Some(1), "{said}");
    assert!(said.contains("t.csv:2:2: error[E015]"), "{said}");
    assert!(!said.contains("what happened"), "{said}");
}

/// Finding 10: the criteria's `miss` outputs have their lanes on both
/// pages, and the scenario's page shades dwells and waits as the report.
#[test]
fn both_timelines_draw_every_output_and_the_shading() {
    let work = tempfile::tempdir().unwrap();
    let criteria = ["--safety", "criteria"];
    let line: Vec<String> = ["convert", "--formats", "report", "-o", "c"]
        .iter()
        .map(|a| a.to_string())
        .chain([sample("paper_example.xlsx").display().to_string()])
        .chain(criteria.iter().map(|a| a.to_string()))
        .collect();
    let (code, said) = run_in(work.path(), &line);
    assert_eq!(code, Some(0), "{said}");
    let (code, said) = paper(
        work.path(),
        &[
            "--safety",
            "criteria",
            "--stick",
            "x21=0@step1",
            "--report",
            "s",
        ],
    );
    assert_eq!(code, Some(0), "{said}");
    for page in [
        "c/paper_example/paper_example.report.html",
        "s/paper_example/paper_example.scenario.report.html",
    ] {
        let html = std::fs::read_to_string(work.path().join(page)).unwrap();
        assert!(
            html.contains("data-signal=\"miss1\""),
            "{page}: no miss1 lane"
        );
    }
    let station = sample("press_station.xlsx").display().to_string();
    let (code, said) = simulate_file(
        work.path(),
        &station,
        &["--press", "START@1s", "--report", "p"],
    );
    assert_eq!(code, Some(0), "{said}");
    let html = std::fs::read_to_string(
        work.path()
            .join("p/press_station/press_station.scenario.report.html"),
    )
    .unwrap();
    assert!(html.contains("<rect class=\"dwell\""), "no dwell shaded");
    assert!(html.contains("<rect class=\"wait\""), "no wait shaded");
}

/// Finding 11: a conversion into the folder of a scenario's page leaves the
/// page, and a scenario's page written beside a conversion leaves its
/// files as they were.
#[test]
fn a_scenario_page_and_a_conversion_leave_each_others_files() {
    let work = tempfile::tempdir().unwrap();
    let input = sample("paper_example.xlsx").display().to_string();
    let convert: Vec<String> = ["convert", &input, "-o", "r"]
        .iter()
        .map(|a| a.to_string())
        .collect();
    let page = work
        .path()
        .join("r/paper_example/paper_example.scenario.report.html");
    let (code, said) = paper(work.path(), &["--press", "START@1s", "--report", "r"]);
    assert_eq!(code, Some(0), "{said}");
    let (code, said) = run_in(work.path(), &convert);
    assert_eq!(code, Some(0), "{said}");
    assert!(!said.contains("removed"), "{said}");
    assert!(page.exists(), "the convert removed the scenario's page");
    let before = files_with_bytes(&work.path().join("r/paper_example"));
    let (code, said) = paper(work.path(), &["--press", "START@2s", "--report", "r"]);
    assert_eq!(code, Some(0), "{said}");
    let after = files_with_bytes(&work.path().join("r/paper_example"));
    let unchanged = |(path, bytes): &(std::path::PathBuf, Vec<u8>)| {
        path == &page
            || path.ends_with(".steptable-manifest")
            || after.iter().any(|(p, b)| p == path && b == bytes)
    };
    assert!(
        before.iter().all(unchanged),
        "the scenario changed the conversion's files"
    );
    assert_eq!(before.len(), after.len());
}

/// The messages: E040 names `--report` (simulate has no `-o`) and no
/// record the folder does not have; a scenario waiting for a cycle that a
/// START event kept from starting says why.
#[test]
fn scenario_messages_name_what_the_command_has() {
    let work = tempfile::tempdir().unwrap();
    std::fs::write(work.path().join("r7"), "a file").unwrap();
    let (code, said) = paper(work.path(), &["--press", "START@1s", "--report", "r7"]);
    assert_eq!(code, Some(1), "{said}");
    assert!(
        said.contains("error[E040]") && said.contains("with --report"),
        "{said}"
    );
    assert!(!said.contains("-o"), "{said}");
    let mine = work.path().join("r8/paper_example");
    std::fs::create_dir_all(&mine).unwrap();
    std::fs::write(mine.join("paper_example.scenario.report.html"), "mine").unwrap();
    let (code, said) = paper(work.path(), &["--press", "START@1s", "--report", "r8"]);
    assert_eq!(code, Some(1), "{said}");
    assert!(said.contains("with --report"), "{said}");
    assert!(
        !said.contains(".steptable-manifest"),
        "no record to see: {said}"
    );
    let (code, said) = paper(
        work.path(),
        &[
            "--modes",
            "stop",
            "--press",
            "STOP@step2",
            "--press",
            "START@+3s",
        ],
    );
    assert_eq!(code, Some(0), "{said}");
    assert!(
        said.contains("no cycle ran: with a START event (--press START@+3s)"),
        "{said}"
    );
}

/// rt7 F18.3: a press of a button still down from the press before it
/// (within its 0.1 s) gives the program no new edge, and the table says
/// so instead of printing a press that did nothing; a press after the
/// button was let go is a press. Single step shows why it matters: the
/// second STEP_PB fires no step.
#[test]
fn a_press_of_a_button_still_down_is_said_to_be_no_new_press() {
    let work = tempfile::tempdir().unwrap();
    let (code, table) = paper(
        work.path(),
        &[
            "--modes",
            "step",
            "--hold",
            "STEP_MODE@0s",
            "--press",
            "STEP_PB@1s",
            "--press",
            "STEP_PB@+50ms",
            "--press",
            "STEP_PB@+1s",
        ],
    );
    assert_eq!(code, Some(0), "{table}");
    let said: Vec<&str> = table.lines().filter(|l| l.contains("STEP_PB@")).collect();
    assert_eq!(said.len(), 3, "{table}");
    assert!(!said[0].contains("still down"), "{table}");
    assert!(
        said[1].contains("STEP_PB pressed while still down: no new press"),
        "{table}"
    );
    assert!(!said[2].contains("still down"), "{table}");
}
