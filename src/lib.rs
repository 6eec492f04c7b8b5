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
//! memory and [`write`] writes the result atomically.

pub mod address;
pub mod alloc_guard;
pub mod batch;
pub mod cell;
pub mod convert;
pub mod diag;
pub mod emit;
pub mod faults;
pub mod manifest;
pub mod names;
pub mod program;
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
pub mod valve;
pub mod write;
