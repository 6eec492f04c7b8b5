//! Structured Text in matiec, the compiler of Beremiz and OpenPLC: the file
//! is compiled to C with `iec2c`, linked with a small harness that plays the
//! runtime (located variables, `__CURRENT_TIME`, one `config_run__` per
//! scan) and run on the recorded inputs.

use std::fmt::Write as _;
use std::path::Path;
use std::process::{Command, Stdio};

use steptable::address::Allocation;
use steptable::simulate::io::IoTrace;

use super::{input_lines, output_lines};

/// The C name matiec gives a located variable: `%QX2.1` → `__QX2_1`.
fn located_name(iec: &str) -> String {
    format!("__{}", iec.trim_start_matches('%').replace('.', "_"))
}

/// The harness: storage for every located variable the program declares
/// (Beremiz's way, from `LOCATED_VARIABLES.h`), then one scan per input line.
fn harness(trace: &IoTrace, allocation: &Allocation) -> Result<String, String> {
    let name = |s| {
        allocation
            .address_of(s)
            .map(|a| located_name(&a.iec()))
            .ok_or_else(|| format!("{s:?} has no address"))
    };
    let mut c = String::from(
        "#include <stdio.h>\n#include \"iec_std_lib.h\"\n\
         #define __LOCATED_VAR(type, name, ...) type __##name;\n#include \"LOCATED_VARIABLES.h\"\n#undef __LOCATED_VAR\n\
         #define __LOCATED_VAR(type, name, ...) type* name = &__##name;\n#include \"LOCATED_VARIABLES.h\"\n#undef __LOCATED_VAR\n\
         TIME __CURRENT_TIME;\nBOOL __DEBUG;\nvoid config_init__(void);\nvoid config_run__(unsigned long tick);\n\
         int main(void) {\n  char line[4096];\n  unsigned long tick = 0;\n  config_init__();\n\
         while (fgets(line, sizeof line, stdin)) {\n",
    );
    let ms = trace.scan_ms as u64;
    writeln!(
        c,
        "    unsigned long long t = (unsigned long long)tick * {ms}ULL;\n    __CURRENT_TIME.tv_sec = t / 1000; __CURRENT_TIME.tv_nsec = (t % 1000) * 1000000;"
    )
    .unwrap();
    for (k, s) in trace.signals.inputs.iter().enumerate() {
        writeln!(c, "    *{} = line[{k}] == '1';", name(*s)?).unwrap();
    }
    c.push_str("    config_run__(tick++);\n");
    for s in &trace.signals.outputs {
        writeln!(c, "    putchar(*{} ? '1' : '0');", name(*s)?).unwrap();
    }
    c.push_str("    putchar('\\n');\n  }\n  return 0;\n}\n");
    Ok(c)
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

/// Runs `st` on the recorded inputs; the outputs of every scan.
pub fn run(
    shared: &Path,
    st: &Path,
    trace: &IoTrace,
    allocation: &Allocation,
) -> Result<Vec<Vec<bool>>, String> {
    let work = tempfile::tempdir().map_err(|e| e.to_string())?;
    let work = work.path();
    compile(shared, st, work)?;
    std::fs::write(work.join("harness.c"), harness(trace, allocation)?)
        .map_err(|e| e.to_string())?;
    // The resource file includes POUS.c; the configuration file is the other.
    let mut sources: Vec<String> = std::fs::read_dir(work)
        .map_err(|e| e.to_string())?
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().to_string())
        .filter(|n| n.ends_with(".c") && n != "POUS.c")
        .collect();
    sources.sort();
    let output = Command::new("cc")
        .current_dir(work)
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
    let mut child = Command::new(work.join("plc"))
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
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
        return Err(format!("the compiled program crashed: {}", output.status));
    }
    Ok(output_lines(&String::from_utf8_lossy(&output.stdout)))
}
