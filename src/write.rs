//! Writing outputs: all files of one conversion land complete or not at all.
//! Each is written to a temporary file in its destination folder and renamed
//! into place only after every file was written; an input is never overwritten.
//!
//! The rename is what makes a file appear whole; flushing each file to the
//! disk as well (fsync) is durability against a power cut, which generated
//! files (rebuilt by one more run) rarely need and which cost most of a
//! batch's time on a busy disk. Like cargo and git, steptable leaves that to
//! the operating system unless asked ([`Durability::Sync`], `--sync`).

use std::collections::HashSet;
use std::io::Write;
use std::path::{Path, PathBuf};

use crate::emit::OutputFile;

/// Why outputs could not be written.
#[derive(Debug, thiserror::Error)]
pub enum WriteError {
    #[error("{path}: {source}")]
    Io {
        path: String,
        #[source]
        source: std::io::Error,
    },
    #[error("{path}: refusing to overwrite an input file; choose another output folder with -o")]
    WouldOverwriteInput { path: String },
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
}

impl Inputs {
    /// The inputs among `paths` that exist now.
    pub fn new(paths: &[PathBuf]) -> Self {
        Self {
            real: paths
                .iter()
                .filter_map(|p| std::fs::canonicalize(p).ok())
                .collect(),
        }
    }

    /// No inputs to keep (outputs made from nothing the user named).
    pub fn none() -> Self {
        Self::default()
    }
}

/// Writes `files` into `folder` (created if missing). Returns the paths written.
pub fn write_files(
    folder: &Path,
    files: &[OutputFile],
    inputs: &Inputs,
    durability: Durability,
) -> Result<Vec<PathBuf>, WriteError> {
    if let Ok(existing) = std::fs::canonicalize(folder) {
        for file in files {
            let target = existing.join(&file.name);
            if inputs.real.contains(&target) {
                return Err(WriteError::WouldOverwriteInput {
                    path: folder.join(&file.name).display().to_string(),
                });
            }
        }
    }
    std::fs::create_dir_all(folder).map_err(|e| io_error(folder, e))?;

    let mut staged = Vec::with_capacity(files.len());
    for file in files {
        let target = folder.join(&file.name);
        // A project folder's files (`NAME.beremiz/plc.xml`) go below it.
        let parent = target.parent().unwrap_or(folder);
        std::fs::create_dir_all(parent).map_err(|e| io_error(parent, e))?;
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
        temp.write_all(&file.bytes)
            .and_then(|_| match durability {
                Durability::Sync => temp.as_file().sync_all(),
                Durability::Rename => Ok(()),
            })
            .map_err(|e| io_error(&target, e))?;
        staged.push((temp, target));
    }
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
