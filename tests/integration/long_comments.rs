//! Hostile rows: a 300-character step comment and actuator name. Where a
//! target limits a comment it is cut by the one cut (`emit::shorten`, three
//! dots) and the whole text is kept beside it: the `.sdf` comment at 80
//! characters (W008), the `.awl` network TITLE at 64 with the whole title
//! as a `//` line, the GRAFCET's panel lines at 64 with the whole text as
//! the panel's tooltip (`<title>`). (awlsim runs that `.awl`: the tools
//! check `long_comments`.) Under `--designations names` the name would be
//! every identifier's stem, longer than any target takes: E025 at its cell.

use crate::helpers::{long_table, long_text, steptable};

#[test]
fn long_comments_are_cut_where_a_target_limits_them() {
    let dir = tempfile::tempdir().unwrap();
    let input = long_table(dir.path());
    steptable()
        .args(["convert", "--formats", "awl,sdf,grafcet", "-o"])
        .arg(dir.path().join("out"))
        .arg(&input)
        .assert()
        .success()
        .stderr(predicates::str::contains("W008"));
    let out = dir.path().join("out").join("long");
    let comment = long_text("clamp the part");
    let name = long_text("clamp");

    let awl = std::fs::read_to_string(out.join("long.awl")).unwrap();
    let titles: Vec<&str> = awl
        .lines()
        .filter_map(|l| l.strip_prefix("TITLE = "))
        .collect();
    let cut: Vec<&&str> = titles.iter().filter(|t| t.ends_with("...")).collect();
    assert!(!cut.is_empty(), "{titles:?}");
    assert!(titles.iter().all(|t| t.chars().count() <= 64), "{titles:?}");
    assert!(cut.iter().all(|t| t.chars().count() == 64), "{cut:?}");
    assert!(
        awl.lines()
            .any(|l| l.starts_with("// ") && l.contains(&comment))
    );
    // The actuator's name is in the line comments whole (no limit known).
    assert!(awl.contains(&format!("extend C1 ({name})")), "{awl}");

    let sdf = std::fs::read_to_string(out.join("long.sdf")).unwrap();
    assert!(!sdf.contains(&name[..100]), "the .sdf holds 80 characters");

    let svg = std::fs::read_to_string(out.join("long.grafcet.svg")).unwrap();
    let shown: Vec<&str> = svg
        .split("<text")
        .skip(1)
        .filter_map(|t| t.split_once('>').and_then(|(_, r)| r.split_once("</text>")))
        .map(|(text, _)| text)
        .collect();
    assert!(
        shown.iter().all(|t| t.chars().count() <= 64 + 40),
        "no line of hundreds: {shown:?}"
    );
    assert!(shown.iter().any(|t| t.ends_with("...")), "{shown:?}");
    let tip = svg
        .split("<title>")
        .nth(1)
        .and_then(|t| t.split_once("</title>"))
        .map(|(t, _)| t)
        .expect("a tooltip");
    assert!(tip.contains(&comment), "{tip}");
    // The panel is as wide as its cut lines, not as the comment.
    let width: f64 = svg
        .split("width=\"")
        .nth(1)
        .and_then(|w| w.split('"').next())
        .and_then(|w| w.parse().ok())
        .unwrap();
    assert!(width < 1000.0, "{width}");
    steptable()
        .args([
            "convert",
            "--designations",
            "names",
            "--formats",
            "awl,grafcet,fst",
            "-o",
        ])
        .arg(dir.path().join("named"))
        .arg(&input)
        .assert()
        .code(1)
        .stderr(predicates::str::contains("SETTINGS!A2: error[E015]: C1 ("));
}

/// A finding names an actuator each time it speaks of it: the 300-character
/// name is cut there (40 characters, three dots), and stays whole in the
/// lists that describe the signal.
#[test]
fn a_long_name_is_cut_in_findings_and_whole_in_the_lists() {
    let dir = tempfile::tempdir().unwrap();
    let input = long_table(dir.path());
    steptable()
        .args(["convert", "--formats", "faults,io", "-o"])
        .arg(dir.path().join("out"))
        .arg(&input)
        .assert()
        .success();
    let out = dir.path().join("out").join("long");
    let name = long_text("clamp");
    let cut: String = name.chars().take(37).chain("...".chars()).collect();
    let faults = std::fs::read_to_string(out.join("long.faults.csv")).unwrap();
    let hazard = faults
        .lines()
        .find(|l| l.starts_with("x11 short circuit"))
        .expect("the early x11 row");
    assert!(
        hazard.contains(&format!("C1 ({cut}) had not reached x11")),
        "{hazard}"
    );
    assert!(!faults.contains(&name), "the whole name in a finding");
    let io = std::fs::read_to_string(out.join("long.io.csv")).unwrap();
    assert!(io.contains(&name), "the I/O list keeps the whole name");
}

/// Every printed line that names an actuator cuts a long name as the
/// findings do: `convert`'s `RESET homes …` line, the rung comments of a
/// program (homing stages), and the last line of a scenario.
#[test]
fn a_long_name_is_cut_in_every_printed_line_and_rung_comment() {
    let dir = tempfile::tempdir().unwrap();
    let input = long_table(dir.path());
    let name = long_text("clamp");
    let cut: String = name.chars().take(37).chain("...".chars()).collect();
    let run = steptable()
        .args(["convert", "--modes", "reset", "--formats", "st", "-o"])
        .arg(dir.path().join("out"))
        .arg(&input)
        .assert()
        .success();
    let stdout = String::from_utf8_lossy(&run.get_output().stdout).into_owned();
    let homes = stdout
        .lines()
        .find(|l| l.contains("RESET homes"))
        .expect("the home order is printed");
    assert!(homes.contains(&format!("C1 ({cut})")), "{homes}");
    assert!(!stdout.contains(&name), "the whole name printed: {stdout}");
    let st = std::fs::read_to_string(dir.path().join("out/long/long.st")).unwrap();
    assert!(
        st.contains(&format!("homing stage 1: C1 ({cut}) home")),
        "the homing rung names C1 by its name"
    );
    let run = steptable()
        .args(["simulate", "--stick", "x11=0@step1"])
        .arg(&input)
        .assert();
    let stdout = String::from_utf8_lossy(&run.get_output().stdout).into_owned();
    let last = stdout.lines().last().unwrap_or_default();
    assert!(last.contains(&format!("C1 ({cut}) at")), "{last}");
    assert!(!stdout.contains(&name), "the whole name printed: {stdout}");
}

/// steptable's own symbol comments fit the 80 characters of `NAME.sdf`:
/// W008 is for what the engineer wrote, who can shorten it, never for a
/// generated comment (MAN_MODE's and man_mem's once were cut, rt7
/// F18.1). Every sample, every mode and safety check, on S7.
#[test]
fn generated_comments_fit_the_symbol_table() {
    let dir = tempfile::tempdir().unwrap();
    for sample in crate::helpers::samples() {
        let out = steptable()
            .args(["convert", "--formats", "sdf", "--target", "siemens"])
            .args(["--modes", "all", "--safety", "all", "-o"])
            .arg(dir.path())
            .arg(&sample)
            .output()
            .unwrap();
        assert!(out.status.success(), "{sample:?}: {out:?}");
        let said = String::from_utf8_lossy(&out.stderr);
        assert!(!said.contains("W008"), "{sample:?}: {said}");
    }
}
