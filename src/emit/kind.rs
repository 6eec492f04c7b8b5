//! The kinds of output file, their names and file-name endings.

use std::collections::BTreeSet;

/// One kind of output file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum OutputKind {
    Workbook,
    StructuredText,
    Fst,
    Allocation,
    Diagram,
    Faults,
    PlcOpen,
    Codesys,
    Gvl,
    TiaTags,
    Awl,
    SymbolTable,
    FstAllocation,
    Rockwell,
    /// CoDeSys V2.3 export (`.exp`).
    CodesysV2,
    /// A Beremiz / OpenPLC Editor project folder (`NAME.beremiz/`).
    Beremiz,
    /// The sequence as an SFC chart in PLCopen XML (`NAME.sfc.xml`): asked
    /// for by name, not written by default (the ST program is).
    Sfc,
    /// The step program as a Ladder body in PLCopen XML (`NAME.ld.xml`):
    /// asked for by name or with `all`, not written by default (the ST
    /// program is).
    Ladder,
    /// A Beremiz / OpenPLC Editor project folder whose `plc.xml` is the SFC
    /// chart (`NAME.sfc.beremiz/`): asked for by name or with `all`.
    BeremizSfc,
    /// A Beremiz / OpenPLC Editor project folder whose `plc.xml` is the
    /// Ladder body (`NAME.ld.beremiz/`): asked for by name or with `all`.
    BeremizLd,
    /// The SFC chart as CODESYS V3 imports it (`NAME.sfc.codesys.xml`):
    /// asked for by name or with `all`.
    CodesysSfc,
    /// The Ladder body as CODESYS V3 imports it (`NAME.ld.codesys.xml`):
    /// asked for by name or with `all`.
    CodesysLd,
    /// TIA Portal SCL external source for the S7-1200/1500 (`.scl`).
    Scl,
    /// Studio 5000 ladder program export (`.L5X`).
    L5x,
    /// The sequence as a GRAFCET (IEC 60848) picture.
    Grafcet,
    /// One self-contained HTML page: table, pictures, I/O, simulation,
    /// timeline and fault table.
    Report,
}

impl OutputKind {
    /// The kinds that show the fault analysis (the fault table, the
    /// workbook's FAULTS sheet): nothing else needs it.
    pub fn shows_faults(self) -> bool {
        matches!(
            self,
            OutputKind::Faults | OutputKind::Workbook | OutputKind::Report
        )
    }

    /// Every kind, in the order files are listed.
    pub const ALL: [OutputKind; 26] = [
        OutputKind::Workbook,
        OutputKind::StructuredText,
        OutputKind::Fst,
        OutputKind::Allocation,
        OutputKind::Diagram,
        OutputKind::Faults,
        OutputKind::PlcOpen,
        OutputKind::Codesys,
        OutputKind::Gvl,
        OutputKind::TiaTags,
        OutputKind::Awl,
        OutputKind::SymbolTable,
        OutputKind::FstAllocation,
        OutputKind::Rockwell,
        OutputKind::CodesysV2,
        OutputKind::Beremiz,
        OutputKind::Sfc,
        OutputKind::Ladder,
        OutputKind::BeremizSfc,
        OutputKind::BeremizLd,
        OutputKind::CodesysSfc,
        OutputKind::CodesysLd,
        OutputKind::Scl,
        OutputKind::L5x,
        OutputKind::Grafcet,
        OutputKind::Report,
    ];

    /// What a conversion writes when `--formats` is not given: every kind
    /// but the graphical bodies, which are asked for by name.
    pub fn defaults() -> BTreeSet<OutputKind> {
        OutputKind::ALL
            .into_iter()
            .filter(|k| k.body().is_none())
            .collect()
    }

