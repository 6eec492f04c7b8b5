//! Every list of valid values is complete: `--help`, the messages for a
//! wrong value (on the command line and on the SETTINGS sheet) and the
//! template's lists name every value of their type, compared here against
//! the type's own list (the source of truth the parsers use), and those
//! lists against the types: a value added to a type cannot be forgotten in
//! one of the places that list it.

use steptable::actuator::ActuatorKind;
use steptable::address::{BOARDS, Mnemonic, Target};
use steptable::emit::OutputKind;
use steptable::program::{Modes, Safety};
use steptable::symbols::Scheme;

use crate::helpers::{sample, steptable, write_xlsx_sheets};

/// The values of each list, from the types.
fn sources() -> Vec<(&'static str, Vec<&'static str>)> {
    vec![
        ("valve", ActuatorKind::names()),
        (
            "formats",
            OutputKind::ALL.iter().map(|k| k.name()).collect(),
        ),
        ("target", Target::NAMES.to_vec()),
        ("board", BOARDS.iter().map(|b| b.name).collect()),
        ("mnemonic", Mnemonic::names()),
        ("safety", Safety::NAMES.to_vec()),
        ("modes", Modes::NAMES.to_vec()),
        ("designations", Scheme::ALL.map(Scheme::name).to_vec()),
    ]
}

fn missing<'a>(text: &str, names: &[&'a str]) -> Vec<&'a str> {
    names
        .iter()
        .copied()
        .filter(|name| !text.contains(name))
        .collect()
}

/// `convert --help`: each option's text lists every value.
#[test]
fn the_help_lists_every_value() {
    let output = steptable().args(["convert", "--help"]).output().unwrap();
    let help = String::from_utf8_lossy(&output.stdout).to_string();
    let lines: Vec<&str> = help.lines().collect();
    for (option, names) in sources() {
        let flag = format!("--{option} <");
        let at = lines
            .iter()
            .position(|l| l.contains(&flag))
            .unwrap_or_else(|| panic!("{flag} in {help}"));
        let text: String = lines[at + 1..]
            .iter()
            .take_while(|l| !l.trim_start().starts_with('-'))
            .copied()
            .collect::<Vec<_>>()
            .join(" ");
        assert_eq!(
            missing(&text, &names),
            Vec::<&str>::new(),
            "--{option}: {text}"
        );
    }
}

/// A wrong value on the command line and on the SETTINGS sheet: the
/// message lists every value.
#[test]
fn the_messages_for_a_wrong_value_list_every_value() {
    let dir = tempfile::tempdir().unwrap();
    for (option, names) in sources() {
        let value = if option == "valve" { "C1=zz" } else { "zz" };
        let output = steptable()
            .arg("convert")
            .arg(sample("paper_example.csv"))
            .args([format!("--{option}"), value.to_string()])
            .arg("-o")
            .arg(dir.path().join("out"))
            .output()
            .unwrap();
        assert_eq!(output.status.code(), Some(1), "--{option}");
        let stderr = String::from_utf8_lossy(&output.stderr).to_string();
        assert_eq!(
            missing(&stderr, &names),
            Vec::<&str>::new(),
            "--{option}: {stderr}"
        );
    }
    assert!(!dir.path().join("out").exists(), "nothing written");
    let path = dir.path().join("line.xlsx");
    let table: &[&[&str]] = &[&["C1+1"], &["C1-0"]];
    let settings: &[&[&str]] = &[
        &["target", "zz"],
        &["board", "zz"],
        &["mnemonic", "zz"],
        &["safety", "zz"],
        &["modes", "zz"],
        &["designations", "zz"],
        &[],
        &["actuator", "valve"],
        &["C1", "zz"],
    ];
    write_xlsx_sheets(&path, &[("TABLE", table), ("SETTINGS", settings)]);
    let output = steptable().arg("check").arg(&path).output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr).to_string();
    for (cell, option) in [
        ("B1", "target"),
        ("B2", "board"),
        ("B3", "mnemonic"),
        ("B4", "safety"),
        ("B5", "modes"),
        ("B6", "designations"),
        ("B9", "valve"),
    ] {
        let line = crate::helpers::line_with(
            &stderr
                .lines()
                .map(|l| l.split_once(": ").map_or(l, |(_, rest)| rest))
                .collect::<Vec<_>>()
                .join("\n"),
            &format!("SETTINGS!{cell}"),
        );
        let names = sources().into_iter().find(|(o, _)| *o == option).unwrap().1;
        assert_eq!(
            missing(&line, &names),
            Vec::<&str>::new(),
            "{option}: {line}"
        );
    }
    // A middle position on a valve without a centre: every valve that has one.
    let centred: Vec<&str> = ActuatorKind::ALL
        .into_iter()
        .filter(|v| v.has_centre())
        .map(|v| v.name())
        .collect();
    let output = steptable()
        .arg("check")
        .arg(sample("paper_example.csv"))
        .args(["--valve", "C2=52bi"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr).to_string();
    assert!(stderr.contains("E031"), "{stderr}");
    assert_eq!(missing(&stderr, &centred), Vec::<&str>::new(), "{stderr}");
}

