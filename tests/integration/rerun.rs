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

/// The ways a rerun with fewer formats could take what the engineer still
/// needs (red team rt8, findings 2, 3 and 11), each kept and said, and no
/// longer in the record: a project folder linked elsewhere (its files
/// were removed through the link), a project folder whose `plc.xml` was
/// edited in Beremiz (its `beremiz.xml` was removed, so the folder no
/// longer opened), an output named as an input of the same run (it was
/// removed before it was read: E001), an edited output.
#[cfg(unix)]
#[test]
fn a_rerun_keeps_and_says_what_the_engineer_may_still_need() {
    struct Case {
        what: &'static str,
        first: &'static str,
        then: &'static str,
        /// What the engineer does between the two runs, in the output
        /// folder `pe/`; returns the extra inputs of the second run.
        meddle: fn(&std::path::Path) -> Vec<std::path::PathBuf>,
        kept: &'static [(&'static str, &'static str)],
    }
    let cases = [
        Case {
            what: "a linked project folder",
            first: "beremiz-sfc,st",
            then: "st",
            meddle: |pe| {
                let away = pe.parent().unwrap().parent().unwrap().join("elsewhere");
                std::fs::rename(pe.join("pe.sfc.beremiz"), &away).unwrap();
                std::os::unix::fs::symlink(&away, pe.join("pe.sfc.beremiz")).unwrap();
                Vec::new()
            },
            kept: &[
                ("pe.sfc.beremiz/beremiz.xml", "reached through a link"),
                ("pe.sfc.beremiz/plc.xml", "reached through a link"),
            ],
        },
        Case {
            what: "a project folder with an edited plc.xml",
            first: "beremiz-ld,st",
            then: "ld,st",
            meddle: |pe| {
                let plc = pe.join("pe.ld.beremiz/plc.xml");
                let mut text = std::fs::read_to_string(&plc).unwrap();
                text.push_str("<!-- edited -->\n");
                std::fs::write(plc, text).unwrap();
                Vec::new()
            },
            kept: &[
                ("pe.ld.beremiz/beremiz.xml", "opens only whole"),
                ("pe.ld.beremiz/plc.xml", "changed since steptable wrote it"),
            ],
        },
        Case {
            what: "an output named as an input of the rerun",
            first: "xlsx,st",
            then: "st",
            meddle: |pe| vec![pe.join("pe.steptable.xlsx")],
            kept: &[("pe.steptable.xlsx", "an input of this run")],
        },
    ];
    for case in cases {
        let dir = tempfile::tempdir().unwrap();
        let input = dir.path().join("pe.xlsx");
        std::fs::copy(sample("paper_example.xlsx"), &input).unwrap();
        let out = dir.path().join("out");
        let pe = out.join("pe");
        let run = |formats: &str, extra: &[std::path::PathBuf]| {
            steptable()
                .args(["convert", "--formats", formats, "-o"])
                .arg(&out)
                .arg(&input)
                .args(extra)
                .output()
                .unwrap()
        };
        assert!(run(case.first, &[]).status.success(), "{}", case.what);
        let extra = (case.meddle)(&pe);
        let second = run(case.then, &extra);
        let said = String::from_utf8_lossy(&second.stdout).to_string();
        let line = said
            .lines()
            .find(|l| l.contains("kept what an earlier run wrote"))
            .unwrap_or_else(|| panic!("{}: {said}", case.what));
        for (name, why) in case.kept {
            let path = pe.join(name);
            assert!(path.exists(), "{}: {name} gone", case.what);
            assert!(line.contains(&format!("{name} (")), "{}: {line}", case.what);
            assert!(line.contains(why), "{}: {line}", case.what);
        }
        assert!(!said.contains("removed what"), "{}: {said}", case.what);
        assert!(second.status.success(), "{}: {second:?}", case.what);
        // Said once: the record no longer holds them.
        let third = run(case.then, &[]);
        let said = String::from_utf8_lossy(&third.stdout).to_string();
        assert!(!said.contains("kept what"), "{}: {said}", case.what);
    }
}
