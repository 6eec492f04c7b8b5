//! STEP 7 statement list in awlsim, through its Python API
//! (`tests/engines/awlsim_replay.py`): one OB 1 cycle per recorded scan, on a
//! virtual clock that advances one scan time per cycle.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use steptable::address::{Allocation, Mnemonic};
use steptable::program::Signal;
use steptable::simulate::io::IoTrace;

use super::{input_lines, output_lines};
use crate::helpers::root;

/// The Python that has awlsim: the one beside `awlsim-test` (a venv).
pub fn python(awlsim_test: &Path) -> PathBuf {
    let beside = awlsim_test.with_file_name("python3");
    if beside.exists() {
        beside
    } else {
        PathBuf::from("python3")
    }
}

fn addresses(signals: &[Signal], allocation: &Allocation) -> Result<String, String> {
    signals
        .iter()
        .map(|s| {
            allocation
                .address_of(*s)
                .map(|a| {
                    let (byte, bit) = a.byte_bit();
                    format!("{byte}.{bit}")
                })
                .ok_or_else(|| format!("{s:?} has no address"))
        })
        .collect::<Result<Vec<_>, _>>()
        .map(|v| v.join(","))
}

/// Runs `awl` on the recorded inputs; the outputs of every scan.
pub fn run(
    python: &Path,
    awl: &Path,
    mnemonic: Mnemonic,
    trace: &IoTrace,
    allocation: &Allocation,
) -> Result<Vec<Vec<bool>>, String> {
    let mut child = Command::new(python)
        .arg(root().join("tests/engines/awlsim_replay.py"))
        .arg(awl)
        .arg(match mnemonic {
            Mnemonic::En => "en",
            Mnemonic::De => "de",
        })
        .arg(trace.scan_ms.to_string())
        .arg(addresses(&trace.signals.inputs, allocation)?)
        .arg(addresses(&trace.signals.outputs, allocation)?)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| e.to_string())?;
    let input = input_lines(trace);
    let mut stdin = child.stdin.take().expect("stdin");
    let writer = std::thread::spawn(move || {
        use std::io::Write;
        let _ = stdin.write_all(input.as_bytes());
    });
    let output = child.wait_with_output().map_err(|e| e.to_string())?;
    let _ = writer.join();
    if !output.status.success() {
        return Err(format!(
            "awlsim failed: {}",
            String::from_utf8_lossy(&output.stderr)
        ));
    }
    Ok(output_lines(&String::from_utf8_lossy(&output.stdout)))
}
