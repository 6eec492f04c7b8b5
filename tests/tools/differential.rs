//! Differential execution of the written files: every program steptable
//! writes is run in the engine that would really run it — matiec (Beremiz,
//! OpenPLC) for the `.st` and the ST inside both XML flavours, OpenPLC's own
//! upload compile, awlsim for the `.awl` in both mnemonic sets, an FST
//! interpreter for the `.fst.txt` — on the inputs steptable's simulation of
//! the same table recorded, and its outputs must equal the simulation's at
//! every scan of two full cycles, and so must the step it shows (ST's
//! `active_step`, the AWL step flag that is on, the FST step label).
//!
//! Matrix: every sample × festo/iec/siemens × plain / `--safety all` /
//! `--modes all --safety all` (AWL also × `--mnemonic de`), and a table of
//! named actuators and commented steps × `--designations iso` / `names`. Without
//! `../shared` or awlsim the checks that need them are reported as ignored
//! (they fail with STEPTABLE_REQUIRE_TOOLS=1).

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::engines::{self, Case, awlsim, fst, matiec, plcxml};
use crate::helpers::samples;
use crate::{Check, Tool, shared, tool};

pub const CHECKS: &[Check] = &[
    Check::new(
        "differential::structured_text_runs_in_matiec_as_simulated",
        &[Tool::Shared],
        structured_text_runs_in_matiec_as_simulated,
    ),
    Check::new(
        "differential::st_inside_plcopen_codesys_and_exp_runs_in_matiec_as_simulated",
        &[Tool::Shared],
        st_inside_plcopen_codesys_and_exp_runs_in_matiec_as_simulated,
    ),
    Check::new(
        "differential::openplc_upload_accepts_every_st",
        &[Tool::Shared],
        openplc_upload_accepts_every_st,
    ),
    Check::new(
        "differential::awl_runs_in_awlsim_as_simulated_in_both_mnemonic_sets",
        &[Tool::Awlsim],
        awl_runs_in_awlsim_as_simulated_in_both_mnemonic_sets,
    ),
    Check::new(
        "differential::fst_runs_in_the_interpreter_as_simulated",
        &[],
        fst_runs_in_the_interpreter_as_simulated,
    ),
    Check::new(
        "differential::a_wrong_fst_file_is_caught_with_its_scan_and_signal",
        &[],
        a_wrong_fst_file_is_caught_with_its_scan_and_signal,
    ),
    Check::new(
        "differential::a_wrong_st_file_is_caught_by_matiec",
        &[Tool::Shared],
        a_wrong_st_file_is_caught_by_matiec,
    ),
    Check::new(
        "differential::a_wrong_awl_timer_is_caught_by_awlsim",
        &[Tool::Awlsim],
        a_wrong_awl_timer_is_caught_by_awlsim,
    ),
    Check::new(
        "differential::the_fst_interpreter_refuses_unknown_statements",
        &[],
        fst::unknown_statements_are_refused,
    ),
];

const TARGETS: [&str; 3] = ["festo", "iec", "siemens"];
/// The third set has every check and the watchdog's criteria analysis
/// (`all` leaves it out): every language renders its awaited memories and
/// missing outputs in every engine of the matrix.
const OPTIONS: [&[&str]; 3] = [
    &[],
    &["--safety", "all"],
    &[
        "--modes",
        "all",
        "--safety",
        "edge,precheck,plausibility,criteria",
    ],
];

/// Every case of the matrix, converted into `dir`, with `extra` arguments.
pub(crate) fn matrix(dir: &Path, extra: &[&str]) -> Vec<Case> {
    let mut cases = Vec::new();
    for (s, sample) in samples().iter().enumerate() {
        // A sample that pins its addresses converts for its target only.
        let targets = crate::helpers::targets_of(sample);
        for target in TARGETS.into_iter().filter(|t| targets.contains(t)) {
            for (o, options) in OPTIONS.iter().enumerate() {
                let mut args = vec!["--target", target];
                args.extend_from_slice(options);
                args.extend_from_slice(extra);
                let out = dir.join(format!("{s}-{target}-{o}"));
                cases.push(engines::prepare(sample, &args, &out));
            }
        }
    }
    // The engineer's names and step comments, under each designation
    // scheme (issue 38): identifiers and comments the engines must take.
    let named = crate::helpers::root().join("tests/fixtures/named_station.xlsx");
    for target in TARGETS {
        for scheme in ["iso", "names"] {
            let mut args = vec![
                "--target",
                target,
                "--modes",
                "all",
                "--safety",
                "all",
                "--designations",
                scheme,
            ];
            args.extend_from_slice(extra);
            let out = dir.join(format!("named-{target}-{scheme}"));
            cases.push(engines::prepare(&named, &args, &out));
        }
    }
    // A retry into its own step with a dwell: the dwell starts again. The
    // SFC chart refuses it (E048: its step stays active, its entry does not
    // run again).
    let retry = crate::helpers::root().join("tests/fixtures/retry_dwell.csv");
    let charts = extra.iter().any(|a| a.contains("sfc"));
    for target in TARGETS.into_iter().filter(|_| !charts) {
        let mut args = vec!["--target", target, "--modes", "all"];
        args.extend_from_slice(extra);
        let out = dir.join(format!("retry-{target}"));
        cases.push(engines::prepare(&retry, &args, &out));
    }
    cases
}

