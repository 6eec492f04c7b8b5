//! The synthesised programs (`NAME.equations.st` and `.equations.il`), as
//! written, compiled with matiec and run in a closed loop against
//! steptable's plant model (two-position cylinders on bistable 5/2 valves,
//! each starting at the complement of its first move) with the mode proof's
//! script: nothing before START, STOP at the end of a cycle, the emergency
//! stop, RESET and one more cycle. Every move must come at the same scan as
//! in the model of the program (`synth::controller`), which the proof
//! judges; both run on the bench of the shared simulation.

use std::path::Path;

use steptable::synth::sequence::{Operation, parse};
use steptable::synth::verify::{self, Trace};
use steptable::synth::{self, Synthesis};

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

/// Runs the written `file` in matiec against the plant with the mode
/// proof's script: the moves it made, at their scans, or why it failed.
fn run(shared: &Path, file: &Path, s: &Synthesis) -> Result<Trace, String> {
    let text = std::fs::read_to_string(file).unwrap();
    let vars = located(&text);
    let address = |name: &str| {
        vars.iter()
            .find(|(n, _)| n == name)
            .map(|(_, a)| a.clone())
            .ok_or_else(|| format!("{name} is not declared"))
    };
    let seq = &s.modified;
    let mut inputs = Vec::new();
    let mut outputs = Vec::new();
    for i in 0..seq.actuators {
        for name in seq.input_names(i) {
            inputs.push(address(&name)?);
        }
        for value in [true, false] {
            outputs.push(address(&seq.output_name(Operation { var: i, value }))?);
        }
    }
    for button in ["START", "STOP", "ESTOP", "RESET_PB"] {
        inputs.push(address(button)?);
    }
    let program = matiec::build(shared, file, 10, &inputs, &outputs)?;
    let mut live = program.live()?;
    let script = verify::script_for(s);
    verify::run(
        s,
        verify::STROKE_MS,
        script.scans,
        &|scan| script.buttons(scan),
        &mut |ends, buttons| {
            let mut read: Vec<bool> = ends.iter().flat_map(|(h, e)| [*h, *e]).collect();
            // STOP and ESTOP are normally closed: pressed reads 0.
            read.extend([buttons.start, !buttons.stop, !buttons.estop, buttons.reset]);
            let coils = live.scan(&read)?;
            Ok(coils.chunks(2).map(|c| (c[0], c[1])).collect())
        },
    )
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
        let (text, flags) = written.split_once(" --").unwrap_or((written, ""));
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
            .args(["synth", "--sequence", text, "-o"])
            .arg(&out)
            .args(&flags)
            .assert()
            .success();
        // The same synthesis in-process, for the model's trace.
        let options = synth::Options {
            prefer: if flags.iter().any(|f| f == "nodes") {
                synth::Prefer::Nodes
            } else {
                synth::Prefer::Memories
            },
            ..synth::Options::default()
        };
        let s = synth::synthesize_with(&parse(text).unwrap(), options).unwrap();
        let model = verify::check(&s).unwrap_or_else(|e| panic!("{text}: the model: {e}"));
        for file in [".equations.st", ".equations.il"] {
            let path = crate::helpers::synthesised(&out, text, file);
            let trace = run(&shared, &path, &s).unwrap_or_else(|e| panic!("{text}: {file}: {e}"));
            assert_eq!(trace, model, "{text}: {file}: matiec against the model");
            checked += 1;
        }
    }
    eprintln!(
        "synth: {checked} programs compiled by matiec ran START, STOP, ESTOP and RESET scan for scan as the model"
    );
}
