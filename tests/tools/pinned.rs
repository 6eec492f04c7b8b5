//! Pinned addresses in the engines: the paper's table with an ADDRESSES
//! sheet moving START, a middle sensor and a coil to other terminals runs
//! in awlsim (siemens), matiec (iec) and the FST interpreter (festo) as
//! simulated, scan for scan, on the pinned addresses.

use crate::engines::{self, Case, awlsim, fst, matiec};
use steptable::template_workbook::PAPER_EXAMPLE;

use crate::helpers::write_xlsx_sheets;
use crate::{Check, Tool, shared, tool};

pub const CHECKS: &[Check] = &[Check::new(
    "pinned::pinned_addresses_run_in_every_engine_as_simulated",
    &[Tool::Shared, Tool::Awlsim],
    pinned_addresses_run_in_every_engine_as_simulated,
)];

/// Converts the paper's table with `pins` for `target` into `dir`.
fn case(dir: &std::path::Path, target: &str, pins: &[&[&str]], format: &str) -> Case {
    let input = dir.join(format!("wired_{target}.xlsx"));
    let paper: Vec<&[&str]> = PAPER_EXAMPLE.iter().map(|r| &r[..]).collect();
    write_xlsx_sheets(&input, &[("TABLE", &paper), ("ADDRESSES", pins)]);
    engines::prepare(
        &input,
        &["--target", target, "--formats", format],
        &dir.join(target),
    )
}

fn pinned_addresses_run_in_every_engine_as_simulated() {
    let dir = tempfile::tempdir().unwrap();
    let siemens = case(
        dir.path(),
        "siemens",
        &[&["START", "I3.0"], &["x22", "I0.0"], &["y2+", "Q5.7"]],
        "awl",
    );
    assert_eq!(
        siemens
            .allocation
            .display(steptable::program::Signal::Start),
        "I3.0"
    );
    let python = awlsim::python(&tool(Tool::Awlsim));
    let awl = awlsim::run(
        &python,
        &siemens.file(".awl"),
        siemens.mnemonic,
        &siemens.trace,
        &siemens.allocation,
    );
    siemens.check("awlsim", awl).unwrap();

    let iec = case(
        dir.path(),
        "iec",
        &[&["START", "%IX3.0"], &["x22", "%IX0.0"], &["y2+", "%QX5.7"]],
        "st",
    );
    let st = matiec::run(&shared(), &iec.file(".st"), &iec.trace, &iec.allocation);
    iec.check("matiec", st).unwrap();

    // On the Raspberry Pi board: packed into the 14 inputs and 11 outputs
    // its hardware layer wires, around a pin on its last input.
    let input = dir.path().join("wired_rpi.xlsx");
    let paper: Vec<&[&str]> = PAPER_EXAMPLE.iter().map(|r| &r[..]).collect();
    let pins: &[&[&str]] = &[&["START", "%IX1.5"]];
    write_xlsx_sheets(&input, &[("TABLE", &paper), ("ADDRESSES", pins)]);
    let rpi = engines::prepare(
        &input,
        &["--board", "rpi", "--valve", "C1=52mono", "--formats", "st"],
        &dir.path().join("rpi"),
    );
    let last = |a: &[steptable::address::Assigned]| a.iter().map(|a| a.address.index()).max();
    assert_eq!(last(&rpi.allocation.inputs), Some(13));
    assert_eq!(
        last(&rpi.allocation.outputs),
        Some(6),
        "seven coils, packed"
    );
    let st = matiec::run(&shared(), &rpi.file(".st"), &rpi.trace, &rpi.allocation);
    rpi.check("matiec", st).unwrap();

    let festo = case(
        dir.path(),
        "festo",
        &[&["START", "I3.0"], &["x22", "I0.0"], &["y2+", "O5.15"]],
        "fst",
    );
    let text = crate::engines::read_ansi(&festo.file(".fst.txt")).unwrap();
    assert!(text.contains("I3.0") && text.contains("O5.15"), "{text}");
    festo
        .check(
            "FST interpreter",
            fst::run(&text, &festo.trace, &festo.festo),
        )
        .unwrap();
    for c in [&siemens, &iec, &rpi, &festo] {
        assert!(c.trace.output_changes() >= 4, "{}", c.label);
    }
    eprintln!(
        "pinned: awlsim, matiec (also on the rpi board) and the FST interpreter run the pinned programs as simulated"
    );
}