/// Runs `check` on every case on two threads; every failure is reported.
pub(crate) fn run_all(cases: &[Case], check: impl Fn(&Case) -> Result<(), String> + Sync) {
    let failures: Vec<String> =
        engines::on_two_threads(cases, |c| check(c).err().into_iter().collect());
    assert!(
        failures.is_empty(),
        "{} of {} cases differ:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
    // A trace in which nothing switches would prove nothing.
    assert!(cases.iter().all(|c| c.trace.output_changes() >= 4));
}

fn structured_text_runs_in_matiec_as_simulated() {
    let shared = shared();
    let dir = tempfile::tempdir().unwrap();
    let cases = matrix(dir.path(), &["--formats", "st"]);
    run_all(&cases, |c| {
        c.check_stepped(
            "matiec .st",
            matiec::run_stepped(&shared, &c.file(".st"), &c.trace, &c.allocation),
        )
    });
    eprintln!("matiec: {} .st files run, traces equal", cases.len());
}

fn st_inside_plcopen_codesys_and_exp_runs_in_matiec_as_simulated() {
    let shared = shared();
    let dir = tempfile::tempdir().unwrap();
    let cases = matrix(dir.path(), &["--formats", "plcopen,codesys,exp"]);
    run_all(&cases, |c| {
        for suffix in [".plcopen.xml", ".codesys.xml", ".exp"] {
            let text = std::fs::read_to_string(c.file(suffix)).unwrap();
            let st = if suffix == ".exp" {
                plcxml::from_codesys_v2(&text)
            } else {
                plcxml::structured_text(&text)
            };
            let st = st.map_err(|e| format!("{}: {suffix}: {e}", c.label))?;
            let path = c.dir.join(format!("{}{suffix}.st", c.name));
            std::fs::write(&path, st).unwrap();
            c.check_stepped(
                &format!("matiec {suffix}"),
                matiec::run_stepped(&shared, &path, &c.trace, &c.allocation),
            )?;
        }
        Ok(())
    });
    eprintln!(
        "matiec: {} PLCopen, {0} CODESYS V3 and {0} CoDeSys V2.3 programs run, traces equal",
        cases.len()
    );
}

/// Runs an OpenPLC build replay (`script`: v3's `check-upload`, v4's
/// `check-upload-v4`) on one file: accepted when it exits 0 and prints
/// `needle`.
pub(crate) fn replay_accepts(script: &Path, needle: &str, st: &Path) -> Result<(), String> {
    let output = Command::new(script)
        .arg(st)
        .output()
        .map_err(|e| e.to_string())?;
    let text = String::from_utf8_lossy(&output.stdout);
    if output.status.success() && text.contains(needle) {
        Ok(())
    } else {
        Err(format!(
            "{}: {text}{}",
            st.display(),
            String::from_utf8_lossy(&output.stderr)
        ))
    }
}

/// `check-upload` replays OpenPLC Runtime v3's upload compile.
pub(crate) fn openplc_accepts(shared: &Path, st: &Path) -> Result<(), String> {
    replay_accepts(
        &shared.join("tools/openplc/check-upload"),
        "openplc: accepted",
        st,
    )
}

fn openplc_upload_accepts_every_st() {
    let shared = shared();
    let dir = tempfile::tempdir().unwrap();
    let cases = matrix(dir.path(), &["--formats", "st"]);
    run_all(&cases, |c| openplc_accepts(&shared, &c.file(".st")));
    eprintln!("openplc: {} .st files accepted", cases.len());
}

fn awl_runs_in_awlsim_as_simulated_in_both_mnemonic_sets() {
    awl_in_awlsim("awlsim", matrix);
}

/// The cases `cases` converts into a folder with the AWL arguments of each
/// mnemonic set, run in awlsim: every trace must be the simulation's.
pub(crate) fn awl_in_awlsim(what: &str, cases: impl Fn(&Path, &[&str]) -> Vec<Case>) {
    let python = awlsim::python(&tool(Tool::Awlsim));
    for mnemonic in ["en", "de"] {
        let dir = tempfile::tempdir().unwrap();
        let cases = cases(
            dir.path(),
            &["--formats", "awl,sdf", "--mnemonic", mnemonic],
        );
        run_all(&cases, |c| {
            c.check_stepped(
                &format!("awlsim ({mnemonic})"),
                awlsim::run_stepped(
                    &python,
                    &c.file(".awl"),
                    c.mnemonic,
                    &c.trace,
                    &c.allocation,
                ),
            )
        });
        eprintln!(
            "{what}: {} .awl files ({mnemonic}) run, traces equal",
            cases.len()
        );
    }
}

fn fst_runs_in_the_interpreter_as_simulated() {
    let dir = tempfile::tempdir().unwrap();
    let cases = matrix(dir.path(), &["--formats", "fst"]);
    run_all(&cases, |c| {
        let text = crate::engines::read_ansi(&c.file(".fst.txt")).unwrap();
        c.check_stepped(
            "FST interpreter",
            fst::run_stepped(&text, &c.trace, &c.festo),
        )
    });
    eprintln!("fst: {} .fst.txt files run, traces equal", cases.len());
}

/// The press station with every safety check, converted: the case the
/// self-tests below break one line of.
pub(crate) fn press_case(dir: &Path) -> Case {
    let sample = crate::helpers::sample("press_station.xlsx");
    engines::prepare(&sample, &["--safety", "all"], dir)
}

/// The layer must be able to fail: a swapped coil in the FST is caught with
/// the scan and the signal.
fn a_wrong_fst_file_is_caught_with_its_scan_and_signal() {
    let dir = tempfile::tempdir().unwrap();
    let case = press_case(dir.path());
    // y2+ where the program says y2- (O1.2 → O0.2 as STEP 3 hands over
    // to STEP 4, C2-0).
    let text = crate::engines::read_ansi(&case.file(".fst.txt")).unwrap();
    let swapped = swap_first_after(&text, "STEP 3", "SET     O1.2", "SET     O0.2");
    let err = case
        .check("FST", fst::run(&swapped, &case.trace, &case.festo))
        .unwrap_err();
    assert!(err.contains("scan ") && err.contains("y2"), "{err}");
}

/// The same swap in the `.st`, run by matiec.
fn a_wrong_st_file_is_caught_by_matiec() {
    let dir = tempfile::tempdir().unwrap();
    let case = press_case(dir.path());
    let st = std::fs::read_to_string(case.file(".st")).unwrap();
    let swapped = swap_first_after(&st, "3: (*", "y2m := TRUE;", "y2p := TRUE;");
    let path: PathBuf = case.dir.join("swapped.st");
    std::fs::write(&path, swapped).unwrap();
    let err = case
        .check(
            "matiec",
            matiec::run(&shared(), &path, &case.trace, &case.allocation),
        )
        .unwrap_err();
    assert!(err.contains("scan ") && err.contains("y2"), "{err}");
}

/// English `SE` is the extended pulse, not the on-delay: an AWL file that
/// used it would end every dwell at once, and awlsim must show it.
fn a_wrong_awl_timer_is_caught_by_awlsim() {
    let dir = tempfile::tempdir().unwrap();
    let case = press_case(dir.path());
    let awl = std::fs::read_to_string(case.file(".awl")).unwrap();
    let wrong = awl.replace("SD    T", "SE    T");
    assert_ne!(wrong, awl);
    let path = case.dir.join("pulse.awl");
    std::fs::write(&path, wrong).unwrap();
    let python = awlsim::python(&tool(Tool::Awlsim));
    let err = case
        .check(
            "awlsim",
            awlsim::run(&python, &path, case.mnemonic, &case.trace, &case.allocation),
        )
        .unwrap_err();
    assert!(err.contains("scan "), "{err}");
}

/// `text` with the first `from` after `marker` replaced by `to`.
pub(crate) fn swap_first_after(text: &str, marker: &str, from: &str, to: &str) -> String {
    let at = text
        .find(marker)
        .unwrap_or_else(|| panic!("{marker} not in the file"));
    let (head, tail) = text.split_at(at);
    assert!(tail.contains(from), "{from} not after {marker}");
    format!("{head}{}", tail.replacen(from, to, 1))
}
