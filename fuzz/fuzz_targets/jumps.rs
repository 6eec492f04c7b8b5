//! Jumps, waits and dwells placed anywhere: a random valid table (its shape
//! and seed from the first bytes) gets items the rest of the bytes choose —
//! `J:<any step or end> if I:<name>[=0]`, `I:<name>[=0]` waits, short and
//! long dwells, in any step, with names that may collide with the program's
//! own or a mode button — and the input delay and modes vary. A table the
//! checks accept must convert: its proof runs every path, and a failure of
//! it on a table steptable accepted is an internal error, i.e. a bug.
#![no_main]

use libfuzzer_sys::fuzz_target;
use steptable::convert::{Failure, check_bytes, generate};
use steptable::program::Modes;
use steptable::random_table::{Shape, add_jumps, random_rows};
use steptable::read::Format;
use steptable::settings::Settings;

const NAMES: [&str; 8] = ["a", "b", "reject", "estop", "stop", "start", "x11", "skip"];

fuzz_target!(|bytes: &[u8]| {
    if bytes.len() < 4 {
        return;
    }
    let (head, items) = bytes.split_at(4);
    let shape = Shape {
        actuators: 1 + u32::from(head[0] % 4),
        max_position: 1 + u32::from(head[0] >> 6),
        branches: 1 + u32::from(head[1] % 3),
        steps: 2 + u32::from(head[1] >> 3) % 12,
    };
    let seed = u64::from(head[2]) | u64::from(head[3]) << 8;
    let mut rows = random_rows(seed, shape);
    add_jumps(seed, &mut rows);
    let steps = rows.len();
    for chunk in items.chunks(3).take(12) {
        let [kind, step, arg] = [
            chunk[0],
            chunk.get(1).copied().unwrap_or(0),
            chunk.get(2).copied().unwrap_or(0),
        ];
        let row = &mut rows[usize::from(step) % steps];
        let name = NAMES[usize::from(arg) % NAMES.len()];
        let value = if arg & 0x80 != 0 { "=0" } else { "" };
        let item = match kind % 4 {
            0 => {
                let target = usize::from(arg >> 3) % (steps + 2);
                let target = if target == 0 {
                    "end".to_string()
                } else {
                    target.to_string()
                };
                format!("J:{target} if I:{name}{value}")
            }
            1 => format!("I:{name}{value}"),
            2 => format!("T={}ms", 10 + u32::from(arg) * 10),
            _ => format!("Y:{name}{}", if arg & 0x80 != 0 { "-" } else { "+" }),
        };
        // Into a filled cell: a bare grid reads only the rectangle of cells
        // that hold moves, and every random row has one.
        let at = usize::from(kind >> 2) % row.len().max(1);
        match row.get_mut(at) {
            Some(cell) => {
                cell.push_str("; ");
                cell.push_str(&item);
            }
            None => row.push(item),
        }
    }
    let csv: String = rows.iter().map(|r| r.join(",") + "\n").collect();
    let mut settings = Settings::new();
    if head[0] & 0x20 != 0 {
        settings.program.modes = Modes::parse("all").unwrap_or_default();
    }
    settings.simulation.scan_ms = [10, 5, 20, 50][usize::from(head[2] % 4)];
    let Ok(checked) = check_bytes("fuzz.csv", Format::Csv, csv.into_bytes(), &settings) else {
        return;
    };
    if let Err(Failure::Internal(why)) = generate("fuzz", checked) {
        panic!("a table the checks accepted failed inside steptable: {why}");
    }
});
