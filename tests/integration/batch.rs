//! Batch conversion of a folder mixing good, bad and colliding files.

use predicates::prelude::*;
use predicates::str::contains;

use crate::helpers::{files_below, sample, steptable};

/// A folder `dir/in` holding `count` copies of the paper sample, `line{i}.xlsx`.
fn copies_of_the_paper(dir: &std::path::Path, count: usize) -> std::path::PathBuf {
    let input = dir.join("in");
    std::fs::create_dir(&input).unwrap();
    for i in 0..count {
        std::fs::copy(
            sample("paper_example.xlsx"),
            input.join(format!("line{i:02}.xlsx")),
        )
        .unwrap();
    }
    input
}

fn folder_of_inputs(dir: &std::path::Path) -> std::path::PathBuf {
    let input = dir.join("in");
    std::fs::create_dir_all(input.join("a")).unwrap();
    std::fs::create_dir_all(input.join("b")).unwrap();
    std::fs::copy(sample("paper_example.xlsx"), input.join("a/line.xlsx")).unwrap();
    std::fs::copy(sample("transfer_line.xlsx"), input.join("b/line.xlsx")).unwrap();
    std::fs::copy(sample("drilling_station.xlsx"), input.join("drill.xlsx")).unwrap();
    std::fs::write(
        input.join("bad.csv"),
        // Two errors of their own: C2-0 is wrong whatever C1+x meant.
        ",BRANCH 1\nSTEP 1,C1+x\nSTEP 2,C2-0\n",
    )
    .unwrap();
    std::fs::write(input.join("notes.txt"), "not a table").unwrap();
    std::fs::write(input.join("~$drill.xlsx"), "Excel lock file").unwrap();
    // Hidden files and folders hold valid tables, so that converting them
    // would show: an editor's backup, a version-control folder.
    std::fs::copy(sample("paper_example.xlsx"), input.join(".backup.xlsx")).unwrap();
    std::fs::create_dir_all(input.join(".git")).unwrap();
    std::fs::copy(sample("paper_example.csv"), input.join(".git/old.csv")).unwrap();
    input
}

#[test]
fn a_folder_with_good_bad_and_colliding_files() {
    let dir = tempfile::tempdir().unwrap();
    let input = folder_of_inputs(dir.path());
    let out = dir.path().join("out");
    steptable()
        .arg("batch")
        .arg(&input)
        .arg("-o")
        .arg(&out)
        .args(["-j", "2", "--formats", "st,io"])
        .assert()
        .code(1)
        .stdout(contains("3 converted, 1 failed"))
        .stdout(contains("failed: ").and(contains("bad.csv:2:2: error[E010]")))
        .stdout(contains("b/line.xlsx -> ").and(contains("(another input has the name line)")));

    // Every good input complete, in its own folder; nothing for the bad one.
    let mut names: Vec<String> = files_below(&out)
        .iter()
        .map(|p| p.strip_prefix(&out).unwrap().to_string_lossy().to_string())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "drill/drill.io.csv",
            "drill/drill.st",
            "line-xlsx/line-xlsx.io.csv",
            "line-xlsx/line-xlsx.st",
            "line/line.io.csv",
            "line/line.st",
            "summary.csv",
        ]
    );
    let summary = std::fs::read_to_string(out.join("summary.csv")).unwrap();
    let rows: Vec<Vec<String>> = csv::Reader::from_reader(summary.as_bytes())
        .records()
        .map(|r| r.unwrap().iter().map(str::to_string).collect())
        .collect();
    assert_eq!(rows.len(), 4);
    let row = |name: &str| rows.iter().find(|r| r[0].ends_with(name)).unwrap().clone();
    assert_eq!(row("bad.csv")[1..3], ["failed", "2"]);
    assert!(row("bad.csv")[3].contains("\"C1+x\" is not a move"));
    assert_eq!(row("a/line.xlsx")[1..3], ["converted", "0"]);
    assert_eq!(row("a/line.xlsx")[4..6], ["8", "4"]);
    assert_eq!(row("b/line.xlsx")[4..6], ["5", "5"]);
    // The folder each input went to; none for one that failed.
    assert_eq!(row("a/line.xlsx")[7], "line");
    assert_eq!(row("b/line.xlsx")[7], "line-xlsx");
    assert_eq!(row("bad.csv")[7], "");
    // The verdict and cycle time of each converted input; no hazard count
    // where the formats asked for no fault analysis.
    assert_eq!(
        row("a/line.xlsx")[8..11],
        ["passed: cycle time 7.47 s", "7.47", ""]
    );
    assert_eq!(row("bad.csv")[8..11], ["", "", ""]);

    // A rerun into a folder inside the inputs does not convert its own outputs.
    let inner = input.join("out");
    steptable()
        .arg("batch")
        .arg(&input)
        .arg("-o")
        .arg(&inner)
        .arg("--quiet")
        .assert()
        .code(1);
    steptable()
        .arg("batch")
        .arg(&input)
        .arg("-o")
        .arg(&inner)
        .arg("--quiet")
        .assert()
        .code(1)
        .stdout(contains("3 converted, 1 failed"));
}

