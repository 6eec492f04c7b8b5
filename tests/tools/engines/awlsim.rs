//! STEP 7 statement list in awlsim, through its Python API
//! (`tests/engines/awlsim_replay.py`): one OB 1 cycle per recorded scan, on a
//! virtual clock that advances one scan time per cycle.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use steptable::address::{Allocation, Mnemonic};
use steptable::program::Signal;
use steptable::simulate::io::IoTrace;

use super::{Stepped, input_lines, output_lines, stepped_lines};
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
    Ok(output_lines(&replay(
        python,
        awl,
        mnemonic,
        trace,
        allocation,
        &[],
    )?))
}

/// A memory bit: byte and bit.
type Bit = (u32, u32);

/// The step flags of the `.sdf` beside `awl`, as its symbol table names
/// them: `step_3` at `M 1.3` is `(3, (1, 3))`.
fn step_flags(awl: &Path) -> Result<Vec<(usize, Bit)>, String> {
    let sdf = awl.with_extension("sdf");
    // Windows-1252, as SIMATIC Manager reads it.
    let bytes = std::fs::read(&sdf).map_err(|e| format!("{}: {e}", sdf.display()))?;
    let (text, _, _) = encoding_rs::WINDOWS_1252.decode(&bytes);
    let mut flags = Vec::new();
    for line in text.lines() {
        let fields: Vec<&str> = line.split('"').collect();
        let (Some(symbol), Some(address)) = (fields.get(1), fields.get(3)) else {
            continue;
        };
        // `step_3` is a step flag; `step_ok` and `step_mem` (single step)
        // are not.
        let Some(number) = symbol
            .trim()
            .strip_prefix("step_")
            .filter(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()))
        else {
            continue;
        };
        let number = number
            .parse()
            .map_err(|_| format!("a step flag {symbol}"))?;
        let bit = address
            .trim()
            .strip_prefix('M')
            .and_then(|b| b.trim().split_once('.'))
            .and_then(|(byte, bit)| Some((byte.parse().ok()?, bit.parse().ok()?)))
            .ok_or_else(|| format!("step flag {symbol} at {address}"))?;
        flags.push((number, bit));
    }
    if flags.is_empty() {
        return Err(format!("no step flag in {}", sdf.display()));
    }
    Ok(flags)
}

/// Runs `awl` on the recorded inputs; the outputs and the step whose flag
/// is on (the flags as the `.sdf` beside it names them) at every scan.
pub fn run_stepped(
    python: &Path,
    awl: &Path,
    mnemonic: Mnemonic,
    trace: &IoTrace,
    allocation: &Allocation,
) -> Result<Stepped, String> {
    let flags = step_flags(awl)?;
    let bits: Vec<Bit> = flags.iter().map(|f| f.1).collect();
    let text = replay(python, awl, mnemonic, trace, allocation, &bits)?;
    stepped_lines(&text, |shown| {
        let on: Vec<usize> = shown
            .chars()
            .zip(&flags)
            .filter(|(c, _)| *c == '1')
            .map(|(_, f)| f.0)
            .collect();
        match on[..] {
            [step] => Ok(step),
            _ => Err(format!("step flags on: {on:?} (exactly one must be)")),
        }
    })
}

/// Runs `awl` in awlsim; what the replay printed (outputs, then the
/// memory bits `probe` after a space when there are any).
fn replay(
    python: &Path,
    awl: &Path,
    mnemonic: Mnemonic,
    trace: &IoTrace,
    allocation: &Allocation,
    probe: &[Bit],
) -> Result<String, String> {
    let probe: Vec<String> = probe.iter().map(|(b, i)| format!("{b}.{i}")).collect();
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
        .arg(probe.join(","))
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
    Ok(String::from_utf8_lossy(&output.stdout).into_owned())
}