    /// The graphical body a kind carries in place of the ST program, if
    /// any: the kind whose file it is (`NAME.sfc.xml` for the SFC project
    /// folder).
    pub fn body(self) -> Option<OutputKind> {
        match self {
            OutputKind::Sfc | OutputKind::BeremizSfc | OutputKind::CodesysSfc => {
                Some(OutputKind::Sfc)
            }
            OutputKind::Ladder | OutputKind::BeremizLd | OutputKind::CodesysLd => {
                Some(OutputKind::Ladder)
            }
            _ => None,
        }
    }

    /// The name used with `--formats`.
    pub fn name(self) -> &'static str {
        match self {
            OutputKind::Workbook => "xlsx",
            OutputKind::StructuredText => "st",
            OutputKind::Fst => "fst",
            OutputKind::Allocation => "io",
            OutputKind::Diagram => "diagram",
            OutputKind::Faults => "faults",
            OutputKind::PlcOpen => "plcopen",
            OutputKind::Codesys => "codesys",
            OutputKind::Gvl => "gvl",
            OutputKind::TiaTags => "tia",
            OutputKind::Awl => "awl",
            OutputKind::SymbolTable => "sdf",
            OutputKind::FstAllocation => "fst-alloc",
            OutputKind::Rockwell => "rockwell",
            OutputKind::CodesysV2 => "exp",
            OutputKind::Beremiz => "beremiz",
            OutputKind::Sfc => "sfc",
            OutputKind::Ladder => "ld",
            OutputKind::BeremizSfc => "beremiz-sfc",
            OutputKind::BeremizLd => "beremiz-ld",
            OutputKind::CodesysSfc => "codesys-sfc",
            OutputKind::CodesysLd => "codesys-ld",
            OutputKind::Scl => "scl",
            OutputKind::L5x => "l5x",
            OutputKind::Grafcet => "grafcet",
            OutputKind::Report => "report",
        }
    }

    /// How many files it writes: a Beremiz project folder holds two.
    pub fn file_count(self) -> usize {
        if self.is_project_folder() { 2 } else { 1 }
    }

    /// Whether it is a Beremiz project folder (`plc.xml`, `beremiz.xml`).
    pub fn is_project_folder(self) -> bool {
        matches!(
            self,
            OutputKind::Beremiz | OutputKind::BeremizSfc | OutputKind::BeremizLd
        )
    }

    /// Whether its lines end in CRLF: the lists Windows tools import (STEP 7
    /// symbol tables, Studio 5000 and FST lists, CoDeSys V2.3 exports).
    pub fn windows_lines(self) -> bool {
        matches!(
            self,
            OutputKind::SymbolTable
                | OutputKind::FstAllocation
                | OutputKind::Rockwell
                | OutputKind::CodesysV2
        )
    }

    /// Whether the kind's file is read by a Windows tool in its ANSI code
    /// page (SIMATIC Manager's symbol import, Festo FST, CoDeSys V2.3):
    /// written in Windows-1252, not UTF-8, which would show `Ä` as `Ã„`
    /// there and widen a fixed-width row by a byte.
    pub fn windows_ansi(self) -> bool {
        matches!(
            self,
            OutputKind::SymbolTable
                | OutputKind::Fst
                | OutputKind::FstAllocation
                | OutputKind::CodesysV2
        )
    }

    /// The file's name for outputs named `name` (`paper` → `paper.st`);
    /// a Beremiz project's is its folder.
    pub fn file_name(self, name: &str) -> String {
        format!("{name}{}", self.suffix())
    }

    /// The end of the file name, after `NAME`.
    pub fn suffix(self) -> &'static str {
        match self {
            // Not `NAME.xlsx`: Excel refuses to open two workbooks of one
            // file name, and the engineer opens this one beside its input.
            OutputKind::Workbook => ".steptable.xlsx",
            OutputKind::StructuredText => ".st",
            OutputKind::Fst => ".fst.txt",
            OutputKind::Allocation => ".io.csv",
            OutputKind::Diagram => ".diagram.svg",
            OutputKind::Faults => ".faults.csv",
            OutputKind::PlcOpen => ".plcopen.xml",
            OutputKind::Codesys => ".codesys.xml",
            OutputKind::Gvl => ".gvl.txt",
            OutputKind::TiaTags => ".tags.xlsx",
            OutputKind::Awl => ".awl",
            OutputKind::SymbolTable => ".sdf",
            OutputKind::FstAllocation => ".fst-alloc.csv",
            OutputKind::Rockwell => ".rockwell.csv",
            OutputKind::CodesysV2 => ".exp",
            OutputKind::Beremiz => ".beremiz",
            OutputKind::Sfc => ".sfc.xml",
            OutputKind::Ladder => ".ld.xml",
            OutputKind::BeremizSfc => ".sfc.beremiz",
            OutputKind::BeremizLd => ".ld.beremiz",
            OutputKind::CodesysSfc => ".sfc.codesys.xml",
            OutputKind::CodesysLd => ".ld.codesys.xml",
            OutputKind::Scl => ".scl",
            // Studio 5000 writes and lists its exports as .L5X.
            OutputKind::L5x => ".L5X",
            OutputKind::Grafcet => ".grafcet.svg",
            OutputKind::Report => ".report.html",
        }
    }

    /// Parses `--formats st,plcopen,awl` (`all` for every kind) with the
    /// list reader `--modes` and `--safety` use: a kind given twice
    /// (`st,ST`) or `all` beside a kind (`all,st`) is refused, not read one
    /// way silently.
    pub fn parse_list(text: &str) -> Result<BTreeSet<OutputKind>, String> {
        let names = OutputKind::ALL.map(OutputKind::name);
        let expected = format!("some of: {}, or all", names.join(", "));
        let items = crate::named_set::NameList {
            names: &names,
            alone: &["all"],
            expected: &expected,
        }
        .parse(text, |item| {
            let item = item.to_ascii_lowercase();
            let hint = OutputKind::suggest(&item)
                .map(|kinds| {
                    let kinds: Vec<String> = kinds
                        .iter()
                        .map(|k| format!("{} (writes NAME{})", k.name(), k.suffix()))
                        .collect();
                    format!("; did you mean {}?", kinds.join(" or "))
                })
                .unwrap_or_default();
            format!("\"{item}\" is not an output format{hint} (expected {expected})")
        })?;
        let mut kinds = BTreeSet::new();
        for item in items {
            match OutputKind::ALL.into_iter().find(|k| k.name() == item) {
                Some(kind) => {
                    kinds.insert(kind);
                }
                // `all`, the only other item the list accepts: every kind,
                // the graphical bodies too (every program has them, timers
                // drawn as TON blocks).
                None => kinds.extend(OutputKind::ALL),
            }
        }
        if kinds.is_empty() {
            return Err("no output format given".to_string());
        }
        Ok(kinds)
    }

    /// The kinds a mistaken `--formats` item may mean: those whose file
    /// name has it as a part (`tags` → tia, for `NAME.tags.xlsx`; `csv` →
    /// the four CSV lists), else the names a letter or two off.
    pub fn suggest(item: &str) -> Option<Vec<OutputKind>> {
        let by_file: Vec<OutputKind> = OutputKind::ALL
            .into_iter()
            .filter(|k| k.suffix().split(['.', '-', '/']).any(|part| part == item))
            .collect();
        if !by_file.is_empty() {
            return Some(by_file);
        }
        let near: Vec<OutputKind> = OutputKind::ALL
            .into_iter()
            // At most one letter in four wrong: `plcopn`, not `pdf` for sdf.
            .filter(|k| {
                crate::cell::edit_distance(item, k.name()) * 4 <= k.name().len().max(item.len())
            })
            .collect();
        (!near.is_empty()).then_some(near)
    }
}

