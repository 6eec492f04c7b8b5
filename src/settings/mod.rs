//! The settings of a run, and where they come from: the command line, a
//! workbook's SETTINGS sheet, the defaults, in that order of precedence
//! (`cli.or(sheet).or(default)`). Each value has one parser ([`FromStr`] on
//! its type), used by clap and by the sheet alike.
//!
//! [`FromStr`]: std::str::FromStr

pub mod halt;
pub mod pins;
mod sheet;
pub mod user_templates;

use std::collections::{BTreeMap, BTreeSet};

use crate::actuator::ActuatorKind;
use crate::address::{Board, Mnemonic, Target};
use crate::emit::OutputKind;
use crate::emit::diagram::DiagramKind;
use crate::emit::templates::Templates;
use crate::program::{Modes, ProgramOptions, Safety};
use crate::simulate::SimSettings;
use crate::stroke::Stroke;

pub use sheet::{LABELS, parse, written_elsewhere, written_with_table};

/// What one source of settings says (the command line or a SETTINGS
/// sheet); `None` and missing entries leave the choice to the next source.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Given {
    pub target: Option<Target>,
    /// The OpenPLC board the program runs on (its addresses are `iec`).
    pub board: Option<Board>,
    pub mnemonic: Option<Mnemonic>,
    pub scan_ms: Option<u32>,
    pub safety: Option<Safety>,
    /// Operating modes (`continuous, stop, estop, reset`).
    pub modes: Option<Modes>,
    /// Homing stages (`C3&C4, C2, C1`, `lift, clamp`), each actuator as
    /// written.
    pub home_order: Option<Vec<Vec<String>>>,
    /// Supervision times by table step (`3=5s, 5=12s`).
    pub supervision: Option<BTreeMap<usize, u32>>,
    /// Stroke times per actuator.
    pub strokes: BTreeMap<u32, Stroke>,
    /// Valve types per actuator.
    pub valves: BTreeMap<u32, ActuatorKind>,
    /// Drift rates per actuator (stroke per second).
    pub loads: BTreeMap<u32, f64>,
    /// Valve types and stroke times the command line gives by an
    /// actuator's name (`--valve clamp=52mono`): resolved once the table's
    /// names are read (`convert`).
    pub named_valves: BTreeMap<String, ActuatorKind>,
    pub named_strokes: BTreeMap<String, Stroke>,
    pub named_loads: BTreeMap<String, f64>,
    /// The engineer's names of actuators (`C1 (clamp)` in the actuator table).
    pub names: BTreeMap<u32, crate::symbols::ActuatorName>,
    /// The designation scheme (`designations`).
    pub designations: Option<crate::symbols::Scheme>,
    /// The rows that name outputs or inputs (`hold-safe`, `on stop`, …),
    /// as written: checked against the table once it is read.
    pub named: halt::NamedRows,
    /// Where each labelled setting was read (a SETTINGS sheet's value
    /// cells, by label), for the messages about it.
    pub cells: BTreeMap<&'static str, crate::diag::Location>,
    /// Where the actuator table gave an actuator's `valve`, `stroke` or
    /// `load`, for the messages about it.
    pub actuator_cells: BTreeMap<(u32, &'static str), crate::diag::Location>,
}

impl Given {
    /// Whether this source gives the setting of `label` (a SETTINGS label).
    pub fn gives(&self, label: &str) -> bool {
        match label {
            "target" => self.target.is_some(),
            "board" => self.board.is_some(),
            "mnemonic" => self.mnemonic.is_some(),
            "scan time" => self.scan_ms.is_some(),
            "safety" => self.safety.is_some(),
            "modes" => self.modes.is_some(),
            "home order" => self.home_order.is_some(),
            "supervision" => self.supervision.is_some(),
            "designations" => self.designations.is_some(),
            other => halt::Row::from_label(other).is_some_and(|row| self.named.contains_key(&row)),
        }
    }

    /// A source that names a board and no target means OpenPLC's
    /// addresses (a board beside another target is the conflict
    /// `convert::allocate` reports).
    pub fn with_board_target(mut self) -> Given {
        if self.board.is_some() && self.target.is_none() {
            self.target = Some(Target::Iec);
        }
        self
    }

