//! The template workbook after LibreOffice opened and saved it: the EXAMPLE
//! sheet still converts to the same files as the bundled sample.

use crate::helpers::{program_texts, sample, steptable};
use crate::{Check, Tool, tool};

pub const CHECKS: &[Check] = &[Check::new(
    "libreoffice::the_templates_example_converts_like_the_sample_after_libreoffice",
    &[Tool::Soffice],
    the_templates_example_converts_like_the_sample_after_libreoffice,
)];

fn the_templates_example_converts_like_the_sample_after_libreoffice() {
    let dir = tempfile::tempdir().unwrap();
    let template = dir.path().join("paper_example.xlsx");
    steptable()
        .arg("template")
        .arg("-o")
        .arg(&template)
        .assert()
        .success();
    let saved = dir.path().join("libreoffice");
    let status = std::process::Command::new(tool(Tool::Soffice))
        .args(["--headless", "--convert-to", "xlsx", "--outdir"])
        .arg(&saved)
        .arg(&template)
        .env("HOME", dir.path())
        .output()
        .unwrap();
    assert!(
        status.status.success(),
        "{}",
        String::from_utf8_lossy(&status.stderr)
    );
    let expected = program_texts(
        &sample("paper_example.xlsx"),
        &dir.path().join("sample"),
        None,
    );
    let got = program_texts(
        &saved.join("paper_example.xlsx"),
        &dir.path().join("t"),
        Some("EXAMPLE"),
    );
    assert_eq!(got, expected);
}
