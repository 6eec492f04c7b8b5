//! Batch conversion of a folder mixing good, bad and colliding files.

use predicates::prelude::*;
use predicates::str::contains;

use crate::helpers::{files_below, sample, steptable};

fn folder_of_inputs(dir: &std::path::Path) -> std::path::PathBuf {
    let input = dir.join("in");
    std::fs::create_dir_all(input.join("a")).unwrap();
    std::fs::create_dir_all(input.join("b")).unwrap();
    std::fs::copy(sample("paper_example.xlsx"), input.join("a/line.xlsx")).unwrap();
    std::fs::copy(sample("transfer_line.xlsx"), input.join("b/line.xlsx")).unwrap();
    std::fs::copy(sample("drilling_station.xlsx"), input.join("drill.xlsx")).unwrap();
    std::fs::write(
        input.join("bad.csv"),
        ",BRANCH 1\nSTEP 1,C1+x\nSTEP 2,C1-0\n",
    )
    .unwrap();
    std::fs::write(input.join("notes.txt"), "not a table").unwrap();
    std::fs::write(input.join("~$drill.xlsx"), "Excel lock file").unwrap();
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
        .stdout(contains("failed: ").and(contains("bad.csv:2:2: error[E010]")));

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
    assert_eq!(objects.len(), 2, "{stdout}");
    assert_eq!(objects[0]["code"], "E010");
    assert_eq!(objects[0]["row"], 2);
    assert_eq!(objects[0]["column"], 2);
    assert_eq!(objects[1]["code"], "E020");
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert!(
        stderr.contains("missing.xlsx: error: no such file or folder"),
        "{stderr}"
    );
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
