//! The template workbook after LibreOffice opened and saved it: the EXAMPLE
//! sheet still converts to the same files as the bundled sample. The output
//! workbook printed by LibreOffice: each sheet on the pages
//! docs/outputs.md states.

use std::io::{Read, Write};
use std::path::{Path, PathBuf};

use crate::helpers::{program_texts, root, sample, steptable};
use crate::{Check, Tool, tool};

pub const CHECKS: &[Check] = &[
    Check::new(
        "libreoffice::the_templates_example_converts_like_the_sample_after_libreoffice",
        &[Tool::Soffice],
        the_templates_example_converts_like_the_sample_after_libreoffice,
    ),
    Check::new(
        "libreoffice::the_workbook_prints_the_pages_the_docs_state",
        &[Tool::Soffice],
        the_workbook_prints_the_pages_the_docs_state,
    ),
];

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

/// The pages each sheet of a sample's workbook prints on, as the table
/// under "Printing" in docs/outputs.md states them: `(sample, [(sheet,
/// pages)])`.
fn stated_pages() -> Vec<(String, Vec<(String, usize)>)> {
    let doc = std::fs::read_to_string(root().join("docs/outputs.md")).unwrap();
    let table: Vec<Vec<String>> = doc
        .split("<!-- page counts -->")
        .nth(1)
        .expect("the page counts in docs/outputs.md")
        .lines()
        .skip(1)
        .take_while(|l| l.starts_with('|'))
        .map(|l| {
            l.trim_matches('|')
                .split('|')
                .map(|c| c.trim().trim_matches('`').to_string())
                .collect()
        })
        .collect();
    let sheets = &table[0][1..];
    table[2..]
        .iter()
        .map(|row| {
            let pages = sheets
                .iter()
                .zip(&row[1..])
                .map(|(sheet, n)| (sheet.clone(), n.parse().expect(n)))
                .collect();
            (row[0].clone(), pages)
        })
        .collect()
}

/// A copy of the workbook with every sheet but `keep` hidden, which
/// LibreOffice does not print: one PDF per sheet.
fn only_sheet(book: &Path, keep: usize, to: &Path) {
    let mut archive = zip::ZipArchive::new(std::fs::File::open(book).unwrap()).unwrap();
    let mut out = zip::ZipWriter::new(std::fs::File::create(to).unwrap());
    for i in 0..archive.len() {
        let mut entry = archive.by_index(i).unwrap();
        let name = entry.name().unwrap().to_string();
        let mut bytes = Vec::new();
        entry.read_to_end(&mut bytes).unwrap();
        if name == "xl/workbook.xml" {
            let xml = String::from_utf8(bytes).unwrap();
            let mut parts = xml.split("<sheet ");
            let mut edited = parts.next().unwrap().to_string();
            for (k, part) in parts.enumerate() {
                edited.push_str(if k == keep {
                    "<sheet "
                } else {
                    "<sheet state=\"hidden\" "
                });
                edited.push_str(part);
            }
            bytes = edited
                .replace(
                    "<workbookView ",
                    &format!("<workbookView activeTab=\"{keep}\" "),
                )
                .into_bytes();
        }
        out.start_file(name, zip::write::SimpleFileOptions::default())
            .unwrap();
        out.write_all(&bytes).unwrap();
    }
    out.finish().unwrap();
}

/// Pages of a PDF: its `/Type /Page` objects (not the `/Pages` tree).
fn pdf_pages(pdf: &Path) -> usize {
    let bytes = std::fs::read(pdf).unwrap();
    let text = String::from_utf8_lossy(&bytes);
    let squeezed = text.replace("/Type /Page", "/Type/Page");
    squeezed.matches("/Type/Page").count() - squeezed.matches("/Type/Pages").count()
}

fn the_workbook_prints_the_pages_the_docs_state() {
    let stated = stated_pages();
    assert!(stated.len() >= 2, "{stated:?}");
    let dir = tempfile::tempdir().unwrap();
    let mut books: Vec<(String, String, PathBuf)> = Vec::new();
    for (name, pages) in &stated {
        steptable()
            .arg("convert")
            .arg(sample(&format!("{name}.xlsx")))
            .args(["--formats", "xlsx", "-o"])
            .arg(dir.path())
            .assert()
            .success();
        let book = dir.path().join(format!("{name}/{name}.steptable.xlsx"));
        for (k, (sheet, _)) in pages.iter().enumerate() {
            let one = dir.path().join(format!("{name}-{k}.xlsx"));
            only_sheet(&book, k, &one);
            books.push((name.clone(), sheet.clone(), one));
        }
    }
    let pdfs = dir.path().join("pdf");
    let status = std::process::Command::new(tool(Tool::Soffice))
        .args(["--headless", "--convert-to", "pdf", "--outdir"])
        .arg(&pdfs)
        .args(books.iter().map(|b| &b.2))
        .env("HOME", dir.path())
        .output()
        .unwrap();
    assert!(
        status.status.success(),
        "{}",
        String::from_utf8_lossy(&status.stderr)
    );
    let mut got = Vec::new();
    for (name, sheet, one) in &books {
        let pdf = pdfs.join(one.file_stem().unwrap()).with_extension("pdf");
        got.push((name.clone(), sheet.clone(), pdf_pages(&pdf)));
    }
    let expected: Vec<(String, String, usize)> = stated
        .iter()
        .flat_map(|(name, pages)| {
            pages
                .iter()
                .map(move |(sheet, n)| (name.clone(), sheet.clone(), *n))
        })
        .collect();
    assert_eq!(got, expected);
}
