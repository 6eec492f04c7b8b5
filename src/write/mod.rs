//! Writing outputs: all files of one conversion land complete or not at all.
//! Each is written to a temporary file in its destination folder and renamed
//! into place only after every file was written; an input is never overwritten.
//! Outputs ([`write_outputs`]) replace only files a run recorded writing in
//! the folder's manifest (see [`crate::manifest`]); anything else in their
//! place (an engineer's file, a folder) refuses the whole write, E040.
//!
//! The rename is what makes a file appear whole; flushing each file to the
//! disk as well (fsync) is durability against a power cut, which generated
//! files (rebuilt by one more run) rarely need and which cost most of a
//! batch's time on a busy disk. Like cargo and git, steptable leaves that to
//! the operating system unless asked ([`Durability::Sync`], `--sync`).

use std::collections::HashSet;
use std::io::Write;
use std::path::{Path, PathBuf};

use crate::diag::{Code, Diagnostic, Location, Severity};
use crate::emit::OutputFile;
use crate::manifest::{self, Found, Manifest, Stamp};

mod cleanup;
pub use cleanup::{Cleanup, write_conversion};

/// Why outputs could not be written.
#[derive(Debug, thiserror::Error)]
pub enum WriteError {
    #[error("{path}: {source}")]
    Io {
        path: String,
        #[source]
        source: std::io::Error,
    },
    /// Something that is not a run's output is where an output would go
    /// (E040, one per path): nothing was written.
    #[error("{}", .0.iter().map(|d| d.to_string()).collect::<Vec<_>>().join("\n"))]
    Taken(Vec<Diagnostic>),
}

/// E040 about `path`.
fn taken(path: &Path, message: impl Into<String>) -> Diagnostic {
    Diagnostic {
        severity: Severity::Error,
        code: Code::E040OutputTaken,
        location: Location {
            file: crate::read::display_name(path),
            sheet: None,
            cell: None,
        },
        message: message.into(),
    }
}

fn io_error(path: &Path, source: std::io::Error) -> WriteError {
    WriteError::Io {
        path: path.display().to_string(),
        source,
    }
}

/// How far a write goes before it counts as done.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Durability {
    /// Complete files renamed into place; the operating system writes them
    /// to the disk in its own time.
    #[default]
    Rename,
    /// Each file flushed to the disk before its rename, and the folder after
    /// them: a power cut leaves the old files or the new ones.
    Sync,
}

/// The files a run reads, which its outputs never replace: resolved once per
/// run (links and `..` followed), not once per folder written, which for a
/// batch of n workbooks resolved n² paths.
#[derive(Debug, Clone, Default)]
pub struct Inputs {
    real: HashSet<PathBuf>,
    /// The option that named the output folder, when not `-o` (`simulate
    /// --report DIR`): E040's advice names the option the command has.
    option: Option<&'static str>,
}

impl Inputs {
    /// The inputs among `paths` that exist now.
    pub fn new(paths: &[PathBuf]) -> Self {
        Self {
            real: paths
                .iter()
                .filter_map(|p| std::fs::canonicalize(p).ok())
                .collect(),
            option: None,
        }
    }

    /// The same, for outputs whose folder the option `option` names.
    pub fn named_by(mut self, option: &'static str) -> Self {
        self.option = Some(option);
        self
    }

    /// E040's advice in the words of the command run: `-o` is the option
    /// of most commands, not of all.
    fn advise(&self, mut problems: Vec<Diagnostic>) -> Vec<Diagnostic> {
        if let Some(option) = self.option {
            for p in &mut problems {
                p.message = p.message.replace(" with -o", &format!(" with {option}"));
            }
        }
        problems
    }

    /// No inputs to keep (outputs made from nothing the user named).
    pub fn none() -> Self {
        Self::default()
    }

    /// Whether `path` is one of the run's inputs (links followed).
    fn holds(&self, path: &Path) -> bool {
        std::fs::canonicalize(path).is_ok_and(|real| self.real.contains(&real))
    }
}

