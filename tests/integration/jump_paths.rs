//! Every path of a table with jumps is a path the machine can take, and the
//! proof runs each: a jump its own step's wait makes certain or impossible
//! is refused at its cell (E028); each jump is proven taken and not taken,
//! with the machine giving whatever value the path needs in time, also on
//! a step shorter than the input delay; a jump input given too late by
//! `--input-delay` is the engineer's setting (E032), not a bug.

use predicates::str::contains;
use proptest::prelude::*;

use crate::helpers::{files_below, sample, steptable};

/// One way to get a jump wrong (or right), and what the binary must say.
struct Row {
    what: &'static str,
    table: &'static str,
    args: &'static [&'static str],
    code: i32,
    /// `file:row:col: error[Exxx]` (or a line of stdout for a table that runs).
    expected: &'static [&'static str],
}

const ROWS: &[Row] = &[
    Row {
        what: "a jump on the input its step waits for, with that value: certain",
        table: "C1+1\nC2+1\n\"C2-0; I:rdy; J:6 if I:rdy\"\nC3+1\nC3-0\nC1-0\n",
        args: &[],
        code: 1,
        expected: &[
            "t.csv:3:1: error[E028]: \"J:6 if I:rdy\" in STEP 3: STEP 3 waits for I:rdy=1, so once the step is done the jump is always taken and steps 4–5 never run",
        ],
    },
    Row {
        what: "a jump on the input its step waits for, with the other value: impossible",
        table: "C1+1\nC2+1\n\"C2-0; I:rdy; J:6 if I:rdy=0\"\nC3+1\nC3-0\nC1-0\n",
        args: &[],
        code: 1,
        expected: &[
            "t.csv:3:1: error[E028]: \"J:6 if I:rdy=0\" in STEP 3: STEP 3 waits for I:rdy=1, so I:rdy is 1 whenever the jump is tested and the jump is never taken",
        ],
    },
    Row {
        what: "the wait in another branch of the same step, waiting for 0",
        table: "C1+1,\nC2+1,\n\"C2-0; J:6 if I:rdy=0\",I:rdy=0\nC3+1,\nC3-0,\nC1-0,\n",
        args: &[],
        code: 1,
        expected: &[
            "t.csv:3:1: error[E028]: \"J:6 if I:rdy=0\" in STEP 3: STEP 3 waits for I:rdy=0, so once the step is done the jump is always taken",
        ],
    },
    Row {
        what: "a certain jump back: the cycle never ends",
        table: "C1+1\nC2+1\n\"C2-0; I:rdy; J:2 if I:rdy\"\nC1-0\n",
        args: &[],
        code: 1,
        expected: &[
            "t.csv:3:1: error[E028]: \"J:2 if I:rdy\" in STEP 3: STEP 3 waits for I:rdy=1, so once the step is done the jump is always taken and steps 2–3 repeat for ever",
        ],
    },
    Row {
        what: "a certain jump to the end, repeated in two steps: both cells",
        table: "C1+1\n\"C1-0; I:a; J:end if I:a\"\nC2+1\n\"C2-0; I:b; J:end if I:b\"\nC3+1\nC3-0\n",
        args: &[],
        code: 1,
        expected: &[
            "t.csv:2:1: error[E028]: \"J:end if I:a\" in STEP 2: STEP 2 waits for I:a=1, so once the step is done the jump is always taken and the steps after STEP 2 never run",
            "t.csv:4:1: error[E028]: \"J:end if I:b\" in STEP 4: STEP 4 waits for I:b=1",
        ],
    },
    Row {
        what: "the same jump twice in a step",
        table: "C1+1\nC2+1\n\"C2-0; J:6 if I:rdy; J:6 if I:rdy\"\nC3+1\nC3-0\nC1-0\n",
        args: &[],
        code: 1,
        expected: &["t.csv:3:1: error[E021]: STEP 3 already jumps on I:rdy"],
    },
    Row {
        what: "a jump on an input named like one the program makes",
        table: "C1+1\nC2+1\n\"C2-0; J:6 if I:x11\"\nC3+1\nC3-0\nC1-0\n",
        args: &[],
        code: 1,
        expected: &["t.csv:3:1: error[E015]: \"x11\" cannot name a machine signal"],
    },
    Row {
        what: "a jump past the table's end",
        table: "C1+1\n\"C1-0; J:9 if I:rdy\"\nC2+1\nC2-0\n",
        args: &[],
        code: 1,
        expected: &["t.csv:2:1: error[E028]: \"J:9 if I:rdy\" in STEP 2: the table has 4 steps"],
    },
    Row {
        what: "a wait in an earlier step on the jump's input: both sides proven",
        table: "\"C1+1; I:rdy\"\nC2+1\n\"C2-0; J:6 if I:rdy=0\"\nC3+1\nC3-0\nC1-0\n",
        args: &[],
        code: 0,
        expected: &[
            "cycles 1, 2 (take no jump); not taken: J:6 if I:rdy=0 after step 3",
            "cycle 3 (takes J:6 if I:rdy=0 after step 3): steps 1, 2, 3, 6,",
        ],
    },
    Row {
        what: "a jump on a 100 ms dwell, shorter than the input delay",
        table: "C1+1\n\"T=100ms; J:5 if I:skip\"\nC2+1\nC2-0\nC1-0\n",
        args: &[],
        code: 0,
        expected: &["cycle 3 (takes J:5 if I:skip after step 2): steps 1, 2, 5, cycle of"],
    },
    Row {
        what: "a jump on a short stroke (a third of the way back)",
        table: "C1+2\n\"C1-1; J:5 if I:skip\"\nC2+1\nC2-0\nC1-0\n",
        args: &[],
        code: 0,
        expected: &["cycle 3 (takes J:5 if I:skip after step 2): steps 1, 2, 5, cycle of"],
    },
    Row {
        what: "the jump input given later than its step lasts",
        table: "C1+1\n\"C1-0; J:end if I:skip\"\nC2+1\nC2-0\n",
        args: &["--input-delay", "skip=2s"],
        code: 1,
        expected: &[
            "t.csv: error[E032]: the machine as set up cannot run this cycle: cycle 3 was to take J:end if I:skip after step 2, but step 3 came first (the machine gives I:skip 2.00 s after its step starts); it runs with I:skip at its default time (without --input-delay skip=…)",
        ],
    },
    Row {
        what: "the jump input given after no time at all",
        table: "C1+1\n\"C1-0; J:end if I:skip\"\nC2+1\nC2-0\n",
        args: &["--input-delay", "skip=0s"],
        code: 1,
        expected: &["\"skip=0s\": expected a time such as 2s or 300ms"],
    },
    Row {
        what: "the jump input given soon enough",
        table: "C1+1\n\"C1-0; J:end if I:skip\"\nC2+1\nC2-0\n",
        args: &["--input-delay", "skip=50ms"],
        code: 0,
        // J:end enters step 0 through the closing transition, no step of the table.
        expected: &["cycle 3 (takes J:end if I:skip after step 2): steps 1, 2, cycle of"],
    },
];

