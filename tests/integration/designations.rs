//! Issue 38, names in and names out: the engineer's actuator names (`C1
//! (clamp)` in the SETTINGS actuator table) and step comments (`STEP 1
//! (clamp part)`) reach every output file of every target; the designation
//! scheme (`--designations paper|iso|names`, SETTINGS `designations`)
//! chooses what the lists call a signal; a name is accepted wherever a
//! signal is named; hostile names are refused at their cell.

use std::path::{Path, PathBuf};

use crate::helpers::{files_below, read_sheet, steptable, write_xlsx_sheets};

/// A stamping station: clamp, punch with a dwell, ejector with a middle
/// stop; named actuators and commented steps.
const TABLE: &[&[&str]] = &[
    &["", "BRANCH 1"],
    &["STEP 1 (clamp part)", "C1+1"],
    &["STEP 2 (punch)", "C2+1"],
    &["STEP 3: dwell", "T=1s"],
    &["STEP 4 (lift punch)", "C2-0"],
    &["STEP 5", "C1-0"],
    &["STEP 6 (eject)", "C3+2"],
    &["STEP 7", "C3-0"],
];

fn station(dir: &Path, settings: &[&[&str]]) -> PathBuf {
    let path = dir.join("stamp.xlsx");
    let mut rows: Vec<&[&str]> = vec![
        &["actuator", "extend", "retract"],
        &["C1 (clamp)", "1s", "1s"],
        &["C2 (punch)"],
        &["C3: ejector"],
    ];
    rows.extend_from_slice(settings);
    write_xlsx_sheets(
        &path,
        &[
            ("SEQUENTIAL CONTROL DESCRIPTION", TABLE),
            ("SETTINGS", &rows),
        ],
    );
    path
}

/// Converts `input` with `args` into a fresh folder below `dir`: every
/// written file (relative name → text; workbooks as their sheets' cells).
fn convert(input: &Path, out: &Path, args: &[&str]) -> Vec<(String, String)> {
    let output = steptable()
        .arg("convert")
        .arg(input)
        .args(args)
        .arg("-o")
        .arg(out)
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    files_below(out)
        .into_iter()
        .filter(|p| !p.ends_with(".steptable-manifest"))
        .map(|p| {
            let name = p.strip_prefix(out).unwrap().to_string_lossy().to_string();
            let text = if name.ends_with(".xlsx") {
                let sheets = calamine::open_workbook_auto(&p).unwrap();
                use calamine::Reader;
                sheets
                    .sheet_names()
                    .iter()
                    .flat_map(|s| read_sheet(&p, s))
                    .flatten()
                    .collect::<Vec<_>>()
                    .join("\n")
            } else {
                String::from_utf8_lossy(&std::fs::read(&p).unwrap()).to_string()
            };
            (name, text)
        })
        .collect()
}

/// What each file kind shows: (file name suffix, texts it must hold).
fn expected(names: bool) -> Vec<(&'static str, Vec<&'static str>)> {
    // Program texts carry the step comments and the actuator names.
    let program = vec!["clamp part", "lift punch", "(clamp)", "(ejector)"];
    let list = vec!["(clamp)", "(punch)", "(ejector)"];
    let mut kinds = vec![
        (".st", program.clone()),
        (".fst.txt", program.clone()),
        (".awl", program.clone()),
        (".plcopen.xml", program.clone()),
        (".codesys.xml", program.clone()),
        (".exp", program.clone()),
        ("beremiz/plc.xml", program.clone()),
        (".gvl.txt", list.clone()),
        (".io.csv", list.clone()),
        (".sdf", list.clone()),
        (".fst-alloc.csv", list.clone()),
        (".rockwell.csv", list.clone()),
        (".tags.xlsx", list.clone()),
        (
            "stamp.steptable.xlsx",
            vec!["STEP 1 (clamp part)", "(clamp)", "C1 (clamp)"],
        ),
        (".diagram.svg", vec!["clamp", "punch", "ejector"]),
    ];
    if names {
        // Under the engineer's names every list and program names the
        // signals so, and the fault table too.
        for (_, texts) in &mut kinds {
            texts.push("clamp_");
        }
        kinds.retain(|(kind, _)| *kind != ".diagram.svg");
        kinds.push((".diagram.svg", vec!["clamp", "punch", "ejector"]));
        kinds.push((".faults.csv", vec!["clamp_home", "punch_end"]));
    }
    kinds
}

#[test]
fn named_actuators_and_step_comments_reach_every_output_file() {
    let dir = tempfile::tempdir().unwrap();
    let input = station(dir.path(), &[]);
    for (scheme, names) in [("paper", false), ("names", true)] {
        for target in ["festo", "iec", "siemens"] {
            let out = dir.path().join(format!("{scheme}-{target}"));
            let files = convert(
                &input,
                &out,
                &["--target", target, "--designations", scheme],
            );
            assert!(files.len() >= 17, "{files:?}");
            for (kind, texts) in expected(names) {
                let (name, text) = files
                    .iter()
                    .find(|(n, _)| n.ends_with(kind))
                    .unwrap_or_else(|| {
                        panic!(
                            "{kind} among {:?}",
                            files.iter().map(|f| &f.0).collect::<Vec<_>>()
                        )
                    });
                for wanted in texts {
                    assert!(
                        text.contains(wanted),
                        "{scheme}, {target}: {name} lacks {wanted:?}"
                    );
                }
            }
        }
    }
}

