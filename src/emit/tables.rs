//! Tag and allocation tables for other engineering tools: the Festo FST
//! allocation list, a Rockwell (Studio 5000) tag import, and a TIA Portal PLC
//! tag table. All use the same identifiers as every other output.

use minijinja::Value;
use minijinja::value::Serde;
use rust_xlsxwriter::{DocProperties, ExcelDateTime, Format, Workbook, XlsxError};
use serde::Serialize;

use super::{EmitInput, one_line, templates};
use crate::address::Mnemonic;
use crate::program::Area;

#[derive(Serialize)]
struct Entry {
    address: String,
    symbol: String,
    comment: String,
}

#[derive(Serialize)]
struct FstContext {
    symbols: Vec<Entry>,
}

/// `NAME.fst-alloc.csv`: absolute operand, symbolic operand, comment, with
/// the Festo operands the `.fst.txt` uses (inputs, outputs, flags, timer).
pub fn render_fst_alloc(input: &EmitInput) -> Result<String, templates::TemplateError> {
    let festo = input.festo;
    let symbols = festo
        .inputs
        .iter()
        .chain(&festo.outputs)
        .chain(&festo.memories)
        .chain(&festo.timers)
        .map(|a| Entry {
            address: a.address.display(Mnemonic::En),
            symbol: input.symbols.fst(a.signal),
            comment: one_line(&input.symbols.comment(a.signal)),
        })
        .collect();
    input.templates.render(
        "fst-alloc.csv.j2",
        Value::from(Serde(&FstContext { symbols })),
    )
}

#[derive(Serialize)]
struct Tag {
    name: String,
    description: String,
    data_type: &'static str,
}

#[derive(Serialize)]
struct RockwellContext {
    version: &'static str,
    source: String,
    tags: Vec<Tag>,
}

/// `NAME.rockwell.csv`: controller tags (BOOL) for every input, output and
/// memory of the program, each described with its address, for Studio 5000's
/// tag import. Aliasing them to I/O modules stays the engineer's job.
pub fn render_rockwell(input: &EmitInput) -> Result<String, templates::TemplateError> {
    let alloc = input.allocation;
    let tags = alloc
        .inputs
        .iter()
        .chain(&alloc.outputs)
        .chain(&alloc.memories)
        .map(|a| Tag {
            name: input.symbols.ident(a.signal),
            description: one_line(&format!(
                "{} {}",
                a.address.display(alloc.mnemonic),
                input.symbols.comment(a.signal)
            )),
            data_type: "BOOL",
        })
        .collect();
    let context = RockwellContext {
        version: env!("CARGO_PKG_VERSION"),
        source: one_line(&input.source()),
        tags,
    };
    input
        .templates
        .render("rockwell.csv.j2", Value::from(Serde(&context)))
}

/// The TIA Portal version the tag table is laid out for.
pub const TIA_VERSION: &str = "V17";

/// The columns of a TIA Portal PLC tag table export, in order.
pub const TIA_COLUMNS: [&str; 10] = [
    "Name",
    "Path",
    "Data Type",
    "Logical Address",
    "Comment",
    "Hmi Visible",
    "Hmi Accessible",
    "Hmi Writeable",
    "Typeobject ID",
    "Version ID",
];

/// `NAME.tags.xlsx`: sheet `PLC Tags` as TIA Portal's tag table import reads
/// it, with `%I0.0` / `%Q0.0` addresses (`%E0.0` / `%A0.0` with German
/// mnemonics; the physical byte.bit of each signal).
pub fn render_tia_tags(input: &EmitInput) -> Result<Vec<u8>, XlsxError> {
    let alloc = input.allocation;
    let mut workbook = Workbook::new();
    workbook.set_zip_compression_level(1);
    // TIA Portal's own tag table exports carry their version as a custom
    // document property.
    workbook.set_properties(
        &DocProperties::new()
            .set_creation_datetime(&ExcelDateTime::from_ymd(2020, 1, 1)?)
            .set_custom_property("TIA_Version", TIA_VERSION),
    );
    let sheet = workbook.add_worksheet();
    sheet.set_name("PLC Tags")?;
    let bold = Format::new().set_bold();
    for (col, header) in TIA_COLUMNS.iter().enumerate() {
        sheet.write_string_with_format(0, col as u16, *header, &bold)?;
    }
    for (i, a) in alloc.inputs.iter().chain(&alloc.outputs).enumerate() {
        let row = i as u32 + 1;
        let (byte, bit) = a.address.byte_bit();
        let letter = match (a.address.area, alloc.mnemonic) {
            (Area::Input, Mnemonic::En) => "I",
            (Area::Input, Mnemonic::De) => "E",
            (_, Mnemonic::En) => "Q",
            (_, Mnemonic::De) => "A",
        };
        sheet.write_string(row, 0, input.symbols.ident(a.signal))?;
        sheet.write_string(row, 1, "Default tag table")?;
        sheet.write_string(row, 2, "Bool")?;
        sheet.write_string(row, 3, format!("%{letter}{byte}.{bit}"))?;
        sheet.write_string(row, 4, one_line(&input.symbols.comment(a.signal)))?;
        for col in 5..8 {
            sheet.write_string(row, col, "True")?;
        }
    }
    sheet.set_column_width(0, 16)?;
    sheet.set_column_width(1, 18)?;
    sheet.set_column_width(3, 14)?;
    sheet.set_column_width(4, 40)?;
    sheet.set_freeze_panes(1, 0)?;
    workbook.save_to_buffer()
}
