//! Dwells, waits on machine inputs, machine outputs and several items in a
//! cell, as a user meets them: the press station sample, and the errors a
//! mistyped item gets.

use predicates::str::contains;

use crate::helpers::{files_below, read_sheet, sample, steptable, write_xlsx};

const SHEET: &str = "SEQUENTIAL CONTROL DESCRIPTION";

#[test]
fn the_press_station_shows_its_dwell_and_wait_in_the_step_timing() {
    steptable()
        .arg("simulate")
        .arg(sample("press_station.xlsx"))
        .assert()
        .success()
        .stdout(contains(
            "1         0.00 s    0.50 s  I:part_present  (I:part_present came after 0.50 s)",
        ))
        // The press dwell starts when C3 reaches x31 (1.47 s into its 1.5 s stroke) and runs 2 s.
        .stdout(contains("C1-0, C3+1; T=2s  (T=2s ran 1.47–3.47 s)"))
        .stdout(contains("second START: identical cycle"));
    // The run's displacement-time diagram shades the dwells and the wait.
    let dir = tempfile::tempdir().unwrap();
    steptable()
        .arg("simulate")
        .arg(sample("press_station.xlsx"))
        .arg("--diagram")
        .arg(dir.path())
        .assert()
        .success()
        .stdout(contains("press_station.time.svg"));
    let svg =
        std::fs::read_to_string(dir.path().join("press_station/press_station.time.svg")).unwrap();
    assert!(svg.contains("Displacement-time diagram"));
    for label in [">T=2s<", ">T=500ms<", ">T=300ms<", ">I:part_present<"] {
        assert!(svg.contains(label), "{label}");
    }
    // A slower part supply lengthens step 1 and nothing else.
    steptable()
        .arg("simulate")
        .arg(sample("press_station.xlsx"))
        .args(["--input-delay", "part_present=2s"])
        .assert()
        .success()
        .stdout(contains("1         0.00 s    2.00 s  I:part_present"));
}

#[test]
fn the_press_station_converts_with_its_machine_signals_everywhere() {
    let dir = tempfile::tempdir().unwrap();
    steptable()
        .arg("convert")
        .arg(sample("press_station.xlsx"))
        .args(["--diagram", "time", "-o"])
        .arg(dir.path())
        .assert()
        .success();
    let out = dir.path().join("press_station");
    let read =
        |ext: &str| std::fs::read_to_string(out.join(format!("press_station.{ext}"))).unwrap();
    // Machine input after the sensors, machine output after the coils.
    let io = read("io.csv");
    assert!(io.contains("I0.7,part_present,input,"), "{io}");
    assert!(io.contains("O1.4,vacuum,output,"), "{io}");
    let st = read("st");
    assert!(st.contains("part_present AT %IX0.7 : BOOL;"));
    assert!(st.contains("dwell3_pt := T#2000ms; dwell3_run := TRUE;"));
    assert!(
        st.contains("IF dw3_arm AND x31 THEN"),
        "the dwell waits for C3+1"
    );
    let fst = read("fst.txt");
    assert!(fst.contains("LOAD    V200"), "2 s in 1/100 s: {fst}");
    assert!(fst.contains("SET     O1.4    \" vacuum on"), "{fst}");
    let awl = read("awl");
    assert!(awl.contains("S5T#2S"), "{awl}");
    // The on-delay timer is SD in English mnemonics (SE is the extended pulse).
    assert!(
        awl.contains("SD    T 3") && !awl.contains("SE    T"),
        "{awl}"
    );
    let svg = read("diagram.svg");
    assert!(svg.contains(">T=2s</text>") && svg.contains(">I:part_present</text>"));
    // The normalised table in the workbook keeps every item of a cell.
    let table = read_sheet(
        &out.join("press_station.steptable.xlsx"),
        "SEQUENTIAL CONTROL DESCRIPTION",
    );
    assert!(
        table.iter().flatten().any(|c| c == "Y:vacuum+; T=500ms"),
        "{table:?}"
    );
    let timing = read_sheet(&out.join("press_station.steptable.xlsx"), "SIMULATION");
    assert!(
        timing
            .iter()
            .flatten()
            .any(|c| c.starts_with("I:part_present came after")),
        "{timing:?}"
    );
    // Step times in seconds, as `steptable simulate` prints them: step 9
    // (C1-0, C3+1; T=2s) starts at 4.64 s and lasts 3.47 s.
    let step9 = timing
        .iter()
        .find(|r| r[0] == "STEP 9")
        .unwrap_or_else(|| panic!("{timing:?}"));
    let seconds = |text: &str| text.parse::<f64>().unwrap_or(f64::NAN);
    assert!((seconds(&step9[1]) - 4.64).abs() < 0.006, "{step9:?}");
    assert!((seconds(&step9[2]) - 3.47).abs() < 0.006, "{step9:?}");
}

