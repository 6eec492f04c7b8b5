//! One integration test binary (faster to link than one per file): the real
//! executable on the bundled samples and on broken workbooks made by helpers.
//! The checks that need a tool outside the crate are in `tests/tools/`.

mod batch;
mod boards;
mod broken;
mod budgets;
mod codes;
// The binary's command-line definition, for the test of every flag.
#[allow(dead_code, unused_imports)]
#[path = "../../src/cli/mod.rs"]
mod cli;
mod designations;
mod diagram;
mod drive_coasting;
mod energy;
mod excel_formula;
mod exports;
mod fault_phases;
mod findings;
mod flags;
mod fuzz_regressions;
mod helpers;
mod homing;
mod hostile;
mod hostile_messages;
mod hostile_settings;
mod identifiers;
mod jump_paths;
mod jumps;
mod layers;
mod lists;
mod machine;
mod machine_limits;
mod messy;
mod modes;
mod motor;
mod name_check;
mod on_stop;
mod output_places;
mod paper;
mod pins;
mod promise_map;
mod properties;
mod rerun;
mod safety;
mod settings_rows;
mod simulate;
mod snapshots;
mod stdout;
mod stepping;
mod stray_cells;
mod synth;
mod synth_short;
mod template;
mod valves;