#[test]
fn iso_designations_on_request_and_from_the_settings_sheet() {
    let dir = tempfile::tempdir().unwrap();
    let input = station(dir.path(), &[]);
    let files = convert(&input, &dir.path().join("iso"), &["--designations", "iso"]);
    let file = |suffix: &str| {
        files
            .iter()
            .find(|(n, _)| n.ends_with(suffix))
            .map(|(_, t)| t.clone())
            .unwrap_or_default()
    };
    let io = file(".io.csv");
    // Sensors home, end, then the middle positions; solenoids + then -.
    for line in [
        "I0.1,1B1,sensor,1,0,,\"1B1: cylinder 1A1 (clamp), home position 0\"",
        "I0.6,3B3,sensor,3,1,,\"3B3: cylinder 3A1 (ejector), middle position 1\"",
        "I0.7,3B2,sensor,3,2,,",
        "O1.1,1M2,coil,1,,-,",
    ] {
        assert!(io.contains(line), "{line} in {io}");
    }
    // Identifiers may not begin with a digit: the ST keeps x10 and says 1B1.
    let st = file(".st");
    assert!(st.contains("x10 AT %IX0.1 : BOOL; (* I0.1 1B1: cylinder 1A1 (clamp)"));
    assert!(st.contains("(* 1M1 on: extend 1A1 (clamp), C1+1 towards 1B2 *)"));
    assert!(file(".faults.csv").contains("1B1 short circuit (stuck at 1),1B1,1"));
    assert!(file(".diagram.svg").contains(">1A1</text>"));
    // The same from a SETTINGS row; the command line wins over it.
    let from_sheet = station(dir.path(), &[&[""], &["designations", "iso"]]);
    let files = convert(&from_sheet, &dir.path().join("sheet"), &[]);
    assert!(
        files
            .iter()
            .any(|(n, t)| n.ends_with(".io.csv") && t.contains(",1B1,"))
    );
    let files = convert(
        &from_sheet,
        &dir.path().join("over"),
        &["--designations", "paper"],
    );
    assert!(
        files
            .iter()
            .any(|(n, t)| n.ends_with(".io.csv") && t.contains(",x10,"))
    );
}

#[test]
fn a_name_is_accepted_where_a_signal_is_named() {
    let dir = tempfile::tempdir().unwrap();
    // `clamp` is C1 (both coils), `punch_in` the punch's retract coil: the
    // program is the one the paper's names give.
    let st = |hold: &str, off: &str, folder: &str| {
        let input = station(
            dir.path(),
            &[
                &[""],
                &["safety", "watchdog"],
                &["hold-safe", hold],
                &["de-energise on halt", off],
            ],
        );
        let files = convert(&input, &dir.path().join(folder), &["--formats", "st"]);
        files[0].1.clone()
    };
    let by_name = st("clamp", "punch_in", "a");
    assert_eq!(by_name, st("C1", "y2-", "b"));
    assert_ne!(by_name, st("C1", "y2+", "c"), "the name chose the coil");
    // A pinned address by the engineer's name and by ISO designation.
    let path = dir.path().join("pinned.xlsx");
    let settings: &[&[&str]] = &[&["actuator", "extend"], &["C1 (clamp)", "1s"]];
    let pins: &[&[&str]] = &[
        &["SIGNAL", "ADDRESS"],
        &["clamp_end", "I1.0"],
        &["2B1", "I1.1"],
    ];
    write_xlsx_sheets(
        &path,
        &[
            ("SEQUENTIAL CONTROL DESCRIPTION", TABLE),
            ("SETTINGS", settings),
            ("ADDRESSES", pins),
        ],
    );
    let files = convert(&path, &dir.path().join("p"), &["--formats", "io"]);
    let io = &files[0].1;
    assert!(io.contains("I1.0,x11,sensor,1,1"), "{io}");
    assert!(io.contains("I1.1,x20,sensor,2,0"), "{io}");
}

/// A hostile case: what, the actuator table's rows (and rows below it),
/// STEP 5's cell, the options, and the message with its code and cell.
type Hostile<'a> = (
    &'a str,
    &'a [&'a [&'a str]],
    &'a str,
    &'a [&'a str],
    &'a str,
);