#[test]
fn malformed_items_are_reported_at_their_cells() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("items.xlsx");
    write_xlsx(
        &path,
        SHEET,
        &[
            &["", "BRANCH 1", "BRANCH 2"],
            &["STEP 1", "C1+1; T=2", "I:part present"],
            &["STEP 2", "T=0.001s", "Y:vacuum"],
            &["STEP 3", "C1-0; Y:x11+", "I:lamp"],
            &["STEP 4", "Y:lamp+", "T=1s; T=2s"],
        ],
    );
    let out = dir.path().join("out");
    steptable()
        .arg("convert")
        .arg(&path)
        .arg("-o")
        .arg(&out)
        .assert()
        .code(1)
        .stderr(contains("!C2: error[E015]: \"I:part present\""))
        .stderr(contains("!B3: error[E014]: \"T=0.001s\" is not a dwell"))
        .stderr(contains(
            "!C3: error[E015]: \"Y:vacuum\": an output is switched with Y:name+",
        ))
        .stderr(contains(
            "!B4: error[E015]: \"x11\" cannot name a machine signal",
        ))
        .stderr(contains(
            "!B5: error[E025]: lamp is used as an output (Y:) here but as an input (I:)",
        ))
        .stderr(contains("!C5: error[E021]: a cell holds at most one dwell"))
        .stderr(contains("nothing written").count(1));
    assert!(files_below(&out).is_empty());
}

#[test]
fn modes_and_home_order_come_from_the_settings_sheet_too() {
    let dir = tempfile::tempdir().unwrap();
    let table: &[&[&str]] = &[
        &["", "BRANCH 1"],
        &["STEP 1", "C1+1"],
        &["STEP 2", "C2+1"],
        &["STEP 3", "C2-0"],
        &["STEP 4", "C1-0"],
    ];
    let good = dir.path().join("good.xlsx");
    crate::helpers::write_xlsx_sheets(
        &good,
        &[
            (SHEET, table),
            (
                "SETTINGS",
                &[&["modes", "estop"], &["home order", "C2, C1"]],
            ),
        ],
    );
    steptable()
        .arg("convert")
        .arg(&good)
        .args(["--formats", "io", "-o"])
        .arg(dir.path().join("out"))
        .assert()
        .success();
    let io = std::fs::read_to_string(dir.path().join("out/good/good.io.csv")).unwrap();
    assert!(io.contains(",ESTOP,estop,"), "{io}");
    assert!(io.contains(",RESET_PB,reset,"), "estop brings reset: {io}");
    // The flag wins over the sheet.
    steptable()
        .arg("convert")
        .arg(&good)
        .args(["--modes", "none", "--formats", "io", "-o"])
        .arg(dir.path().join("plain"))
        .assert()
        .success();
    let io = std::fs::read_to_string(dir.path().join("plain/good/good.io.csv")).unwrap();
    assert!(!io.contains("ESTOP"), "{io}");

    let bad = dir.path().join("bad.xlsx");
    crate::helpers::write_xlsx_sheets(
        &bad,
        &[
            (SHEET, table),
            ("SETTINGS", &[&["modes", "reset"], &["home order", "C1"]]),
        ],
    );
    steptable()
        .arg("convert")
        .arg(&bad)
        .arg("-o")
        .arg(dir.path().join("bad"))
        .assert()
        .code(1)
        .stderr(contains("error[E030]: the home order leaves out C2"));
}

#[test]
fn faults_that_cut_a_dwell_or_skip_a_wait_are_hazards() {
    let dir = tempfile::tempdir().unwrap();
    steptable()
        .arg("faults")
        .arg(sample("press_station.xlsx"))
        .arg("-o")
        .arg(dir.path())
        .assert()
        .success()
        // x31 shorted: the press dwell starts with the stroke, not at its end.
        .stdout(contains(
            "dwell 3 (T=2s) of step 9 started before C3 reached x31",
        ))
        // The part sensor shorted: the gripper goes down for a part that is not there.
        .stdout(contains(
            "step 2 started before the machine gave part_present=1",
        ))
        .stdout(contains("step 2 never fires: waiting for part_present"));
}

