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
}

impl OutputKind {
    /// The kinds that show the fault analysis (the fault table, the
    /// workbook's FAULTS sheet): nothing else needs it.
    pub fn shows_faults(self) -> bool {
        matches!(self, OutputKind::Faults | OutputKind::Workbook)
    }

    /// Every kind, in the order files are listed.
    pub const ALL: [OutputKind; 16] = [
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
    ];

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
        }
    }

    /// How many files it writes: a Beremiz project folder holds two.
    pub fn file_count(self) -> usize {
        if self == OutputKind::Beremiz { 2 } else { 1 }
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

    /// The end of the file name, after `NAME`.
    pub fn suffix(self) -> &'static str {
        match self {
            OutputKind::Workbook => ".xlsx",
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
        }
    }

    /// Parses `--formats st,plcopen,awl` (`all` for every kind).
    pub fn parse_list(text: &str) -> Result<BTreeSet<OutputKind>, String> {
        let mut kinds = BTreeSet::new();
        for item in text.split(',').map(|s| s.trim().to_ascii_lowercase()) {
            if item == "all" {
                kinds.extend(OutputKind::ALL);
                continue;
            }
            match OutputKind::ALL.iter().find(|k| k.name() == item) {
                Some(kind) => {
                    kinds.insert(*kind);
                }
                None => {
                    let names: Vec<&str> = OutputKind::ALL.iter().map(|k| k.name()).collect();
                    return Err(format!(
                        "\"{item}\" is not an output format (expected some of: {}, or all)",
                        names.join(", ")
                    ));
                }
            }
        }
        if kinds.is_empty() {
            return Err("no output format given".to_string());
        }
        Ok(kinds)
    }
}
