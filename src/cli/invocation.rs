//! The command line as every output records it (see
//! [`crate::provenance`]): the command, the inputs by file name, and the
//! options that change what is written, each as typed. Options that change
//! only where files go or how a run speaks (`-o`, `--message-format`,
//! `--sync`, `--jobs`, `--quiet`, `--force`, and the folders of `simulate
//! --diagram DIR` and `--report DIR`) are left out, and the folder of `--templates` is cut to
//! its last part, as inputs are to their file names, so that the same run
//! from another folder writes the same bytes.

use std::ffi::OsString;
use std::path::Path;

use clap::CommandFactory;

/// Options that never change a byte of an output.
const LEFT_OUT: [&str; 6] = ["output", "message_format", "sync", "jobs", "quiet", "force"];

/// `convert paper.xlsx --target siemens` for the arguments after the
/// program's name.
pub(crate) fn invocation(args: &[OsString]) -> String {
    let args: Vec<String> = args
        .iter()
        .map(|a| a.to_string_lossy().to_string())
        .collect();
    let cli = super::Cli::command();
    let Some(name) = args.first() else {
        return String::new();
    };
    let Some(command) = cli.find_subcommand(name) else {
        return quote(name);
    };
    let mut words = vec![quote(name)];
    let mut rest = args[1..].iter();
    let mut positional_only = false;
    while let Some(word) = rest.next() {
        if !positional_only && word == "--" {
            // Kept: what follows is an input even if it starts with `-`.
            positional_only = true;
            words.push(word.clone());
            continue;
        }
        if positional_only || word == "-" || !word.starts_with('-') {
            words.push(quote(&last_part(word)));
            continue;
        }
        // `--long`, `--long=value`, `-s`, `-svalue`.
        let (arg, inline) = match word.strip_prefix("--") {
            Some(long) => {
                let (flag, inline) = match long.split_once('=') {
                    Some((flag, value)) => (flag, Some(value.to_string())),
                    None => (long, None),
                };
                (
                    command.get_arguments().find(|a| a.get_long() == Some(flag)),
                    inline,
                )
            }
            None => {
                let mut chars = word.chars().skip(1);
                let short = chars.next();
                let tail: String = chars.collect();
                (
                    command.get_arguments().find(|a| a.get_short() == short),
                    (!tail.is_empty()).then_some(tail),
                )
            }
        };
        let Some(arg) = arg else {
            words.push(quote(word));
            continue;
        };
        let value = if arg.get_action().takes_values() {
            inline.or_else(|| rest.next().cloned())
        } else {
            None
        };
        let names_a_folder = arg
            .get_value_names()
            .is_some_and(|names| names.iter().any(|n| n == "DIR" || n == "FILE"));
        // A folder says where files go, except the templates' (which lay
        // the files out).
        let id = arg.get_id().as_str();
        if LEFT_OUT.contains(&id) || (names_a_folder && id != "templates") {
            continue;
        }
        let flag = match arg.get_long() {
            Some(long) => format!("--{long}"),
            None => word.chars().take(2).collect(),
        };
        words.push(flag);
        if let Some(value) = value {
            let value = if names_a_folder {
                last_part(&value)
            } else {
                value
            };
            words.push(quote(&value));
        }
    }
    words.join(" ")
}

/// A path's last part: the file name a header may show.
fn last_part(path: &str) -> String {
    Path::new(path)
        .file_name()
        .map(|n| n.to_string_lossy().to_string())
        .unwrap_or_else(|| path.to_string())
}

/// A word as a shell takes it back: quoted when it holds anything but
/// letters, digits and `_.,=+-/:%@&`.
fn quote(word: &str) -> String {
    let plain = !word.is_empty()
        && word
            .chars()
            .all(|c| c.is_alphanumeric() || "_.,=+-/:%@".contains(c));
    if plain {
        word.to_string()
    } else {
        format!("'{}'", word.replace('\'', r"'\''"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn of(args: &[&str]) -> String {
        let args: Vec<OsString> = args.iter().map(OsString::from).collect();
        invocation(&args)
    }

    #[test]
    fn the_record_keeps_what_changes_the_output_and_no_folder() {
        assert_eq!(
            of(&[
                "convert",
                "/tmp/x/paper.xlsx",
                "-o",
                "/tmp/out",
                "--target=siemens",
                "--message-format",
                "json",
                "--home-order",
                "C3&C4,C2",
                "--templates",
                "/home/me/my templates",
                "--sync",
            ]),
            "convert paper.xlsx --target siemens --home-order 'C3&C4,C2' --templates 'my templates'"
        );
        assert_eq!(
            of(&[
                "synth",
                "--sequence",
                "A1 A0 B1 B0",
                "-o/tmp/o",
                "--seed",
                "3"
            ]),
            "synth --sequence 'A1 A0 B1 B0' --seed 3"
        );
        assert_eq!(
            of(&["faults", "--pairs", "a b.csv", "--", "/in/-c.csv"]),
            "faults --pairs 'a b.csv' -- -c.csv"
        );
        assert_eq!(of(&["batch", "-j", "4", "-q", "lines/"]), "batch lines");
        assert_eq!(
            of(&["simulate", "t.csv", "--diagram", "/tmp/d", "--scan", "5ms"]),
            "simulate t.csv --scan 5ms"
        );
    }
}
