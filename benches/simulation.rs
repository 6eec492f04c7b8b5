//! Benchmark (not a test): prints the median wall time of
//! - simulating the paper's example (two cycles), event-driven and scan by scan,
//! - its single-fault table and `faults --pairs` (every pair of stuck inputs),
//! - simulating a 100-actuator × 1,000-step table (two cycles), both ways,
//! - converting the paper's sample in memory (read → every output),
//! - what the report adds to a conversion, on the paper's example and on the
//!   two lines of docs/development.md ("What the report costs"), which it
//!   writes to `target/report-tables/` for measuring whole processes.
//!
//! Run with `cargo bench --bench simulation`.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use steptable::convert;
use steptable::emit::OutputKind;
use steptable::faults;
use steptable::random_table::{Shape, random_rows};
use steptable::settings::Settings;
use steptable::simulate::{SimSettings, Stepping, simulate_stepping};

fn median(mut runs: Vec<Duration>) -> Duration {
    runs.sort();
    runs[runs.len() / 2]
}

fn time<T>(runs: usize, mut f: impl FnMut() -> T) -> (Duration, T) {
    let mut times = Vec::with_capacity(runs);
    let mut last = None;
    for _ in 0..runs {
        let start = Instant::now();
        last = Some(f());
        times.push(start.elapsed());
    }
    (median(times), last.expect("at least one run"))
}

fn main() {
    let paper = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("samples/paper_example.xlsx");
    let settings = Settings::new();
    let checked = convert::check_path(&paper, &settings).expect("paper sample");
    let program = convert::build_program(&checked.table, &settings);

    for stepping in [Stepping::Events, Stepping::EveryScan] {
        let (t, report) = time(51, || {
            simulate_stepping(&checked.table, &program, &settings.simulation, stepping)
        });
        println!(
            "simulate paper example ({stepping:?}): median {:.3} ms over 51 runs ({})",
            t.as_secs_f64() * 1e3,
            report.verdict()
        );
    }
    // Single faults resumed from the healthy run (the default) and from
    // power-up (the reference), on the paper's example and on a 12-cylinder
    // 60-step table with middle positions and four branches.
    let medium_rows = random_rows(
        7,
        Shape {
            actuators: 12,
            max_position: 3,
            branches: 4,
            steps: 60,
        },
    );
    let medium = steptable::table::from_rows("medium.csv", &medium_rows).expect("valid table");
    let medium_program = convert::build_program(&medium, &settings);
    for (what, table, program) in [
        ("paper example", &checked.table, &program),
        ("12 cylinders x 60 steps", &medium, &medium_program),
    ] {
        let mut times = Vec::new();
        for runs in [faults::FaultRuns::Resumed, faults::FaultRuns::FromPowerUp] {
            let (t, analysed) = time(11, || {
                faults::analyse_runs(table, program, &settings.simulation, 1, runs, &|_, _| {})
            });
            times.push(t);
            println!(
                "faults at every phase, {what} ({runs:?}): median {:.2} ms over 11 runs ({})",
                t.as_secs_f64() * 1e3,
                analysed.summary(),
            );
        }
        println!(
            "  resumed runs {:.1}x faster than runs from power-up",
            times[1].as_secs_f64() / times[0].as_secs_f64()
        );
    }
    let (t, table) = time(5, || {
        faults::analyse(&checked.table, &program, &settings.simulation, 2)
    });
    println!(
        "faults --pairs at every phase, paper example: median {:.1} ms over 5 runs ({}; {} cases)",
        t.as_secs_f64() * 1e3,
        table.summary(),
        table.cases.len()
    );

    let rows = random_rows(
        2026,
        Shape {
            actuators: 100,
            max_position: 3,
            branches: 4,
            steps: 1000,
        },
    );
    let big = steptable::table::from_rows("big.csv", &rows).expect("valid generated table");
    let big_program = convert::build_program(&big, &settings);
    for stepping in [Stepping::Events, Stepping::EveryScan] {
        let (t, report) = time(5, || {
            simulate_stepping(&big, &big_program, &SimSettings::default(), stepping)
        });
        let scans = report.cycles.iter().filter_map(|c| c.cycle_ms).sum::<u64>() / 10;
        println!(
            "simulate 100 actuators x {} steps ({stepping:?}): median {:.1} ms over 5 runs ({}; about {} scans)",
            big.steps.len(),
            t.as_secs_f64() * 1e3,
            report.verdict(),
            scans
        );
    }

    let (t, _) = time(21, || {
        convert::convert_path(&paper, &settings).expect("converts")
    });
    println!(
        "convert paper example in memory (with simulation and single faults): median {:.2} ms over 21 runs",
        t.as_secs_f64() * 1e3
    );
    report_cost(&paper);
}

