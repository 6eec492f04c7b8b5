//! The differential layer over random valid tables: moves in parallel
//! branches and middle stops, dwells of any length up to 9.99 s, waits on
//! machine inputs, machine outputs, valve types, operating modes, safety
//! checks, every target and both mnemonic sets. Each table is written by the
//! binary and its `.st` (matiec), `.awl` (awlsim), `.fst.txt` (the FST
//! interpreter), `.scl` (the SCL interpreter) and `.L5X` (the RLL
//! interpreter) must give the simulation's outputs at every scan; one check
//! per engine, so that a missing engine is an ignored check, not a pass.
//!
//! The tables come from fixed seeds, so CI always runs the same ones;
//! `STEPTABLE_DIFF_CASES=N` runs N of them (default 100) and
//! `STEPTABLE_DIFF_SEED=S` starts elsewhere.

use std::path::Path;

use steptable::random_table::{Shape, SplitMix64, random_rows};

use crate::engines::{self, Case, Engine, awlsim, fst, matiec};
use crate::helpers::write_xlsx;
use crate::{Check, Tool, shared, tool};

pub const CHECKS: &[Check] = &[
    Check::new(
        "differential_random::random_tables_run_in_the_fst_interpreter_as_simulated",
        &[],
        || random_tables_run_as_simulated(Engine::Fst),
    ),
    Check::new(
        "differential_random::random_tables_run_in_the_scl_interpreter_as_simulated",
        &[],
        || random_tables_run_as_simulated(Engine::Scl),
    ),
    Check::new(
        "differential_random::random_tables_run_in_the_rll_interpreter_as_simulated",
        &[],
        || random_tables_run_as_simulated(Engine::Rll),
    ),
    Check::new(
        "differential_random::random_tables_run_in_matiec_as_simulated",
        &[Tool::Shared],
        || random_tables_run_as_simulated(Engine::Matiec),
    ),
    Check::new(
        "differential_random::random_tables_run_in_awlsim_as_simulated",
        &[Tool::Awlsim],
        || random_tables_run_as_simulated(Engine::Awlsim),
    ),
    Check::new(
        "differential_random::random_charts_run_in_matiec_as_simulated",
        &[Tool::Shared, Tool::BeremizPython],
        random_charts_run_in_matiec_as_simulated,
    ),
];

/// A random table with its command-line options.
pub(crate) struct Drawn {
    pub(crate) rows: Vec<Vec<String>>,
    pub(crate) args: Vec<String>,
}

fn pick<'a>(rng: &mut SplitMix64, items: &[&'a str]) -> &'a str {
    items[rng.range(0, items.len() as u32 - 1) as usize]
}

pub(crate) fn draw(seed: u64) -> Drawn {
    let mut rng = SplitMix64::new(seed.wrapping_mul(0x2545_F491_4F6C_DD1D) ^ 0xD1FF);
    let shape = Shape {
        actuators: rng.range(1, 5),
        max_position: rng.range(1, 3),
        branches: rng.range(1, 3),
        steps: rng.range(2, 12),
    };
    let mut rows = random_rows(seed, shape);
    for row in &mut rows {
        let mut add = |rng: &mut SplitMix64, item: String| {
            let branch = rng.range(0, row.len() as u32) as usize;
            if branch == row.len() {
                row.push(item);
            } else if row[branch].is_empty() {
                row[branch] = item;
            } else {
                row[branch] = format!("{}; {item}", row[branch]);
            }
        };
        if rng.range(0, 3) == 0 {
            // Any length, awkward ones too: 15 ms, 1005 ms, 9990 ms.
            let ms = match rng.range(0, 3) {
                0 => rng.range(10, 99),
                1 => rng.range(100, 1999),
                _ => rng.range(2000, 9990),
            };
            add(&mut rng, format!("T={ms}ms"));
        }
        if rng.range(0, 4) == 0 {
            let (value, k) = (rng.range(0, 1), rng.range(0, 2));
            add(&mut rng, format!("I:part{k}={value}"));
        }
        if rng.range(0, 3) == 0 {
            let (sign, k) = (pick(&mut rng, &["+", "-"]), rng.range(0, 2));
            add(&mut rng, format!("Y:lamp{k}{sign}"));
        }
    }
    steptable::random_table::add_jumps(seed, &mut rows);
    let jumps = rows.iter().flatten().any(|c| c.starts_with("J:"));
    // Highest position of each actuator, for its valve.
    let mut pmax = std::collections::BTreeMap::new();
    for cell in rows.iter().flatten() {
        for item in cell.split(';') {
            let item = item.trim();
            if let Some(rest) = item.strip_prefix('C')
                && let Some(at) = rest.find(['+', '-'])
            {
                let actuator: u32 = rest[..at].parse().unwrap();
                let position: u32 = rest[at + 1..].parse().unwrap_or(1);
                let entry = pmax.entry(actuator).or_insert(0);
                *entry = (*entry).max(position);
            }
        }
    }
    let valves: Vec<String> = pmax
        .iter()
        .map(|(a, p)| {
            let valve = if *p > 1 {
                "53closed"
            } else {
                pick(&mut rng, &["52bi", "52mono", "53closed"])
            };
            format!("C{a}={valve}")
        })
        .collect();
    let mut args: Vec<String> = vec![
        "--target".into(),
        pick(&mut rng, &["festo", "iec", "siemens"]).into(),
        "--mnemonic".into(),
        pick(&mut rng, &["en", "de"]).into(),
        "--valve".into(),
        valves.join(","),
    ];
    if jumps {
        // The machine gives a jump's input as its step fires, before any
        // step could be done.
        args.extend(["--input-delay".into(), "jmp0=10ms,jmp1=10ms".into()]);
    }
    let safety = pick(
        &mut rng,
        &["", "all", "edge,watchdog", "precheck,plausibility"],
    );
    if !safety.is_empty() {
        args.extend(["--safety".into(), safety.into()]);
    }
    let modes = pick(&mut rng, &["", "all", "continuous,stop", "stop,reset"]);
    if !modes.is_empty() {
        args.extend(["--modes".into(), modes.into()]);
    }
    Drawn { rows, args }
}

