//! A guard in front of calamine's `.xls` reader, for two damaged-file traps
//! fuzzing found in it:
//!
//! - An `.xls` file is an OLE compound file: sectors linked into chains by a
//!   table (the FAT). calamine follows a chain until its end marker, so a FAT
//!   whose chain loops makes it read the same sectors for ever, allocating
//!   without bound (a 5.8 KB file took 7.5 GB in 10 s). A valid file never
//!   has a loop.
//! - Each sheet's DIMENSIONS record says how many rows and columns it spans,
//!   and calamine reserves memory for all of them at once: a 5.6 KB file
//!   claiming billions of cells asked for 171 GB and the process aborted.
//!
//! Both are checked here, on calamine's own reading paths, before calamine
//! sees the file.

const SIGNATURE: &[u8; 8] = b"\xD0\xCF\x11\xE0\xA1\xB1\x1A\xE1";
/// Sector numbers from here up are markers (end of chain, free, FAT, DIFAT).
const MAX_REGULAR: u32 = 0xFFFF_FFFA;
const DIFAT_SECTOR: u32 = 0xFFFF_FFFC;

/// Most cells a sheet's DIMENSIONS record may span: the format's own limit,
/// 65,536 rows × 256 columns.
pub const MAX_SPAN: i64 = 65_536 * 256;

/// Why an `.xls` file is not decoded.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Refusal {
    /// Its structure is impossible (a looping chain, wrapped dimensions).
    Damaged(String),
    /// A sheet's cells spread over more than [`MAX_CELL_SPAN`] cells.
    TooLarge(String),
}

/// Why the `.xls` file is unsafe to decode, if it is. Files that are not
/// compound files at all pass: calamine reports those itself.
pub fn unsafe_to_decode(bytes: &[u8]) -> Option<Refusal> {
    let (sector_size, fat) = match read_fat(bytes)? {
        Ok(found) => found,
        Err(why) => return Some(Refusal::Damaged(why)),
    };
    if let Some(why) = find_loop(&fat) {
        return Some(Refusal::Damaged(why));
    }
    let file = Compound {
        bytes,
        sector_size,
        fat,
    };
    let stream = file.stream("Workbook").or_else(|| file.stream("Book"))?;
    oversized_sheet(&stream)
}

/// A compound file's header facts and its FAT.
struct Compound<'a> {
    bytes: &'a [u8],
    sector_size: usize,
    fat: Vec<u32>,
}

impl<'a> Compound<'a> {
    fn sector(&self, id: u32) -> &'a [u8] {
        sector(self.bytes, self.sector_size, id)
    }

    /// The bytes of the chain from `start` (the FAT has no loop, so it ends).
    fn chain(&self, start: u32) -> Vec<u8> {
        let mut data = Vec::new();
        let mut id = start;
        while (id as usize) < self.fat.len() && data.len() < self.bytes.len() {
            data.extend_from_slice(self.sector(id));
            id = self.fat[id as usize];
        }
        data
    }

    /// The named stream, read the way calamine reads it: from the mini
    /// stream when shorter than 4096 bytes, else from the sectors.
    fn stream(&self, name: &str) -> Option<Vec<u8>> {
        let directory = self.chain(u32_at(self.bytes, 48)?);
        let entries: Vec<&[u8]> = directory.chunks_exact(128).collect();
        let entry = entries
            .iter()
            .find(|e| entry_name(e).eq_ignore_ascii_case(name))?;
        let start = u32_at(entry, 116)?;
        let size = u32_at(entry, 120)? as usize;
        let mut data = if size < 4096 {
            let root = entries.first()?;
            let mini_stream = self.chain(u32_at(root, 116)?);
            let mini_fat: Vec<u32> = words(&self.chain(u32_at(self.bytes, 60)?));
            let mut data = Vec::new();
            let mut id = start;
            // Mini chains may loop too; calamine stops at the stream's size.
            while data.len() < size && (id as usize) < mini_fat.len() {
                let at = id as usize * 64;
                data.extend_from_slice(mini_stream.get(at..at + 64).unwrap_or(&[]));
                id = mini_fat[id as usize];
            }
            data
        } else {
            self.chain(start)
        };
        data.truncate(size);
        Some(data)
    }
}

