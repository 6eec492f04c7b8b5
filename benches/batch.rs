//! Benchmark (not a test): generates 1,000 realistic workbooks (2–12
//! actuators, up to 60 steps, up to 4 branches, some middle positions) and
//! prints the batch throughput for 1 and 2 jobs beside the I/O floor's
//! (`floor.rs`) from the same run, and where the time of one conversion goes
//! (read, check, generate, write).
//!
//! Run with `cargo bench --bench batch` (set STEPTABLE_BENCH_WORKBOOKS to
//! change the count; STEPTABLE_BENCH_CORPUS=DIR only writes the workbooks
//! there, for a profiler to run `steptable batch` on).

#[path = "support/floor.rs"]
mod floor;

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use rust_xlsxwriter::Workbook;
use steptable::batch;
use steptable::convert;
use steptable::diag::Diagnostics;
use steptable::random_table::{Shape, SplitMix64, random_rows};
use steptable::settings::Settings;

fn write_workbook(path: &Path, rows: &[Vec<String>]) {
    let mut workbook = Workbook::new();
    let sheet = workbook.add_worksheet();
    sheet.set_name("SEQUENTIAL CONTROL DESCRIPTION").unwrap();
    sheet
        .write_string(0, 0, "SEQUENTIAL CONTROL DESCRIPTION")
        .unwrap();
    let branches = rows.iter().map(Vec::len).max().unwrap_or(1);
    for b in 0..branches {
        sheet
            .write_string(2, b as u16 + 1, format!("BRANCH {}", b + 1))
            .unwrap();
    }
    for (k, row) in rows.iter().enumerate() {
        sheet
            .write_string(3 + k as u32, 0, format!("STEP {}", k + 1))
            .unwrap();
        for (b, cell) in row.iter().enumerate() {
            sheet
                .write_string(3 + k as u32, b as u16 + 1, cell)
                .unwrap();
        }
    }
    workbook.save(path).unwrap();
}

fn generate(dir: &Path, count: usize) -> Vec<PathBuf> {
    let mut rng = SplitMix64::new(5);
    (0..count)
        .map(|i| {
            let shape = Shape {
                actuators: rng.range(2, 12),
                max_position: if rng.range(0, 3) == 0 { 3 } else { 1 },
                branches: rng.range(1, 4),
                steps: rng.range(4, 60),
            };
            let rows = random_rows(i as u64, shape);
            let path = dir.join(format!("line_{i:04}.xlsx"));
            write_workbook(&path, &rows);
            path
        })
        .collect()
}

fn median(mut runs: Vec<Duration>) -> Duration {
    runs.sort();
    runs[runs.len() / 2]
}

/// The outputs the floor writes as bytes (all but the workbook, which it
/// builds itself): converted once, outside any timing.
fn floor_texts(input: &Path, name: &str, settings: &Settings) -> Vec<steptable::emit::OutputFile> {
    convert::convert_path_as(input, name, settings)
        .expect("converts")
        .files
        .into_iter()
        .filter(|f| !f.name.ends_with(".xlsx") || f.name.ends_with(".tags.xlsx"))
        .collect()
}

/// `convert` of one workbook as a whole process, steptable's binary beside
/// the floor's (this bench started again as [`floor::one_as_process`]),
/// alternating, median of `runs` each.
fn whole_process(
    input: &Path,
    texts: &[steptable::emit::OutputFile],
    dir: &Path,
    place: &str,
    runs: usize,
) {
    let files: Vec<String> = texts
        .iter()
        .map(|f| format!("{}:{}", f.name, f.bytes.len()))
        .collect();
    let (mut ours, mut floors) = (Vec::new(), Vec::new());
    for i in 0..runs {
        let out = dir.join(format!("process{i}"));
        let start = Instant::now();
        let status = std::process::Command::new(env!("CARGO_BIN_EXE_steptable"))
            .arg("convert")
            .arg(input)
            .arg("-o")
            .arg(&out)
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .status()
            .unwrap();
        ours.push(start.elapsed());
        assert!(status.success(), "steptable convert failed");
        let start = Instant::now();
        let status = std::process::Command::new(std::env::current_exe().unwrap())
            .env("STEPTABLE_FLOOR_ONE", input)
            .env("STEPTABLE_FLOOR_OUT", dir.join(format!("floor-process{i}")))
            .env("STEPTABLE_FLOOR_FILES", files.join(","))
            .status()
            .unwrap();
        floors.push(start.elapsed());
        assert!(status.success(), "the floor process failed");
    }
    let (ours, floor) = (median(ours), median(floors));
    println!(
        "convert {} as a whole process, output on {place}, median of {runs}: {:.1} ms; floor {:.1} ms, ratio {:.2}x",
        input.file_name().unwrap().to_string_lossy(),
        ours.as_secs_f64() * 1e3,
        floor.as_secs_f64() * 1e3,
        ours.as_secs_f64() / floor.as_secs_f64()
    );
}

