//! A run says where it wrote, and every output records how it was made
//! (issue 38, item 5): `faults` and `synth` print the paths they wrote;
//! `synth --sequence` names its folder after the sequence and never
//! replaces another sequence's outputs; each program and list carries the
//! command line that made it in its own comment syntax (a workbook as its
//! Comments property, the lists that take no comment in the manifest), with
//! no time and no folder in it. The hostile arrangements are a table: what
//! the engineer has, the command, and the code and message that must come.

use std::path::Path;

use crate::helpers::{files_below, files_with_bytes, sample, steptable, synthesised, xlsx_part};

const VERSION: &str = env!("CARGO_PKG_VERSION");

/// One hostile arrangement: the files made in the work folder, the
/// command, and what must come of it.
struct Case {
    what: &'static str,
    /// Makes the files in the work folder; returns the arguments.
    setup: fn(&Path) -> Vec<String>,
    exit: i32,
    /// What stdout and stderr together must say (code and message).
    said: &'static [&'static str],
    /// Files (relative) that must be left byte for byte as they were.
    kept: &'static [&'static str],
}

fn args(items: &[&str]) -> Vec<String> {
    items.iter().map(|i| i.to_string()).collect()
}

/// A synth.json as a synthesis of `tokens` writes it (the part read).
fn synth_json(folder: &Path, name: &str, tokens: &str) {
    std::fs::create_dir_all(folder).unwrap();
    let tokens: Vec<String> = tokens.split(' ').map(|t| format!("\"{t}\"")).collect();
    std::fs::write(
        folder.join(format!("{name}.synth.json")),
        format!("{{\"sequence\": [{}]}}", tokens.join(", ")),
    )
    .unwrap();
}

fn two_moves(work: &Path) -> String {
    std::fs::write(work.join("t.csv"), "C1+1\nC1-0\n").unwrap();
    "t.csv".to_string()
}