/// Every row through `convert` (nothing written when refused) and, for
/// the tables that run, `simulate` showing each path.
#[test]
fn hostile_jumps_are_refused_at_their_cell_and_valid_ones_proven_both_ways() {
    for row in ROWS {
        let dir = tempfile::tempdir().unwrap();
        let table = dir.path().join("t.csv");
        std::fs::write(&table, row.table).unwrap();
        let out = dir.path().join("out");
        let convert = steptable()
            .arg("convert")
            .args(row.args)
            .arg(&table)
            .arg("-o")
            .arg(&out)
            .output()
            .unwrap();
        let stderr =
            String::from_utf8_lossy(&convert.stderr).replace(&*dir.path().to_string_lossy(), "");
        let stderr = stderr.replace("/t.csv", "t.csv");
        assert_eq!(
            convert.status.code(),
            Some(row.code),
            "{}: {stderr}",
            row.what
        );
        if row.code != 0 {
            for line in row.expected {
                assert!(
                    stderr.contains(line),
                    "{}: {line}\nnot in\n{stderr}",
                    row.what
                );
            }
            assert!(files_below(&out).is_empty(), "{}: wrote files", row.what);
            continue;
        }
        assert!(!files_below(&out).is_empty(), "{}", row.what);
        let simulate = steptable()
            .arg("simulate")
            .args(row.args)
            .arg(&table)
            .output()
            .unwrap();
        let stdout = String::from_utf8_lossy(&simulate.stdout);
        assert_eq!(simulate.status.code(), Some(0), "{}: {stdout}", row.what);
        for line in row.expected {
            assert!(
                stdout.contains(line),
                "{}: {line}\nnot in\n{stdout}",
                row.what
            );
        }
    }
}

