//! The allocation list (`NAME.io.csv`): one row per input and output, in
//! address order, with exactly the columns
//! `address,symbol,kind,actuator,position,direction,comment`.

use super::EmitInput;
use crate::program::Signal;

/// The header row.
pub const COLUMNS: [&str; 7] = [
    "address",
    "symbol",
    "kind",
    "actuator",
    "position",
    "direction",
    "comment",
];

/// One row of the allocation list, as text.
pub fn rows(input: &EmitInput) -> Vec<[String; 7]> {
    let alloc = input.allocation;
    alloc
        .inputs
        .iter()
        .chain(&alloc.outputs)
        .map(|a| {
            let (actuator, position, direction) = match a.signal {
                Signal::Sensor { actuator, position } => {
                    (actuator.to_string(), position.to_string(), String::new())
                }
                Signal::Coil { actuator, sign } => (
                    actuator.to_string(),
                    String::new(),
                    sign.symbol().to_string(),
                ),
                Signal::SingleCoil { actuator } => {
                    (actuator.to_string(), String::new(), "+".to_string())
                }
                _ => (String::new(), String::new(), String::new()),
            };
            [
                a.address.display(alloc.mnemonic),
                input.symbols.designation(a.signal),
                input.symbols.role(a.signal).to_string(),
                actuator,
                position,
                direction,
                input.symbols.comment(a.signal),
            ]
        })
        .collect()
}

/// Renders `NAME.io.csv`.
pub fn render(input: &EmitInput) -> Result<Vec<u8>, csv::Error> {
    let mut writer = csv::Writer::from_writer(Vec::new());
    writer.write_record(COLUMNS)?;
    for row in rows(input) {
        writer.write_record(&row)?;
    }
    writer
        .into_inner()
        .map_err(|e| csv::Error::from(std::io::Error::other(e.to_string())))
}
