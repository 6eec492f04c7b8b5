//! Structured Text in matiec, the compiler of Beremiz and OpenPLC: the file
//! is compiled to C with `iec2c`, linked with a small harness that plays the
//! runtime (located variables, `__CURRENT_TIME`, one `config_run__` per
//! scan) and run on the recorded inputs.

use std::fmt::Write as _;
use std::path::Path;
use std::process::{Command, Stdio};

use steptable::address::Allocation;
use steptable::simulate::io::IoTrace;

use super::{Stepped, input_lines, output_lines, stepped_lines};

/// The C name matiec gives a located variable: `%QX2.1` → `__QX2_1`.
fn located_name(iec: &str) -> String {
    format!("__{}", iec.trim_start_matches('%').replace('.', "_"))
}

/// The harness: storage for every located variable the program declares
/// (Beremiz's way, from `LOCATED_VARIABLES.h`), then one scan per input line
/// (`%IX0.1` order as given), printing the outputs after each. With `probe`
/// (the program instance's C name) it also prints the instance's
/// `active_step` after the outputs, as an online view would show it.
fn harness(scan_ms: u32, inputs: &[String], outputs: &[String], probe: Option<&str>) -> String {
    let mut c = String::from("#include <stdio.h>\n#include \"iec_std_lib.h\"\n");
    if let Some(instance) = probe {
        writeln!(c, "#include \"POUS.h\"\nextern STEPTABLE_MAIN {instance};").unwrap();
    }
    c.push_str(
        "#define __LOCATED_VAR(type, name, ...) type __##name;\n#include \"LOCATED_VARIABLES.h\"\n#undef __LOCATED_VAR\n\
         #define __LOCATED_VAR(type, name, ...) type* name = &__##name;\n#include \"LOCATED_VARIABLES.h\"\n#undef __LOCATED_VAR\n\
         TIME __CURRENT_TIME;\nBOOL __DEBUG;\nvoid config_init__(void);\nvoid config_run__(unsigned long tick);\n\
         int main(void) {\n  char line[4096];\n  unsigned long tick = 0;\n  config_init__();\n\
         while (fgets(line, sizeof line, stdin)) {\n",
    );
    writeln!(
        c,
        "    unsigned long long t = (unsigned long long)tick * {scan_ms}ULL;\n    __CURRENT_TIME.tv_sec = t / 1000; __CURRENT_TIME.tv_nsec = (t % 1000) * 1000000;"
    )
    .unwrap();
    for (k, address) in inputs.iter().enumerate() {
        writeln!(c, "    *{} = line[{k}] == '1';", located_name(address)).unwrap();
    }
    c.push_str("    config_run__(tick++);\n");
    for address in outputs {
        writeln!(c, "    putchar(*{} ? '1' : '0');", located_name(address)).unwrap();
    }
    if let Some(instance) = probe {
        writeln!(c, "    printf(\" %d\", (int){instance}.ACTIVE_STEP.value);").unwrap();
    }
    c.push_str("    putchar('\\n');\n    fflush(stdout);\n  }\n  return 0;\n}\n");
    c
}

/// The IEC addresses of the trace's inputs and outputs.
fn addresses(
    trace: &IoTrace,
    allocation: &Allocation,
) -> Result<(Vec<String>, Vec<String>), String> {
    let iec = |signals: &[steptable::program::Signal]| {
        signals
            .iter()
            .map(|s| {
                allocation
                    .address_of(*s)
                    .map(|a| a.iec())
                    .ok_or_else(|| format!("{s:?} has no address"))
            })
            .collect::<Result<Vec<_>, _>>()
    };
    Ok((iec(&trace.signals.inputs)?, iec(&trace.signals.outputs)?))
}

/// Compiles `st` with matiec (`shared/tools/matiec`) and returns the C files'
/// folder, or matiec's complaint.
pub fn compile(shared: &Path, st: &Path, work: &Path) -> Result<(), String> {
    let matiec = shared.join("tools/matiec");
    let output = Command::new(matiec.join("iec2c"))
        .arg("-I")
        .arg(matiec.join("lib"))
        .arg("-T")
        .arg(work)
        .arg(st)
        .output()
        .map_err(|e| format!("iec2c: {e}"))?;
    if !output.status.success() {
        return Err(format!(
            "matiec rejects {}: {}{}",
            st.display(),
            String::from_utf8_lossy(&output.stdout),
            String::from_utf8_lossy(&output.stderr)
        ));
    }
    Ok(())
}

/// A program compiled with matiec and linked with the harness.
pub struct Program {
    _work: tempfile::TempDir,
    exe: std::path::PathBuf,
}

/// Compiles `st` and links it with a harness that reads `inputs` and prints
/// `outputs` (IEC addresses) once per scan of `scan_ms`.
pub fn build(
    shared: &Path,
    st: &Path,
    scan_ms: u32,
    inputs: &[String],
    outputs: &[String],
) -> Result<Program, String> {
    build_with(shared, st, scan_ms, inputs, outputs, false)
}

/// The C name matiec gives the instance of `steptable_main` (its resource
/// file declares `STEPTABLE_MAIN RES0__MAIN_INSTANCE;`).
fn instance_name(dir: &Path) -> Result<String, String> {
    for entry in std::fs::read_dir(dir).map_err(|e| e.to_string())? {
        let path = entry.map_err(|e| e.to_string())?.path();
        if path.extension().is_none_or(|e| e != "c") {
            continue;
        }
        let text = std::fs::read_to_string(&path).map_err(|e| e.to_string())?;
        if let Some(name) = text.lines().find_map(|l| {
            l.strip_prefix("STEPTABLE_MAIN ")
                .and_then(|rest| rest.strip_suffix(';'))
        }) {
            return Ok(name.trim().to_string());
        }
    }
    Err("no instance of steptable_main in the C matiec wrote".to_string())
}