fn cases() -> Vec<Case> {
    vec![
        Case {
            what: "synth --sequence into a folder holding another sequence's synthesis",
            setup: |work| {
                // A name cut short, or a table named so, can lead there.
                synth_json(&work.join("out/A1B1A0B0"), "A1B1A0B0", "A1 A0 B1 B0");
                args(&["synth", "--sequence", "A1 B1 A0 B0", "-o", "out"])
            },
            exit: 1,
            said: &[
                "out/A1B1A0B0/A1B1A0B0.synth.json: error[E040]: holds the synthesis of another sequence (A1 A0 B1 B0), and this one (A1 B1 A0 B0) would replace it; nothing written",
            ],
            kept: &["out/A1B1A0B0/A1B1A0B0.synth.json"],
        },
        Case {
            what: "synth --sequence where a run for a table of that name wrote (the manifest vouches for it)",
            setup: |work| {
                std::fs::write(work.join("A1B1A0B0.csv"), "C1+1\nC1-0\nC2+1\nC2-0\n").unwrap();
                steptable()
                    .current_dir(work)
                    .args(["synth", "A1B1A0B0.csv", "-o", "out"])
                    .assert()
                    .success();
                args(&["synth", "--sequence", "A1 B1 A0 B0", "-o", "out"])
            },
            exit: 1,
            said: &[
                "out/A1B1A0B0/A1B1A0B0.synth.json: error[E040]: holds the synthesis of another sequence (C1+1 C1-0 C2+1 C2-0), and this one (A1 B1 A0 B0) would replace it",
            ],
            kept: &[
                "out/A1B1A0B0/A1B1A0B0.synth.json",
                "out/A1B1A0B0/A1B1A0B0.equations.st",
            ],
        },
        Case {
            what: "synth --sequence over a synth.json of the engineer's that is not one",
            setup: |work| {
                std::fs::create_dir_all(work.join("out/A1A0")).unwrap();
                std::fs::write(work.join("out/A1A0/A1A0.synth.json"), "my notes").unwrap();
                args(&["synth", "--sequence", "A1 A0", "-o", "out"])
            },
            exit: 1,
            said: &[
                "out/A1A0/A1A0.synth.json: error[E040]: an output goes here, and no steptable run recorded writing this file",
            ],
            kept: &["out/A1A0/A1A0.synth.json"],
        },
        Case {
            what: "a sequence with a path in it is no sequence",
            setup: |_| args(&["synth", "--sequence", "A1 ../B1 A0", "-o", "out"]),
            exit: 1,
            said: &["--sequence: error[E034]: \"../B1\" is not an action"],
            kept: &[],
        },
        Case {
            what: "a sequence with a slash or a NUL is no sequence",
            setup: |_| args(&["synth", "--sequence", "A1 A0 /B1", "-o", "out"]),
            exit: 1,
            said: &["--sequence: error[E034]: \"/B1\" is not an action"],
            kept: &[],
        },
        Case {
            what: "synth -o onto a file",
            setup: |work| {
                std::fs::write(work.join("notes.txt"), "mine").unwrap();
                args(&["synth", "--sequence", "A1 A0", "-o", "notes.txt"])
            },
            exit: 1,
            said: &["notes.txt: error[E040]: is a file, and outputs go into a folder"],
            kept: &["notes.txt"],
        },
        Case {
            what: "faults -o onto a file",
            setup: |work| {
                std::fs::write(work.join("notes.txt"), "mine").unwrap();
                let table = two_moves(work);
                args(&["faults", &table, "-o", "notes.txt"])
            },
            exit: 1,
            said: &["notes.txt: error[E040]: is a file, and outputs go into a folder"],
            kept: &["notes.txt"],
        },
        Case {
            what: "faults over a fault table of the engineer's",
            setup: |work| {
                let table = two_moves(work);
                std::fs::create_dir_all(work.join("out/t")).unwrap();
                std::fs::write(work.join("out/t/t.faults.csv"), "my analysis").unwrap();
                args(&["faults", &table, "-o", "out"])
            },
            exit: 1,
            said: &[
                "out/t/t.faults.csv: error[E040]: an output goes here, and no steptable run recorded writing this file",
            ],
            kept: &["out/t/t.faults.csv"],
        },
        Case {
            what: "faults beyond the case budget is E033 from the library",
            setup: |work| {
                // 12 actuators, 25 inputs: 4 at once is far over 100,000.
                let mut rows: Vec<String> = (1..=12).map(|i| format!("C{i}+1")).collect();
                rows.extend((1..=12).map(|i| format!("C{i}-0")));
                std::fs::write(work.join("big.csv"), rows.join("\n")).unwrap();
                args(&["faults", "big.csv", "--faults", "4", "-o", "out"])
            },
            exit: 1,
            said: &[
                "big.csv: error[E033]: --faults 4 would simulate",
                "steptable runs at most 100000",
            ],
            kept: &[],
        },
        Case {
            what: "simulate --diagram onto a file",
            setup: |work| {
                std::fs::write(work.join("notes.txt"), "mine").unwrap();
                let table = two_moves(work);
                args(&["simulate", &table, "--diagram", "notes.txt"])
            },
            exit: 1,
            said: &["notes.txt: error[E040]: is a file, and outputs go into a folder"],
            kept: &["notes.txt"],
        },
        Case {
            what: "the same sequence spelt otherwise replaces its own outputs",
            setup: |work| {
                let out = work.join("out").to_string_lossy().to_string();
                steptable()
                    .args(["synth", "--sequence", "A1 A0 B1 B0", "-o", &out])
                    .assert()
                    .success();
                args(&["synth", "--sequence", "A+ A- B+ B-", "-o", "out"])
            },
            exit: 0,
            said: &["wrote out/A1A0B1B0/ (A1A0B1B0.synth.txt, "],
            kept: &[],
        },
    ]
}