    /// What `self` gives, and what `other` gives where `self` is silent.
    pub fn or(&self, other: &Given) -> Given {
        fn merged<K: Ord + Copy, V: Clone>(
            first: &BTreeMap<K, V>,
            then: &BTreeMap<K, V>,
        ) -> BTreeMap<K, V> {
            let mut all = then.clone();
            all.extend(first.iter().map(|(k, v)| (*k, v.clone())));
            all
        }
        Given {
            target: self.target.or(other.target),
            board: self.board.or(other.board),
            mnemonic: self.mnemonic.or(other.mnemonic),
            scan_ms: self.scan_ms.or(other.scan_ms),
            safety: self.safety.or(other.safety),
            modes: self.modes.clone().or_else(|| other.modes.clone()),
            home_order: self.home_order.clone().or_else(|| other.home_order.clone()),
            supervision: self
                .supervision
                .clone()
                .or_else(|| other.supervision.clone()),
            strokes: merged(&self.strokes, &other.strokes),
            valves: merged(&self.valves, &other.valves),
            loads: merged(&self.loads, &other.loads),
            names: merged(&self.names, &other.names),
            // The command line's word wins: it comes last.
            named_valves: other
                .named_valves
                .clone()
                .into_iter()
                .chain(self.named_valves.clone())
                .collect(),
            named_strokes: other
                .named_strokes
                .clone()
                .into_iter()
                .chain(self.named_strokes.clone())
                .collect(),
            named_loads: other
                .named_loads
                .clone()
                .into_iter()
                .chain(self.named_loads.clone())
                .collect(),
            designations: self.designations.or(other.designations),
            named: merged(&self.named, &other.named),
            cells: other
                .cells
                .iter()
                .filter(|(label, _)| !self.gives(label))
                .chain(&self.cells)
                .map(|(label, at)| (*label, at.clone()))
                .collect(),
            actuator_cells: merged(&self.actuator_cells, &other.actuator_cells),
        }
    }
}

/// Validated settings of one run (raw command-line values are turned into this
/// before any work starts).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Settings {
    pub target: Target,
    /// Only the addresses this OpenPLC board wires may be used.
    pub board: Option<Board>,
    pub mnemonic: Mnemonic,
    /// Sheet to read instead of the default choice.
    pub sheet: Option<String>,
    pub program: ProgramOptions,
    /// Simulation settings; `simulation.scan_ms` is also the generated task's cycle.
    pub simulation: SimSettings,
    /// Horizontal axis of `NAME.diagram.svg`.
    pub diagram: DiagramKind,
    /// How signals are designated, and the engineer's names of actuators.
    pub naming: crate::symbols::Naming,
    /// Which files to write.
    pub formats: BTreeSet<OutputKind>,
    /// The templates text outputs are laid out by.
    pub templates: Templates,
    /// Whether written files are flushed to the disk (`--sync`).
    pub durability: crate::write::Durability,
    /// What the command line gave: a workbook's SETTINGS sheet decides
    /// only what it leaves open.
    pub given: Given,
    /// The workbook's ADDRESSES sheet: signals pinned to the wiring.
    pub pins: Vec<pins::PinRow>,
    /// The SETTINGS rows that name outputs or inputs, as written;
    /// `program.halt`, `program.permissive` and `program.interlocks` once
    /// checked against the table.
    pub named: halt::NamedRows,
    /// The home order in force as written (`lift, clamp`);
    /// `program.modes.home_order` once its names are read with the table.
    pub home_order: Option<Vec<Vec<String>>>,
    /// Where the settings in force that a SETTINGS sheet gave were read, by
    /// label (the others came from the command line or are defaults).
    pub cells: BTreeMap<&'static str, crate::diag::Location>,
    /// The command line that asked for this run, as every output records
    /// it (`convert paper.xlsx --target siemens`: the command, its inputs'
    /// file names and the options that change the output; see
    /// the `provenance` module). `None` for a library call.
    pub invocation: Option<String>,
}

/// The command-line option that gives the SETTINGS row `label`: `scan
/// time` is `--scan`, the others their label with dashes (`--home-order`).
pub fn option_for(label: &str) -> String {
    match label {
        "scan time" => "--scan".to_string(),
        other => format!("--{}", other.replace(' ', "-")),
    }
}

impl Settings {
    /// Whether a Festo FST file is written (`fst`, `fst-alloc`): only then
    /// do the 9 characters FST keeps of a name have to tell it apart.
    pub fn writes_fst(&self) -> bool {
        [OutputKind::Fst, OutputKind::FstAllocation]
            .iter()
            .any(|k| self.formats.contains(k))
    }

    /// Where the setting of `label` in force comes from, for a message:
    /// its SETTINGS cell (`SETTINGS!B5`), or the command line's option.
    pub fn origin(&self, label: &str) -> String {
        match self.cells.get(label) {
            Some(at) => halt::place(at),
            None if self.given.gives(label) => option_for(label),
            None => "the default".to_string(),
        }
    }

    /// Takes `given` as the command line's word (over what it said before)
    /// and puts it in force.
    pub fn give(&mut self, given: Given) {
        self.given = given.or(&self.given);
        let layer = self.given.clone();
        self.apply(&layer);
    }

