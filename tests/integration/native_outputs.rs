//! Issue 41, the TIA Portal SCL source (`NAME.scl`) and the Studio 5000
//! program (`NAME.L5X`): what an engineer may do wrong on the way to them,
//! each row through the binary (exit code, code, cell, message, nothing
//! written), and what the files hold for the engineer's names. What they
//! do in a PLC is proven in `tests/tools/differential_native.rs`.

use std::path::Path;

use crate::helpers::{files_below, steptable};

/// A table whose STEP 2 cell (CSV 3:2) holds `item` beside `C1-0`.
fn table_with(dir: &Path, name: &str, item: &str) -> std::path::PathBuf {
    let path = dir.join(format!("{name}.csv"));
    std::fs::write(
        &path,
        format!(",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C1-0; {item}\nSTEP 3,C2+1\nSTEP 4,C2-0\n"),
    )
    .unwrap();
    path
}

/// Every hostile row: exit 1, its code, cell and words, nothing written.
#[test]
fn hostile_inputs_to_the_scl_and_l5x_outputs_are_refused_at_their_place() {
    let dir = tempfile::tempdir().unwrap();
    // (what, STEP 2's extra item, --formats, expected stderr parts)
    let rows: &[(&str, &str, &str, &[&str])] = &[
        (
            "a format repeated",
            "I:part",
            "scl,scl",
            &["\"scl\" is given twice"],
        ),
        (
            "the same format in another case",
            "I:part",
            "l5x,L5X",
            &["\"l5x\" is given twice"],
        ),
        (
            "all beside a format",
            "I:part",
            "all,l5x",
            &["\"all\" stands alone"],
        ),
        (
            "an empty item",
            "I:part",
            "scl,,l5x",
            &["has an empty item"],
        ),
        (
            "a near miss",
            "I:part",
            "scll",
            &["\"scll\" is not an output format", "did you mean scl"],
        ),
        ("a doubled letter", "I:part", "l5xx", &["did you mean l5x"]),
        (
            "an input named as the cyclic OB the SCL replaces",
            "I:Main",
            "scl",
            &[
                "error[E015]",
                ":3:2:",
                "\"main\" cannot name a machine signal",
            ],
        ),
        (
            "an output named as the L5X's program",
            "Y:MainProgram+",
            "l5x",
            &["error[E015]", ":3:2:", "\"mainprogram\" cannot name"],
        ),
        (
            "an input named as the L5X's routine, in other case",
            "I:MAINROUTINE",
            "l5x",
            &["error[E015]", ":3:2:", "\"mainroutine\" cannot name"],
        ),
        (
            "an input named as a step flag of the L5X",
            "I:step_3",
            "l5x",
            &["error[E015]", ":3:2:", "\"step_3\" cannot name"],
        ),
        (
            "an output named as an SCL timer's run flag",
            "Y:dwell1_run+",
            "scl",
            &["error[E015]", ":3:2:", "\"dwell1_run\" cannot name"],
        ),
        (
            "a name Logix refuses (double underscore)",
            "I:part__ok",
            "l5x",
            &["error[E015]", ":3:2:", "forbids a double or trailing _"],
        ),
    ];
    for (k, (what, item, formats, wanted)) in rows.iter().enumerate() {
        let input = table_with(dir.path(), &format!("t{k}"), item);
        let out = dir.path().join(format!("out{k}"));
        let output = steptable()
            .arg("convert")
            .arg(&input)
            .args(["--formats", formats, "-o"])
            .arg(&out)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(1), "{what}: {stderr}");
        for part in *wanted {
            assert!(stderr.contains(part), "{what}: {part:?} not in {stderr}");
        }
        assert!(
            files_below(&out).is_empty(),
            "{what}: something was written"
        );
    }
}

/// The engineer's names reach both files: a name that only looks like a
/// reserved one (`mains`) is a quoted PLC tag in the SCL and a controller
/// tag in the L5X, with its address from the tag lists beside them.
#[test]
fn names_close_to_the_reserved_ones_are_tags_in_both_files() {
    let dir = tempfile::tempdir().unwrap();
    let input = table_with(dir.path(), "close", "I:mains");
    let out = dir.path().join("out");
    steptable()
        .arg("convert")
        .arg(&input)
        .args(["--target", "siemens", "--formats", "scl,l5x,rockwell", "-o"])
        .arg(&out)
        .assert()
        .success();
    let folder = out.join("close");
    let scl = std::fs::read_to_string(folder.join("close.scl")).unwrap();
    assert!(scl.contains("IF \"x10\" AND \"mains\" THEN"), "{scl}");
    assert!(scl.contains("ORGANIZATION_BLOCK \"Main\""));
    assert!(scl.contains("#active_step := 2;"));
    let l5x = std::fs::read_to_string(folder.join("close.L5X")).unwrap();
    assert!(l5x.contains("XIC(mains)"), "{l5x}");
    let csv = std::fs::read_to_string(folder.join("close.rockwell.csv")).unwrap();
    assert!(csv.contains("TAG,,mains,\"I0.5 "), "{csv}");
    assert!(l5x.contains("<Tag Name=\"mains\" TagType=\"Base\" DataType=\"BOOL\""));
}
