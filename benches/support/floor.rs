//! The I/O floor of a batch conversion: what no converter can avoid, done
//! as cheaply as the same crates allow. Read the workbook with calamine;
//! write a four-sheet workbook of its cells (no charts) with
//! rust_xlsxwriter; write the same bytes as steptable's other outputs, each
//! through a temporary file and a rename. `batch` prints steptable's times
//! beside it, from the same run and the same files.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use calamine::{Data, Reader, open_workbook_auto};
use rust_xlsxwriter::Workbook;
use steptable::emit::OutputFile;

/// One input's floor work.
pub fn one(input: &Path, texts: &[OutputFile], out: &Path) {
    let mut workbook = open_workbook_auto(input).expect("a workbook");
    let sheet = workbook.sheet_names()[0].clone();
    let range = workbook.worksheet_range(&sheet).expect("a sheet");
    let cells: Vec<(u32, u32, String)> = range
        .used_cells()
        .filter(|(_, _, d)| !matches!(d, Data::Empty))
        .map(|(r, c, d)| (r as u32, c as u32, d.to_string()))
        .collect();
    let name = input.file_stem().unwrap().to_string_lossy().to_string();
    let folder = out.join(&name);
    std::fs::create_dir_all(&folder).unwrap();
    let mut book = Workbook::new();
    for title in [
        "TABLE",
        "INPUT ADDRESSES",
        "OUTPUT ADDRESSES",
        "PLC PROGRAM",
    ] {
        let sheet = book.add_worksheet();
        sheet.set_name(title).unwrap();
        for (r, c, text) in &cells {
            sheet.write_string(*r, *c as u16, text).unwrap();
        }
    }
    let bytes = book.save_to_buffer().unwrap();
    let mut files = vec![(format!("{name}.xlsx"), bytes)];
    files.extend(texts.iter().map(|f| (f.name.clone(), f.bytes.clone())));
    for (file, bytes) in files {
        let target = folder.join(&file);
        if let Some(parent) = target.parent() {
            std::fs::create_dir_all(parent).unwrap();
        }
        let mut temp = tempfile::NamedTempFile::new_in(target.parent().unwrap()).unwrap();
        std::io::Write::write_all(&mut temp, &bytes).unwrap();
        temp.persist(&target).unwrap();
    }
}

/// The floor over every input on `jobs` threads; `texts[i]` are the bytes of
/// input i's outputs other than its workbook.
pub fn run(inputs: &[PathBuf], texts: &[Vec<OutputFile>], out: &Path, jobs: usize) -> Duration {
    use rayon::prelude::*;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs)
        .build()
        .unwrap();
    let start = Instant::now();
    pool.install(|| {
        inputs
            .par_iter()
            .zip(texts)
            .for_each(|(input, texts)| one(input, texts, out));
    });
    start.elapsed()
}

/// The floor as a whole process (the bench binary started again with
/// `STEPTABLE_FLOOR_ONE=input`, `STEPTABLE_FLOOR_OUT=folder` and
/// `STEPTABLE_FLOOR_FILES=name:length,…`): one input's work with files of
/// the other outputs' names and lengths. Returns whether it was asked for.
pub fn one_as_process() -> bool {
    let (Ok(input), Ok(out), Ok(files)) = (
        std::env::var("STEPTABLE_FLOOR_ONE"),
        std::env::var("STEPTABLE_FLOOR_OUT"),
        std::env::var("STEPTABLE_FLOOR_FILES"),
    ) else {
        return false;
    };
    let texts: Vec<OutputFile> = files
        .split(',')
        .filter_map(|entry| entry.rsplit_once(':'))
        .map(|(name, length)| OutputFile {
            name: name.to_string(),
            bytes: vec![b'x'; length.parse().unwrap_or(0)],
        })
        .collect();
    one(Path::new(&input), &texts, Path::new(&out));
    true
}