    /// These settings with a SETTINGS sheet filling in what the command line
    /// did not give; per actuator, the command line wins.
    pub fn with_sheet(&self, sheet: &Given) -> Settings {
        let mut merged = self.clone();
        merged.apply(&self.given.or(sheet));
        merged
    }

    /// Puts every value `layer` gives in force; the others stay as they are.
    fn apply(&mut self, layer: &Given) {
        if let Some(target) = layer.target {
            self.target = target;
        }
        if let Some(board) = layer.board {
            self.board = Some(board);
        }
        self.named
            .extend(layer.named.iter().map(|(row, list)| (*row, list.clone())));
        for (label, at) in &layer.cells {
            self.cells.insert(label, at.clone());
        }
        // What the command line gives, no cell of the sheet says.
        let given = self.given.clone();
        self.cells.retain(|label, _| !given.gives(label));
        if let Some(mnemonic) = layer.mnemonic {
            self.mnemonic = mnemonic;
        }
        if let Some(scan) = layer.scan_ms {
            self.simulation.scan_ms = scan;
        }
        if let Some(safety) = layer.safety {
            self.program.safety = safety;
        }
        let modes = &mut self.program.modes;
        if let Some(given) = &layer.modes {
            let order = modes.home_order.take();
            *modes = given.clone();
            modes.home_order = order;
        }
        if let Some(order) = &layer.home_order {
            self.home_order = Some(order.clone());
        }
        if let Some(times) = &layer.supervision {
            self.program.supervision = times.clone();
        }
        let simulation = &mut self.simulation;
        simulation
            .machine
            .strokes
            .per_actuator
            .extend(&layer.strokes);
        simulation.machine.valves.per_actuator.extend(&layer.valves);
        simulation.machine.loads.extend(&layer.loads);
        self.naming
            .actuators
            .extend(layer.names.iter().map(|(n, name)| (*n, name.clone())));
        if let Some(scheme) = layer.designations {
            self.naming.scheme = scheme;
        }
    }

    /// Defaults: Festo addresses, middle stops, no safety checks, every format
    /// but the SFC chart (asked for by name).
    pub fn new() -> Self {
        Settings {
            formats: OutputKind::defaults(),
            ..Settings::default()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stroke(ms: u32) -> Stroke {
        Stroke {
            extend_ms: ms,
            retract_ms: ms,
        }
    }

    #[test]
    fn the_command_line_wins_and_the_sheet_fills_in_per_actuator() {
        let mut settings = Settings::new();
        settings.give(Given {
            target: Some(Target::Iec),
            strokes: [(1, stroke(500))].into(),
            ..Given::default()
        });
        let sheet = Given {
            target: Some(Target::Siemens),
            mnemonic: Some(Mnemonic::De),
            scan_ms: Some(20),
            strokes: [(1, stroke(900)), (2, stroke(700))].into(),
            ..Given::default()
        };
        let merged = settings.with_sheet(&sheet);
        assert_eq!(merged.target, Target::Iec);
        assert_eq!(merged.mnemonic, Mnemonic::De);
        assert_eq!(merged.simulation.scan_ms, 20);
        assert_eq!(merged.simulation.machine.strokes.of(1), stroke(500));
        assert_eq!(merged.simulation.machine.strokes.of(2), stroke(700));
        // Without a sheet value the default stays.
        assert_eq!(
            settings.with_sheet(&Given::default()).simulation.scan_ms,
            10
        );
    }

    #[test]
    fn sheet_modes_keep_the_command_lines_home_order() {
        let mut settings = Settings::new();
        settings.give(Given {
            home_order: Some(vec![vec!["C2".into()], vec!["C1".into()]]),
            ..Given::default()
        });
        let sheet = Given {
            modes: Some("reset".parse().unwrap()),
            home_order: Some(vec![vec!["C1".into(), "C2".into()]]),
            ..Given::default()
        };
        let merged = settings.with_sheet(&sheet);
        assert!(merged.program.modes.reset);
        assert_eq!(
            merged.home_order,
            Some(vec![vec!["C2".into()], vec!["C1".into()]])
        );
    }

    #[test]
    fn one_parser_per_value_in_any_case() {
        assert_eq!("Siemens".parse::<Target>(), Ok(Target::Siemens));
        assert_eq!(" DE ".parse::<Mnemonic>(), Ok(Mnemonic::De));
        assert!("s7".parse::<Target>().is_err());
        assert_eq!("5/2 mono".parse::<ActuatorKind>(), Ok(ActuatorKind::Mono52));
        assert_eq!(crate::stroke::parse_scan("0,02s"), Ok(20));
        assert!(crate::stroke::parse_scan("2s").is_err());
    }
}