#[test]
fn patterns_and_json_diagnostics() {
    let dir = tempfile::tempdir().unwrap();
    let input = folder_of_inputs(dir.path());
    let pattern = format!("{}/*.csv", input.display());
    let output = steptable()
        .arg("batch")
        .arg(&pattern)
        .arg(input.join("missing.xlsx"))
        .arg("-o")
        .arg(dir.path().join("out"))
        .args(["--message-format", "json"])
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(1));
    let stdout = String::from_utf8(output.stdout).unwrap();
    let objects: Vec<serde_json::Value> = stdout
        .lines()
        .map(|l| serde_json::from_str(l).expect("one JSON object per line"))
        .collect();
    assert_eq!(objects.len(), 3, "{stdout}");
    // The path that names nothing is E001, a file that cannot be read.
    assert_eq!(objects[0]["code"], "E001");
    assert!(
        objects[0]["file"]
            .as_str()
            .unwrap()
            .ends_with("missing.xlsx"),
        "{stdout}"
    );
    assert_eq!(objects[1]["code"], "E010");
    assert_eq!(objects[1]["row"], 2);
    assert_eq!(objects[1]["column"], 2);
    assert_eq!(objects[2]["code"], "E020");
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert!(stderr.contains("0 converted, 2 failed"), "{stderr}");
}

#[test]
fn check_and_convert_speak_json_too() {
    let dir = tempfile::tempdir().unwrap();
    let input = folder_of_inputs(dir.path());
    for command in ["check", "convert"] {
        let output = steptable()
            .arg(command)
            .arg(input.join("bad.csv"))
            .args(["--message-format", "json"])
            .current_dir(dir.path())
            .output()
            .unwrap();
        assert_eq!(output.status.code(), Some(1));
        let first: serde_json::Value = serde_json::from_str(
            String::from_utf8(output.stdout)
                .unwrap()
                .lines()
                .next()
                .unwrap(),
        )
        .unwrap();
        assert_eq!(first["severity"], "error");
        assert_eq!(first["cell"], "B2");
        assert!(first["file"].as_str().unwrap().ends_with("bad.csv"));
        assert_eq!(first["sheet"], serde_json::Value::Null);
    }
}

