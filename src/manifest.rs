//! What a run wrote into an output folder: `.steptable-manifest`, one line
//! per file (size, hash of its bytes, name relative to the folder). It is
//! how steptable tells its own outputs from an engineer's files without
//! guessing from their names: a rerun replaces a file only if the manifest
//! lists it with the bytes it still has (or if the new bytes are the same),
//! and a folder walk skips a table only if a manifest lists it so. A file
//! changed since it was written is the engineer's again.
//!
//! Under each file's line, indented, the line that says how the run made
//! it (see the `provenance` module): the record of the command line for the
//! files that take no comment of their own (the CSV lists, the STEP 7
//! symbol table, synth's reports).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The manifest's file name in every folder outputs are written to.
pub const FILE_NAME: &str = ".steptable-manifest";

/// The first line, which marks a manifest as steptable's.
const HEADER: &str = "# steptable manifest: files steptable wrote in this folder (bytes, fnv1a64, name); a rerun replaces only these";

/// What starts the line under a file's that says how it was made.
const MADE_BY_INDENT: &str = "  ";

/// What a made-by line (`made by steptable 0.1.0 from paper.xlsx: steptable
/// convert …`, the `provenance` module's) names its outputs made from;
/// `None` for a line not of that form.
pub fn made_from(line: &str) -> Option<&str> {
    let rest = line.strip_prefix("made by steptable ")?;
    let (_, rest) = rest.split_once(" from ")?;
    let end = [": steptable ", ": a library call"]
        .iter()
        .filter_map(|m| rest.find(m))
        .min()?;
    Some(&rest[..end])
}

/// Size and hash of a file's bytes as written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Stamp {
    pub size: u64,
    pub hash: u64,
}

impl Stamp {
    pub fn of(bytes: &[u8]) -> Stamp {
        Stamp {
            size: bytes.len() as u64,
            hash: fnv1a64(bytes),
        }
    }
}

/// FNV-1a, 64 bits: stable across Rust versions and platforms (the
/// standard hasher is not), and enough to notice a file was edited.
fn fnv1a64(bytes: &[u8]) -> u64 {
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in bytes {
        hash ^= u64::from(b);
        hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
    }
    hash
}

/// A folder's manifest: file name (relative, `/`-separated) → stamp.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Manifest {
    pub files: BTreeMap<String, Stamp>,
    /// File name → how the run that wrote it made it (one line).
    pub made_by: BTreeMap<String, String>,
}

/// What is in a folder's manifest place.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Found {
    /// No manifest: no run of this version wrote into the folder.
    None,
    Manifest(Manifest),
    /// A file of that name that is not a manifest (the engineer's).
    Foreign,
}

impl Manifest {
    /// Reads `folder`'s manifest.
    pub fn read(folder: &Path) -> Found {
        match std::fs::read(folder.join(FILE_NAME)) {
            Ok(bytes) => match Manifest::parse(&String::from_utf8_lossy(&bytes)) {
                Some(manifest) => Found::Manifest(manifest),
                None => Found::Foreign,
            },
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => Found::None,
            // A folder of that name, or one we may not read: not ours.
            Err(_) => Found::Foreign,
        }
    }

    fn parse(text: &str) -> Option<Manifest> {
        let mut lines = text.lines();
        if lines.next()? != HEADER {
            return None;
        }
        let mut files = BTreeMap::new();
        let mut made_by = BTreeMap::new();
        let mut last: Option<String> = None;
        for line in lines.filter(|l| !l.is_empty()) {
            if let Some(text) = line.strip_prefix(MADE_BY_INDENT) {
                made_by.insert(last.clone()?, text.to_string());
                continue;
            }
            let mut parts = line.splitn(3, ' ');
            let size = parts.next()?.parse().ok()?;
            let hash = u64::from_str_radix(parts.next()?, 16).ok()?;
            let name = unescape(parts.next()?);
            files.insert(name.clone(), Stamp { size, hash });
            last = Some(name);
        }
        Some(Manifest { files, made_by })
    }

