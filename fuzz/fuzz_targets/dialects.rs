//! CSV dialects: a valid random table written as Excel and other programs
//! write CSV — comma, semicolon or tab, CRLF or LF, quoted or bare fields,
//! UTF-8 with or without BOM, UTF-16 LE or BE, a decimal comma in a dwell —
//! reads back as the same table, or the ambiguity is said (W005). Never a
//! different table in silence.
#![no_main]

use libfuzzer_sys::fuzz_target;
use steptable::convert::check_bytes;
use steptable::settings::Settings;
use steptable::diag::Code;
use steptable::random_table::{Shape, random_rows};
use steptable::read::Format;

fuzz_target!(|bytes: &[u8]| {
    if bytes.len() < 10 {
        return;
    }
    let seed = u64::from_le_bytes(bytes[..8].try_into().unwrap());
    let (shape_byte, dialect) = (bytes[8], bytes[9]);
    let shape = Shape {
        actuators: 1 + u32::from(shape_byte % 5),
        max_position: 1 + u32::from(shape_byte / 5 % 3),
        branches: 1 + u32::from(shape_byte / 15 % 3),
        steps: 2 + u32::from(shape_byte / 45),
    };
    let mut rows = random_rows(seed, shape);
    if rows.is_empty() {
        return;
    }
    // A dwell in the first cell, with a decimal point or a decimal comma.
    let dwell = if dialect & 0x40 != 0 { "T=1,5s" } else { "T=1.5s" };
    if dialect & 0x80 != 0 {
        rows[0][0] = format!("{}; {dwell}", rows[0][0]);
    }
    let width = rows.iter().map(Vec::len).max().unwrap_or(1);
    let written = |delimiter: char, quote_all: bool, newline: &str| -> String {
        let mut text = String::new();
        for row in &rows {
            let fields: Vec<String> = (0..width)
                .map(|c| {
                    let field = row.get(c).map(String::as_str).unwrap_or("");
                    let must = field.contains([delimiter, '"', ',', ';']);
                    if (quote_all && !field.is_empty()) || must {
                        format!("\"{}\"", field.replace('"', "\"\""))
                    } else {
                        field.to_string()
                    }
                })
                .collect();
            text.push_str(&fields.join(&delimiter.to_string()));
            text.push_str(newline);
        }
        text
    };
    let delimiter = [',', ';', '\t'][usize::from(dialect % 3)];
    let newline = if dialect & 0x04 != 0 { "\r\n" } else { "\n" };
    let text = written(delimiter, dialect & 0x08 != 0, newline);
    let encoded: Vec<u8> = match (dialect >> 4) & 0x03 {
        0 => text.into_bytes(),
        1 => [b"\xEF\xBB\xBF".as_slice(), text.as_bytes()].concat(),
        2 => [0xFF, 0xFE]
            .into_iter()
            .chain(text.encode_utf16().flat_map(u16::to_le_bytes))
            .collect(),
        _ => [0xFE, 0xFF]
            .into_iter()
            .chain(text.encode_utf16().flat_map(u16::to_be_bytes))
            .collect(),
    };
    let settings = Settings::new();
    let plain = check_bytes(
        "fuzz.csv",
        Format::Csv,
        written(',', true, "\n").into_bytes(),
        &settings,
    );
    let dialected = check_bytes("fuzz.csv", Format::Csv, encoded, &settings);
    match (plain, dialected) {
        (Ok(plain), Ok(read)) => {
            let said = read.warnings.iter().any(|w| w.code == Code::W005Delimiter);
            assert!(
                said || read.table == plain.table,
                "the {delimiter:?} file read as another table without a word"
            );
        }
        // A decimal comma with a comma delimiter is refused (E014) in
        // either spelling when the field is quoted; refusals must agree.
        (Err(_), Err(_)) => {}
        (plain, read) => panic!(
            "the plain and the {delimiter:?} file disagree: {:?} vs {:?}",
            plain.err(),
            read.err()
        ),
    }
});