/// The template's SETTINGS lists: each the type's values, with the
/// template's own `default` and `none` (and `all`) in front.
#[test]
fn the_templates_lists_offer_every_value() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.xlsx");
    steptable()
        .arg("template")
        .arg("-o")
        .arg(&path)
        .assert()
        .success();
    let lists = crate::template::template_lists(&path);
    let with = |first: &[&str], names: Vec<&str>| -> Vec<String> {
        first
            .iter()
            .copied()
            .chain(names)
            .map(str::to_string)
            .collect()
    };
    let expected = [
        ("target", with(&["default"], Target::NAMES.to_vec())),
        (
            "board",
            with(&["none"], BOARDS.iter().map(|b| b.name).collect()),
        ),
        ("mnemonic", with(&[], Mnemonic::names())),
        ("safety", with(&["none", "all"], Safety::NAMES.to_vec())),
        ("modes", with(&["none", "all"], Modes::NAMES.to_vec())),
        ("valve", with(&[], ActuatorKind::names())),
    ];
    for (label, values) in expected {
        assert_eq!(lists.get(label), Some(&values), "{label}: {lists:?}");
    }
    // The notes beside safety and modes name every check and mode.
    let settings = crate::helpers::read_sheet(&path, "SETTINGS");
    for (label, names) in [
        ("safety", Safety::NAMES.to_vec()),
        ("modes", Modes::NAMES.to_vec()),
    ] {
        let row = settings.iter().find(|r| r[0] == label).unwrap();
        assert_eq!(
            missing(&row[3], &names),
            Vec::<&str>::new(),
            "{label}: {row:?}"
        );
    }
}

/// The types' lists are complete: each list holds every variant (a new
/// variant fails to compile in these matches until it is counted), every
/// name parses, and the names of the checks and modes are all of them.
#[test]
fn the_types_lists_hold_every_value() {
    fn valve(v: ActuatorKind) -> usize {
        match v {
            ActuatorKind::Bistable52 => 0,
            ActuatorKind::Mono52 => 1,
            ActuatorKind::Closed53 => 2,
            ActuatorKind::Exhaust53 => 3,
            ActuatorKind::Pressure53 => 4,
            ActuatorKind::Motor => 5,
            ActuatorKind::Vacuum => 6,
            ActuatorKind::Swivel => 7,
        }
    }
    fn target(t: Target) -> usize {
        match t {
            Target::Festo => 0,
            Target::Iec => 1,
            Target::Siemens => 2,
        }
    }
    fn mnemonic(m: Mnemonic) -> usize {
        match m {
            Mnemonic::En => 0,
            Mnemonic::De => 1,
        }
    }
    fn kind(k: OutputKind) -> usize {
        use OutputKind::*;
        match k {
            Workbook => 0,
            StructuredText => 1,
            Fst => 2,
            Allocation => 3,
            Diagram => 4,
            Faults => 5,
            PlcOpen => 6,
            Codesys => 7,
            Gvl => 8,
            TiaTags => 9,
            Awl => 10,
            SymbolTable => 11,
            FstAllocation => 12,
            Rockwell => 13,
            CodesysV2 => 14,
            Beremiz => 15,
            Sfc => 16,
            Scl => 17,
            L5x => 18,
            Grafcet => 19,
            Report => 20,
            Ladder => 21,
            BeremizSfc => 22,
            BeremizLd => 23,
            CodesysSfc => 24,
            CodesysLd => 25,
        }
    }
    fn all_of(indices: Vec<usize>, count: usize) {
        let set: std::collections::BTreeSet<usize> = indices.into_iter().collect();
        assert_eq!(set, (0..count).collect(), "every variant once");
    }
    all_of(ActuatorKind::ALL.map(valve).to_vec(), 8);
    all_of(Target::ALL.map(target).to_vec(), 3);
    all_of(Mnemonic::ALL.map(mnemonic).to_vec(), 2);
    all_of(OutputKind::ALL.map(kind).to_vec(), 26);
    for name in ActuatorKind::names() {
        assert!(name.parse::<ActuatorKind>().is_ok(), "{name}");
    }
    for name in Target::NAMES {
        assert!(name.parse::<Target>().is_ok(), "{name}");
    }
    for name in Mnemonic::names() {
        assert!(name.parse::<Mnemonic>().is_ok(), "{name}");
    }
    assert!(OutputKind::parse_list(&OutputKind::ALL.map(|k| k.name()).join(",")).is_ok());
    // `all` is every check but the criteria analysis, asked for by name.
    let every = Safety {
        criteria: true,
        ..Safety::all()
    };
    assert_eq!(Safety::parse(&Safety::NAMES.join(",")), Ok(every));
    for name in Safety::NAMES {
        assert_ne!(Safety::parse(name), Ok(Safety::default()), "{name}");
    }
    // `all` is every mode, single step and manual among them.
    let every = Modes::parse("all").unwrap();
    assert_eq!(Modes::parse(&Modes::NAMES.join(",")), Ok(every));
    for name in Modes::NAMES {
        assert_ne!(Modes::parse(name), Ok(Modes::default()), "{name}");
    }
}