#[test]
fn hostile_output_places_of_faults_simulate_and_synth_are_refused_with_their_code() {
    for case in cases() {
        let dir = tempfile::tempdir().unwrap();
        let work = dir.path();
        let args = (case.setup)(work);
        let before: Vec<(String, Vec<u8>)> = case
            .kept
            .iter()
            .map(|k| (k.to_string(), std::fs::read(work.join(k)).unwrap()))
            .collect();
        let all_before = files_with_bytes(work);
        let (exit, said) = crate::helpers::run_in(work, &args);
        assert_eq!(exit, Some(case.exit), "{}: {said}", case.what);
        for text in case.said {
            assert!(said.contains(text), "{}: no `{text}` in {said}", case.what);
        }
        for (kept, bytes) in before {
            assert_eq!(
                std::fs::read(work.join(&kept)).ok().as_ref(),
                Some(&bytes),
                "{}: {kept} changed",
                case.what
            );
        }
        if case.exit != 0 {
            // Nothing of this run landed anywhere.
            assert_eq!(files_with_bytes(work), all_before, "{}: wrote", case.what);
        }
    }
}

#[test]
fn faults_and_synth_print_the_paths_they_wrote() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let faults = steptable()
        .args(["faults"])
        .arg(sample("paper_example.xlsx"))
        .arg("-o")
        .arg(&out)
        .assert()
        .success();
    let stdout = String::from_utf8_lossy(&faults.get_output().stdout).to_string();
    let csv = out.join("paper_example/paper_example.faults.csv");
    assert!(
        stdout.contains(&format!("  wrote {}\n", csv.display())),
        "{stdout}"
    );
    assert!(csv.is_file());

    let synth = steptable()
        .args(["synth", "--sequence", "A1 A0 B1 B0", "-o"])
        .arg(&out)
        .assert()
        .success();
    let stdout = String::from_utf8_lossy(&synth.get_output().stdout).to_string();
    let folder = out.join("A1A0B1B0");
    assert!(
        stdout.contains(&format!(
            "wrote {}/ (A1A0B1B0.synth.txt, A1A0B1B0.synth.json, A1A0B1B0.equations.st, A1A0B1B0.equations.il, A1A0B1B0.synth.xlsx)",
            folder.display()
        )),
        "{stdout}"
    );
    // A second sequence goes beside the first, which stays.
    steptable()
        .args(["synth", "--sequence", "A1 B1 A0 B0", "-o"])
        .arg(&out)
        .assert()
        .success();
    for sequence in ["A1 A0 B1 B0", "A1 B1 A0 B0"] {
        let json = std::fs::read_to_string(synthesised(&out, sequence, ".synth.json")).unwrap();
        let first = sequence.split(' ').next().unwrap();
        assert!(json.contains(&format!("\"{first}\"")), "{sequence}");
    }
    assert!(out.join("A1B1A0B0/A1B1A0B0.equations.st").is_file());
    assert!(out.join("A1A0B1B0/A1A0B1B0.equations.st").is_file());
}

/// The line each file records, per file name; the lists without a comment
/// of their own have it in the manifest under their name.
fn recorded(folder: &Path, file: &Path) -> String {
    let name = file
        .strip_prefix(folder)
        .unwrap()
        .to_string_lossy()
        .to_string();
    if name.ends_with(".xlsx") {
        return xlsx_part(file, "docProps/core.xml");
    }
    let text = String::from_utf8_lossy(&std::fs::read(file).unwrap()).to_string();
    let takes_none = [".io.csv", ".faults.csv", ".fst-alloc.csv", ".sdf", ".svg"];
    if takes_none.iter().any(|s| name.ends_with(s)) {
        let manifest =
            std::fs::read_to_string(folder.join(steptable::manifest::FILE_NAME)).unwrap();
        let mut lines = manifest.lines();
        lines.find(|l| l.ends_with(&format!(" {name}")));
        return lines.next().unwrap_or_default().to_string();
    }
    // The comment is in the file's first lines (after the XML declaration
    // or CoDeSys' pragmas).
    text.lines()
        .find(|l| l.contains("made by steptable"))
        .unwrap_or_default()
        .to_string()
}

