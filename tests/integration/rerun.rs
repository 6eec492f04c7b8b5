//! A rerun leaves no output of an earlier run that this one did not write:
//! with fewer `--formats` the folder must not hold the old AWL and
//! allocation list beside the new program. What the engineer changed since
//! is kept.

use predicates::prelude::PredicateBooleanExt;
use predicates::str::contains;

use crate::helpers::{sample, steptable};

#[test]
fn a_rerun_with_fewer_formats_removes_the_earlier_runs_other_files() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("line.csv");
    std::fs::copy(sample("paper_example.csv"), &input).unwrap();
    let out = dir.path().join("out");
    let folder = out.join("line");
    steptable()
        .arg("convert")
        .arg(&input)
        .arg("-o")
        .arg(&out)
        .assert()
        .success();
    assert!(folder.join("line.awl").exists() && folder.join("line.io.csv").exists());
    // The engineer edits one output; the rerun must keep it.
    std::fs::write(folder.join("line.sdf"), "my notes").unwrap();
    std::fs::write(&input, "C1+1\nC1-0\n").unwrap();
    steptable()
        .args(["convert", "--formats", "st"])
        .arg(&input)
        .arg("-o")
        .arg(&out)
        .assert()
        .success()
        .stdout(contains(
            "removed what an earlier run wrote there and this one did not: ",
        ))
        .stdout(contains("line.awl"));
    let left: Vec<String> = std::fs::read_dir(&folder)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
        .filter(|n| !n.starts_with('.'))
        .collect();
    let mut left = left;
    left.sort();
    // The emptied project folder (line.beremiz/) goes too.
    assert_eq!(left, ["line.sdf", "line.st"], "{left:?}");
    assert_eq!(
        std::fs::read_to_string(folder.join("line.sdf")).unwrap(),
        "my notes"
    );
    // A rerun of the same conversion removes nothing.
    steptable()
        .args(["convert", "--formats", "st"])
        .arg(&input)
        .arg("-o")
        .arg(&out)
        .assert()
        .success()
        .stdout(predicates::str::contains("removed").not());
}

/// A manifest is a file anyone can edit: an entry that leads out of the
/// output folder (`../`, an absolute path) never removes anything there.
#[test]
fn a_manifest_entry_outside_the_folder_removes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("p.csv");
    std::fs::copy(sample("paper_example.csv"), &input).unwrap();
    let precious = dir.path().join("precious.txt");
    let absolute = dir.path().join("absolute.txt");
    std::fs::write(&precious, "precious\n").unwrap();
    std::fs::write(&absolute, "precious\n").unwrap();
    let out = dir.path().join("out");
    let convert = || {
        steptable()
            .args(["convert", "--formats", "st", "-o"])
            .arg(&out)
            .arg(&input)
            .assert()
            .success()
    };
    convert();
    // The stamp of "precious\n" (9 bytes), as the manifest writes it.
    let manifest = out.join("p/.steptable-manifest");
    let mut text = std::fs::read_to_string(&manifest).unwrap();
    let stamp = steptable::manifest::Stamp::of(b"precious\n");
    for name in [
        "../../precious.txt".to_string(),
        absolute.display().to_string(),
    ] {
        text.push_str(&format!("{} {:016x} {name}\n", stamp.size, stamp.hash));
    }
    std::fs::write(&manifest, text).unwrap();
    convert().stdout(contains("removed").not());
    assert!(precious.exists() && absolute.exists());
}
