//! Diagnostics: every problem found in an input, with where it is and a stable
//! code, collected rather than thrown so that an engineer sees all of them at once.

use std::fmt;

/// How bad a diagnostic is. Any error stops the conversion; warnings do not.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Severity {
    Warning,
    Error,
}

/// Stable diagnostic codes. The numbers never change meaning; new kinds get new numbers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Code {
    /// The file could not be read from disk.
    E001Unreadable,
    /// The file is not a workbook or CSV we can decode (corrupt zip, binary data, …).
    E002NotAWorkbook,
    /// No step table was found (empty sheet, no moves).
    E003NoTable,
    /// The sheet asked for with `--sheet` does not exist.
    E004NoSuchSheet,
    /// The file is larger than the limit.
    E005TooLarge,
    /// A cell inside the table is not a move.
    E010NotAMove,
    /// Actuator number out of range (0 or too large).
    E011BadActuator,
    /// Position number out of range.
    E012BadPosition,
    /// A `+` move that does not go up or a `-` move that does not go down.
    E020WrongDirection,
    /// The same actuator moves twice in one step.
    E021TwiceInStep,
    /// An actuator is not back at position 0 when the cycle ends.
    E022NotHome,
    /// A step row without any move between steps that have moves.
    E023EmptyStep,
    /// The table is larger than the limits.
    E024TableTooLarge,
    /// A value on the SETTINGS sheet is not valid.
    E030BadSetting,
    /// A valve that cannot do what the table asks (a middle stop on a 5/2 valve).
    E031ValveCannotStop,
    /// A cell's text is longer than any move could be.
    E013CellTooLong,
    /// `T=` with a malformed or out-of-range duration.
    E014BadDwell,
    /// `I:` / `Y:` with a malformed or reserved name.
    E015BadName,
    /// One name used for an input and an output, or two names FST cannot tell apart.
    E025NameClash,
    /// More dwells than the PLCs have timers.
    E026TooManyDwells,
    /// Two step tables on one sheet.
    E027TwoTables,
    /// A formula cell whose value was never computed.
    E016FormulaNotComputed,
    /// The valves, loads, strokes or scan given make the cycle impossible.
    E032MachineCannotRun,
    /// The work asked for exceeds a stated budget (fault pairs, synthesis).
    E033OverBudget,
    /// A sequence or table that synthesis does not handle.
    E034NotSynthesisable,
    /// A row of the ADDRESSES sheet: an unknown signal, an address not in
    /// the target's notation or out of range, the wrong area, a clash.
    E035BadPinnedAddress,
    /// The program needs more inputs or outputs than the OpenPLC board
    /// wires, or the board is given with a target that is not OpenPLC's.
    E036BoardTooSmall,
    /// `J:` that is not `J:<step> if I:<name>` / `J:end if I:<name>`.
    E017BadJump,
    /// A jump to a step the table does not have, to where the step goes
    /// anyway, or from the last step (the cycle ends there).
    E028JumpTarget,
    /// A jump that leaves an actuator away from where the target step
    /// expects it.
    E029JumpPositions,
    /// Something steptable did not write is where an output goes (a file of
    /// the engineer's, a folder, a file where the output folder goes, an
    /// input of the run): nothing is written for that input.
    E040OutputTaken,
    /// The command line itself is wrong: an unknown option, a bad value.
    E041BadCommandLine,
    /// A scenario event of `simulate` (`--press`, `--hold`, `--release`,
    /// `--stick`) that this table's program cannot run: an unknown signal,
    /// a button whose mode is off, a step it lacks, a malformed time, two
    /// events contradicting or repeating each other.
    E042BadScenarioEvent,
    /// A move asks an actuator for a position its kind cannot hold (a
    /// vacuum gripper has released 0 and held 1 only).
    E045KindCannotHold,
    /// A SETTINGS label that is a known setting misspelt (`mode`, `hold
    /// safe`, `supervison`), or a setting and its value in one cell: the
    /// program would be written without the setting.
    E046MistypedSetting,
    /// Two sheets are each the sheet asked for when names are compared
    /// without case and the spaces around them (`Line A` and `Line A `),
    /// and none is named exactly: reading one would be a silent choice.
    E047SheetAmbiguous,
    /// The SFC chart was asked for (`--formats sfc`, `beremiz-sfc`,
    /// `codesys-sfc`, `all`) of a table with a jump back into its own step
    /// that restarts something (a dwell, the watchdog): an SFC step that
    /// stays active does not run its entry again, so the chart would not
    /// do what the program does.
    E048RetryInChart,
    /// A value lies under a merged cell, where the spreadsheet shows only
    /// the merge's first cell: steptable would read what nobody sees.
    E049HiddenUnderMerge,
    /// A CSV field starts with a space after a filled one, in a file whose
    /// other fields start right after their delimiter: one cell's items
    /// split in two (`C1-0; T=2s` unquoted in a semicolon file).
    E050CellSplit,
    /// The file was read in an encoding other than UTF-8.
    W001Encoding,
    /// A `STEP n` label does not match the row's place in the table.
    W002StepNumber,
    /// A filled cell in or beside the table that is not part of it.
    W003Ignored,
    /// The table's sheet was chosen among several, or is hidden.
    W004SheetChoice,
    /// The CSV delimiter was chosen among several that read as a table.
    W005Delimiter,
    /// A setting that the other settings make ineffective.
    W006NoEffect,
    /// A value read under an assumption the engineer did not write (a dwell
    /// without a unit, read as seconds).
    W007Assumed,
    /// An output holds less of what the engineer wrote than the table (a
    /// comment cut to the width a symbol table's field holds).
    W008Shortened,
    /// A safety check leaves part of the table unchecked (the watchdog
    /// does not time a step that waits on an input, nor its moves).
    W009Unsupervised,
    /// A jump leaves a machine output otherwise than the sequence without
    /// it (a switch-off it leaves out).
    W010JumpLeavesOutput,
    /// An output written for a tool that will refuse it (an SFC chart with
    /// timers for OpenPLC v3, whose upload cannot build a global TON).
    W011RefusedByTool,
    /// The program halts (a safety check, an interlock, a STOP that acts
    /// at once) but has no RESET: nothing acknowledges the halt, and the
    /// machine stands away from home until the PLC restarts.
    W012HaltForGood,
    /// An interlock's halt leaves the coils of closed-, exhausted- or
    /// pressurised-centre valves on: a piston under way when the guard
    /// opens drives on to its end, which the centre would have stopped.
    W013GuardLeavesMotion,
    /// A scenario's run found a problem (motion no step commands, a
    /// collision risk, both coils on): said as JSON, where the printed
    /// table goes to stderr.
    W014ScenarioProblem,
    /// Settings written on a workbook's sheet of another name (`Config`,
    /// `PARAMETERS`): only the sheet named SETTINGS is read for them.
    W015SettingsElsewhere,
}