/// Writes the outputs `files` into `folder` (created if missing) and records
/// them in its manifest. A file already in an output's place is replaced
/// only if the manifest says a run wrote it and it is unchanged since, or
/// if it holds the very bytes about to be written (nothing is lost; an
/// output folder of a version without manifests reruns so). Anything else
/// there — an engineer's file, a link, a folder, a file where a folder must
/// be, an input of this run — is E040 for each, and nothing is written.
/// `made_by`, the line that says how the run made them (see
/// the `provenance` module), is recorded for each in the manifest. Returns
/// the paths written.
pub fn write_outputs(
    folder: &Path,
    files: &[OutputFile],
    inputs: &Inputs,
    durability: Durability,
    made_by: Option<&str>,
) -> Result<Vec<PathBuf>, WriteError> {
    write_recorded(folder, files, inputs, durability, made_by, Links::Refused)
}

/// As [`write_outputs`], into the folder the user named with `-o` (the
/// batch summary): that folder may be a link the user made (a share, a
/// folder on another disk); the folders steptable makes below it may not.
pub fn write_into_named_folder(
    folder: &Path,
    files: &[OutputFile],
    inputs: &Inputs,
    durability: Durability,
    made_by: Option<&str>,
) -> Result<Vec<PathBuf>, WriteError> {
    write_recorded(
        folder,
        files,
        inputs,
        durability,
        made_by,
        Links::FolderItself,
    )
}

/// Whether the output folder itself may be a link.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Links {
    Refused,
    FolderItself,
}

fn write_recorded(
    folder: &Path,
    files: &[OutputFile],
    inputs: &Inputs,
    durability: Durability,
    made_by: Option<&str>,
    links: Links,
) -> Result<Vec<PathBuf>, WriteError> {
    let mut problems = folder_problems(folder, files, inputs, links);
    // A folder that is not there (or is a file: said above) has no record.
    let found = if folder.is_dir() {
        Manifest::read(folder)
    } else {
        Found::None
    };
    let found_none = found == Found::None;
    let read_first = found.clone();
    let mut recorded = match found {
        Found::Manifest(m) => m,
        Found::None => Manifest::default(),
        Found::Foreign => {
            problems.push(taken(
                &folder.join(manifest::FILE_NAME),
                "steptable records its outputs in a file of this name, and this one is not such a record; nothing written: move it, or choose another output folder with -o",
            ));
            Manifest::default()
        }
    };
    // Without a manifest the folder may be an older version's outputs.
    let unrecorded = if found_none {
        "an output goes here, and no steptable run recorded writing this file (the folder has no record: if a steptable before manifests wrote it, delete those old outputs once)"
    } else {
        "an output goes here, and no steptable run recorded writing this file"
    };
    // Each file already in place is read and hashed: on both cores, in
    // the order of the files.
    use rayon::prelude::*;
    let said = |target: &Path| {
        let shown = crate::read::display_name(target);
        problems.iter().any(|d| d.location.file == shown) // an input
    };
    let in_place: Vec<Diagnostic> = files
        .par_iter()
        .filter_map(|file| {
            let target = folder.join(&file.name);
            let meta = std::fs::symlink_metadata(&target).ok()?;
            if said(&target) {
                return None;
            }
            if meta.file_type().is_symlink() {
                return Some(taken(&target, LINKED_FILE));
            }
            if meta.is_dir() {
                return Some(taken(
                    &target,
                    "an output file goes here, and this is a folder; nothing written: move or rename the folder, or choose another output folder with -o",
                ));
            }
            if recorded.vouches_for(folder, &file.name) || same_bytes(&meta, &target, file) {
                return None;
            }
            let why = if recorded.files.contains_key(&file.name) {
                "an output goes here, and this file changed since steptable wrote it (it may hold your edits)"
            } else {
                unrecorded
            };
            // The record is named only where there is one to read.
            let see = if found_none {
                String::new()
            } else {
                format!(" (see {})", manifest::FILE_NAME)
            };
            Some(taken(
                &target,
                format!(
                    "{why}; nothing written: move it, or choose another output folder with -o{see}"
                ),
            ))
        })
        .collect();
    problems.extend(in_place);
    if !problems.is_empty() {
        // A run writing into the folder at the same time may have put its
        // record and its files in place between our reading the one and
        // looking at the others: look again with its record.
        if folder.is_dir() && Manifest::read(folder) != read_first {
            return write_recorded(folder, files, inputs, durability, made_by, links);
        }
        return Err(WriteError::Taken(inputs.advise(problems)));
    }
    // Entries whose files are gone are dropped; the rest stay ours.
    recorded
        .files
        .retain(|name, _| std::fs::symlink_metadata(folder.join(name)).is_ok());
    let kept = recorded.files.clone();
    recorded.made_by.retain(|name, _| kept.contains_key(name));
    let stamps: Vec<Stamp> = files.par_iter().map(|f| Stamp::of(&f.bytes)).collect();
    for (file, stamp) in files.iter().zip(stamps) {
        recorded.files.insert(file.name.clone(), stamp);
        match made_by {
            Some(line) => recorded.made_by.insert(file.name.clone(), line.to_string()),
            None => recorded.made_by.remove(&file.name),
        };
    }
    // First, so that a file of this run is never seen in place before the
    // record that vouches for it (a second run into the folder at the
    // same time replaces it then, rather than taking it for a user's).
    let record = recorded.to_bytes();
    let mut all = vec![(manifest::FILE_NAME, record.as_slice())];
    all.extend(files.iter().map(|f| (f.name.as_str(), f.bytes.as_slice())));
    let mut written = stage_and_rename(folder, &all, durability)?;
    written.remove(0);
    Ok(written)
}

