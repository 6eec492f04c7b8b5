//! Every flag of every command, through the binary, with its effect.
//!
//! The list of (command, flag) pairs comes from clap's own command tree (the
//! CLI module is compiled into this test), so a new flag without a case here
//! fails `every_flag_has_a_case`. Each case runs the command with the flag
//! and, where the effect is a difference, without it, in a fresh folder, and
//! asserts what a user would see change. No run may panic or exit 2 (which
//! the README keeps for internal and I/O failures).

use std::path::Path;
use std::process::Output;

use clap::CommandFactory;

use crate::helpers::{sample, steptable, write_xlsx_sheets};

/// The table a case starts from, written as `in/t.<ext>`.
#[derive(Clone, Copy)]
enum Input {
    /// The paper's example (three branches, middle stops).
    Paper,
    /// The press station (dwells, a machine input `part_present`).
    Press,
    /// The template workbook: an empty table sheet and the EXAMPLE sheet.
    Template,
    /// A CSV with a bad cell.
    Bad,
    /// Two single-branch tables, on the sheets `first` and `line`.
    SecondSheet,
    /// The paper's example and, in `tpl/`, the templates with the ST one
    /// marked.
    PaperWithTemplates,
    /// Two actuators named alike in FST's 9 characters (`gripper_arm`,
    /// `gripper_arm2`), on a SETTINGS sheet.
    AlikeNames,
    /// Nothing.
    None,
}

/// Where an effect shows.
#[derive(Clone)]
enum Place {
    Stdout,
    Stderr,
    /// A written file's text (empty when it was not written).
    File(String),
    /// The strings of a written workbook.
    Workbook(String),
    /// What the terminal shows when the command runs on one (`script`).
    Terminal,
}