/// A 40-step line of 20 cylinders, `C1+1 … C20+1, C20-0 … C1-0` (82 single
/// faults, 40 of them hazards), and 30 steps of 6 cylinders on two branches
/// (C1–C3 out and home five times on one, C4–C6 four times on the other).
fn report_tables() -> [(&'static str, String); 2] {
    let line: Vec<String> = (1..=20)
        .map(|i| format!("C{i}+1"))
        .chain((1..=20).rev().map(|i| format!("C{i}-0")))
        .collect();
    let round = |first: u32| {
        let out = (first..first + 3).map(move |i| format!("C{i}+1"));
        out.chain((first..first + 3).map(|i| format!("C{i}-0")))
    };
    let one: Vec<String> = (0..5).flat_map(|_| round(1)).collect();
    let other: Vec<String> = (0..4).flat_map(|_| round(4)).collect();
    let csv = |branches: &[&[String]]| {
        let header: Vec<String> = (1..=branches.len())
            .map(|b| format!(",BRANCH {b}"))
            .collect();
        let mut text = format!("{}\n", header.concat());
        for k in 0..branches[0].len() {
            text.push_str(&format!("STEP {}", k + 1));
            for moves in branches {
                text.push_str(&format!(",{}", moves.get(k).map_or("", String::as_str)));
            }
            text.push('\n');
        }
        text
    };
    [
        ("two_branches_30.csv", csv(&[&one, &other])),
        ("line_40.csv", csv(&[&line])),
    ]
}

/// `convert` in memory with every output and with every output but the
/// report, and the mitigations alone; the tables are written out beside.
fn report_cost(paper: &std::path::Path) {
    let folder = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/report-tables");
    std::fs::create_dir_all(&folder).expect("a folder for the tables");
    let mut inputs = vec![paper.to_path_buf()];
    for (name, csv) in report_tables() {
        let path = folder.join(name);
        std::fs::write(&path, csv).expect("table written");
        inputs.push(path);
    }
    let with = Settings::new();
    let mut without = Settings::new();
    without.formats.remove(&OutputKind::Report);
    for path in inputs {
        let convert =
            |settings: &Settings| convert::convert_path(&path, settings).expect("converts");
        let (t_with, conversion) = time(11, || convert(&with));
        let (t_without, _) = time(11, || convert(&without));
        let report = conversion
            .files
            .iter()
            .find(|f| f.name.ends_with(".report.html"))
            .map_or(0, |f| f.bytes.len());
        let faults = conversion
            .faults
            .as_ref()
            .expect("the report shows the faults");
        // As a conversion runs them: beside the healthy run it proved the
        // program with.
        let program = convert::build_program(&conversion.table, &with);
        let healthy = faults::healthy_run(&conversion.table, &program, &with.simulation);
        let (t_mitigations, _) = time(11, || {
            faults::mitigation::mitigations(
                &conversion.table,
                &with.program,
                &with.simulation,
                faults,
                Some(&healthy),
                &|_| true,
            )
        });
        println!(
            "convert {} in memory: median {:.1} ms with the report, {:.1} ms without ({:.2}x); its mitigations alone {:.1} ms; report {report} bytes",
            path.display(),
            t_with.as_secs_f64() * 1e3,
            t_without.as_secs_f64() * 1e3,
            t_with.as_secs_f64() / t_without.as_secs_f64(),
            t_mitigations.as_secs_f64() * 1e3,
        );
    }
}