/// The files the commands besides convert write (simulate's time diagram,
/// synth's report, programs and workbook), each with its name rule as the
/// kinds above have theirs: every file name a command writes is decided
/// here. Not a `--formats` choice: each command writes all of its own.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum CommandFile {
    /// `simulate --diagram DIR`: the run's displacement-time diagram.
    TimeDiagram,
    /// `simulate --press … --report DIR`: the scenario on one page, drawn
    /// on the report's timeline; `.report.html` at its end, as the
    /// report's, so that it opens in a browser and is stamped alike.
    ScenarioReport,
    /// synth's report, as printed.
    SynthReport,
    /// synth's report for programs.
    SynthJson,
    /// The synthesised equations as a Structured Text program.
    EquationsSt,
    /// The same program in instruction list.
    EquationsIl,
    /// The equations and truth table as a workbook; not
    /// `NAME.steptable.xlsx`, convert's workbook of the same table in the
    /// same folder.
    SynthWorkbook,
}

impl CommandFile {
    pub const ALL: [CommandFile; 7] = [
        CommandFile::TimeDiagram,
        CommandFile::ScenarioReport,
        CommandFile::SynthReport,
        CommandFile::SynthJson,
        CommandFile::EquationsSt,
        CommandFile::EquationsIl,
        CommandFile::SynthWorkbook,
    ];

