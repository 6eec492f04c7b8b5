//! One integration test binary (faster to link than one per file): the real
//! executable on the bundled samples and on broken workbooks made by helpers.
//! The checks that need a tool outside the crate are in `tests/tools/`.

mod batch;
mod boards;
mod broken;
mod codes;
// The binary's command-line definition, for the test of every flag.
#[allow(dead_code, unused_imports)]
#[path = "../../src/cli/mod.rs"]
mod cli;
mod diagram;
mod energy;
mod excel_formula;
mod exports;
mod fault_phases;
mod flags;
mod fuzz_regressions;
mod helpers;
mod hostile;
mod jumps;
mod layers;
mod lists;
mod machine;
mod messy;
mod modes;
mod motor;
mod on_stop;
mod paper;
mod pins;
mod promise_map;
mod properties;
mod safety;
mod settings_rows;
mod simulate;
mod snapshots;
mod stepping;
mod stray_cells;
mod synth;
mod template;
mod valves;