impl Code {
    /// The code as printed, e.g. `E010`.
    pub fn as_str(self) -> &'static str {
        match self {
            Code::E001Unreadable => "E001",
            Code::E002NotAWorkbook => "E002",
            Code::E003NoTable => "E003",
            Code::E004NoSuchSheet => "E004",
            Code::E005TooLarge => "E005",
            Code::E010NotAMove => "E010",
            Code::E011BadActuator => "E011",
            Code::E012BadPosition => "E012",
            Code::E020WrongDirection => "E020",
            Code::E021TwiceInStep => "E021",
            Code::E022NotHome => "E022",
            Code::E023EmptyStep => "E023",
            Code::E024TableTooLarge => "E024",
            Code::E030BadSetting => "E030",
            Code::E031ValveCannotStop => "E031",
            Code::E013CellTooLong => "E013",
            Code::E014BadDwell => "E014",
            Code::E015BadName => "E015",
            Code::E025NameClash => "E025",
            Code::E026TooManyDwells => "E026",
            Code::W001Encoding => "W001",
            Code::W002StepNumber => "W002",
            Code::W003Ignored => "W003",
            Code::W004SheetChoice => "W004",
            Code::W005Delimiter => "W005",
            Code::W006NoEffect => "W006",
            Code::W007Assumed => "W007",
            Code::W008Shortened => "W008",
            Code::W009Unsupervised => "W009",
            Code::W010JumpLeavesOutput => "W010",
            Code::W011RefusedByTool => "W011",
            Code::W012HaltForGood => "W012",
            Code::W013GuardLeavesMotion => "W013",
            Code::W014ScenarioProblem => "W014",
            Code::W015SettingsElsewhere => "W015",
            Code::E027TwoTables => "E027",
            Code::E016FormulaNotComputed => "E016",
            Code::E032MachineCannotRun => "E032",
            Code::E033OverBudget => "E033",
            Code::E034NotSynthesisable => "E034",
            Code::E035BadPinnedAddress => "E035",
            Code::E036BoardTooSmall => "E036",
            Code::E017BadJump => "E017",
            Code::E028JumpTarget => "E028",
            Code::E029JumpPositions => "E029",
            Code::E040OutputTaken => "E040",
            Code::E041BadCommandLine => "E041",
            Code::E042BadScenarioEvent => "E042",
            Code::E045KindCannotHold => "E045",
            Code::E046MistypedSetting => "E046",
            Code::E047SheetAmbiguous => "E047",
            Code::E048RetryInChart => "E048",
            Code::E049HiddenUnderMerge => "E049",
            Code::E050CellSplit => "E050",
        }
    }
}