/// Ctrl-C during a batch: conversions under way finish, the rest are skipped,
/// every folder written is complete, and the summary says what was done.
#[cfg(unix)]
#[test]
fn ctrl_c_leaves_only_complete_outputs_and_a_summary() {
    const COPIES: usize = 400;
    let dir = tempfile::tempdir().unwrap();
    // Enough tables that the run is certainly still going when the signal
    // comes (the first complete folder): each is ~20 ms, 400 are seconds.
    let input = copies_of_the_paper(dir.path(), COPIES);
    let out = dir.path().join("out");
    let child = std::process::Command::new(assert_cmd::cargo::cargo_bin("steptable"))
        .arg("batch")
        .arg(&input)
        .arg("-o")
        .arg(&out)
        .args(["-j", "1", "--quiet"])
        .stdout(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // Wait until some outputs exist, then interrupt.
    let start = std::time::Instant::now();
    while files_below(&out).len() < crate::helpers::all_files()
        && start.elapsed() < std::time::Duration::from_secs(20)
    {
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let output = crate::helpers::interrupt(child);
    let stdout = String::from_utf8_lossy(&output.stdout);
    let summary = std::fs::read_to_string(out.join("summary.csv")).unwrap();
    let rows = summary.lines().count() - 1;
    assert_eq!(rows, COPIES, "every input is listed");
    let converted = summary.matches(",converted,").count();
    let skipped = summary.matches(",skipped (interrupted),").count();
    assert_eq!(output.status.code(), Some(130), "{stdout}");
    assert!(skipped > 0, "{stdout}");
    assert!(converted > 0, "the signal came after a folder was complete");
    assert!(stdout.contains("interrupted:"), "{stdout}");
    assert_eq!(converted + skipped, COPIES, "{summary}");
    // Each folder is complete: every file, no temporary file left.
    let kinds = crate::helpers::all_files();
    for entry in std::fs::read_dir(&out).unwrap().flatten() {
        if entry.path().is_dir() {
            let files = files_below(&entry.path());
            assert_eq!(files.len(), kinds, "{}", entry.path().display());
            assert!(
                files
                    .iter()
                    .all(|f| !f.to_string_lossy().contains(".steptable-"))
            );
        }
    }
    assert_eq!(
        std::fs::read_dir(&out)
            .unwrap()
            .flatten()
            .filter(|e| e.path().is_dir())
            .count(),
        converted
    );
}

/// Two batch runs into the same folder at once leave every output complete.
#[test]
fn two_runs_into_one_folder_leave_complete_outputs() {
    let dir = tempfile::tempdir().unwrap();
    let input = copies_of_the_paper(dir.path(), 6);
    let out = dir.path().join("out");
    let spawn = || {
        std::process::Command::new(assert_cmd::cargo::cargo_bin("steptable"))
            .arg("batch")
            .arg(&input)
            .arg("-o")
            .arg(&out)
            .arg("--quiet")
            .stdout(std::process::Stdio::null())
            .spawn()
            .unwrap()
    };
    let (mut a, mut b) = (spawn(), spawn());
    assert!(a.wait().unwrap().success());
    assert!(b.wait().unwrap().success());
    // Every file equals what one run alone writes, byte for byte.
    let alone = dir.path().join("alone");
    steptable()
        .arg("batch")
        .arg(&input)
        .arg("-o")
        .arg(&alone)
        .arg("--quiet")
        .assert()
        .success();
    for i in 0..6 {
        let name = format!("line{i:02}");
        let files = files_below(&out.join(&name));
        assert_eq!(files.len(), crate::helpers::all_files());
        for file in files {
            let relative = file.strip_prefix(&out).unwrap();
            assert!(
                std::fs::read(&file).unwrap() == std::fs::read(alone.join(relative)).unwrap(),
                "{} differs from a run alone",
                relative.display()
            );
        }
    }
}

/// `batch . -o .`: the tables in the folder are converted (not skipped as
/// "the output folder"), a rerun does not convert what the first run wrote,
/// and a table of the user's named summary.csv is never overwritten: the
/// summary takes another name and says so.
#[test]
fn batch_into_its_own_input_folder() {
    let dir = tempfile::tempdir().unwrap();
    let table = "C1+1\nC1-0\n";
    std::fs::write(dir.path().join("line.csv"), table).unwrap();
    std::fs::write(dir.path().join("summary.csv"), table).unwrap();
    for run in 0..2 {
        let output = steptable()
            .current_dir(dir.path())
            .args(["batch", ".", "-o", "."])
            .output()
            .unwrap();
        let stdout = String::from_utf8_lossy(&output.stdout);
        assert!(output.status.success(), "run {run}: {stdout}");
        assert!(
            stdout.contains("steptable-summary.csv"),
            "run {run}: {stdout}"
        );
        assert_eq!(
            std::fs::read_to_string(dir.path().join("summary.csv")).unwrap(),
            table
        );
        let summary = std::fs::read_to_string(dir.path().join("steptable-summary.csv")).unwrap();
        assert_eq!(
            summary.lines().count(),
            3,
            "run {run}: two tables, no outputs: {summary}"
        );
        assert_eq!(summary.matches(",converted,").count(), 2, "{summary}");
        assert_eq!(
            files_below(&dir.path().join("line")).len(),
            crate::helpers::all_files()
        );
    }
}

/// A table named where another's output would go
/// (`OUT/NAME/NAME.steptable.xlsx`, here through `..`) is kept, and
/// reported; the batch's other tables still land.
#[test]
fn a_batch_never_overwrites_an_input() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("cell")).unwrap();
    let kept = dir.path().join("cell/cell.steptable.xlsx");
    std::fs::copy(sample("paper_example.xlsx"), &kept).unwrap();
    std::fs::copy(sample("paper_example.xlsx"), dir.path().join("cell.xlsx")).unwrap();
    let before = std::fs::read(&kept).unwrap();
    let output = steptable()
        .current_dir(dir.path())
        .args([
            "batch",
            "cell/../cell/cell.steptable.xlsx",
            "cell.xlsx",
            "-j",
            "1",
            "-o",
            ".",
        ])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(!output.status.success(), "{stdout}");
    assert!(stdout.contains("1 converted, 1 failed"), "{stdout}");
    assert!(
        stdout.contains("error[E040]: (converting cell.xlsx) is an input of this run"),
        "{stdout}"
    );
    assert_eq!(std::fs::read(&kept).unwrap(), before);
    assert_eq!(files_below(&dir.path().join("cell")), [kept]);
    assert_eq!(
        files_below(&dir.path().join("cell.steptable")).len(),
        crate::helpers::all_files()
    );
}

