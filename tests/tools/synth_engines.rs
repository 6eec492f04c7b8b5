//! The synthesised programs (`NAME.equations.st` and `.equations.il`), as
//! written, compiled with matiec and run in a closed loop against
//! steptable's plant model: two-position cylinders on bistable 5/2 valves,
//! each starting at the complement of its first move. The moves must come in
//! the sequence's order for two full cycles, and no valve may see both coils.

use std::path::Path;

use steptable::simulate::plant::Piston;
use steptable::stroke::Stroke;

use crate::engines::matiec;
use crate::helpers::steptable;
use crate::{Check, Tool, shared};

pub const CHECKS: &[Check] = &[Check::new(
    "synth_engines::synthesised_programs_run_the_sequence_in_matiec",
    &[Tool::Shared],
    synthesised_programs_run_the_sequence_in_matiec,
)];

/// `name AT %IX0.1 : BOOL;` declarations of a written program.
fn located(text: &str) -> Vec<(String, String)> {
    text.lines()
        .filter_map(|l| {
            let (name, rest) = l.trim().split_once(" AT ")?;
            let address = rest.split_whitespace().next()?;
            Some((name.to_string(), address.to_string()))
        })
        .collect()
}

/// A move as the sequence writes it: `A1`, `A0`; `C1+1`, `C1-0` for a
/// table's names.
fn token(name: &str, extended: bool) -> String {
    if name.ends_with(|c: char| c.is_ascii_digit()) {
        format!("{name}{}", if extended { "+1" } else { "-0" })
    } else {
        format!("{name}{}", u8::from(extended))
    }
}

/// Runs `file` against the plant; the moves in the order they ended
/// (`A1`, `B0`, …), or why it failed.
fn run(
    shared: &Path,
    file: &Path,
    letters: &[String],
    start: &[bool],
    scans: usize,
) -> Result<Vec<String>, String> {
    let text = std::fs::read_to_string(file).unwrap();
    let vars = located(&text);
    let address = |name: &str| {
        vars.iter()
            .find(|(n, _)| n == name)
            .map(|(_, a)| a.clone())
            .ok_or_else(|| format!("{name} is not declared"))
    };
    let mut inputs = Vec::new();
    let mut outputs = Vec::new();
    for l in letters {
        let l = l.to_ascii_lowercase();
        inputs.push(address(&format!("{l}_home"))?);
        inputs.push(address(&format!("{l}_end"))?);
        outputs.push(address(&format!("y{l}_p"))?);
        outputs.push(address(&format!("y{l}_m"))?);
    }
    let program = matiec::build(shared, file, 10, &inputs, &outputs)?;
    let mut live = program.live()?;
    let stroke = Stroke {
        extend_ms: 200,
        retract_ms: 200,
    };
    let mut pistons: Vec<Piston> = (0..letters.len())
        .map(|i| {
            let mut p = Piston::new(i as u32 + 1, 1, stroke, 10);
            p.s = if start[i] { 1.0 } else { 0.0 };
            p
        })
        .collect();
    let mut at_end: Vec<Option<bool>> = start.iter().map(|s| Some(*s)).collect();
    let mut moves = Vec::new();
    for scan in 0..scans {
        let read: Vec<bool> = pistons
            .iter()
            .flat_map(|p| [p.sensor(0, 0.02), p.sensor(1, 0.02)])
            .collect();
        let coils = live.scan(&read)?;
        for (i, p) in pistons.iter_mut().enumerate() {
            if p.drive(coils[2 * i], coils[2 * i + 1]) {
                return Err(format!(
                    "scan {scan}: the valve of {} sees both coils",
                    letters[i]
                ));
            }
            p.advance();
            let now = if p.sensor(1, 0.02) {
                Some(true)
            } else if p.sensor(0, 0.02) {
                Some(false)
            } else {
                None
            };
            if now.is_some() && now != at_end[i] {
                moves.push(token(&letters[i], now == Some(true)));
            }
            if now.is_some() {
                at_end[i] = now;
            }
        }
    }
    Ok(moves)
}

fn synthesised_programs_run_the_sequence_in_matiec() {
    let shared = shared();
    let dir = tempfile::tempdir().unwrap();
    let sequences = [
        "A1 A0 B1 B0",
        "A0 A1 C1 C0 B1 B0",
        "A1 A0 A1 A0 A1 A0 B1 B0 C1 C0",
        "A1 A0 B1 B0 C1 C0 D1 D0 E1 E0 F1 F0",
        "A1 B1 A0 B0",
        "A1 B1 B0 A0",
        "A1 B1 C1 C0 B0 A0",
        // Names kept: a table's C1, C2 and letters that are memories'
        // usual letters (the memories take others).
        "C1+1 C2+1 C2-0 C1-0",
        "W1 X1 X0 W0",
        // The front's other point: 4 memories, 48 nodes.
        "A1 A0 A1 A0 A1 A0 B1 B0 C1 C0 --prefer nodes",
    ];
    let mut checked = 0;
    for (k, written) in sequences.iter().enumerate() {
        let out = dir.path().join(format!("s{k}"));
        let (sequence, flags) = written.split_once(" --").unwrap_or((written, ""));
        let flags: Vec<String> = flags
            .split_whitespace()
            .enumerate()
            .map(|(i, f)| {
                if i == 0 {
                    format!("--{f}")
                } else {
                    f.to_string()
                }
            })
            .collect();
        steptable()
            .args(["synth", "--sequence", sequence, "-o"])
            .arg(&out)
            .args(&flags)
            .assert()
            .success();
        let actions: Vec<&str> = sequence.split_whitespace().collect();
        // The name: the token without its move (`A1` → A, `C1+1` → C1).
        let name_of = |a: &str| -> String {
            match a.find(['+', '-']) {
                Some(sign) => a[..sign].to_string(),
                None => a[..a.len() - 1].to_string(),
            }
        };
        let mut letters: Vec<String> = actions.iter().map(|a| name_of(a)).collect();
        letters.sort();
        letters.dedup();
        // Each cylinder starts where its first move does not go.
        let start: Vec<bool> = letters
            .iter()
            .map(|l| {
                actions
                    .iter()
                    .find(|a| name_of(a) == *l)
                    .unwrap()
                    .ends_with('0')
            })
            .collect();
        let expected: Vec<String> = actions
            .iter()
            .chain(&actions)
            .map(|a| a.to_string())
            .collect();
        let scans = 2 * actions.len() * 30 + 200;
        for file in ["sequence.equations.st", "sequence.equations.il"] {
            let path = out.join("sequence").join(file);
            let moves = run(&shared, &path, &letters, &start, scans)
                .unwrap_or_else(|e| panic!("{sequence}: {file}: {e}"));
            assert!(
                moves.len() >= expected.len() && moves[..expected.len()] == expected[..],
                "{sequence}: {file} moved {moves:?}"
            );
            checked += 1;
        }
    }
    eprintln!("synth: {checked} programs compiled by matiec ran their sequence twice");
}