/// `a, b or c`: the valid values of a setting, as messages, `--help` and
/// the template list them (each list is built from its type's own list of
/// values, so a value added there is never left out here).
pub fn or_list<S: AsRef<str>>(items: &[S]) -> String {
    match items {
        [] => String::new(),
        [one] => one.as_ref().to_string(),
        [rest @ .., last] => format!(
            "{} or {}",
            rest.iter()
                .map(|s| s.as_ref())
                .collect::<Vec<_>>()
                .join(", "),
            last.as_ref()
        ),
    }
}

/// Where a cell is: zero-based absolute row and column on its sheet.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct CellPos {
    pub row: u32,
    pub col: u32,
}

impl CellPos {
    pub fn new(row: u32, col: u32) -> Self {
        CellPos { row, col }
    }

    /// A1 notation (`D7`).
    pub fn a1(self) -> String {
        format!("{}{}", column_letters(self.col), self.row + 1)
    }
}

/// Excel column letters for a zero-based column index (0 → A, 26 → AA).
pub fn column_letters(col: u32) -> String {
    let mut n = col as u64 + 1;
    let mut letters = Vec::new();
    while n > 0 {
        let rem = ((n - 1) % 26) as u8;
        letters.push(b'A' + rem);
        n = (n - 1) / 26;
    }
    letters.reverse();
    String::from_utf8(letters).unwrap_or_default()
}

/// The place a diagnostic points at.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    /// File name as the user gave it (display form).
    pub file: String,
    /// Sheet name for workbooks; `None` for CSV files and whole-file problems.
    pub sheet: Option<String>,
    /// The cell, if the problem has one.
    pub cell: Option<CellPos>,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (&self.sheet, self.cell) {
            (Some(sheet), Some(cell)) => write!(f, "{}: {}!{}", self.file, sheet, cell.a1()),
            (Some(sheet), None) => write!(f, "{}: {}", self.file, sheet),
            // CSV: line:column, both one-based, as compilers print them.
            (None, Some(cell)) => write!(f, "{}:{}:{}", self.file, cell.row + 1, cell.col + 1),
            (None, None) => write!(f, "{}", self.file),
        }
    }
}

/// One problem found in an input.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Diagnostic {
    pub severity: Severity,
    pub code: Code,
    pub location: Location,
    pub message: String,
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let kind = match self.severity {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        // One line per problem: a line break quoted from a cell (Alt+Enter)
        // is shown as `\n`, so that grep and CI logs keep it whole.
        let message = self
            .message
            .replace("\r\n", "\\n")
            .replace(['\n', '\r'], "\\n")
            .replace('\t', "\\t");
        write!(
            f,
            "{}: {kind}[{}]: {message}",
            self.location,
            self.code.as_str(),
        )
    }
}

impl Diagnostic {
    /// One JSON object: file, sheet, cell (A1), row and column (one-based),
    /// severity, code and message; absent parts are null.
    pub fn to_json(&self) -> String {
        let cell = self.location.cell;
        let value = serde_json::json!({
            "file": self.location.file,
            "sheet": self.location.sheet,
            "cell": cell.map(|c| c.a1()),
            "row": cell.map(|c| c.row + 1),
            "column": cell.map(|c| c.col + 1),
            "severity": self.severity,
            "code": self.code.as_str(),
            "message": self.message,
        });
        value.to_string()
    }
}

/// Collects diagnostics for one input file.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Diagnostics {
    items: Vec<Diagnostic>,
    /// Cells an error speaks for besides its own (a setting's value beside
    /// the label it names): no "not read" note is said of them either.
    spoken_for: Vec<Location>,
}