/// Names of the IEC libraries and names whose first 9 characters (all FST
/// keeps) are a generated name are refused as machine signal names (E015),
/// each at its cell (every name of the libraries matiec and OpenPLC ship:
/// `tests/tools/names.rs`).
#[test]
fn standard_library_and_generated_names_are_refused() {
    // Through the binary: each at its cell, all at once.
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("names.csv");
    std::fs::write(
        &input,
        "C1+1; Y:max+\nC1-0; I:r_trig\nC1+1; Y:lword+\nC1-0; Y:cycle_req_lamp+\nC1+1; Y:start_memory+\nC1-0\n",
    )
    .unwrap();
    let output = crate::helpers::steptable()
        .arg("check")
        .arg(&input)
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(1));
    let text = String::from_utf8_lossy(&output.stderr).to_string()
        + &String::from_utf8_lossy(&output.stdout);
    for (cell, name) in [
        ("names.csv:1:", "max"),
        ("names.csv:2:", "r_trig"),
        ("names.csv:3:", "lword"),
        ("names.csv:4:", "cycle_req_lamp"),
        ("names.csv:5:", "start_memory"),
    ] {
        assert!(
            text.lines()
                .any(|l| l.contains("E015") && l.contains(cell) && l.contains(name)),
            "{name} at {cell}: {text}"
        );
    }
}

/// Every name the generated program declares for itself is refused as a
/// machine signal name, so that an engineer's `I:`/`Y:` name can never
/// clash with one: the names are read from the written `.st` of every
/// operating mode and safety check, and only the table's own machine
/// inputs and outputs may pass.
/// Aly 2008's oven has an input called STOP; it is refused only when the
/// program has a STOP button of its own.
#[test]
fn a_machine_signal_may_be_called_stop_unless_the_program_has_stop() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("oven.csv");
    std::fs::write(&csv, "C1+1\nI:stop=1; C1-0\n").unwrap();
    steptable().args(["check"]).arg(&csv).assert().success();
    steptable()
        .args(["check", "--modes", "continuous,reset"])
        .arg(&csv)
        .assert()
        .success();
    steptable()
        .args(["check", "--modes", "stop"])
        .arg(&csv)
        .assert()
        .code(1)
        .stderr(predicates::str::contains("E015"))
        .stderr(predicates::str::contains("operating-mode button STOP"))
        .stderr(predicates::str::contains("oven.csv:2:1"));
    // Y:estop as an output clashes with the EMERGENCY STOP input.
    std::fs::write(&csv, "C1+1; Y:estop+\nC1-0; Y:estop-\n").unwrap();
    steptable()
        .args(["check", "--modes", "estop"])
        .arg(&csv)
        .assert()
        .code(1)
        .stderr(predicates::str::contains("operating-mode button ESTOP"));
}

#[test]
fn every_name_the_program_declares_is_reserved() {
    use steptable::names::reserved_name;
    let dir = tempfile::tempdir().unwrap();
    let mut checked = 0;
    for name in ["paper_example", "press_station"] {
        for options in [&[][..], &["--modes", "all", "--safety", "all"][..]] {
            let out = dir.path().join(format!("{name}{}", options.len()));
            steptable()
                .arg("convert")
                .arg(sample(&format!("{name}.xlsx")))
                .args(options)
                .args(["--target", "iec", "--formats", "st,io", "-o"])
                .arg(&out)
                .assert()
                .success();
            let io = std::fs::read_to_string(out.join(format!("{name}/{name}.io.csv"))).unwrap();
            let machine: Vec<String> = io
                .lines()
                .filter_map(|l| {
                    let cells: Vec<&str> = l.split(',').collect();
                    matches!(cells.get(2), Some(&"input") | Some(&"output"))
                        .then(|| cells[1].to_ascii_lowercase())
                })
                .collect();
            let st = std::fs::read_to_string(out.join(format!("{name}/{name}.st"))).unwrap();
            let mut in_var = false;
            for line in st.lines().map(str::trim) {
                if line.starts_with("VAR") {
                    in_var = true;
                } else if line.starts_with("END_VAR") {
                    in_var = false;
                } else if in_var && let Some(ident) = line.split([' ', ':']).next() {
                    let ident = ident.to_ascii_lowercase();
                    // The mode buttons are taken while their mode is on:
                    // `a_machine_signal_may_be_called_stop_unless_the_program_has_stop`.
                    // Single step's and manual mode's too (`all` has them):
                    // `single_step.rs`, `manual.rs` test them taken.
                    let jog = ident.strip_prefix("jog").is_some_and(|n| {
                        n.len() > 1
                            && (n.ends_with('p') || n.ends_with('m'))
                            && n[..n.len() - 1].chars().all(|c| c.is_ascii_digit())
                    });
                    let button = [
                        "cont",
                        "stop",
                        "estop",
                        "reset_pb",
                        "step_mode",
                        "step_pb",
                        "man_mode",
                    ]
                    .contains(&ident.as_str())
                        || jog;
                    if ident.is_empty()
                        || ident.starts_with("(*")
                        || machine.contains(&ident)
                        || button
                    {
                        continue;
                    }
                    assert!(
                        reserved_name(&ident).is_some(),
                        "{name} {options:?}: the program declares {ident}, which a table may use as a machine signal"
                    );
                    checked += 1;
                }
            }
        }
    }
    assert!(checked > 60, "{checked}");
}
