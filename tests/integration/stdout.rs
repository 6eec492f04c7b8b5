//! Standard output that cannot be written never hides what the command
//! found: a closed pipe (`| head`) keeps the exit code the work earned, and
//! a failing one (a full disk) is an I/O error.

use std::process::{Command, Stdio};

use crate::helpers::sample;

fn bad_table(dir: &std::path::Path) -> std::path::PathBuf {
    let path = dir.join("bad.csv");
    std::fs::write(&path, "C1+1\nC1+x\n").unwrap();
    path
}

/// Runs steptable with stdout a pipe whose reader is already gone.
#[cfg(unix)]
fn with_closed_stdout(args: &[&std::ffi::OsStr]) -> std::process::ExitStatus {
    let mut child = Command::new(assert_cmd::cargo::cargo_bin("steptable"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    child.wait().unwrap()
}

#[cfg(unix)]
#[test]
fn a_closed_pipe_keeps_the_exit_code_of_the_work() {
    let dir = tempfile::tempdir().unwrap();
    let bad = bad_table(dir.path());
    let status = with_closed_stdout(&["check".as_ref(), bad.as_os_str()]);
    assert_eq!(status.code(), Some(1), "a bad table stays exit 1");
    let good = sample("paper_example.xlsx");
    let status = with_closed_stdout(&["check".as_ref(), good.as_os_str()]);
    assert_eq!(status.code(), Some(0));
    let status = with_closed_stdout(&[
        "simulate".as_ref(),
        good.as_os_str(),
        "--no-middle-stop".as_ref(),
    ]);
    assert_eq!(status.code(), Some(1), "a failed simulation stays exit 1");
}

#[cfg(target_os = "linux")]
#[test]
fn a_full_disk_on_stdout_is_an_io_error() {
    let dir = tempfile::tempdir().unwrap();
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let output = Command::new(assert_cmd::cargo::cargo_bin("steptable"))
        .arg("check")
        .arg(bad_table(dir.path()))
        .stdout(full)
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("cannot write to standard output"),
        "{stderr}"
    );
    assert!(
        stderr.contains("error[E010]"),
        "the problems still reach stderr: {stderr}"
    );
}

/// Standard error closed or full never turns into a panic (exit 101): the
/// problems are lost, the exit code is still the work's.
#[cfg(target_os = "linux")]
#[test]
fn a_full_stderr_keeps_the_exit_code_of_the_work() {
    let dir = tempfile::tempdir().unwrap();
    let full = || {
        std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap()
    };
    let status = Command::new(assert_cmd::cargo::cargo_bin("steptable"))
        .arg("convert")
        .arg(bad_table(dir.path()))
        .arg("-o")
        .arg(dir.path().join("out"))
        .stdout(Stdio::null())
        .stderr(full())
        .status()
        .unwrap();
    assert_eq!(status.code(), Some(1));
    let status = Command::new(assert_cmd::cargo::cargo_bin("steptable"))
        .args(["templates", "-o", "x"])
        .stdout(Stdio::null())
        .stderr(full())
        .status()
        .unwrap();
    assert_eq!(status.code(), Some(1), "a wrong command line stays exit 1");
}

/// `--help` and `--version` that cannot be written are an I/O error (exit
/// 2), like any other output; written, they print in full and exit 0.
#[cfg(target_os = "linux")]
#[test]
fn help_and_version_into_a_full_disk_fail() {
    for args in [&["--help"][..], &["--version"], &["convert", "--help"]] {
        let full = std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap();
        let output = Command::new(assert_cmd::cargo::cargo_bin("steptable"))
            .args(args)
            .stdout(full)
            .output()
            .unwrap();
        assert_eq!(output.status.code(), Some(2), "{args:?}");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(
            stderr.contains("cannot write to standard output"),
            "{stderr}"
        );
        let output = Command::new(assert_cmd::cargo::cargo_bin("steptable"))
            .args(args)
            .output()
            .unwrap();
        assert_eq!(output.status.code(), Some(0), "{args:?}");
        let stdout = String::from_utf8_lossy(&output.stdout);
        assert!(
            stdout.contains("steptable") && stdout.ends_with('\n'),
            "{stdout}"
        );
    }
}
