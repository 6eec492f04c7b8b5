//! Checks that run steptable's written files in the tools that will really
//! run them (matiec, OpenPLC's upload, awlsim, the FST interpreter) and
//! that validate them with other tools (xmllint, blark, LibreOffice).
//!
//! A custom harness (libtest-mimic), so that a check whose tool is missing
//! is counted as *ignored*, with one note naming the tool, never as passed.
//! With STEPTABLE_REQUIRE_TOOLS=1 (`.ci/run`) every check runs and a
//! missing tool fails it.

#[allow(dead_code)]
#[path = "../integration/helpers.rs"]
mod helpers;
mod kinds;

mod browser;
mod differential;
mod differential_native;
mod differential_random;
mod differential_timing;
mod editor_load;
mod engines;
mod exports;
mod halt;
mod homing;
mod ladder;
mod libreoffice;
mod long_comments;
mod manual;
mod names;
mod pinned;
mod scenario;
mod sfc;
mod single_step;
mod step_numbers;
mod supervision;
mod swivel;
mod sync;
mod synth_engines;
mod vacuum;

use std::collections::BTreeSet;
use std::path::PathBuf;

use libtest_mimic::{Arguments, Trial};

/// Something outside the crate that a check needs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Tool {
    /// `../shared` beside the repository: matiec, OpenPLC's compiler and
    /// upload replay, the PLCopen schema.
    Shared,
    Awlsim,
    Xmllint,
    Blark,
    Soffice,
    Strace,
    /// Headless Chromium, Debian's package.
    Chromium,
    /// A Python with lxml and numpy, for Beremiz's generator.
    BeremizPython,
    /// `../shared/tools/openplc4/check-upload-v4`, OpenPLC v4's build
    /// replayed (STruC++ and g++, run with node).
    OpenPlc4,
}

impl Tool {
    fn find(self) -> Option<PathBuf> {
        match self {
            Tool::Shared => {
                let dir = helpers::root().join("../shared");
                dir.join("tools")
                    .is_dir()
                    .then(|| dir.canonicalize().unwrap_or(dir))
            }
            Tool::Awlsim => find_program("awlsim-test"),
            Tool::Xmllint => find_program("xmllint"),
            Tool::Blark => find_program("blark"),
            Tool::Soffice => find_program("soffice"),
            Tool::Strace => find_program("strace"),
            Tool::Chromium => find_program("chromium"),
            // The tools' venv may lack numpy: PATH's Python is tried too.
            Tool::BeremizPython => ["python3", "python"]
                .into_iter()
                .flat_map(|n| [find_program(n), on_path(n)])
                .flatten()
                .find(|p| {
                    std::process::Command::new(p)
                        .args(["-c", "import lxml, numpy"])
                        .output()
                        .is_ok_and(|o| o.status.success())
                }),
            Tool::OpenPlc4 => {
                let script = Tool::Shared.find()?.join("tools/openplc4/check-upload-v4");
                (script.is_file() && find_program("node").is_some()).then_some(script)
            }
        }
    }

    fn describe(self) -> &'static str {
        match self {
            Tool::Shared => {
                "../shared (matiec, OpenPLC, the PLCopen schema) is not beside the repository"
            }
            Tool::Awlsim => {
                "awlsim-test was not found (set STEPTABLE_TOOLS or PATH; .ci/run installs it)"
            }
            Tool::Xmllint => "xmllint was not found (.ci/run installs libxml2-utils)",
            Tool::Blark => "blark was not found (set STEPTABLE_TOOLS or PATH; .ci/run installs it)",
            Tool::Soffice => "soffice was not found (.ci/run installs libreoffice-calc)",
            Tool::Strace => "strace was not found (.ci/run installs it)",
            Tool::Chromium => "chromium was not found (.ci/run installs Debian's chromium)",
            Tool::BeremizPython => {
                "no python3 with lxml and numpy for Beremiz's generator (set STEPTABLE_TOOLS or PATH; pip install lxml numpy)"
            }
            Tool::OpenPlc4 => {
                "../shared/tools/openplc4/check-upload-v4 or node (>= 18) was not found"
            }
        }
    }
}

/// A program from `STEPTABLE_TOOLS` (a folder) or PATH.
fn find_program(name: &str) -> Option<PathBuf> {
    if let Ok(dir) = std::env::var("STEPTABLE_TOOLS") {
        let path = PathBuf::from(dir).join(name);
        if path.exists() {
            return Some(path);
        }
    }
    on_path(name)
}

/// A program found on PATH alone.
fn on_path(name: &str) -> Option<PathBuf> {
    let found = std::process::Command::new("sh")
        .arg("-c")
        .arg(format!("command -v {name}"))
        .output()
        .ok()?;
    let path = String::from_utf8_lossy(&found.stdout).trim().to_string();
    (found.status.success() && !path.is_empty()).then(|| PathBuf::from(path))
}

/// Whether a missing tool must fail its checks (CI) rather than skip them.
fn tools_required() -> bool {
    std::env::var("STEPTABLE_REQUIRE_TOOLS").is_ok_and(|v| !v.is_empty() && v != "0")
}

/// The path of a tool a running check needs. A check runs without its tool
/// only under STEPTABLE_REQUIRE_TOOLS, where this failure is the point.
pub fn tool(tool: Tool) -> PathBuf {
    tool.find()
        .unwrap_or_else(|| panic!("required: {}", tool.describe()))
}

/// `../shared`, for the checks that need it.
pub fn shared() -> PathBuf {
    tool(Tool::Shared)
}

/// One check: its name (module::function, for filtering), the tools it
/// needs and its body, which panics on failure.
#[derive(Clone, Copy)]
pub struct Check {
    name: &'static str,
    needs: &'static [Tool],
    run: fn(),
}

impl Check {
    pub const fn new(name: &'static str, needs: &'static [Tool], run: fn()) -> Check {
        Check { name, needs, run }
    }
}

fn main() {
    let args = Arguments::from_args();
    let required = tools_required();
    let checks = [
        browser::CHECKS,
        differential::CHECKS,
        differential_native::CHECKS,
        differential_random::CHECKS,
        differential_timing::CHECKS,
        exports::CHECKS,
        libreoffice::CHECKS,
        long_comments::CHECKS,
        manual::CHECKS,
        names::CHECKS,
        pinned::CHECKS,
        scenario::CHECKS,
        sfc::CHECKS,
        single_step::CHECKS,
        supervision::CHECKS,
        step_numbers::CHECKS,
        halt::CHECKS,
        homing::CHECKS,
        ladder::CHECKS,
        editor_load::CHECKS,
        sync::CHECKS,
        synth_engines::CHECKS,
        swivel::CHECKS,
        vacuum::CHECKS,
    ]
    .concat();
    let mut missing = BTreeSet::new();
    let trials: Vec<Trial> = checks
        .iter()
        .map(|check| {
            let absent: Vec<Tool> = check
                .needs
                .iter()
                .copied()
                .filter(|t| t.find().is_none())
                .collect();
            let skip = !absent.is_empty() && !required;
            if skip {
                missing.extend(absent);
            }
            let run = check.run;
            Trial::test(check.name, move || {
                run();
                Ok(())
            })
            .with_ignored_flag(skip)
        })
        .collect();
    for tool in missing {
        eprintln!(
            "note: {}, so the checks that need it are ignored",
            tool.describe()
        );
    }
    libtest_mimic::run(&args, trials).exit();
}
