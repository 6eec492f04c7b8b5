//! Benchmark (not a test): prints the median wall time of
//! - simulating the paper's example (two cycles), event-driven and scan by scan,
//! - its single-fault table and `faults --pairs` (every pair of stuck inputs),
//! - simulating a 100-actuator × 1,000-step table (two cycles), both ways,
//! - converting the paper's sample in memory (read → every output).
//!
//! Run with `cargo bench --bench simulation`.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use steptable::convert;
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
}
