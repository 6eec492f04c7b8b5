//! steptable turns a step table of pneumatic cylinder moves (a branches × steps
//! spreadsheet of `C1+1`, `C2-0` cells, as in Blagojević et al. 2019) into I/O
//! address lists and PLC programs.
//!
//! The pipeline, one module per stage, data flowing one way:
//! [`read`] (file → grid of cells) → [`table`] (grid → checked steps and moves)
//! → [`program`] (the step program every output is rendered from) →
//! [`address`] (the program's signals → addresses per PLC dialect) → [`emit`]
//! (one file per output language, every name read from [`symbols`]); [`simulate`] and [`faults`] run the
//! program, [`synth`] stands beside. [`convert`] runs the whole pipeline in
//! memory, [`write`] writes the result atomically (replacing only what a
//! [`manifest`] records), and [`batch`] converts many inputs in parallel.
//! [`settings`] holds a run's choices, from the command line, the workbook's
//! SETTINGS sheet and the defaults; [`diag`] the diagnostics every stage
//! collects. [`cli`] is the command line over them: it parses, calls
//! [`commands`] and prints.
//!
//! `ARCHITECTURE.md` at the repository root says what each module owns,
//! which imports `tests/integration/layers.rs` forbids, and where to add an
//! output language, an actuator kind, a setting or an error code.

pub mod actuator;
pub mod address;
pub mod alloc_guard;
pub mod batch;
pub mod cell;
pub mod cli;
pub mod commands;
pub mod convert;
pub mod diag;
pub mod emit;
pub mod faults;
pub mod manifest;
pub mod named_set;
pub mod names;
pub mod program;
pub mod provenance;
#[cfg(feature = "testing")]
pub mod random_table;
pub mod read;
pub mod settings;
pub mod sheets;
pub mod simulate;
pub mod stroke;
pub mod symbols;
pub mod synth;
pub mod table;
pub mod template_workbook;
pub mod write;