impl Diagnostics {
    pub fn new() -> Self {
        Self::default()
    }

    pub fn push(&mut self, diagnostic: Diagnostic) {
        self.items.push(diagnostic);
    }

    pub fn error(&mut self, code: Code, location: Location, message: impl Into<String>) {
        self.push(Diagnostic {
            severity: Severity::Error,
            code,
            location,
            message: message.into(),
        });
    }

    pub fn warning(&mut self, code: Code, location: Location, message: impl Into<String>) {
        self.push(Diagnostic {
            severity: Severity::Warning,
            code,
            location,
            message: message.into(),
        });
    }

    /// `location` is part of what an error said: the value of the label it
    /// names, a row of the table it is at.
    pub fn speaks_for(&mut self, location: Location) {
        self.spoken_for.push(location);
    }

    pub fn has_errors(&self) -> bool {
        self.items.iter().any(|d| d.severity == Severity::Error)
    }

    pub fn error_count(&self) -> usize {
        self.items
            .iter()
            .filter(|d| d.severity == Severity::Error)
            .count()
    }

    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    pub fn warning_count(&self) -> usize {
        self.items.len() - self.error_count()
    }

    /// All diagnostics, sorted by position in the file so they read top to
    /// bottom. A cell refused says why once: its "not read" note (W003),
    /// from a look at the cells left over, adds nothing beside its error.
    pub fn into_sorted(mut self) -> Vec<Diagnostic> {
        let place = |l: &Location| Some((l.file.clone(), l.sheet.clone(), l.cell?));
        let errors = self.items.iter().filter(|d| d.severity == Severity::Error);
        let refused: std::collections::HashSet<_> = errors
            .map(|d| &d.location)
            .chain(&self.spoken_for)
            .filter_map(place)
            .collect();
        if !refused.is_empty() {
            self.items.retain(|d| {
                d.code != Code::W003Ignored
                    || place(&d.location).is_none_or(|p| !refused.contains(&p))
            });
        }
        self.items.sort_by(|a, b| {
            let key = |d: &Diagnostic| {
                (
                    d.location.sheet.clone(),
                    d.location.cell.map(|c| (c.row, c.col)),
                )
            };
            key(a).cmp(&key(b))
        });
        self.items
    }

    pub fn iter(&self) -> impl Iterator<Item = &Diagnostic> {
        self.items.iter()
    }

    pub fn extend(&mut self, other: Diagnostics) {
        self.items.extend(other.items);
        self.spoken_for.extend(other.spoken_for);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn column_letters_follow_excel() {
        assert_eq!(column_letters(0), "A");
        assert_eq!(column_letters(25), "Z");
        assert_eq!(column_letters(26), "AA");
        assert_eq!(column_letters(701), "ZZ");
        assert_eq!(column_letters(702), "AAA");
        assert_eq!(column_letters(16383), "XFD");
    }

    #[test]
    fn json_diagnostics_carry_every_field() {
        let d = Diagnostic {
            severity: Severity::Error,
            code: Code::E010NotAMove,
            location: Location {
                file: "line.xlsx".into(),
                sheet: Some("S".into()),
                cell: Some(CellPos::new(6, 3)),
            },
            message: "\"C2+x\" is not a move".into(),
        };
        let v: serde_json::Value = serde_json::from_str(&d.to_json()).unwrap();
        assert_eq!(v["cell"], "D7");
        assert_eq!(v["row"], 7);
        assert_eq!(v["column"], 4);
        assert_eq!(v["severity"], "error");
        assert_eq!(v["code"], "E010");
        assert_eq!(v["message"], "\"C2+x\" is not a move");
    }

    #[test]
    fn locations_print_as_engineers_read_them() {
        let sheet = Location {
            file: "line.xlsx".into(),
            sheet: Some("SEQUENTIAL CONTROL DESCRIPTION".into()),
            cell: Some(CellPos::new(6, 3)),
        };
        assert_eq!(
            sheet.to_string(),
            "line.xlsx: SEQUENTIAL CONTROL DESCRIPTION!D7"
        );
        let csv = Location {
            file: "line.csv".into(),
            sheet: None,
            cell: Some(CellPos::new(6, 2)),
        };
        assert_eq!(csv.to_string(), "line.csv:7:3");
    }
}
