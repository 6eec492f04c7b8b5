//! The engineer's own output templates: a folder whose files replace the
//! built-in minijinja templates by name (`--templates DIR`), and the export
//! of the built-in ones to start from (`steptable templates export`).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use crate::emit::OutputFile;
use crate::emit::templates::{DEFAULTS, TemplateError, Templates};
use crate::write::{Durability, Inputs, WriteError, write_files};

/// The defaults, with every file of `dir` that has a template's name in
/// its place. A file in `dir` that is no template's name, or a folder, is
/// an error, so a typo or a misplaced template does not silently keep the
/// default.
pub fn load_dir(dir: &Path) -> Result<Templates, TemplateError> {
    let error = |file: String, detail: String| TemplateError {
        file,
        user: true,
        line: None,
        detail,
    };
    let entries = std::fs::read_dir(dir).map_err(|e| {
        error(
            dir.display().to_string(),
            format!("cannot read the folder: {e}"),
        )
    })?;
    let mut overrides = BTreeMap::new();
    let mut names: Vec<PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
    names.sort();
    for path in names {
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().to_string())
            .unwrap_or_default();
        if editor_leftover(&name) {
            continue;
        }
        // Only the folder's own files are read: a folder in it (`old/`
        // holding templates, a folder named `program.st.j2`) would be
        // passed over silently and its templates never used, so it is an
        // error like any other stray name. Hidden ones (`.git`) are not.
        if path.is_dir() {
            return Err(error(
                path.display().to_string(),
                format!(
                    "a folder; templates are read only from {} itself, not from folders in it (move the templates meant up into it, or the folder out)",
                    dir.display()
                ),
            ));
        }
        if !DEFAULTS.iter().any(|(n, _)| *n == name) {
            let known: Vec<&str> = DEFAULTS.iter().map(|(n, _)| *n).collect();
            return Err(error(
                path.display().to_string(),
                format!(
                    "no template has this name (templates: {})",
                    known.join(", ")
                ),
            ));
        }
        let source = std::fs::read_to_string(&path)
            .map_err(|e| error(path.display().to_string(), format!("cannot read: {e}")))?;
        overrides.insert(name, (path, source));
    }
    Templates::with_overrides(overrides)
}

/// Files an editor leaves beside the ones it edits (`.program.st.j2.swp`,
/// `program.st.j2~`, `#program.st.j2#`, `.bak`): not templates, not typos.
fn editor_leftover(name: &str) -> bool {
    name.starts_with('.')
        || name.starts_with('#')
        || name.ends_with('~')
        || [".swp", ".swo", ".bak", ".orig", ".tmp"]
            .iter()
            .any(|ext| name.ends_with(ext))
}

/// Writes the default templates into `dir` (created if missing), to start
/// from. Templates already there are edits of someone's: without `force`
/// nothing is written and their paths are the error. Each file is written
/// to a temporary file and renamed, so a symbolic link in `dir` is replaced,
/// never written through.
pub fn export_defaults(dir: &Path, force: bool) -> Result<Vec<PathBuf>, ExportError> {
    let existing: Vec<PathBuf> = DEFAULTS
        .iter()
        .map(|(name, _)| dir.join(name))
        .filter(|p| p.symlink_metadata().is_ok())
        .collect();
    if !existing.is_empty() && !force {
        return Err(ExportError::Exists(existing));
    }
    let files: Vec<OutputFile> = DEFAULTS
        .iter()
        .map(|(name, source)| OutputFile {
            name: name.to_string(),
            bytes: source.as_bytes().to_vec(),
        })
        .collect();
    write_files(dir, &files, &Inputs::none(), Durability::Rename).map_err(ExportError::Write)
}

/// Why `templates export` wrote nothing.
#[derive(Debug)]
pub enum ExportError {
    /// These templates exist already (add `--force` to replace them).
    Exists(Vec<PathBuf>),
    Write(WriteError),
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn editor_leftovers_are_told_from_templates() {
        for name in [
            ".program.st.j2.swp",
            "#program.st.j2#",
            "program.st.j2~",
            "program.st.j2.bak",
            "gvl.txt.j2.orig",
        ] {
            assert!(editor_leftover(name), "{name}");
        }
        for name in ["program.st.j2", "gvl.txt.j2", "equations.il.j2"] {
            assert!(!editor_leftover(name), "{name}");
        }
    }
    use minijinja::Value;

    #[test]
    fn user_template_errors_name_file_line_and_variable() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(
            dir.path().join("gvl.txt.j2"),
            "VAR_GLOBAL\n{{ no_such_thing }}\nEND_VAR\n",
        )
        .unwrap();
        let templates = load_dir(dir.path()).unwrap();
        let err = templates
            .render("gvl.txt.j2", Value::from(BTreeMap::<String, String>::new()))
            .unwrap_err();
        assert!(err.user);
        assert_eq!(err.line, Some(2));
        assert!(err.to_string().contains("gvl.txt.j2:2:"), "{err}");
        assert!(err.to_string().contains("no_such_thing"), "{err}");
    }

    #[test]
    fn unknown_template_names_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("progam.st.j2"), "typo").unwrap();
        let err = load_dir(dir.path()).unwrap_err();
        assert!(err.detail.contains("no template has this name"), "{err}");
    }

    #[test]
    fn a_folder_among_the_templates_is_refused_by_name() {
        for folder in ["program.st.j2", "old"] {
            let dir = tempfile::tempdir().unwrap();
            std::fs::create_dir(dir.path().join(folder)).unwrap();
            std::fs::write(dir.path().join(folder).join("program.st.j2"), "x").unwrap();
            let err = load_dir(dir.path()).unwrap_err();
            assert!(err.file.ends_with(folder), "{err}");
            assert!(err.detail.starts_with("a folder;"), "{err}");
        }
        // A hidden folder (a git checkout of the templates) is not one.
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir(dir.path().join(".git")).unwrap();
        assert!(load_dir(dir.path()).is_ok());
    }
}
