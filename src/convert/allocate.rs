//! The program's addresses: the target's layout, the ADDRESSES sheet's
//! pins, an OpenPLC board, and the limits of a process image.

use crate::address::{Allocation, Mnemonic, Target};
use crate::diag::{Code, Diagnostic, Diagnostics, Location};
use crate::program::StepProgram;
use crate::settings::Settings;

use super::pins;

/// The program's addresses for the target `settings` name, with the
/// ADDRESSES sheet's pins, on the OpenPLC board if one is named; every wrong
/// pin, and a board too small for the program, is a diagnostic. `file`
/// names the table in them.
pub fn allocate(
    program: &StepProgram,
    settings: &Settings,
    file: &str,
) -> Result<Allocation, Vec<Diagnostic>> {
    let mut diags = crate::diag::Diagnostics::new();
    let whole_file = || Location {
        file: file.to_string(),
        sheet: None,
        cell: None,
    };
    if let Some(board) = settings.board
        && settings.target != Target::Iec
    {
        // At the board's cell when the SETTINGS sheet names it, else the
        // target's; the message says where each came from.
        let at = ["board", "target"]
            .iter()
            .find_map(|label| settings.cells.get(label))
            .cloned()
            .unwrap_or_else(whole_file);
        diags.error(
            Code::E036BoardTooSmall,
            at,
            format!(
                "the {} board is OpenPLC's, whose addresses are %IX/%QX, but the target is {}: make the target iec (or openplc, or default), or leave it out (the board from {}, the target from {})",
                board.name,
                settings.target.name(),
                settings.origin("board"),
                settings.origin("target"),
            ),
        );
        return Err(diags.into_sorted());
    }
    let pins = pins::resolve(
        program,
        &settings.pins,
        settings.target,
        settings.board,
        &settings.naming,
        &mut diags,
    );
    if diags.has_errors() {
        return Err(diags.into_sorted());
    }
    let Some(board) = settings.board else {
        let allocation = Allocation::pinned(program, settings.target, settings.mnemonic, &pins);
        beyond_the_image(&allocation, whole_file(), &mut diags);
        if diags.has_errors() {
            return Err(diags.into_sorted());
        }
        return Ok(allocation);
    };
    let allocation = Allocation::on_board(program, settings.mnemonic, &pins);
    for (input, needed, wired) in [
        (true, allocation.inputs.len(), board.inputs),
        (false, allocation.outputs.len(), board.outputs),
    ] {
        if needed > wired as usize {
            diags.error(
                Code::E036BoardTooSmall,
                whole_file(),
                format!(
                    "the program needs {needed} {}, but the {} board ({}) wires {}: choose a board with more, or split the machine",
                    if input { "inputs" } else { "outputs" },
                    board.name,
                    board.label,
                    board.span(input)
                ),
            );
        }
    }
    if diags.has_errors() {
        return Err(diags.into_sorted());
    }
    Ok(allocation)
}

/// A table so large that its inputs or outputs run past byte (or word) 255
/// would get addresses no PLC's process image has, and that steptable
/// refuses when they are pinned (E035): E024, with the counts.
fn beyond_the_image(allocation: &Allocation, at: Location, diags: &mut Diagnostics) {
    let max = crate::address::MAX_PINNED_UNIT;
    for (what, list) in [
        ("inputs", &allocation.inputs),
        ("outputs", &allocation.outputs),
    ] {
        if list.iter().any(|a| a.address.unit > max)
            && let Some(last) = list.last().map(|a| a.address)
        {
            diags.error(
                Code::E024TableTooLarge,
                at.clone(),
                format!(
                    "the program needs {} {what}, which run to {}, past the last address of the process image ({max}): split the machine into smaller tables",
                    list.len(),
                    last.display(allocation.mnemonic)
                ),
            );
        }
    }
}

/// The Festo allocation the FST files use whatever the target: `allocation`
/// itself on Festo; else Festo's own layout (the pins are in the target's
/// notation, so they hold only there).
pub fn festo_allocation(program: &StepProgram, allocation: &Allocation) -> Allocation {
    match allocation.target {
        Target::Festo => allocation.clone(),
        _ => Allocation::new(program, Target::Festo, Mnemonic::En),
    }
}