fn main() {
    if floor::one_as_process() {
        return;
    }
    let count: usize = std::env::var("STEPTABLE_BENCH_WORKBOOKS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1000);
    // For a profiler: only write the workbooks, to run `steptable batch` on.
    if let Ok(corpus) = std::env::var("STEPTABLE_BENCH_CORPUS") {
        std::fs::create_dir_all(&corpus).unwrap();
        generate(Path::new(&corpus), count);
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let settings = Settings::new();
    // The paper's example as one `convert`, process start included: first,
    // before 1,000 new workbooks give the disk write-back to do.
    let paper = Path::new(env!("CARGO_MANIFEST_DIR")).join("samples/paper_example.xlsx");
    let paper_texts = floor_texts(&paper, "paper_example", &settings);
    whole_process(&paper, &paper_texts, dir.path(), "disk", 31);
    if let Ok(shm) = tempfile::tempdir_in("/dev/shm") {
        whole_process(&paper, &paper_texts, shm.path(), "tmpfs", 31);
    }
    let inputs = generate(dir.path(), count);

    // The floor writes the same bytes as steptable's outputs but the
    // workbook: made once here, outside the timing.
    let texts: Vec<Vec<steptable::emit::OutputFile>> = inputs
        .iter()
        .map(|input| {
            let name = input.file_stem().unwrap().to_string_lossy().to_string();
            floor_texts(input, &name, &settings)
        })
        .collect();
    // Floor and steptable alternate, three rounds each, so that both see
    // the same caches and the same load; medians are printed.
    // Output on this disk, then (where there is one) on tmpfs, where the
    // file system costs least and the CPU shows.
    let tmpfs = Path::new("/dev/shm");
    let shm = (tmpfs.is_dir())
        .then(|| tempfile::tempdir_in(tmpfs).ok())
        .flatten();
    let mut runs = vec![("disk", dir.path(), 1), ("disk", dir.path(), 2)];
    if let Some(shm) = &shm {
        runs.push(("tmpfs", shm.path(), 1));
        runs.push(("tmpfs", shm.path(), 2));
    }
    // `-j 1` on the same file system, for the speed-up of `-j 2`.
    let mut single = std::collections::HashMap::new();
    for (place, out_dir, jobs) in runs {
        let (mut floors, mut ours) = (Vec::new(), Vec::new());
        let mut failed = 0;
        for round in 0..3 {
            let floor_dir = out_dir.join(format!("floor{jobs}-{round}"));
            floors.push(floor::run(&inputs, &texts, &floor_dir, jobs));
            let out = out_dir.join(format!("out{jobs}-{round}"));
            let start = Instant::now();
            let stop = std::sync::atomic::AtomicBool::new(false);
            let outcomes = batch::run(&inputs, &out, &settings, jobs, &stop, &|_| {});
            ours.push(start.elapsed());
            failed = outcomes
                .iter()
                .filter(|o| o.status != batch::Status::Converted)
                .count();
            // tmpfs is memory: leave it as it was.
            if place == "tmpfs" {
                let _ = std::fs::remove_dir_all(&floor_dir);
                let _ = std::fs::remove_dir_all(&out);
            }
        }
        let (floor, elapsed) = (median(floors), median(ours));
        let seconds = elapsed.as_secs_f64();
        if jobs == 1 {
            single.insert(place, elapsed);
        }
        println!(
            "batch -j {jobs}, output on {place}: {count} workbooks in {seconds:.2} s = {:.1} workbooks/s ({failed} failed); floor {:.2} s, ratio {:.2}x{}",
            count as f64 / seconds,
            floor.as_secs_f64(),
            seconds / floor.as_secs_f64(),
            match single.get(place).filter(|_| jobs > 1) {
                Some(one) => format!("; speed-up over -j 1 {:.2}x", one.as_secs_f64() / seconds),
                None => String::new(),
            }
        );
    }

    // One typical workbook, stage by stage (median of 31 runs).
    std::fs::create_dir_all(dir.path().join("one")).unwrap();
    let one = dir.path().join("one/line.xlsx");
    write_workbook(
        &one,
        &random_rows(
            99,
            Shape {
                actuators: 6,
                max_position: 3,
                branches: 3,
                steps: 30,
            },
        ),
    );
    let (mut read, mut check, mut generate_t, mut write) = (vec![], vec![], vec![], vec![]);
    for i in 0..31 {
        let t = Instant::now();
        let mut diags = Diagnostics::new();
        let input = steptable::read::read_path(&one, None, &mut diags).unwrap();
        read.push(t.elapsed());
        let t = Instant::now();
        let table = steptable::table::build(&input.table, &mut diags).unwrap();
        check.push(t.elapsed());
        let t = Instant::now();
        let checked = convert::Checked {
            table,
            warnings: Vec::new(),
            settings: settings.clone(),
        };
        let conversion = convert::generate("line", checked).ok().unwrap();
        generate_t.push(t.elapsed());
        let t = Instant::now();
        steptable::write::write_outputs(
            &dir.path().join(format!("w{i}")),
            &conversion.files,
            &steptable::write::Inputs::none(),
            steptable::write::Durability::Rename,
            Some(conversion.made_by.text()),
        )
        .unwrap();
        write.push(t.elapsed());
    }
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    let (r, c, g, w) = (
        median(read),
        median(check),
        median(generate_t),
        median(write),
    );
    println!(
        "one workbook (6 actuators, 30 steps, all outputs), median of 31: read {:.2} ms, check {:.2} ms, generate {:.2} ms, write {:.2} ms",
        ms(r),
        ms(c),
        ms(g),
        ms(w)
    );
    // Where generate's time goes.
    let mut diags = Diagnostics::new();
    let input = steptable::read::read_path(&one, None, &mut diags).unwrap();
    let table = steptable::table::build(&input.table, &mut diags).unwrap();
    let program = convert::build_program(&table, &settings);
    let t = Instant::now();
    let report = steptable::simulate::simulate(&table, &program, &settings.simulation);
    let sim = t.elapsed();
    let t = Instant::now();
    let faults = steptable::faults::analyse(&table, &program, &settings.simulation, 1);
    let fault_time = t.elapsed();
    println!(
        "  of generate: simulation {:.2} ms ({}), single-fault table {:.2} ms ({})",
        ms(sim),
        report.verdict(),
        ms(fault_time),
        faults.summary()
    );
}
