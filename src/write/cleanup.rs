//! After a conversion's files are written, the files an earlier run wrote
//! into the folder and this one did not (a rerun with fewer `--formats`)
//! are removed, so that a folder never holds a program beside the lists of
//! another table — but never one the engineer may still need: a file
//! changed since it was written, the other files of a project folder that
//! holds one (Beremiz opens the folder only whole), a file reached through
//! a link, an input of this run. Each of those is kept and said.

use std::path::{Path, PathBuf};

use super::{Durability, Inputs, WriteError, stage_and_rename, write_outputs};
use crate::emit::OutputFile;
use crate::manifest::{self, Found, Manifest};

/// What the cleanup after a conversion did.
#[derive(Debug, Default, Clone)]
pub struct Cleanup {
    /// Files of an earlier run removed.
    pub removed: Vec<PathBuf>,
    /// Files of an earlier run this one did not write and kept, each with
    /// why: they are the engineer's now, and no longer in the record (said
    /// once, and a later run would not replace them unasked).
    pub kept: Vec<(PathBuf, &'static str)>,
    /// The inputs an earlier run made the files this one replaced from,
    /// where they are not this run's (`a.csv` converted, then `a.xlsx`
    /// into the same folder): said, as a rerun of the same table is not.
    pub replaced_from: Vec<String>,
}

const CHANGED: &str = "changed since steptable wrote it (it may hold your edits)";
const WITH_PROJECT: &str =
    "its project folder holds a file changed since, and the folder opens only whole";
const LINKED: &str = "reached through a link, which steptable never removes through";
const INPUT: &str = "an input of this run";

/// Writes a conversion's whole set of files, as [`write_outputs`] does, and
/// then removes the files an earlier run recorded writing into the folder
/// that this run did not write (a rerun with fewer `--formats`, or after
/// `faults -o` wrote beside it), where they are still as written. A
/// scenario's page (`simulate --report`), which no conversion writes
/// again, stays without a word; what the engineer may need stays and is
/// said ([`Cleanup::kept`]). Returns the paths written and the cleanup.
pub fn write_conversion(
    folder: &Path,
    files: &[OutputFile],
    inputs: &Inputs,
    durability: Durability,
    made_by: Option<&str>,
) -> Result<(Vec<PathBuf>, Cleanup), WriteError> {
    let before = match folder.is_dir().then(|| Manifest::read(folder)) {
        Some(Found::Manifest(m)) => m,
        _ => Manifest::default(),
    };
    let (stale, kept) = sort_out(folder, files, &before, inputs);
    let replaced_from = other_sources(&before, made_by);
    let written = write_outputs(folder, files, inputs, durability, made_by)?;
    let mut cleanup = Cleanup {
        removed: Vec::new(),
        kept: kept
            .iter()
            .map(|(name, why)| (folder.join(name), *why))
            .collect(),
        replaced_from,
    };
    if stale.is_empty() && kept.is_empty() {
        return Ok((written, cleanup));
    }
    let Found::Manifest(mut record) = Manifest::read(folder) else {
        return Ok((written, cleanup));
    };
    for (name, _) in &kept {
        record.files.remove(name);
        record.made_by.remove(name);
    }
    for name in stale {
        let path = folder.join(&name);
        if std::fs::remove_file(&path).is_ok() {
            record.files.remove(&name);
            record.made_by.remove(&name);
            // A project folder (`NAME.beremiz/`) emptied goes too; one that
            // still holds anything stays.
            if let Some(parent) = path.parent().filter(|p| *p != folder) {
                let _ = std::fs::remove_dir(parent);
            }
            cleanup.removed.push(path);
        }
    }
    let bytes = record.to_bytes();
    stage_and_rename(
        folder,
        &[(manifest::FILE_NAME, bytes.as_slice())],
        durability,
    )?;
    Ok((written, cleanup))
}

/// The inputs, other than this run's, that the earlier run's record says
/// the files in the folder were made from.
fn other_sources(before: &Manifest, made_by: Option<&str>) -> Vec<String> {
    let Some(own) = made_by.and_then(manifest::made_from) else {
        return Vec::new();
    };
    let mut sources: Vec<String> = before
        .made_by
        .values()
        .filter_map(|line| manifest::made_from(line))
        .filter(|source| *source != own)
        .map(str::to_string)
        .collect();
    sources.sort();
    sources.dedup();
    sources
}

/// The files of an earlier run this one does not write, sorted into those
/// to remove and those to keep (with why).
fn sort_out(
    folder: &Path,
    files: &[OutputFile],
    before: &Manifest,
    inputs: &Inputs,
) -> (Vec<String>, Vec<(String, &'static str)>) {
    let left: Vec<&String> = before
        .files
        .keys()
        .filter(|name| inside(name))
        .filter(|name| !files.iter().any(|f| &f.name == *name))
        .filter(|name| !crate::emit::CommandFile::outlives_conversion(name))
        .filter(|name| std::fs::symlink_metadata(folder.join(name)).is_ok())
        .collect();
    let changed = |name: &str| !before.vouches_for(folder, name);
    // Project folders holding a changed file stay whole.
    let edited: Vec<&Path> = left
        .iter()
        .filter(|name| !through_link(folder, name) && changed(name))
        .filter_map(|name| project_of(name))
        .collect();
    let mut stale = Vec::new();
    let mut kept = Vec::new();
    for name in left {
        let path = folder.join(name);
        let why = if through_link(folder, name) {
            LINKED
        } else if changed(name) {
            CHANGED
        } else if inputs.holds(&path) {
            INPUT
        } else if project_of(name).is_some_and(|p| edited.contains(&p)) {
            WITH_PROJECT
        } else {
            stale.push(name.clone());
            continue;
        };
        kept.push((name.clone(), why));
    }
    (stale, kept)
}

/// The project folder (`NAME.beremiz`) a recorded name lies in, if any.
fn project_of(name: &str) -> Option<&Path> {
    Path::new(name)
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
}

/// Whether a folder between `folder` and the file `name` is a link.
fn through_link(folder: &Path, name: &str) -> bool {
    Path::new(name)
        .ancestors()
        .skip(1)
        .filter(|p| !p.as_os_str().is_empty())
        .any(|p| {
            std::fs::symlink_metadata(folder.join(p)).is_ok_and(|m| m.file_type().is_symlink())
        })
}

/// Whether a manifest's file name stays inside its folder: plain names
/// only, no `..`, no root. A manifest is a file anyone can edit; only what
/// lies in the folder is ever removed on its word.
fn inside(name: &str) -> bool {
    let path = Path::new(name);
    !name.is_empty()
        && path
            .components()
            .all(|c| matches!(c, std::path::Component::Normal(_)))
}
