//! A guard in front of calamine's `.xls` reader. An `.xls` file is an OLE
//! compound file: sectors linked into chains by a table (the FAT). calamine
//! follows a chain until its end marker, so a damaged FAT whose chain loops
//! makes it read the same sectors for ever, allocating without bound
//! (fuzzing found a 5.8 KB file that took 7.5 GB in 10 s). A valid file
//! never has a loop, so one found here refuses the file before calamine
//! sees it.

const SIGNATURE: &[u8; 8] = b"\xD0\xCF\x11\xE0\xA1\xB1\x1A\xE1";
/// Sector numbers from here up are markers (end of chain, free, FAT, DIFAT).
const MAX_REGULAR: u32 = 0xFFFF_FFFA;
const DIFAT_SECTOR: u32 = 0xFFFF_FFFC;

/// Why the compound file is unsafe to decode, if it is. Files that are not
/// compound files at all pass: calamine reports those itself.
pub fn looping_chain(bytes: &[u8]) -> Option<String> {
    if bytes.len() < 512 || &bytes[..8] != SIGNATURE {
        return None;
    }
    let sector_size: usize = match u16::from_le_bytes([bytes[30], bytes[31]]) {
        9 => 512,
        12 => 4096,
        _ => return None,
    };
    let word = |at: usize| -> Option<u32> {
        bytes
            .get(at..at + 4)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    };
    // Sector n starts after the header, which fills sector -1.
    let sector = |id: u32| -> &[u8] {
        let start = (id as usize + 1).saturating_mul(sector_size);
        let end = start.saturating_add(sector_size).min(bytes.len());
        bytes.get(start..end).unwrap_or(&[])
    };
    let words = |data: &[u8]| -> Vec<u32> {
        data.chunks_exact(4)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .collect()
    };
    let max_sectors = bytes.len() / sector_size + 1;

    // The FAT's own sectors: 109 in the header, the rest in the DIFAT chain.
    let mut fat_sectors: Vec<u32> = words(&bytes[76..512]);
    let mut next = word(68)?;
    let mut hops = 0;
    while next < MAX_REGULAR {
        hops += 1;
        if hops > max_sectors {
            return Some("its DIFAT chain loops".to_string());
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

    // Every chain must end: look for a cycle in the FAT, each sector once.
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
            looping_chain(&compound(&[0xFFFF_FFFD, 2, 0xFFFF_FFFE])),
            None
        );
        // 1 → 2 → 1.
        let looping = looping_chain(&compound(&[0xFFFF_FFFD, 2, 1]));
        assert!(looping.is_some_and(|why| why.contains("loops")));
        // Not a compound file at all: calamine's to judge.
        assert_eq!(looping_chain(b"PK\x03\x04 not ole"), None);
    }
}