#[test]
fn options_name_an_actuator_by_its_name() {
    let dir = tempfile::tempdir().unwrap();
    let input = station(dir.path(), &[]);
    // A single-solenoid clamp has no retract coil.
    let files = convert(
        &input,
        &dir.path().join("v"),
        &["--valve", "clamp=52mono", "--formats", "io"],
    );
    assert!(!files[0].1.contains(",y1-,"), "{}", files[0].1);
    assert!(files[0].1.contains(",y2-,"), "{}", files[0].1);
    // A slow punch takes the cycle longer, as C2=3s does.
    let cycle = |args: &[&str]| {
        let output = steptable()
            .arg("simulate")
            .arg(&input)
            .args(args)
            .output()
            .unwrap();
        assert!(output.status.success(), "{args:?}");
        String::from_utf8_lossy(&output.stdout).to_string()
    };
    let by_name = cycle(&["--stroke", "punch=3s"]);
    assert_eq!(by_name, cycle(&["--stroke", "C2=3s"]));
    assert_ne!(by_name, cycle(&[]));
    // A name no actuator has, or one actuator twice: E030, nothing written.
    for (args, message) in [
        (
            ["--valve", "clamps=52mono"],
            "error[E030]: --valve clamps=…: no actuator is named clamps (the actuator table names C1 (clamp), C2 (punch), C3 (ejector))",
        ),
        (
            ["--stroke", "C1=2s,clamp=3s"],
            "error[E030]: --stroke clamp=…: clamp is C1, which is given by number too",
        ),
    ] {
        let out = dir.path().join("bad");
        let output = steptable()
            .arg("convert")
            .arg(&input)
            .args(args)
            .arg("-o")
            .arg(&out)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(1), "{stderr}");
        assert!(stderr.contains(message), "{stderr}");
        assert!(files_below(&out).is_empty());
    }
}

#[test]
fn hostile_names_are_refused_with_their_code_and_cell() {
    let dir = tempfile::tempdir().unwrap();
    // (what, actuator rows, table cell of STEP 5, args, code and message)
    let cases: &[Hostile] = &[
        (
            "two actuators with one name",
            &[&["C1 (clamp)"], &["C2 (Clamp)"]],
            "C1-0",
            &[],
            "SETTINGS!A3: error[E025]: C2 (Clamp): clamp is named for C1 at SETTINGS!A2 too; give them different names",
        ),
        (
            "a name that is a machine input's",
            &[&["C1 (part)"]],
            "C1-0; I:part",
            &[],
            "SETTINGS!A2: error[E025]: C1 (part): part is named in cell B6 too",
        ),
        (
            "a name colliding with a generated name",
            &[&["C1 (x1)"]],
            "C1-0",
            &["--designations", "names"],
            "SETTINGS!A2: error[E015]: C1 (x1): \"x1\" cannot name an actuator: the generated program uses it",
        ),
        (
            "an engineer's signal named like a machine input",
            &[&["C1 (clamp)"]],
            "C1-0; I:clamp_home",
            &["--designations", "names"],
            "SETTINGS!A2: error[E025]: C1 (clamp): clamp_home is named in cell B6 too",
        ),
        (
            "names one to FST",
            &[&["C1 (gripper arm)"]],
            "C1-0",
            &["--designations", "names"],
            "SETTINGS!A2: error[E025]: C1 (gripper arm): gripper_arm_end and gripper_arm_home begin with the same 9 characters, which is all Festo FST keeps of a symbol",
        ),
        (
            "a name that gives no identifier",
            &[&["C1 (2nd clamp)"]],
            "C1-0",
            &["--designations", "names"],
            "SETTINGS!A2: error[E015]: C1 (2nd clamp): \"2nd clamp\" gives no identifier",
        ),
        (
            "a name where a signal is expected that names nothing",
            &[&["C1 (clamp)"], &[""], &["hold-safe", "clamps"]],
            "C1-0",
            &[],
            "SETTINGS!B4: error[E030]: hold-safe: \"clamps\" is not an output of this table",
        ),
        (
            "a scheme that does not exist",
            &[&["C1 (clamp)"], &[""], &["designations", "din"]],
            "C1-0",
            &[],
            "SETTINGS!B4: error[E030]: designations: \"din\" is not valid (expected paper, iso or names)",
        ),
        (
            "a scheme given twice",
            &[
                &["C1 (clamp)"],
                &["designations", "iso"],
                &["designations", "names"],
            ],
            "C1-0",
            &[],
            "SETTINGS!B4: error[E030]: designations is given twice: here and at B3",
        ),
    ];
    for (k, (what, actuators, step5, args, message)) in cases.iter().enumerate() {
        let path = dir.path().join(format!("h{k}.xlsx"));
        let mut table: Vec<&[&str]> = TABLE.to_vec();
        let row5 = ["STEP 5", step5];
        table[5] = &row5;
        let mut settings: Vec<&[&str]> = vec![&["actuator", "extend"]];
        settings.extend_from_slice(actuators);
        write_xlsx_sheets(
            &path,
            &[
                ("SEQUENTIAL CONTROL DESCRIPTION", &table),
                ("SETTINGS", &settings),
            ],
        );
        let out = dir.path().join(format!("o{k}"));
        let output = steptable()
            .arg("convert")
            .arg(&path)
            .args(*args)
            .arg("-o")
            .arg(&out)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(1), "{what}: {stderr}");
        assert!(stderr.contains(message), "{what}: {stderr}");
        assert!(files_below(&out).is_empty(), "{what}: written");
    }
}