fn entry_name(entry: &[u8]) -> String {
    let units: Vec<u16> = entry[..64]
        .chunks_exact(2)
        .map(|b| u16::from_le_bytes([b[0], b[1]]))
        .take_while(|u| *u != 0)
        .collect();
    String::from_utf16_lossy(&units)
}

fn u16_at(bytes: &[u8], at: usize) -> Option<u16> {
    bytes
        .get(at..at + 2)
        .map(|b| u16::from_le_bytes([b[0], b[1]]))
}

fn u32_at(bytes: &[u8], at: usize) -> Option<u32> {
    bytes
        .get(at..at + 4)
        .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
}

fn words(data: &[u8]) -> Vec<u32> {
    data.chunks_exact(4)
        .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect()
}

/// The BIFF records from `at` on: (type, data).
fn records(stream: &[u8], mut at: usize) -> impl Iterator<Item = (u16, &[u8])> {
    std::iter::from_fn(move || {
        let typ = u16_at(stream, at)?;
        let len = u16_at(stream, at + 2)? as usize;
        let data = stream.get(at + 4..at + 4 + len)?;
        at += 4 + len;
        Some((typ, data))
    })
}

/// A sheet whose DIMENSIONS record spans more than [`MAX_SPAN`] cells, or
/// whose last row or column comes before its first, as calamine reads it:
/// the sheets at the offsets the workbook globals give, nested substreams
/// (charts) skipped.
fn oversized_sheet(stream: &[u8]) -> Option<Refusal> {
    let sheets: Vec<usize> = records(stream, 0)
        .take_while(|(typ, _)| *typ != 0x000A)
        .filter(|(typ, _)| *typ == 0x0085)
        .filter_map(|(_, data)| u32_at(data, 0).map(|p| p as usize))
        .collect();
    for start in sheets {
        let mut seen_bof = false;
        let mut depth = 0usize;
        let mut cells = BoundingBox::default();
        for (typ, data) in records(stream, start) {
            if depth > 0 {
                match typ {
                    0x0809 => depth += 1,
                    0x000A => depth -= 1,
                    _ => {}
                }
                continue;
            }
            match typ {
                0x0809 if seen_bof => depth += 1,
                0x0809 => seen_bof = true,
                0x000A => break,
                // Cell records: row and column first.
                0x0203 | 0x0204 | 0x00D6 | 0x0205 | 0x027E | 0x00FD | 0x0006 => {
                    if let (Some(row), Some(col)) = (u16_at(data, 0), u16_at(data, 2)) {
                        cells.add(row, col);
                    }
                }
                // MulRk: a run of cells in one row, its last column at the end.
                0x00BD if data.len() >= 6 => {
                    if let (Some(row), Some(first), Some(last)) = (
                        u16_at(data, 0),
                        u16_at(data, 2),
                        u16_at(data, data.len() - 2),
                    ) {
                        cells.add(row, first);
                        cells.add(row, last);
                    }
                }
                0x0200 => match dimensions_span(data) {
                    Some(span) if span < 1 => {
                        return Some(Refusal::Damaged(
                            "a sheet's dimensions end before they start".to_string(),
                        ));
                    }
                    Some(span) if span > MAX_SPAN => {
                        return Some(Refusal::Damaged(format!(
                            "a sheet claims to span {span} cells; an .xls sheet has at most {MAX_SPAN}"
                        )));
                    }
                    _ => {}
                },
                _ => {}
            }
        }
        // calamine lays a sheet's cells out as one dense rectangle.
        let span = cells.span();
        if span > MAX_CELL_SPAN {
            return Some(Refusal::TooLarge(format!(
                "a sheet's cells spread over a rectangle of {span} cells; at most {MAX_CELL_SPAN} are read"
            )));
        }
    }
    None
}