    /// The end of the file name, after `NAME`.
    pub fn suffix(self) -> &'static str {
        match self {
            CommandFile::TimeDiagram => ".time.svg",
            CommandFile::ScenarioReport => ".scenario.report.html",
            CommandFile::SynthReport => ".synth.txt",
            CommandFile::SynthJson => ".synth.json",
            CommandFile::EquationsSt => ".equations.st",
            CommandFile::EquationsIl => ".equations.il",
            CommandFile::SynthWorkbook => ".synth.xlsx",
        }
    }

    /// The file's name for outputs named `name`.
    pub fn file_name(self, name: &str) -> String {
        format!("{name}{}", self.suffix())
    }

    /// Whether the file named `file` is one a conversion leaves in its
    /// folder although it did not write it: a scenario's page records a
    /// run the engineer chose (its events are in no table), opens beside
    /// the report, and no rerun of `convert` could write it again.
    pub fn outlives_conversion(file: &str) -> bool {
        file.ends_with(CommandFile::ScenarioReport.suffix())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_mistaken_format_is_pointed_to_the_kind_meant() {
        let err = OutputKind::parse_list("st,tags").unwrap_err();
        assert!(
            err.contains("did you mean tia (writes NAME.tags.xlsx)?"),
            "{err}"
        );
        let err = OutputKind::parse_list("plcopn").unwrap_err();
        assert!(err.contains("did you mean plcopen"), "{err}");
        let err = OutputKind::parse_list("csv").unwrap_err();
        for kind in ["io", "faults", "fst-alloc", "rockwell"] {
            assert!(err.contains(&format!("{kind} (writes")), "{err}");
        }
        let err = OutputKind::parse_list("pdf").unwrap_err();
        assert!(!err.contains("did you mean"), "{err}");
        // The same list reader as --modes and --safety: twice, or beside all.
        for (list, said) in [
            ("st,st", "\"st\" is given twice in \"st,st\""),
            ("st,ST", "\"st\" is given twice in \"st,ST\""),
            ("all,st", "\"all\" stands alone"),
            ("st,,awl", "has an empty item"),
        ] {
            let err = OutputKind::parse_list(list).unwrap_err();
            assert!(err.contains(said), "{list}: {err}");
        }
        // `all` is every kind, the graphical bodies and their Beremiz and
        // CODESYS containers too (the ladder draws every timer).
        let all = OutputKind::parse_list("ALL").unwrap();
        assert_eq!(all.len(), 26);
        assert!(all.contains(&OutputKind::Ladder) && all.contains(&OutputKind::Sfc));
        assert!(all.contains(&OutputKind::BeremizSfc) && all.contains(&OutputKind::CodesysLd));
        // None of them by default: the ST program stays the default.
        let defaults = OutputKind::defaults();
        assert_eq!(defaults.len(), 20);
        assert!(defaults.iter().all(|k| k.body().is_none()));
        assert!(OutputKind::parse_list(" ").is_err());
        assert_eq!(crate::cell::edit_distance("kitten", "sitting"), 3);
    }
}