    /// The manifest's text.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut text = format!("{HEADER}\n");
        for (name, stamp) in &self.files {
            text.push_str(&format!(
                "{} {:016x} {}\n",
                stamp.size,
                stamp.hash,
                escape(name)
            ));
            if let Some(made) = self.made_by.get(name) {
                let made: String = made
                    .chars()
                    .map(|c| if c.is_control() { ' ' } else { c })
                    .collect();
                text.push_str(&format!("{MADE_BY_INDENT}{made}\n"));
            }
        }
        text.into_bytes()
    }

    /// Whether the file `name` in `folder` is, byte for byte, what a run
    /// recorded writing there.
    pub fn vouches_for(&self, folder: &Path, name: &str) -> bool {
        let Some(stamp) = self.files.get(name) else {
            return false;
        };
        let path = folder.join(name);
        // A link is never written by steptable, whatever it points to.
        match std::fs::symlink_metadata(&path) {
            Ok(meta) if meta.is_file() && meta.len() == stamp.size => {}
            _ => return false,
        }
        std::fs::read(&path).is_ok_and(|bytes| Stamp::of(&bytes) == *stamp)
    }
}

/// Whether `path` (a file found in a folder walk) is one a run wrote, as
/// the manifest of its folder (or of the folder above, for a project
/// folder's files) records it.
pub fn written_by_a_run(path: &Path, cache: &mut BTreeMap<PathBuf, Found>) -> bool {
    let mut name = match path.file_name() {
        Some(n) => n.to_string_lossy().to_string(),
        None => return false,
    };
    let mut folder = path.parent();
    for _ in 0..2 {
        let Some(dir) = folder else {
            return false;
        };
        let found = cache
            .entry(dir.to_path_buf())
            .or_insert_with(|| Manifest::read(dir));
        if let Found::Manifest(manifest) = found
            && manifest.vouches_for(dir, &name)
        {
            return true;
        }
        let Some(up) = dir.file_name() else {
            return false;
        };
        name = format!("{}/{name}", up.to_string_lossy());
        folder = dir.parent();
    }
    false
}

/// Names hold any character but a line break; `\` escapes it.
fn escape(name: &str) -> String {
    name.replace('\\', "\\\\")
        .replace('\n', "\\n")
        .replace('\r', "\\r")
}

fn unescape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut chars = text.chars();
    while let Some(c) = chars.next() {
        if c != '\\' {
            out.push(c);
            continue;
        }
        match chars.next() {
            Some('n') => out.push('\n'),
            Some('r') => out.push('\r'),
            Some(other) => out.push(other),
            None => out.push('\\'),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The input a made-by line names, also one whose name holds a colon.
    #[test]
    fn a_made_by_line_names_its_input() {
        let line = "made by steptable 0.1.0 from a: b.xlsx: steptable convert x; settings: y";
        assert_eq!(made_from(line), Some("a: b.xlsx"));
        let line = "made by steptable 0.1.0 from p.csv: a library call; settings: y";
        assert_eq!(made_from(line), Some("p.csv"));
        assert_eq!(made_from("# a note of yours"), None);
    }

    #[test]
    fn a_manifest_reads_back_what_it_wrote_and_refuses_what_is_not_one() {
        let mut manifest = Manifest::default();
        manifest.files.insert("a b.st".into(), Stamp::of(b"x"));
        manifest
            .files
            .insert("odd\\name\n.csv".into(), Stamp::of(b""));
        manifest
            .files
            .insert("p.beremiz/plc.xml".into(), Stamp::of(b"y"));
        manifest
            .made_by
            .insert("a b.st".into(), "made by steptable\nconvert".into());
        let text = String::from_utf8(manifest.to_bytes()).unwrap();
        // A line break in the record of a run would end it: a space.
        manifest
            .made_by
            .insert("a b.st".into(), "made by steptable convert".into());
        assert_eq!(Manifest::parse(&text), Some(manifest));
        // The record of a run comes under a file's line, never first.
        assert_eq!(Manifest::parse(&format!("{HEADER}\n  made by\n")), None);
        assert_eq!(Manifest::parse("C1+1\nC1-0\n"), None);
        assert_eq!(Manifest::parse(&format!("{HEADER}\nnot a line\n")), None);
    }

    #[test]
    fn the_hash_is_fnv1a_64() {
        // The published test vectors.
        assert_eq!(fnv1a64(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv1a64(b"a"), 0xaf63_dc4c_8601_ec8c);
    }
}
