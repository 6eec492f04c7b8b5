//! `--sync` is the only way steptable flushes files to the disk: counted
//! with strace, a conversion makes no fsync without it, and one per file and
//! folder with it (convert and batch).

use crate::helpers::{all_files, sample};
use crate::{Check, Tool, tool};

pub const CHECKS: &[Check] = &[Check::new(
    "sync::files_are_flushed_only_with_sync",
    &[Tool::Strace],
    files_are_flushed_only_with_sync,
)];

/// How many fsync/fdatasync calls `args` makes, traced through its threads.
fn flushes(dir: &std::path::Path, args: &[&str]) -> usize {
    let trace = dir.join("trace.txt");
    let bin = assert_cmd::cargo::cargo_bin("steptable");
    let status = std::process::Command::new(tool(Tool::Strace))
        .args(["-f", "-e", "trace=fsync,fdatasync", "-o"])
        .arg(&trace)
        .arg(&bin)
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap();
    assert!(status.status.success(), "{status:?}");
    std::fs::read_to_string(&trace)
        .unwrap()
        .lines()
        .filter(|l| l.contains("fsync(") || l.contains("fdatasync("))
        .count()
}

fn files_are_flushed_only_with_sync() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("in")).unwrap();
    std::fs::copy(sample("paper_example.xlsx"), dir.path().join("in/t.xlsx")).unwrap();
    let files = all_files();
    assert_eq!(flushes(dir.path(), &["convert", "in/t.xlsx", "-o", "a"]), 0);
    let synced = flushes(dir.path(), &["convert", "in/t.xlsx", "-o", "b", "--sync"]);
    // Every file, its folder and the project folder below it.
    assert!(
        synced > files && synced <= files + 3,
        "{synced} flushes for {files} files"
    );
    assert_eq!(flushes(dir.path(), &["batch", "in", "-o", "c"]), 0);
    let synced = flushes(dir.path(), &["batch", "in", "-o", "d", "--sync"]);
    // The table's files and folders, and the summary with its folder.
    assert!(synced > files + 1, "{synced} flushes in a batch of one");
    // The outputs are the same either way.
    let read = |p: &str| std::fs::read(dir.path().join(p)).unwrap();
    assert_eq!(read("a/t/t.st"), read("b/t/t.st"));
}
