//! Invisible characters a cell can hold (Word's soft line break pasted into
//! Excel is stored as `_x000B_`, a vertical tab; a bell or escape from a
//! terminal; the noncharacters U+FFFE and U+FFFF) are read as what they
//! show: a line break or nothing. Before, they reached the GRAFCET, the
//! diagram and every XML file, which then no longer parsed (exit 0).

use crate::helpers::{files_with_bytes, steptable, write_xlsx_sheets};

/// Characters XML 1.0 forbids in a document (and that no PLC text
/// format expects): C0 controls but tab, line feed and carriage return,
/// and the noncharacters U+FFFE and U+FFFF.
fn forbidden(text: &str) -> Option<char> {
    text.chars().find(|&c| {
        (c.is_control() && !matches!(c, '\t' | '\n' | '\r')) || matches!(c, '\u{fffe}' | '\u{ffff}')
    })
}

#[test]
fn no_written_file_carries_an_invisible_character_of_a_cell() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("soft.xlsx");
    let table: &[&[&str]] = &[
        &["", "BRANCH 1"],
        &["STEP 1 (clamp\u{b}part)", "C1+1"],
        &["STEP 2 (bell\u{7} and escape\u{1b})", "C2+1"],
        &["STEP 3 (odd\u{fffe}\u{ffff} end)", "C2-0"],
        &["STEP 4", "C1-0"],
    ];
    let settings: &[&[&str]] = &[
        &["actuator", "extend", "retract"],
        &["C1 (clamp)", "1s", "1s"],
        &["C2 (lift\u{b}unit)"],
    ];
    write_xlsx_sheets(
        &input,
        &[
            ("SEQUENTIAL CONTROL DESCRIPTION", table),
            ("SETTINGS", settings),
        ],
    );
    let out = dir.path().join("out");
    let output = steptable()
        .arg("convert")
        .arg(&input)
        .args(["--formats", "all", "-o"])
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    let files = files_with_bytes(&out);
    assert!(files.len() > 15, "{}", files.len());
    let mut texts = 0;
    for (path, bytes) in files {
        // Workbooks are zipped XML: their parts are checked as written
        // by the XML writer, which escapes controls itself.
        let Ok(text) = String::from_utf8(bytes) else {
            continue;
        };
        texts += 1;
        if let Some(c) = forbidden(&text) {
            panic!("{} holds U+{:04X}", path.display(), c as u32);
        }
    }
    assert!(texts > 10, "{texts}");
    // The comment is still there, its soft break a line break or a space.
    let st = std::fs::read_to_string(out.join("soft").join("soft.st")).unwrap();
    assert!(st.contains("clamp") && st.contains("part"), "{st}");
    assert!(st.contains("bell and escape"), "{st}");
}