#[test]
fn every_output_records_the_command_line_and_no_folder_or_time() {
    let dir = tempfile::tempdir().unwrap();
    let work = dir.path().join("some where");
    std::fs::create_dir_all(&work).unwrap();
    std::fs::copy(sample("carwash.xlsx"), work.join("carwash.xlsx")).unwrap();
    let convert = |out: &str| {
        steptable()
            .current_dir(&work)
            .args([
                "convert",
                "carwash.xlsx",
                "--target",
                "siemens",
                "--scan=20ms",
                "--message-format",
                "json",
                "-o",
            ])
            .arg(work.join(out))
            .assert()
            .success();
        work.join(out).join("carwash")
    };
    let folder = convert("out");
    let files = files_below(&folder);
    assert_eq!(files.len(), crate::helpers::all_files(), "{files:?}");
    let line = format!(
        "made by steptable {VERSION} from carwash.xlsx: steptable convert carwash.xlsx --target siemens --scan 20ms; settings: the command line, the SETTINGS sheet (C1 stroke, C1 valve, de-energise on halt, modes), defaults for the rest"
    );
    // XML forbids `--` in a comment: the options' dashes are `- -` there.
    let in_xml = line.replace("--", "- -");
    for file in &files {
        let record = recorded(&folder, file);
        let name = file.display();
        let wanted = if name.to_string().ends_with(".xml") || name.to_string().ends_with(".L5X") {
            &in_xml
        } else {
            &line
        };
        assert!(record.contains(wanted.as_str()), "{name}: {record}");
        // Neither the folder it ran in nor the one it wrote to.
        let bytes = String::from_utf8_lossy(&std::fs::read(file).unwrap()).to_string();
        assert!(!bytes.contains("some where"), "{name}");
    }
    // The same run into another folder writes the same bytes.
    let again = convert("elsewhere");
    for file in &files {
        let other = again.join(file.strip_prefix(&folder).unwrap());
        assert_eq!(
            std::fs::read(file).unwrap(),
            std::fs::read(&other).unwrap(),
            "{}",
            file.display()
        );
    }
}

#[test]
fn synth_and_faults_outputs_record_their_command_line() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path();
    steptable()
        .args(["synth", "--sequence", "A+ A- B+ B-", "--seed", "2", "-o"])
        .arg(out)
        .assert()
        .success();
    let line = format!(
        "made by steptable {VERSION} from the sequence A1 A0 B1 B0: steptable synth --sequence 'A+ A- B+ B-' --seed 2; settings:"
    );
    for suffix in [".equations.st", ".equations.il"] {
        let text = std::fs::read_to_string(synthesised(out, "A1 A0 B1 B0", suffix)).unwrap();
        assert!(text.starts_with(&format!("(* {line}")), "{suffix}: {text}");
    }
    let core = xlsx_part(
        &synthesised(out, "A1 A0 B1 B0", ".synth.xlsx"),
        "docProps/core.xml",
    );
    assert!(core.contains("<dc:description>made by steptable"), "{core}");

    steptable()
        .args(["faults"])
        .arg(sample("paper_example.xlsx"))
        .args(["--pairs", "--modes", "all", "-o"])
        .arg(out)
        .assert()
        .success();
    let manifest = std::fs::read_to_string(
        out.join("paper_example")
            .join(steptable::manifest::FILE_NAME),
    )
    .unwrap();
    assert!(
        manifest.contains(&format!(
            " paper_example.faults.csv\n  made by steptable {VERSION} from paper_example.xlsx: steptable faults paper_example.xlsx --pairs --modes all; settings:"
        )),
        "{manifest}"
    );
}
