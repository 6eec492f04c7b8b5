//! One library entry per command that runs the stages for a table and
//! writes what it made or found (`check`, `convert`, `faults`, `simulate`,
//! `synth`; `batch` runs `convert` for many): each takes validated settings,
//! wires read → table → program → simulate / faults / synth, names its
//! files by the rules of [`crate::emit::OutputKind`] and
//! [`crate::emit::CommandFile`], writes them through [`crate::write`] with
//! the line that says how they were made, and returns what it found and
//! the paths it wrote. The command line only parses, calls and prints.

pub mod convert;
pub mod faults;
pub mod simulate;
pub mod synth;

use crate::convert::Failure;
use crate::diag::Diagnostic;
use crate::emit::templates::TemplateError;
use crate::write::WriteError;

/// Why a command produced nothing (for this input).
#[derive(Debug)]
pub enum CommandError {
    /// The input or a setting is wrong: every problem found, warnings first.
    Input(Vec<Diagnostic>),
    /// A template failed to render: the user's (fix it) or a default (a bug).
    Template(TemplateError),
    /// A bug or an environment problem.
    Internal(String),
    /// The files could not be written (E040 for a place taken, or I/O).
    Write(WriteError),
}

impl CommandError {
    /// `self`, with `warnings` said before its problems (a table's warnings
    /// stand even when a later stage refuses it).
    fn after(self, warnings: &[Diagnostic]) -> CommandError {
        match self {
            CommandError::Input(problems) => {
                CommandError::Input(warnings.iter().cloned().chain(problems).collect())
            }
            other => other,
        }
    }
}

impl From<Failure> for CommandError {
    fn from(failure: Failure) -> Self {
        match failure {
            Failure::Input(diagnostics) => CommandError::Input(diagnostics),
            Failure::Internal(why) => CommandError::Internal(why),
            Failure::Template(err) => CommandError::Template(err),
        }
    }
}