/// The sample's jump input given after its 0.96 s step: the engineer's
/// setting, named, never "a bug in steptable"; `faults` says the same.
#[test]
fn a_jump_input_given_too_late_names_the_setting() {
    for command in ["convert", "faults"] {
        let dir = tempfile::tempdir().unwrap();
        let assert = steptable()
            .args([command, "--input-delay", "reject=2s", "-o"])
            .arg(dir.path())
            .arg(sample("sorting_station.xlsx"))
            .assert()
            .code(1)
            .stderr(contains("error[E032]"))
            .stderr(contains(
                "it runs with I:reject at its default time (without --input-delay reject=…)",
            ));
        let stderr = String::from_utf8_lossy(&assert.get_output().stderr).to_string();
        assert!(!stderr.contains("internal error"), "{stderr}");
        assert!(files_below(dir.path()).is_empty(), "{command}");
    }
}

/// Waits on the jumps' inputs and on others, in random steps and with
/// random values, on top of a random table's cells.
fn with_waits(rows: &mut [Vec<String>], waits: &[(usize, u8, bool)]) {
    for &(step, input, value) in waits {
        let Some(row) = rows.get_mut(step % rows.len().max(1)) else {
            continue;
        };
        let name = ["jmp0", "jmp1", "part0"][input as usize % 3];
        let cell = &mut row[0];
        if !cell.contains(&format!("I:{name}")) {
            *cell = format!("{cell}; I:{name}={}", u8::from(value));
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    /// Every step of every accepted table with jumps (and waits, some on
    /// the jumps' own inputs; strokes as short as 400 ms, a middle stop
    /// a fifth of that) is run by a
    /// cycle of a passed proof; a table refused is refused for a jump its
    /// step's wait decides.
    #[test]
    fn every_step_of_an_accepted_table_is_run_by_a_proven_cycle(
        seed in any::<u64>(),
        actuators in 1u32..=4,
        max_position in 1u32..=3,
        branches in 1u32..=3,
        steps in 3u32..=12,
        waits in prop::collection::vec((0usize..12, 0u8..3, any::<bool>()), 0..4),
        strokes in prop::collection::vec(400u32..=2000, 4),
    ) {
        use steptable::random_table::{Shape, add_jumps, random_rows};
        let shape = Shape { actuators, max_position, branches, steps };
        let mut rows = random_rows(seed, shape);
        add_jumps(seed, &mut rows);
        with_waits(&mut rows, &waits);
        let table = match steptable::table::from_rows("random.csv", &rows) {
            Ok(table) => table,
            Err(diagnostics) => {
                let errors = diagnostics
                    .iter()
                    .filter(|d| d.severity == steptable::diag::Severity::Error);
                for d in errors {
                    prop_assert!(
                        d.code.as_str() == "E028" && d.message.contains(" waits for I:"),
                        "{d:?}\n{rows:?}"
                    );
                }
                return Ok(());
            }
        };
        let mut settings = steptable::settings::Settings::new();
        for (i, ms) in strokes.iter().enumerate() {
            settings.simulation.machine.strokes.per_actuator.insert(
                i as u32 + 1,
                steptable::stroke::Stroke { extend_ms: *ms, retract_ms: *ms },
            );
        }
        let program = steptable::convert::build_program(&table, &settings);
        let report = steptable::simulate::simulate(&table, &program, &settings.simulation);
        prop_assert!(report.passed, "{}\n{rows:?}", report.verdict());
        let run: std::collections::BTreeSet<usize> = report
            .cycles
            .iter()
            .filter(|c| c.cycle_ms.is_some())
            .flat_map(|c| c.steps.iter().map(|s| s.step))
            .collect();
        for step in &table.steps {
            prop_assert!(run.contains(&step.number), "step {} never ran\n{rows:?}", step.number);
        }
        // Each jump is proven both ways: not taken in the plain cycles,
        // taken in a cycle of its own.
        let jumps: usize = table.steps.iter().map(|s| s.jumps.len()).sum();
        let taken = report.cycles.iter().filter(|c| c.jump.is_some()).count();
        prop_assert_eq!(taken, jumps);
        let declined = report.cycles.first().map_or(0, |c| c.declined.len());
        prop_assert_eq!(declined, jumps);
    }
}