/// The effect asserted, comparing the run with the flag to the run without.
#[derive(Clone)]
enum Effect {
    /// The text shows with the flag and not without.
    Has(Place, &'static str),
    /// The text shows without the flag and not with.
    Lacks(Place, &'static str),
    /// The place differs (timings masked).
    Differs(Place),
    /// Exit 0 with the flag, 1 without.
    Succeeds,
    /// Exit 1 with this code with the flag, 0 without.
    Fails(&'static str),
    /// The run with the flag writes this file (there is no run without).
    Writes(&'static str),
    /// Stdout and every written file are the same with and without; the
    /// reason says why that is right.
    Unchanged(&'static str),
}

struct Case {
    command: &'static str,
    flag: &'static str,
    input: Input,
    with: Vec<&'static str>,
    without: Vec<&'static str>,
    effect: Effect,
}

/// Eleven cylinders: minutes to compare every candidate for the smallest
/// equations, so 1 s always cuts the comparison (ten compare in seconds).
const ELEVEN_CYLINDERS: &str = "A1 A0 B1 B0 C1 C0 D1 D0 E1 E0 F1 F0 G1 G0 H1 H0 I1 I0 J1 J0 K1 K0";
const TEN_CYLINDERS: &str = "A1 A0 B1 B0 C1 C0 D1 D0 E1 E0 F1 F0 G1 G0 H1 H0 I1 I0 J1 J0";

fn case(
    command: &'static str,
    flag: &'static str,
    input: Input,
    with: &[&'static str],
    without: &[&'static str],
    effect: Effect,
) -> Case {
    Case {
        command,
        flag,
        input,
        with: with.to_vec(),
        without: without.to_vec(),
        effect,
    }
}

/// The options every command that reads tables shares, for `command`
/// (convert, check, simulate, faults, batch), whose outputs are under `out`.
fn table_cases(command: &'static str, out: &'static str) -> Vec<Case> {
    use Effect::*;
    use Input::*;
    let writes_files = matches!(command, "convert" | "batch");
    let file = |name: &str| Place::File(format!("{out}/t/t.{name}"));
    let summary = if writes_files {
        file("io.csv")
    } else {
        Place::Stdout
    };
    let mut cases = vec![
        case(
            command,
            "--sheet",
            Template,
            &["--sheet", "EXAMPLE"],
            &[],
            Succeeds,
        ),
        case(
            command,
            "--message-format",
            Bad,
            &["--message-format", "json"],
            &[],
            Has(Place::Stdout, "\"code\":\"E0"),
        ),
        case(
            command,
            "--home-order",
            Paper,
            &["--home-order", "C4&C3, C2, C1"],
            &[],
            Has(Place::Stderr, "warning[W006]"),
        ),
        // A supervision time sets the watchdog's preset: without the
        // watchdog it is refused, in every command that reads tables.
        case(
            command,
            "--supervision",
            Paper,
            &["--supervision", "2=5s"],
            &[],
            Has(
                Place::Stderr,
                "error[E030]: --supervision: a supervision time sets the step watchdog",
            ),
        ),
    ];
    cases.push(match command {
        "convert" | "batch" => case(
            command,
            "--designations",
            Paper,
            &["--designations", "iso"],
            &[],
            Has(file("io.csv"), ",1B1,"),
        ),
        // The fault table on stdout names each signal by its designation.
        "faults" => case(
            command,
            "--designations",
            Paper,
            &["--designations", "iso"],
            &[],
            Has(Place::Stdout, "1B1 short circuit"),
        ),
        _ => case(
            command,
            "--designations",
            Paper,
            &["--designations", "iso"],
            &[],
            Unchanged(
                "check counts the signals and simulate speaks in the table's moves: neither prints a signal's designation",
            ),
        ),
    });
    if command == "check" {
        // FST's 9 characters bind only where its file is written, as in
        // `convert --formats`.
        cases.push(case(
            command,
            "--formats",
            AlikeNames,
            &["--designations", "names", "--formats", "st,awl"],
            &["--designations", "names"],
            Succeeds,
        ));
    }
    let simulates = command != "check";
    if command == "check" || writes_files {
        cases.extend([
            case(
                command,
                "--target",
                Paper,
                &["--target", "iec"],
                &[],
                Has(summary.clone(), "%IX0.0"),
            ),
            case(
                command,
                "--mnemonic",
                Paper,
                &["--target", "siemens", "--mnemonic", "de"],
                &["--target", "siemens"],
                Has(summary.clone(), "E0.0"),
            ),
            case(
                command,
                "--board",
                Paper,
                &["--board", "uno"],
                &[],
                Fails("E036"),
            ),
        ]);
    } else {
        let reason = "the simulation runs the program, whose behaviour does not depend on how its addresses are spelled";
        cases.extend([
            case(
                command,
                "--target",
                Paper,
                &["--target", "iec"],
                &[],
                Unchanged(reason),
            ),
            case(
                command,
                "--mnemonic",
                Paper,
                &["--target", "siemens", "--mnemonic", "de"],
                &["--target", "siemens"],
                Unchanged(reason),
            ),
            case(
                command,
                "--board",
                Paper,
                &["--board", "uno"],
                &[],
                // The fault table is of a program `convert` would write:
                // one too large for the board has none.
                match command {
                    "faults" => Fails("E036"),
                    _ => Unchanged(reason),
                },
            ),
        ]);
    }
    if command == "batch" {
        // batch prints no per-table summary: the I/O list shows the signals.
        cases.extend([
            case(
                command,
                "--valve",
                Paper,
                &["--valve", "C1=52mono"],
                &[],
                Lacks(file("io.csv"), "y1-,"),
            ),
            case(
                command,
                "--safety",
                Paper,
                &["--safety", "watchdog"],
                &[],
                Has(file("io.csv"), "alarm_wd,"),
            ),
            case(
                command,
                "--modes",
                Paper,
                &["--modes", "stop"],
                &[],
                Has(file("io.csv"), "STOP,"),
            ),
        ]);
    } else if command == "check" || writes_files {
        // The summary line counts the signals.
        cases.extend([
            case(
                command,
                "--valve",
                Paper,
                &["--valve", "C1=52mono"],
                &[],
                Has(Place::Stdout, "7 outputs"),
            ),
            case(
                command,
                "--safety",
                Paper,
                &["--safety", "watchdog"],
                &[],
                Has(Place::Stdout, "9 outputs"),
            ),
            case(
                command,
                "--modes",
                Paper,
                &["--modes", "stop"],
                &[],
                Has(Place::Stdout, "13 inputs"),
            ),
        ]);
    } else {
        cases.extend([
            case(
                command,
                "--valve",
                Paper,
                &["--valve", "C2=52bi"],
                &[],
                Fails("E031"),
            ),
            // A healthy simulation runs the same with the checks: the paper
            // without its middle stops hangs, and the watchdog's alarm says
            // so.
            if command == "simulate" {
                case(
                    command,
                    "--safety",
                    Paper,
                    &["--no-middle-stop", "--safety", "all"],
                    &["--no-middle-stop"],
                    Has(Place::Stdout, "(alarm: alarm_wd)"),
                )
            } else {
                case(
                    command,
                    "--safety",
                    Paper,
                    &["--safety", "all"],
                    &[],
                    Differs(Place::Stdout),
                )
            },
            // With the buttons a cycle starts on the scan after START
            // (the request, then step 1).
            case(
                command,
                "--modes",
                Paper,
                &["--modes", "stop"],
                &[],
                if command == "faults" {
                    Has(Place::Stdout, "STOP")
                } else {
                    Differs(Place::Stdout)
                },
            ),
        ]);
    }
    if simulates {
        // A retract of 3 s, a scan too slow for the middle stops, a valve
        // that cannot hold its load, a part that comes late.
        let timing = |flag: &'static str, with: &[&'static str], input: Input| {
            let (with, without, effect): (Vec<&'static str>, Vec<&'static str>, Effect) =
                match command {
                    "simulate" => (with.to_vec(), vec![], Differs(Place::Stdout)),
                    "faults" => (with.to_vec(), vec![], Differs(Place::Stdout)),
                    _ => {
                        let mut w = vec!["--diagram", "time"];
                        w.extend_from_slice(with);
                        (w, vec!["--diagram", "time"], Differs(file("diagram.svg")))
                    }
                };
            Case {
                command,
                flag,
                input,
                with,
                without,
                effect,
            }
        };
        if command == "faults" {
            // Fault outcomes do not depend on how long a stroke takes, but a
            // setting that stops the healthy cycle is refused.
            cases.extend([
                case(
                    command,
                    "--stroke",
                    Paper,
                    &["--stroke", "C2=100ms"],
                    &[],
                    Fails("E032"),
                ),
                case(
                    command,
                    "--scan",
                    Paper,
                    &["--scan", "100ms"],
                    &[],
                    Fails("E032"),
                ),
                case(
                    command,
                    "--input-delay",
                    Press,
                    &["--input-delay", "part_present=2s"],
                    &[],
                    Unchanged("a late part delays the cycle; every fault still ends the same way"),
                ),
            ]);
        } else {
            cases.extend([
                timing("--stroke", &["--stroke", "C1=3s"], Paper),
                timing("--scan", &["--scan", "20ms"], Paper),
                timing(
                    "--input-delay",
                    &["--input-delay", "part_present=2s"],
                    Press,
                ),
            ]);
        }
    }
    if simulates {
        // A valve whose middle position exhausts cannot hold a loaded
        // piston; without a load it can.
        cases.push(case(
            command,
            "--load",
            Paper,
            &["--valve", "C3=53exhaust", "--load", "C3=0"],
            &["--valve", "C3=53exhaust"],
            Succeeds,
        ));
    }
    if writes_files {
        cases.push(case(
            command,
            "--sync",
            Paper,
            &["--sync"],
            &[],
            Unchanged(
                "the same files, flushed to the disk before the command ends; tools/sync.rs counts the flushes",
            ),
        ));
        cases.extend([
            case(
                command,
                "--diagram",
                Paper,
                &["--diagram", "time"],
                &[],
                Differs(file("diagram.svg")),
            ),
            case(
                command,
                "--formats",
                Paper,
                &["--formats", "st"],
                &[],
                Lacks(file("awl"), "NETWORK"),
            ),
            case(
                command,
                "--templates",
                PaperWithTemplates,
                &["--templates", "tpl"],
                &[],
                Has(file("st"), "(* marked template *)"),
            ),
        ]);
    }
    cases
}

fn all_cases() -> Vec<Case> {
    use Effect::*;
    use Input::*;
    let mut cases = Vec::new();
    for (command, out) in [
        ("convert", "steptable-out"),
        ("check", ""),
        ("simulate", ""),
        ("faults", "steptable-out"),
        ("batch", "out"),
    ] {
        cases.extend(table_cases(command, out));
    }
    cases.extend([
        case(
            "convert",
            "--output",
            Paper,
            &["-o", "o2"],
            &[],
            Writes("o2/t/t.st"),
        ),
        case(
            "simulate",
            "--no-middle-stop",
            Paper,
            &["--no-middle-stop"],
            &[],
            Has(Place::Stdout, "FAILED"),
        ),
        case(
            "simulate",
            "--diagram",
            Paper,
            &["--diagram", "d"],
            &[],
            Has(Place::File("d/t/t.time.svg".into()), "<svg"),
        ),
        case(
            "simulate",
            "--press",
            Paper,
            &["--modes", "estop", "--press", "ESTOP@step2"],
            &["--modes", "estop"],
            Has(Place::Stdout, "--press ESTOP@step2: ESTOP pressed"),
        ),
        case(
            "simulate",
            "--hold",
            Paper,
            &["--modes", "estop", "--hold", "ESTOP@1s"],
            &["--modes", "estop"],
            Has(Place::Stdout, "--hold ESTOP@1s: ESTOP held"),
        ),
        case(
            "simulate",
            "--release",
            Paper,
            &[
                "--modes",
                "estop",
                "--hold",
                "ESTOP@1s",
                "--release",
                "ESTOP@+1s",
            ],
            &["--modes", "estop", "--hold", "ESTOP@1s"],
            Has(Place::Stdout, "--release ESTOP@+1s: ESTOP released"),
        ),
        case(
            "simulate",
            "--report",
            Paper,
            &["--stick", "x11=0@1s", "--report", "d"],
            &["--stick", "x11=0@1s"],
            Has(
                Place::File("d/t/t.scenario.report.html".into()),
                "<title>--stick x11=0@1s</title>",
            ),
        ),
        case(
            "simulate",
            "--stick",
            Paper,
            &["--stick", "x11=0@0.2s"],
            &[],
            Has(Place::Stdout, "x11 stuck at 0"),
        ),
        case(
            "faults",
            "--pairs",
            Paper,
            &["--pairs"],
            &[],
            Has(Place::Stdout, "288 fault case(s)"),
        ),
        case(
            "faults",
            "--faults",
            Press,
            &["--faults", "3"],
            &[],
            Has(Place::Stdout, "576 fault case(s)"),
        ),
        case(
            "faults",
            "--output",
            Paper,
            &["-o", "o2"],
            &[],
            Writes("o2/t/t.faults.csv"),
        ),
        case(
            "batch",
            "--output",
            Paper,
            &[],
            &[],
            Writes("out/summary.csv"),
        ),
        case(
            "batch",
            "--jobs",
            Paper,
            &["-j", "1"],
            &[],
            Has(Place::Stdout, "1 job)"),
        ),
        case(
            "batch",
            "--quiet",
            Paper,
            &["--quiet"],
            &[],
            Lacks(Place::Terminal, "workbooks,"),
        ),
        case(
            "templates export",
            "--force",
            PaperWithTemplates,
            &["tpl", "--force"],
            &["tpl"],
            Succeeds,
        ),
        case(
            "template",
            "--output",
            None,
            &["-o", "w.xlsx"],
            &[],
            Writes("w.xlsx"),
        ),
        case(
            "template",
            "--branches",
            None,
            &["--branches", "5"],
            &[],
            Has(
                Place::Workbook("steptable-template.xlsx".into()),
                "BRANCH 5",
            ),
        ),
        case(
            "template",
            "--steps",
            None,
            &["--steps", "40"],
            &[],
            Has(Place::Workbook("steptable-template.xlsx".into()), "STEP 40"),
        ),
        case(
            "template",
            "--force",
            Template,
            &["-o", "in/t.xlsx", "--force"],
            &["-o", "in/t.xlsx"],
            Succeeds,
        ),
    ]);
    let seq = "A1 A0 B1 B0 A1 B1 A0 B0";
    let ga = ["--sequence", seq, "--method", "ga", "--seed", "1"];
    cases.extend([
        case(
            "synth",
            "--sequence",
            None,
            &["--sequence", "A1 B1 A0 B0"],
            &[],
            Writes("steptable-out/A1B1A0B0/A1B1A0B0.equations.st"),
        ),
        case(
            "synth",
            "--templates",
            PaperWithTemplates,
            &["--sequence", "A1 B1 A0 B0", "--templates", "tpl"],
            &["--sequence", "A1 B1 A0 B0"],
            Has(
                Place::File("steptable-out/A1B1A0B0/A1B1A0B0.equations.st".to_string()),
                "(* marked template *)",
            ),
        ),
        case(
            "synth",
            "--output",
            None,
            &["--sequence", "A1 B1 A0 B0", "-o", "o2"],
            &[],
            Writes("o2/A1B1A0B0/A1B1A0B0.equations.st"),
        ),
        case(
            "synth",
            "--sheet",
            SecondSheet,
            &["in/t.xlsx", "--sheet", "line"],
            &["in/t.xlsx"],
            Differs(Place::Stdout),
        ),
        case(
            "synth",
            "--method",
            None,
            &["--sequence", seq, "--method", "ga"],
            &["--sequence", seq],
            Has(Place::Stdout, "found by the GA"),
        ),
        case(
            "synth",
            "--seed",
            None,
            &["--sequence", seq, "--method", "ga", "--seed", "7"],
            &ga,
            Differs(Place::Stdout),
        ),
        case(
            "synth",
            "--mu",
            None,
            &[
                "--sequence",
                seq,
                "--method",
                "ga",
                "--seed",
                "1",
                "--mu",
                "10",
            ],
            &ga,
            Differs(Place::Stdout),
        ),
        case(
            "synth",
            "--ratio",
            None,
            &[
                "--sequence",
                seq,
                "--method",
                "ga",
                "--seed",
                "1",
                "--ratio",
                "3",
            ],
            &ga,
            Differs(Place::Stdout),
        ),
        case(
            "synth",
            "--generations",
            None,
            &[
                "--sequence",
                seq,
                "--method",
                "ga",
                "--seed",
                "1",
                "--generations",
                "3",
            ],
            &ga,
            Has(Place::Stdout, "3 generations"),
        ),
        case(
            "synth",
            "--time-limit",
            None,
            &[
                "--sequence",
                ELEVEN_CYLINDERS,
                "--method",
                "exact",
                "--time-limit",
                "1s",
            ],
            &[
                "--sequence",
                TEN_CYLINDERS,
                "--method",
                "exact",
                "--time-limit",
                "300s",
            ],
            Has(Place::Stdout, "best found: "),
        ),
        case(
            "synth",
            "--prefer",
            None,
            &[
                "--sequence",
                "A1 A0 A1 A0 A1 A0 B1 B0 C1 C0",
                "--prefer",
                "nodes",
            ],
            &["--sequence", "A1 A0 A1 A0 A1 A0 B1 B0 C1 C0"],
            Has(
                Place::Stdout,
                "4 memory(ies), one more than the proven minimum of 3",
            ),
        ),
        case(
            "synth",
            "--message-format",
            None,
            &["--sequence", "A1 A1", "--message-format", "json"],
            &["--sequence", "A1 A1"],
            Has(Place::Stdout, "\"code\":\"E034\""),
        ),
    ]);
    cases
}

/// Writes the case's input into `dir`.
fn prepare(dir: &Path, input: Input) {
    let inputs = dir.join("in");
    std::fs::create_dir_all(&inputs).unwrap();
    let copy = |name: &str| std::fs::copy(sample(name), inputs.join("t.xlsx")).unwrap();
    match input {
        Input::Paper => {
            copy("paper_example.xlsx");
        }
        Input::Press => {
            copy("press_station.xlsx");
        }
        Input::Template => {
            let out = steptable()
                .current_dir(dir)
                .args(["template", "-o", "in/t.xlsx"])
                .output()
                .unwrap();
            assert!(out.status.success());
        }
        Input::Bad => std::fs::write(inputs.join("t.csv"), "C1+1\nC1-9x\n").unwrap(),
        Input::SecondSheet => write_xlsx_sheets(
            &inputs.join("t.xlsx"),
            &[
                (
                    "first",
                    &[
                        &["", "BRANCH 1"],
                        &["STEP 1", "C1+1"],
                        &["STEP 2", "C1-0"],
                        &["STEP 3", "C2+1"],
                        &["STEP 4", "C2-0"],
                    ],
                ),
                (
                    "line",
                    &[
                        &["", "BRANCH 1"],
                        &["STEP 1", "C1+1"],
                        &["STEP 2", "C2+1"],
                        &["STEP 3", "C2-0"],
                        &["STEP 4", "C1-0"],
                    ],
                ),
            ],
        ),
        Input::AlikeNames => write_xlsx_sheets(
            &inputs.join("t.xlsx"),
            &[
                (
                    "SEQUENTIAL CONTROL DESCRIPTION",
                    &[
                        &["", "BRANCH 1"],
                        &["STEP 1", "C1+1"],
                        &["STEP 2", "C2+1"],
                        &["STEP 3", "C2-0"],
                        &["STEP 4", "C1-0"],
                    ],
                ),
                (
                    "SETTINGS",
                    &[
                        &["actuator", "name"],
                        &["C1", "gripper_arm"],
                        &["C2", "gripper_arm2"],
                    ],
                ),
            ],
        ),
        Input::PaperWithTemplates => {
            copy("paper_example.xlsx");
            let out = steptable()
                .current_dir(dir)
                .args(["templates", "export", "tpl"])
                .output()
                .unwrap();
            assert!(out.status.success());
            for name in ["program.st.j2", "equations.st.j2"] {
                let st = dir.join("tpl").join(name);
                let text = std::fs::read_to_string(&st).unwrap();
                std::fs::write(&st, format!("(* marked template *)\n{text}")).unwrap();
            }
        }
        Input::None => {}
    }
}

/// The arguments before a case's own: the command and its input.
fn base(command: &str, input: Input) -> Vec<String> {
    let mut args: Vec<String> = command.split(' ').map(String::from).collect();
    let table = match input {
        Input::Bad => "in/t.csv",
        _ => "in/t.xlsx",
    };
    match command {
        "convert" | "check" | "simulate" | "faults" => args.push(table.into()),
        "batch" => args.extend(["in".into(), "-o".into(), "out".into()]),
        _ => {}
    }
    args
}

/// One run in a fresh folder: its output, the folder, and what the terminal
/// showed when asked for.
struct Run {
    output: Output,
    dir: tempfile::TempDir,
    terminal: String,
}

fn run(case: &Case, extra: &[&str], terminal: bool) -> Run {
    let dir = tempfile::tempdir().unwrap();
    prepare(dir.path(), case.input);
    let mut args = base(case.command, case.input);
    args.extend(extra.iter().map(|s| s.to_string()));
    let output = steptable()
        .current_dir(dir.path())
        .args(&args)
        .output()
        .unwrap();
    let mut shown = String::new();
    if terminal {
        // A second run on a pseudo-terminal, for what only a terminal sees.
        let bin = assert_cmd::cargo::cargo_bin("steptable");
        let line = std::iter::once(bin.to_string_lossy().to_string())
            .chain(args.iter().cloned())
            .map(|a| format!("'{a}'"))
            .collect::<Vec<_>>()
            .join(" ");
        let cmd = format!("rm -rf out && {line}");
        let script = std::process::Command::new("script")
            .args(["-qec", &cmd, "/dev/null"])
            .current_dir(dir.path())
            .output()
            .expect("script (util-linux) runs a command on a terminal");
        shown = String::from_utf8_lossy(&script.stdout).to_string();
    }
    let label = format!("{} {}", case.command, extra.join(" "));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        !stderr.contains("panicked") && !matches!(output.status.code(), Some(2) | Some(101) | None),
        "{label}: exit {:?}\n{stderr}",
        output.status.code()
    );
    Run {
        output,
        dir,
        terminal: shown,
    }
}

/// Timings vary between runs; they are not an effect.
fn masked(text: &str) -> String {
    let timing = regex::Regex::new(r"[0-9.]+ (ms|s \(|workbooks/s)").unwrap();
    timing.replace_all(text, "#").to_string()
}

fn text_at(run: &Run, place: &Place) -> String {
    match place {
        Place::Stdout => masked(&String::from_utf8_lossy(&run.output.stdout)),
        Place::Stderr => String::from_utf8_lossy(&run.output.stderr).to_string(),
        Place::File(path) => std::fs::read_to_string(run.dir.path().join(path)).unwrap_or_default(),
        Place::Workbook(path) => {
            let path = run.dir.path().join(path);
            if path.exists() {
                crate::helpers::xlsx_part(&path, "xl/sharedStrings.xml")
            } else {
                String::new()
            }
        }
        Place::Terminal => run.terminal.clone(),
    }
}

/// Every written file's bytes, by path (batch's summary.csv aside: it holds
/// each conversion's time).
fn written(run: &Run) -> Vec<(String, Vec<u8>)> {
    crate::helpers::files_below(run.dir.path())
        .into_iter()
        .filter(|p| !p.ends_with("summary.csv"))
        .map(|p| {
            let name = p
                .strip_prefix(run.dir.path())
                .unwrap()
                .display()
                .to_string();
            (name, std::fs::read(&p).unwrap())
        })
        .collect()
}

fn check(case: &Case) {
    let label = format!("{} {}", case.command, case.flag);
    let terminal = matches!(
        &case.effect,
        Effect::Has(Place::Terminal, _) | Effect::Lacks(Place::Terminal, _)
    );
    let with = run(case, &case.with, terminal);
    let without = || run(case, &case.without, terminal);
    let code = |r: &Run| r.output.status.code();
    match &case.effect {
        Effect::Has(place, text) => {
            let (a, b) = (text_at(&with, place), text_at(&without(), place));
            assert!(
                a.contains(text),
                "{label}: {text:?} not shown with the flag:\n{a}"
            );
            assert!(
                !b.contains(text),
                "{label}: {text:?} shown without the flag too:\n{b}"
            );
        }
        Effect::Lacks(place, text) => {
            let (a, b) = (text_at(&with, place), text_at(&without(), place));
            assert!(
                !a.contains(text),
                "{label}: {text:?} shown with the flag:\n{a}"
            );
            assert!(
                b.contains(text),
                "{label}: {text:?} not shown without the flag:\n{b}"
            );
        }
        Effect::Differs(place) => {
            let (a, b) = (text_at(&with, place), text_at(&without(), place));
            assert!(!a.is_empty(), "{label}: nothing at the place compared");
            assert_ne!(a, b, "{label}: the same with and without the flag");
        }
        Effect::Succeeds => {
            assert_eq!(code(&with), Some(0), "{label}: {:?}", with.output);
            assert_eq!(code(&without()), Some(1), "{label}: without the flag");
        }
        Effect::Fails(code_text) => {
            assert_eq!(code(&with), Some(1), "{label}: {:?}", with.output);
            let stderr = String::from_utf8_lossy(&with.output.stderr);
            assert!(
                stderr.contains(&format!("error[{code_text}]")),
                "{label}: {stderr}"
            );
            let other = without();
            assert_eq!(
                code(&other),
                Some(0),
                "{label}: without the flag: {:?}",
                other.output
            );
        }
        Effect::Writes(path) => {
            assert_eq!(code(&with), Some(0), "{label}: {:?}", with.output);
            assert!(
                with.dir.path().join(path).is_file(),
                "{label}: {path} not written"
            );
        }
        Effect::Unchanged(reason) => {
            // Said here so that a reviewer can judge it: {reason}.
            let other = without();
            assert_eq!(code(&with), code(&other), "{label} ({reason})");
            assert_eq!(
                text_at(&with, &Place::Stdout),
                text_at(&other, &Place::Stdout),
                "{label} ({reason})"
            );
            assert!(
                written(&with) == written(&other),
                "{label}: the files differ ({reason})"
            );
        }
    }
}

/// (command, flag) for every long flag clap defines, `help` and `version`
/// aside; a nested command is "templates export".
fn clap_flags() -> Vec<(String, String)> {
    fn walk(cmd: &clap::Command, path: &str, out: &mut Vec<(String, String)>) {
        for arg in cmd.get_arguments() {
            if let Some(long) = arg.get_long()
                && !["help", "version"].contains(&long)
                && !path.is_empty()
            {
                out.push((path.to_string(), format!("--{long}")));
            }
        }
        for sub in cmd.get_subcommands() {
            let name = if path.is_empty() {
                sub.get_name().to_string()
            } else {
                format!("{path} {}", sub.get_name())
            };
            walk(sub, &name, out);
        }
    }
    let mut out = Vec::new();
    walk(&steptable::cli::Cli::command(), "", &mut out);
    out.sort();
    out
}

#[test]
fn every_flag_has_a_case() {
    let flags = clap_flags();
    assert!(flags.len() > 80, "{}", flags.len());
    let mut cased: Vec<(String, String)> = all_cases()
        .iter()
        .map(|c| (c.command.to_string(), c.flag.to_string()))
        .collect();
    cased.sort();
    let before = cased.len();
    cased.dedup();
    assert_eq!(before, cased.len(), "one case per flag");
    let missing: Vec<_> = flags.iter().filter(|f| !cased.contains(f)).collect();
    let unknown: Vec<_> = cased.iter().filter(|c| !flags.contains(c)).collect();
    assert!(missing.is_empty(), "flags without a case: {missing:?}");
    assert!(
        unknown.is_empty(),
        "cases for flags clap does not define: {unknown:?}"
    );
}

#[test]
fn every_flag_has_its_effect() {
    let cases = all_cases();
    let failures: Vec<String> = crate::helpers::on_threads(&cases, |case| {
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| check(case)))
            .err()
            .map(|e| {
                e.downcast_ref::<String>()
                    .cloned()
                    .or_else(|| e.downcast_ref::<&str>().map(|s| s.to_string()))
                    .unwrap_or_default()
            })
    });
    assert!(
        failures.is_empty(),
        "{} of {} cases:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n\n")
    );
}