/// A folder with symbolic links to itself is walked once, and an absurd
/// `-j` is capped with a note instead of starting 100,000 threads.
#[cfg(unix)]
#[test]
fn self_linked_folders_and_huge_job_counts_end() {
    let dir = tempfile::tempdir().unwrap();
    let tables = dir.path().join("tables");
    std::fs::create_dir_all(&tables).unwrap();
    std::fs::write(tables.join("line.csv"), "C1+1\nC1-0\n").unwrap();
    std::os::unix::fs::symlink(&tables, tables.join("again")).unwrap();
    std::os::unix::fs::symlink(&tables, tables.join("and_again")).unwrap();
    let output = steptable()
        .arg("batch")
        .arg(&tables)
        .args(["-j", "100000", "-o"])
        .arg(dir.path().join("out"))
        .timeout(std::time::Duration::from_secs(60))
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success(), "{stdout}");
    assert!(stdout.contains("1 converted"), "{stdout}");
    assert!(stdout.contains("note: -j 100000"), "{stdout}");
}

/// With the fault analysis, the summary counts each workbook's hazards as
/// its fault table has them.
#[test]
fn the_summary_has_verdict_cycle_time_and_hazards() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    steptable()
        .arg("batch")
        .arg(sample("paper_example.xlsx"))
        .arg(sample("sorting_station.xlsx"))
        .arg("-o")
        .arg(&out)
        .args(["--formats", "faults", "--quiet"])
        .assert()
        .success();
    let summary = std::fs::read_to_string(out.join("summary.csv")).unwrap();
    let mut reader = csv::Reader::from_reader(summary.as_bytes());
    let header: Vec<String> = reader
        .headers()
        .unwrap()
        .iter()
        .map(str::to_string)
        .collect();
    assert_eq!(header[8..], ["verdict", "cycle seconds", "hazards"]);
    for row in reader.records() {
        let row = row.unwrap();
        let name = &row[7];
        let faults =
            std::fs::read_to_string(out.join(name).join(format!("{name}.faults.csv"))).unwrap();
        let hazards = csv::Reader::from_reader(faults.as_bytes())
            .records()
            .filter(|r| &r.as_ref().unwrap()[3] == "hazard")
            .count();
        assert!(hazards > 0, "{name}");
        assert_eq!(row[10], hazards.to_string(), "{name}");
        let seconds: f64 = row[9].parse().unwrap();
        assert_eq!(
            row[8],
            format!("passed: cycle time {seconds:.2} s"),
            "{name}"
        );
    }
}

/// A batch rerun with fewer formats keeps an output the engineer edited
/// and says so in its summary lines, as `convert` does (it kept it
/// without a word).
#[test]
fn a_batch_rerun_says_what_it_kept() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("in");
    std::fs::create_dir(&input).unwrap();
    std::fs::copy(sample("paper_example.csv"), input.join("line.csv")).unwrap();
    let out = dir.path().join("out");
    let batch = |formats: &str| {
        let out_ = steptable()
            .arg("batch")
            .arg(&input)
            .arg("-o")
            .arg(&out)
            .args(["--formats", formats])
            .output()
            .unwrap();
        assert!(out_.status.success(), "{out_:?}");
        String::from_utf8(out_.stdout).unwrap()
    };
    batch("st,sdf");
    std::fs::write(out.join("line/line.sdf"), "my notes").unwrap();
    let said = batch("st");
    let line = said
        .lines()
        .find(|l| l.contains("kept in"))
        .unwrap_or_else(|| panic!("{said}"));
    assert!(
        line.contains("line.sdf (changed since steptable wrote it"),
        "{line}"
    );
    assert_eq!(
        std::fs::read_to_string(out.join("line/line.sdf")).unwrap(),
        "my notes"
    );
    assert!(!batch("st").contains("kept in"), "said once");
}
