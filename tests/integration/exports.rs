//! Exports to other engineering tools: layouts, file selection, user
//! templates. The checks by other tools (xmllint, blark) and the engines
//! live in `tests/tools/`.

use std::path::Path;

use predicates::prelude::PredicateBooleanExt;
use predicates::str::contains;

use crate::helpers::{files_below, read_sheet, sample, steptable};

#[test]
fn tia_tag_table_has_the_import_layout() {
    let dir = tempfile::tempdir().unwrap();
    steptable()
        .arg("convert")
        .arg(sample("paper_example.xlsx"))
        .args(["--formats", "tia", "-o"])
        .arg(dir.path())
        .assert()
        .success();
    let path = dir.path().join("paper_example/paper_example.tags.xlsx");
    assert_eq!(files_below(dir.path()), std::slice::from_ref(&path));
    let rows = read_sheet(&path, "PLC Tags");
    assert_eq!(
        rows[0],
        [
            "Name",
            "Path",
            "Data Type",
            "Logical Address",
            "Comment",
            "Hmi Visible",
            "Hmi Accessible",
            "Hmi Writeable",
            "Typeobject ID",
            "Version ID"
        ]
    );
    assert_eq!(
        rows[1][..4],
        ["START", "Default tag table", "Bool", "%I0.0"]
    );
    // Festo I0.10 is the low bit 2 of the second byte.
    assert!(rows.iter().any(|r| r[0] == "x40" && r[3] == "%I1.2"));
    assert!(rows.iter().any(|r| r[0] == "y1m" && r[3] == "%Q2.1"));
    assert!(
        rows[1..]
            .iter()
            .all(|r| r[3].starts_with("%I") || r[3].starts_with("%Q"))
    );
}

#[test]
fn formats_selects_the_files() {
    let dir = tempfile::tempdir().unwrap();
    steptable()
        .arg("convert")
        .arg(sample("paper_example.xlsx"))
        .args(["--formats", "st,awl,sdf,gvl,fst-alloc,rockwell", "-o"])
        .arg(dir.path())
        .assert()
        .success();
    let names: Vec<String> = files_below(dir.path())
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().to_string())
        .collect();
    assert_eq!(
        names,
        [
            "paper_example.awl",
            "paper_example.fst-alloc.csv",
            "paper_example.gvl.txt",
            "paper_example.rockwell.csv",
            "paper_example.sdf",
            "paper_example.st"
        ]
    );
    steptable()
        .arg("convert")
        .arg(sample("paper_example.xlsx"))
        .args(["--formats", "st,pdf"])
        .assert()
        .code(1)
        .stderr(contains("\"pdf\" is not an output format"));
}

/// Changing one template changes that output and nothing else; exported
/// defaults reproduce the built-in outputs byte for byte.
#[test]
fn templates_export_round_trips_and_one_override_changes_one_file() {
    let dir = tempfile::tempdir().unwrap();
    let templates = dir.path().join("templates");
    steptable()
        .args(["templates", "export"])
        .arg(&templates)
        .assert()
        .success()
        .stdout(contains("program.awl.j2"));
    // Every output records its command line, `--templates templates`
    // too: the built-in run names an empty folder of that name, so that
    // only the templates' text can make a difference.
    let empty = dir.path().join("empty").join("templates");
    std::fs::create_dir_all(&empty).unwrap();
    let convert = |out: &str, with_templates: bool| {
        let mut cmd = steptable();
        cmd.arg("convert")
            .arg(sample("paper_example.xlsx"))
            .arg("-o")
            .arg(dir.path().join(out))
            .arg("--templates")
            .arg(if with_templates { &templates } else { &empty });
        cmd.assert().success();
        let folder = dir.path().join(out).join("paper_example");
        files_below(&folder)
            .into_iter()
            .map(|p| {
                (
                    p.file_name().unwrap().to_string_lossy().to_string(),
                    std::fs::read(&p).unwrap(),
                )
            })
            .collect::<Vec<_>>()
    };
    let builtin = convert("builtin", false);
    assert_eq!(
        convert("exported", true),
        builtin,
        "exported defaults must give identical files"
    );

    let gvl = templates.join("gvl.txt.j2");
    let text = std::fs::read_to_string(&gvl).unwrap();
    std::fs::write(
        &gvl,
        text.replace("VAR_GLOBAL", "VAR_GLOBAL (* house style *)"),
    )
    .unwrap();
    let changed = convert("changed", true);
    for ((name, before), (_, after)) in builtin.iter().zip(&changed) {
        if name.ends_with(".gvl.txt") {
            assert_ne!(before, after, "{name} should change");
            assert!(String::from_utf8_lossy(after).contains("(* house style *)"));
        } else {
            assert_eq!(before, after, "{name} should not change");
        }
    }
}

#[test]
fn a_broken_user_template_names_file_line_and_variable() {
    let dir = tempfile::tempdir().unwrap();
    let templates = dir.path().join("templates");
    std::fs::create_dir(&templates).unwrap();
    std::fs::write(
        templates.join("program.awl.j2"),
        "ORGANIZATION_BLOCK OB 1\n{{ networks | length }}\n{{ netwerks }}\n",
    )
    .unwrap();
    let convert = || {
        steptable()
            .arg("convert")
            .arg(sample("paper_example.xlsx"))
            .arg("--templates")
            .arg(&templates)
            .arg("-o")
            .arg(dir.path().join("out"))
            .assert()
            .code(1)
    };
    convert()
        .stderr(contains("program.awl.j2:3: `netwerks` is undefined"))
        .stderr(contains("nothing written"));
    assert!(files_below(&dir.path().join("out")).is_empty());
    // Two broken: the one of the kind listed first is reported, though the
    // outputs render side by side (the CoDeSys V2.3 export with the other
    // IEC files, the Rockwell list alone).
    std::fs::remove_file(templates.join("program.awl.j2")).unwrap();
    std::fs::write(templates.join("program.exp.j2"), "{{ exp_typo }}\n").unwrap();
    std::fs::write(templates.join("rockwell.csv.j2"), "{{ rockwell_typo }}\n").unwrap();
    for _ in 0..5 {
        convert()
            .stderr(contains("rockwell.csv.j2:1: `rockwell_typo` is undefined"))
            .stderr(contains("exp_typo").not());
    }
}