/// Most cells the rectangle around a sheet's filled cells may hold (what
/// calamine allocates for it), as for every other format.
pub const MAX_CELL_SPAN: u64 = super::MAX_FILLED_CELLS as u64;

/// The rectangle around the cells seen so far.
#[derive(Default)]
struct BoundingBox {
    corners: Option<((u16, u16), (u16, u16))>,
}

impl BoundingBox {
    fn add(&mut self, row: u16, col: u16) {
        self.corners = Some(match self.corners {
            None => ((row, col), (row, col)),
            Some(((r0, c0), (r1, c1))) => ((r0.min(row), c0.min(col)), (r1.max(row), c1.max(col))),
        });
    }

    fn span(&self) -> u64 {
        self.corners.map_or(0, |((r0, c0), (r1, c1))| {
            ((r1 - r0) as u64 + 1).saturating_mul((c1 - c0) as u64 + 1)
        })
    }
}

/// The cells a DIMENSIONS record spans, computed as calamine does (a
/// negative or zero count is what its unsigned arithmetic would wrap).
fn dimensions_span(data: &[u8]) -> Option<i64> {
    let (first_row, last_row, mut first_col, last_col): (i64, i64, i64, i64) = match data.len() {
        10 => (
            u16_at(data, 0)?.into(),
            u16_at(data, 2)?.into(),
            u16_at(data, 4)?.into(),
            u16_at(data, 6)?.into(),
        ),
        14 | 16 => (
            u32_at(data, 0)?.into(),
            u32_at(data, 4)?.into(),
            u16_at(data, 8)?.into(),
            u16_at(data, 10)?.into(),
        ),
        _ => return None,
    };
    if first_col > 0xFF || last_col < first_col {
        first_col = 0;
    }
    let (end_row, end_col) = if last_row >= 1 && last_col >= 1 {
        (last_row - 1, last_col - 1)
    } else {
        (first_row, first_col)
    };
    let rows = end_row - first_row + 1;
    let cols = end_col - first_col + 1;
    if rows <= 0 || cols <= 0 {
        return Some(0);
    }
    Some(rows.saturating_mul(cols))
}

/// Sector `id` of a compound file (what of it the file holds). Sector n
/// starts after the header, which fills sector -1.
fn sector(bytes: &[u8], sector_size: usize, id: u32) -> &[u8] {
    let start = (id as usize + 1).saturating_mul(sector_size);
    let end = start.saturating_add(sector_size).min(bytes.len());
    bytes.get(start..end).unwrap_or(&[])
}

/// The sector size and the FAT, or why the FAT cannot be trusted; `None`
/// when the bytes are not a compound file at all.
fn read_fat(bytes: &[u8]) -> Option<Result<(usize, Vec<u32>), String>> {
    if bytes.len() < 512 || &bytes[..8] != SIGNATURE {
        return None;
    }
    let sector_size: usize = match u16_at(bytes, 30)? {
        9 => 512,
        12 => 4096,
        _ => return None,
    };
    let sector = |id: u32| sector(bytes, sector_size, id);
    let max_sectors = bytes.len() / sector_size + 1;

    // The FAT's own sectors: 109 in the header, the rest in the DIFAT chain.
    let mut fat_sectors: Vec<u32> = words(&bytes[76..512]);
    let mut next = u32_at(bytes, 68)?;
    let mut hops = 0;
    while next < MAX_REGULAR {
        hops += 1;
        if hops > max_sectors {
            return Some(Err("its DIFAT chain loops".to_string()));
        }
        let mut entries = words(sector(next));
        next = entries.pop().unwrap_or(u32::MAX);
        fat_sectors.extend(entries);
    }
    let fat: Vec<u32> = fat_sectors
        .into_iter()
        .filter(|id| *id < DIFAT_SECTOR)
        .flat_map(|id| words(sector(id)))
        .collect();
    Some(Ok((sector_size, fat)))
}