/// Writes `files` into `folder` (created if missing), replacing what is
/// there except an input: for a caller that decided already what may be
/// replaced (`--force`). Returns the paths written.
pub fn write_files(
    folder: &Path,
    files: &[OutputFile],
    inputs: &Inputs,
    durability: Durability,
) -> Result<Vec<PathBuf>, WriteError> {
    let problems = folder_problems(folder, files, inputs, Links::FolderItself);
    if !problems.is_empty() {
        return Err(WriteError::Taken(problems));
    }
    let all: Vec<(&str, &[u8])> = files
        .iter()
        .map(|f| (f.name.as_str(), f.bytes.as_slice()))
        .collect();
    stage_and_rename(folder, &all, durability)
}

/// Whether the file at `target` (not a link) already holds `file`'s bytes:
/// replacing it loses nothing.
fn same_bytes(meta: &std::fs::Metadata, target: &Path, file: &OutputFile) -> bool {
    meta.is_file()
        && meta.len() == file.bytes.len() as u64
        && std::fs::read(target).is_ok_and(|b| b == file.bytes)
}

/// E040 when the nearest part of `folder` that exists is no folder (`-o`
/// names a file, or a file stands where an output's folder goes).
pub fn output_folder_problem(folder: &Path) -> Option<Diagnostic> {
    let existing = folder
        .ancestors()
        .filter(|a| !a.as_os_str().is_empty())
        .find(|a| std::fs::metadata(a).is_ok())?;
    (!existing.is_dir()).then(|| {
        taken(
            existing,
            "is a file, and outputs go into a folder of this name; nothing written: choose another output folder with -o, or move the file",
        )
    })
}

/// What stands where the folders of the outputs must be (a file where a
/// folder goes), and outputs that would replace an input of the run.
fn folder_problems(
    folder: &Path,
    files: &[OutputFile],
    inputs: &Inputs,
    links: Links,
) -> Vec<Diagnostic> {
    let mut problems = Vec::new();
    let mut parents: Vec<PathBuf> = files
        .iter()
        .filter_map(|f| folder.join(&f.name).parent().map(Path::to_path_buf))
        .collect();
    parents.push(folder.to_path_buf());
    parents.sort();
    parents.dedup();
    for parent in parents {
        // Writing through a linked folder would put (and on a rerun,
        // remove) files wherever the link points.
        let linked = (links == Links::Refused || parent != folder)
            && std::fs::symlink_metadata(&parent).is_ok_and(|m| m.file_type().is_symlink());
        let problem = if linked {
            Some(taken(&parent, LINKED_FOLDER))
        } else {
            output_folder_problem(&parent)
        };
        if let Some(problem) = problem
            && !problems.contains(&problem)
        {
            problems.push(problem);
        }
    }
    if let Ok(existing) = std::fs::canonicalize(folder) {
        for file in files {
            let target = existing.join(&file.name);
            if inputs.real.contains(&target) {
                problems.push(taken(
                    &folder.join(&file.name),
                    "is an input of this run, and an output would replace it; nothing written: choose another output folder with -o",
                ));
            }
        }
    }
    problems
}

