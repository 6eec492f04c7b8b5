//! The ADDRESSES sheet's rows against the program and the target: which
//! signal each names, whether its address is one of the target's inputs or
//! outputs, and that no two share one. Every problem is an error at its cell.

use crate::address::{Address, Assigned, Board, Target};
use crate::diag::{Code, Diagnostics};
use crate::program::{Area, Signal, StepProgram};
use crate::settings::pins::PinRow;

/// The pinned signals at their addresses, or every problem found.
pub fn resolve(
    program: &StepProgram,
    rows: &[PinRow],
    target: Target,
    board: Option<Board>,
    naming: &crate::symbols::Naming,
    diags: &mut Diagnostics,
) -> Vec<Assigned> {
    // Every input and output of the allocation list: the alarm lamps and
    // the criteria analysis's outputs too.
    let signals: Vec<Signal> = program
        .signals
        .inputs
        .iter()
        .copied()
        .chain(program.signals.driven())
        .chain(program.signals.alarms())
        .chain(program.signals.misses())
        .collect();
    let mut pins: Vec<(Assigned, &PinRow)> = Vec::new();
    for row in rows {
        if row.address.is_empty() || row.signal.is_empty() {
            let message = if row.address.is_empty() {
                format!("\"{}\" has no address beside it", row.signal)
            } else {
                format!("the address \"{}\" has no signal beside it", row.address)
            };
            diags.error(Code::E035BadPinnedAddress, row.signal_at.clone(), message);
            continue;
        }
        let pmax = |a: u32| highest_position(&signals, a);
        let Some(signal) = pinned_signal(row, &signals, naming, diags) else {
            continue;
        };
        let Some(address) = pinned_address(row, signal, target, board, &signals, naming, diags)
        else {
            continue;
        };
        if let Some((_, first)) = pins.iter().find(|(p, _)| p.signal == signal) {
            diags.error(
                Code::E035BadPinnedAddress,
                row.signal_at.clone(),
                format!(
                    "{} is pinned twice (first at {})",
                    naming.called_by(signal, &pmax),
                    first.signal_at.cell.map(|c| c.a1()).unwrap_or_default()
                ),
            );
            continue;
        }
        if let Some((other, _)) = pins.iter().find(|(p, _)| p.address == address) {
            diags.error(
                Code::E035BadPinnedAddress,
                row.address_at.clone(),
                format!(
                    "\"{}\" is already {}'s address",
                    row.address.trim(),
                    naming.called_by(other.signal, &pmax)
                ),
            );
            continue;
        }
        pins.push((Assigned { signal, address }, row));
    }
    pins.into_iter().map(|(pin, _)| pin).collect()
}

/// The highest position of actuator `a` a sensor signal names; at least 1.
fn highest_position(signals: &[Signal], a: u32) -> u32 {
    signals
        .iter()
        .filter_map(|s| match s {
            Signal::Sensor { actuator, position } if *actuator == a => Some(*position),
            _ => None,
        })
        .max()
        .unwrap_or(1)
}

/// The signal a row names: by its paper symbol (`x11`), identifier, ISO
/// designation (`1B2`) or the engineer's name (`clamp_end`); E035 when it
/// is none of the program's inputs and outputs.
fn pinned_signal(
    row: &PinRow,
    signals: &[Signal],
    naming: &crate::symbols::Naming,
    diags: &mut Diagnostics,
) -> Option<Signal> {
    let pmax = |a: u32| highest_position(signals, a);
    let Some(signal) = signals.iter().copied().find(|s| {
        naming
            .aliases_by(*s, &pmax)
            .iter()
            .any(|a| a.eq_ignore_ascii_case(row.signal.trim()))
    }) else {
        let names: Vec<String> = signals.iter().take(12).map(|s| s.symbol()).collect();
        let more = if signals.len() > names.len() {
            ", …"
        } else {
            ""
        };
        diags.error(
            Code::E035BadPinnedAddress,
            row.signal_at.clone(),
            format!(
                "\"{}\" is not an input or output of this program (it has {}{more}; names as in the allocation list)",
                row.signal,
                names.join(", ")
            ),
        );
        return None;
    };
    Some(signal)
}

/// The row's address: one of the target's, of the signal's area, on the
/// board when one is named; E035 otherwise.
fn pinned_address(
    row: &PinRow,
    signal: Signal,
    target: Target,
    board: Option<Board>,
    signals: &[Signal],
    naming: &crate::symbols::Naming,
    diags: &mut Diagnostics,
) -> Option<Address> {
    let pmax = |a: u32| highest_position(signals, a);
    let address = match Address::parse(&row.address, target) {
        Ok(address) => address,
        Err(why) => {
            diags.error(Code::E035BadPinnedAddress, row.address_at.clone(), why);
            return None;
        }
    };
    let wanted = signal.area();
    if address.area != wanted {
        let area = |a: Area| {
            if a == Area::Input {
                "an input"
            } else {
                "an output"
            }
        };
        diags.error(
            Code::E035BadPinnedAddress,
            row.address_at.clone(),
            format!(
                "{} is {}, but \"{}\" is {} address",
                naming.called_by(signal, &pmax),
                area(wanted),
                row.address.trim(),
                area(address.area)
            ),
        );
        return None;
    }
    if let Some(board) = board {
        let input = address.area == Area::Input;
        let wired = if input { board.inputs } else { board.outputs };
        if address.index() >= wired {
            diags.error(
                Code::E035BadPinnedAddress,
                row.address_at.clone(),
                format!(
                    "\"{}\" is not on the {} board, which wires {}",
                    row.address.trim(),
                    board.name,
                    board.span(input)
                ),
            );
            return None;
        }
    }
    Some(address)
}