/// Every chain must end: a cycle in the FAT, found visiting each sector once.
fn find_loop(fat: &[u32]) -> Option<String> {
    const NEW: u8 = 0;
    const ON_PATH: u8 = 1;
    const DONE: u8 = 2;
    let mut state = vec![NEW; fat.len()];
    let mut path = Vec::new();
    for start in 0..fat.len() {
        let mut at = start;
        while at < fat.len() && state[at] == NEW {
            state[at] = ON_PATH;
            path.push(at);
            at = fat[at] as usize;
        }
        if at < fat.len() && state[at] == ON_PATH {
            return Some(format!("the sector chain through sector {at} loops"));
        }
        for visited in path.drain(..) {
            state[visited] = DONE;
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A minimal compound file: header, one FAT sector, then `chain` as the
    /// FAT's first entries.
    fn compound(chain: &[u32]) -> Vec<u8> {
        let mut bytes = vec![0u8; 512 * 3];
        bytes[..8].copy_from_slice(SIGNATURE);
        bytes[30..32].copy_from_slice(&9u16.to_le_bytes());
        bytes[68..72].copy_from_slice(&0xFFFF_FFFEu32.to_le_bytes());
        // DIFAT: the FAT is sector 0, the other header slots are free.
        for slot in 0..109 {
            let id: u32 = if slot == 0 { 0 } else { 0xFFFF_FFFF };
            bytes[76 + 4 * slot..80 + 4 * slot].copy_from_slice(&id.to_le_bytes());
        }
        let fat_start = 512;
        for i in 0..128 {
            let value = chain.get(i).copied().unwrap_or(0xFFFF_FFFF);
            bytes[fat_start + 4 * i..fat_start + 4 * i + 4].copy_from_slice(&value.to_le_bytes());
        }
        bytes
    }

    #[test]
    fn finds_a_loop_and_passes_a_proper_chain() {
        // Sector 0 is the FAT itself (0xFFFFFFFD), 1 → 2 → end.
        assert_eq!(
            unsafe_to_decode(&compound(&[0xFFFF_FFFD, 2, 0xFFFF_FFFE])),
            None
        );
        // 1 → 2 → 1.
        let looping = unsafe_to_decode(&compound(&[0xFFFF_FFFD, 2, 1]));
        assert!(matches!(looping, Some(Refusal::Damaged(why)) if why.contains("loops")));
        // Not a compound file at all: calamine's to judge.
        assert_eq!(unsafe_to_decode(b"PK\x03\x04 not ole"), None);
    }

    fn dims(first_row: u32, last_row: u32, first_col: u16, last_col: u16) -> Vec<u8> {
        let mut data = Vec::new();
        data.extend(first_row.to_le_bytes());
        data.extend(last_row.to_le_bytes());
        data.extend(first_col.to_le_bytes());
        data.extend(last_col.to_le_bytes());
        data.extend([0, 0]);
        data
    }

    #[test]
    fn sheet_dimensions_are_read_as_calamine_reads_them() {
        // Rows 0..13, columns 2..6 (the last row and column are one past).
        assert_eq!(dimensions_span(&dims(1, 13, 2, 6)), Some(12 * 4));
        assert_eq!(
            dimensions_span(&dims(0, 1_000_000, 0, 200)),
            Some(200_000_000)
        );
        // A last row before the first wraps in calamine's arithmetic.
        assert!(dimensions_span(&dims(10, 5, 0, 1)).is_some_and(|s| s < 1));
        // A sheet stream: globals with one BoundSheet pointing at the sheet.
        let record = |typ: u16, data: &[u8]| {
            let mut r = typ.to_le_bytes().to_vec();
            r.extend((data.len() as u16).to_le_bytes());
            r.extend(data);
            r
        };
        let sheet_at = 4 + 8 + 4;
        let mut stream = record(0x0085, &(sheet_at as u32).to_le_bytes().repeat(2));
        stream.extend(record(0x000A, &[]));
        assert_eq!(stream.len(), sheet_at);
        stream.extend(record(0x0809, &[0; 4]));
        stream.extend(record(0x0200, &dims(0, 70_000, 0, 256)));
        assert!(
            matches!(oversized_sheet(&stream), Some(Refusal::Damaged(why)) if why.contains("17920000 cells"))
        );
    }
}