fn env_number(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

fn prepare(dir: &Path, seed: u64) -> Case {
    convert_drawn(
        dir,
        seed,
        &draw(seed),
        "st,awl,fst,sfc,scl,tia,l5x,rockwell",
    )
}

/// Writes `drawn` as a workbook in `dir` and converts it to `formats`.
pub(crate) fn convert_drawn(dir: &Path, seed: u64, drawn: &Drawn, formats: &str) -> Case {
    let input = dir.join(format!("random{seed}.xlsx"));
    let rows: Vec<Vec<&str>> = drawn
        .rows
        .iter()
        .map(|r| r.iter().map(String::as_str).collect())
        .collect();
    let rows: Vec<&[&str]> = rows.iter().map(Vec::as_slice).collect();
    write_xlsx(&input, "Sheet1", &rows);
    let mut args: Vec<&str> = drawn.args.iter().map(String::as_str).collect();
    args.extend(["--formats", formats]);
    let mut case = engines::prepare(&input, &args, &dir.join(format!("out{seed}")));
    case.label = format!("seed {seed}: {:?} {}", drawn.rows, drawn.args.join(" "));
    case
}

/// The seeds of a run: `STEPTABLE_DIFF_SEED` on, `STEPTABLE_DIFF_CASES` of them.
pub(crate) fn seeds() -> Vec<u64> {
    let first = env_number("STEPTABLE_DIFF_SEED", 0);
    let count = env_number("STEPTABLE_DIFF_CASES", 100);
    (first..first + count).collect()
}

/// The SFC chart of every random table, through Beremiz's generator and
/// matiec (issue 39).
fn random_charts_run_in_matiec_as_simulated() {
    let shared = shared();
    let python = tool(Tool::BeremizPython);
    let dir = tempfile::tempdir().unwrap();
    let seeds = seeds();
    let failures: Vec<String> = engines::on_two_threads(&seeds, |&seed| {
        let case = prepare(dir.path(), seed);
        crate::sfc::run_chart(&python, &shared, &case, &case.file(".sfc.xml"))
            .err()
            .into_iter()
            .collect()
    });
    assert!(
        failures.is_empty(),
        "{} differences over {} random charts:\n{}",
        failures.len(),
        seeds.len(),
        failures.join("\n")
    );
    eprintln!(
        "random tables: {} SFC charts run in matiec, traces equal",
        seeds.len()
    );
}

fn random_tables_run_as_simulated(engine: Engine) {
    let shared = matches!(engine, Engine::Matiec).then(shared);
    let python = matches!(engine, Engine::Awlsim).then(|| awlsim::python(&tool(Tool::Awlsim)));
    let first = env_number("STEPTABLE_DIFF_SEED", 0);
    let count = env_number("STEPTABLE_DIFF_CASES", 100);
    let dir = tempfile::tempdir().unwrap();
    let seeds: Vec<u64> = (first..first + count).collect();
    let failures: Vec<String> = engines::on_two_threads(&seeds, |&seed| {
        let case = prepare(dir.path(), seed);
        let result = match engine {
            Engine::Fst => {
                let text = crate::engines::read_ansi(&case.file(".fst.txt")).unwrap();
                case.check("FST", fst::run(&text, &case.trace, &case.festo))
            }
            Engine::Scl => case.check_stepped("SCL", crate::differential_native::run_scl(&case)),
            Engine::Rll => case.check_stepped("RLL", crate::differential_native::run_l5x(&case)),
            Engine::Matiec => case.check(
                "matiec",
                matiec::run(
                    shared.as_deref().unwrap(),
                    &case.file(".st"),
                    &case.trace,
                    &case.allocation,
                ),
            ),
            Engine::Awlsim => case.check(
                "awlsim",
                awlsim::run(
                    python.as_deref().unwrap(),
                    &case.file(".awl"),
                    case.mnemonic,
                    &case.trace,
                    &case.allocation,
                ),
            ),
        };
        result.err().into_iter().collect()
    });
    assert!(
        failures.is_empty(),
        "{} differences over {count} random tables ({engine:?}):\n{}",
        failures.len(),
        failures.join("\n")
    );
    eprintln!("random tables: {count} run in {engine:?}, traces equal");
}