const LINKED_FILE: &str = "an output goes here, and this is a link; steptable never writes through a link nor replaces one (it would change the file it points to, or undo your link); nothing written: remove the link, or choose another output folder with -o";

const LINKED_FOLDER: &str = "outputs go into this folder, and it is a link; steptable never writes through a linked folder it makes (its files would land, and a rerun would remove them, wherever the link points); nothing written: remove the link, or name the linked folder itself with -o";

/// Every file to a temporary file beside its place, then all renamed into
/// place: all land, or none.
fn stage_and_rename(
    folder: &Path,
    files: &[(&str, &[u8])],
    durability: Durability,
) -> Result<Vec<PathBuf>, WriteError> {
    std::fs::create_dir_all(folder).map_err(|e| io_error(folder, e))?;
    // A project folder's files (`NAME.beremiz/plc.xml`) go below it.
    let mut parents: Vec<&Path> = files
        .iter()
        .filter_map(|(name, _)| Path::new(name).parent())
        .collect();
    parents.sort();
    parents.dedup();
    for parent in parents {
        let parent = folder.join(parent);
        std::fs::create_dir_all(&parent).map_err(|e| io_error(&parent, e))?;
    }
    // Staged on both cores; a file that fails drops (and so removes) the
    // temporary files staged beside it.
    use rayon::prelude::*;
    let staged: Vec<(tempfile::NamedTempFile, PathBuf)> = files
        .par_iter()
        .map(|(name, bytes)| stage(folder, name, bytes, durability))
        .collect::<Result<_, _>>()?;
    let mut written: Vec<PathBuf> = Vec::with_capacity(staged.len());
    for (temp, target) in staged {
        if let Err(e) = temp.persist(&target) {
            // All or none: take back what this run already put in place.
            for path in &written {
                let _ = std::fs::remove_file(path);
            }
            return Err(io_error(&target, e.error));
        }
        written.push(target);
    }
    if durability == Durability::Sync {
        sync_folders(folder, &written)?;
    }
    Ok(written)
}

/// `bytes` in a temporary file beside `name`'s place in `folder`, flushed
/// to the disk when `durability` asks; with that place.
fn stage(
    folder: &Path,
    name: &str,
    bytes: &[u8],
    durability: Durability,
) -> Result<(tempfile::NamedTempFile, PathBuf), WriteError> {
    let target = folder.join(name);
    let parent = target.parent().unwrap_or(folder);
    let mut builder = tempfile::Builder::new();
    builder.prefix(".steptable-").suffix(".tmp");
    // Temporary files are private (0600); outputs are ordinary files,
    // readable as the umask allows.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    let mut temp = builder
        .tempfile_in(parent)
        .map_err(|e| io_error(&target, e))?;
    temp.write_all(bytes)
        .and_then(|_| match durability {
            Durability::Sync => temp.as_file().sync_all(),
            Durability::Rename => Ok(()),
        })
        .map_err(|e| io_error(&target, e))?;
    Ok((temp, target))
}

/// Flushes the folders that received files, so that the renames survive a
/// power cut too (on Windows a folder cannot be opened to flush: the file
/// flushes above are what there is).
fn sync_folders(folder: &Path, written: &[PathBuf]) -> Result<(), WriteError> {
    let mut folders: Vec<&Path> = written.iter().filter_map(|p| p.parent()).collect();
    folders.push(folder);
    folders.sort();
    folders.dedup();
    for dir in folders {
        #[cfg(unix)]
        std::fs::File::open(dir)
            .and_then(|f| f.sync_all())
            .map_err(|e| io_error(dir, e))?;
        #[cfg(not(unix))]
        let _ = dir;
    }
    Ok(())
}