/// The lists Windows tools import use CRLF; the CoDeSys V2.3 export has the
/// markers of CoDeSys' own export files; the Beremiz project folder holds
/// the PLCopen XML as plc.xml beside beremiz.xml; the TIA tag table carries
/// TIA_Version and German %E/%A addresses with --mnemonic de.
#[test]
fn windows_lists_codesys_v2_beremiz_and_tia_details() {
    let dir = tempfile::tempdir().unwrap();
    steptable()
        .arg("convert")
        .arg(sample("press_station.xlsx"))
        .args(["--mnemonic", "de", "--target", "siemens", "-o"])
        .arg(dir.path())
        .assert()
        .success();
    let out = dir.path().join("press_station");
    for suffix in [".sdf", ".rockwell.csv", ".fst-alloc.csv", ".exp"] {
        let bytes = std::fs::read(out.join(format!("press_station{suffix}"))).unwrap();
        let text = String::from_utf8(bytes).unwrap();
        let lf = text.matches('\n').count();
        assert!(lf > 3, "{suffix}");
        assert_eq!(
            text.matches("\r\n").count(),
            lf,
            "{suffix}: every line ends in CRLF"
        );
    }
    // The others keep Unix line ends: no CR anywhere.
    for suffix in [
        ".st",
        ".io.csv",
        ".awl",
        ".faults.csv",
        ".plcopen.xml",
        ".fst.txt",
    ] {
        let bytes = std::fs::read(out.join(format!("press_station{suffix}"))).unwrap();
        assert!(!bytes.contains(&b'\r'), "{suffix}: a CR");
    }
    let exp = std::fs::read_to_string(out.join("press_station.exp")).unwrap();
    for marker in [
        "(* @NESTEDCOMMENTS := 'Yes' *)",
        "(* @GLOBAL_VARIABLE_LIST := 'GVL_IO' *)",
        "(* @PATH := '' *)",
        "(* @OBJECTFLAGS := '0, 8' *)",
        "(* @END_DECLARATION := '0' *)",
        "(* @OBJECT_END := 'GVL_IO' *)",
        "PROGRAM steptable_main\r\n",
        "part_present AT %IX0.7 : BOOL;",
    ] {
        assert!(exp.contains(marker), "{marker}: {exp}");
    }
    let beremiz = out.join("press_station.beremiz");
    assert_eq!(
        std::fs::read(beremiz.join("plc.xml")).unwrap(),
        std::fs::read(out.join("press_station.plcopen.xml")).unwrap()
    );
    let project = std::fs::read_to_string(beremiz.join("beremiz.xml")).unwrap();
    assert!(project.contains("<BeremizRoot") && project.contains("<TargetType/>"));
    let tags = out.join("press_station.tags.xlsx");
    let custom = crate::helpers::xlsx_part(&tags, "docProps/custom.xml");
    assert!(custom.contains("name=\"TIA_Version\""), "{custom}");
    let rows = read_sheet(&tags, "PLC Tags");
    assert!(
        rows[1..]
            .iter()
            .all(|r| r[3].starts_with("%E") || r[3].starts_with("%A")),
        "{rows:?}"
    );
}

/// A user's template can neither crash steptable nor keep it busy for ever:
/// a huge `pad` width is capped, a runaway loop runs out of fuel (exit 1,
/// the template named, nothing written).
#[test]
fn runaway_user_templates_are_stopped() {
    let dir = tempfile::tempdir().unwrap();
    let templates = dir.path().join("t");
    std::fs::create_dir_all(&templates).unwrap();
    let convert_with = |template: &str, out: &Path| {
        std::fs::write(templates.join("gvl.txt.j2"), template).unwrap();
        let mut cmd = steptable();
        cmd.arg("convert")
            .arg(sample("paper_example.xlsx"))
            .args(["--formats", "gvl", "--templates"])
            .arg(&templates)
            .arg("-o")
            .arg(out);
        cmd.assert()
    };
    let out = dir.path().join("out1");
    convert_with("{{ title | pad(70000) }}|\n", &out).success();
    let gvl = std::fs::read_to_string(out.join("paper_example/paper_example.gvl.txt")).unwrap();
    // After the line that says how it was made, the template's one line.
    let (made_by, gvl) = gvl.split_once('\n').unwrap();
    assert!(made_by.starts_with("(* made by steptable"), "{made_by}");
    assert_eq!(gvl.trim_end().len(), 1001, "padded to the 1,000-column cap");
    let out = dir.path().join("out2");
    let started = std::time::Instant::now();
    convert_with(
        "{% for a in range(100000) %}{% for b in range(100000) %}.{% endfor %}{% endfor %}\n",
        &out,
    )
    .code(1)
    .stderr(contains("gvl.txt.j2"));
    assert!(started.elapsed() < std::time::Duration::from_secs(120));
    assert!(files_below(&out).is_empty());
}