fn build_with(
    shared: &Path,
    st: &Path,
    scan_ms: u32,
    inputs: &[String],
    outputs: &[String],
    probe: bool,
) -> Result<Program, String> {
    let work = tempfile::tempdir().map_err(|e| e.to_string())?;
    let dir = work.path();
    compile(shared, st, dir)?;
    // matiec lists a resource's unlocated globals in LOCATED_VARIABLES.h
    // too, run together on one line; Beremiz reads only the
    // `__LOCATED_VAR(` lines of that file, and so does the harness.
    let located = dir.join("LOCATED_VARIABLES.h");
    let text = std::fs::read_to_string(&located).map_err(|e| e.to_string())?;
    let kept: String = text
        .lines()
        .filter(|l| l.starts_with("__LOCATED_VAR("))
        .map(|l| format!("{l}\n"))
        .collect();
    std::fs::write(&located, kept).map_err(|e| e.to_string())?;
    let instance = if probe {
        Some(instance_name(dir)?)
    } else {
        None
    };
    std::fs::write(
        dir.join("harness.c"),
        harness(scan_ms, inputs, outputs, instance.as_deref()),
    )
    .map_err(|e| e.to_string())?;
    // The resource file includes POUS.c; the configuration file is the other.
    let mut sources: Vec<String> = std::fs::read_dir(dir)
        .map_err(|e| e.to_string())?
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().to_string())
        .filter(|n| n.ends_with(".c") && n != "POUS.c")
        .collect();
    sources.sort();
    let output = Command::new("cc")
        .current_dir(dir)
        .args(["-O0", "-w", "-I"])
        .arg(shared.join("tools/matiec/lib/C"))
        .args(["-I", "."])
        .args(&sources)
        .args(["-o", "plc"])
        .output()
        .map_err(|e| format!("cc: {e}"))?;
    if !output.status.success() {
        return Err(format!(
            "the C that matiec wrote does not build: {}",
            String::from_utf8_lossy(&output.stderr)
        ));
    }
    let exe = dir.join("plc");
    Ok(Program { _work: work, exe })
}

impl Program {
    /// Runs every input line at once; the outputs of every scan.
    pub fn replay(&self, lines: String) -> Result<Vec<Vec<bool>>, String> {
        Ok(output_lines(&self.replay_text(lines)?))
    }

    /// Runs every input line at once; what the harness printed.
    fn replay_text(&self, lines: String) -> Result<String, String> {
        let mut child = Command::new(&self.exe)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()
            .map_err(|e| e.to_string())?;
        let mut stdin = child.stdin.take().expect("stdin");
        let writer = std::thread::spawn(move || {
            use std::io::Write;
            let _ = stdin.write_all(lines.as_bytes());
        });
        let output = child.wait_with_output().map_err(|e| e.to_string())?;
        let _ = writer.join();
        if !output.status.success() {
            return Err(format!("the compiled program crashed: {}", output.status));
        }
        Ok(String::from_utf8_lossy(&output.stdout).into_owned())
    }

    /// Starts the program for a closed loop: one scan per [`Live::scan`].
    pub fn live(&self) -> Result<Live, String> {
        let mut child = Command::new(&self.exe)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()
            .map_err(|e| e.to_string())?;
        let stdin = child.stdin.take().expect("stdin");
        let stdout = std::io::BufReader::new(child.stdout.take().expect("stdout"));
        Ok(Live {
            child,
            stdin,
            stdout,
        })
    }
}

/// A running program, scanned one cycle at a time.
pub struct Live {
    child: std::process::Child,
    stdin: std::process::ChildStdin,
    stdout: std::io::BufReader<std::process::ChildStdout>,
}

impl Live {
    /// One scan: the inputs in, the outputs out.
    pub fn scan(&mut self, inputs: &[bool]) -> Result<Vec<bool>, String> {
        use std::io::{BufRead, Write};
        let line: String = inputs.iter().map(|b| if *b { '1' } else { '0' }).collect();
        writeln!(self.stdin, "{line}").map_err(|e| e.to_string())?;
        let mut out = String::new();
        self.stdout.read_line(&mut out).map_err(|e| e.to_string())?;
        if out.is_empty() {
            return Err("the program ended".to_string());
        }
        Ok(out.trim_end().chars().map(|c| c == '1').collect())
    }
}

impl Drop for Live {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Runs `st` on the recorded inputs; the outputs of every scan.
pub fn run(
    shared: &Path,
    st: &Path,
    trace: &IoTrace,
    allocation: &Allocation,
) -> Result<Vec<Vec<bool>>, String> {
    let (inputs, outputs) = addresses(trace, allocation)?;
    build(shared, st, trace.scan_ms, &inputs, &outputs)?.replay(input_lines(trace))
}

/// Runs `st` on the recorded inputs; the outputs and the program's
/// `active_step` at the end of every scan.
pub fn run_stepped(
    shared: &Path,
    st: &Path,
    trace: &IoTrace,
    allocation: &Allocation,
) -> Result<Stepped, String> {
    let (inputs, outputs) = addresses(trace, allocation)?;
    let program = build_with(shared, st, trace.scan_ms, &inputs, &outputs, true)?;
    stepped_lines(&program.replay_text(input_lines(trace))?, |text| {
        text.parse()
            .map_err(|_| format!("not a step number: {text}"))
    })
}
