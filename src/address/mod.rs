//! Addresses: which input, output, memory bit and timer each signal of a
//! step program gets, in each PLC dialect's notation (DESIGN §3). The
//! program says which signals exist; this stage only lays them out.

mod board;

use crate::program::{Area, Signal, StepProgram};
pub use board::{BOARDS, Board};

/// The PLC dialect whose address notation is used.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Target {
    /// Festo FST: 16-bit words, `I0.0` / `O0.0`, the paper's layout.
    #[default]
    Festo,
    /// IEC 61131-3 direct addresses `%IX0.0` / `%QX0.0`, 8 bits per byte (CODESYS, OpenPLC).
    Iec,
    /// Siemens `I0.0` / `Q0.0` (German `E` / `A`), 8 bits per byte.
    Siemens,
}

impl Target {
    pub fn name(self) -> &'static str {
        match self {
            Target::Festo => "festo",
            Target::Iec => "iec",
            Target::Siemens => "siemens",
        }
    }

    fn bits_per_unit(self) -> u32 {
        match self {
            Target::Festo => 16,
            Target::Iec | Target::Siemens => 8,
        }
    }
}

/// English or German operand letters (Siemens `I`/`Q` or `E`/`A`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Mnemonic {
    #[default]
    En,
    De,
}

/// A bit address: unit (word or byte, per target) and bit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Address {
    pub area: Area,
    pub target: Target,
    pub unit: u32,
    pub bit: u32,
}

impl Address {
    fn from_index(area: Area, target: Target, index: u32) -> Self {
        let width = target.bits_per_unit();
        Address {
            area,
            target,
            unit: index / width,
            bit: index % width,
        }
    }

    /// An input or output bit written in `target`'s notation: `I0.3` /
    /// `O1.2` (Festo, 16 bits a word), `%IX0.3` / `%QX1.2` (IEC), `I0.3` /
    /// `Q1.2` or `E0.3` / `A1.2` (Siemens, either set of letters).
    pub fn parse(text: &str, target: Target) -> Result<Address, String> {
        let t = text.trim().to_ascii_uppercase();
        let letters: &[(&str, Area)] = match target {
            Target::Festo => &[("I", Area::Input), ("O", Area::Output)],
            Target::Iec => &[("%IX", Area::Input), ("%QX", Area::Output)],
            Target::Siemens => &[
                ("I", Area::Input),
                ("E", Area::Input),
                ("Q", Area::Output),
                ("A", Area::Output),
            ],
        };
        let expected = || {
            let examples = match target {
                Target::Festo => "I0.0 … I0.15 or O0.0 …",
                Target::Iec => "%IX0.0 … %IX0.7 or %QX0.0 …",
                Target::Siemens => "I0.0 … I0.7 (E0.0) or Q0.0 … (A0.0)",
            };
            format!(
                "\"{}\" is not an input or output address of the {} target (expected {examples})",
                text.trim(),
                target.name()
            )
        };
        let (area, rest) = letters
            .iter()
            .find_map(|(letter, area)| t.strip_prefix(letter).map(|rest| (*area, rest)))
            .ok_or_else(expected)?;
        let (unit, bit) = rest.split_once('.').ok_or_else(expected)?;
        let number = |digits: &str| {
            (!digits.is_empty() && digits.len() <= 5 && digits.bytes().all(|b| b.is_ascii_digit()))
                .then(|| digits.parse::<u32>().ok())
                .flatten()
        };
        let (Some(unit), Some(bit)) = (number(unit), number(bit)) else {
            return Err(expected());
        };
        let width = target.bits_per_unit();
        if bit >= width {
            return Err(format!(
                "\"{}\": bit {bit} is out of range, a {} has bits 0 to {}",
                text.trim(),
                if width == 16 { "word" } else { "byte" },
                width - 1
            ));
        }
        if unit > MAX_PINNED_UNIT {
            return Err(format!(
                "\"{}\": {} {unit} is out of range (0 to {MAX_PINNED_UNIT})",
                text.trim(),
                if width == 16 { "word" } else { "byte" }
            ));
        }
        Ok(Address {
            area,
            target,
            unit,
            bit,
        })
    }

    /// The bit's place among its area's bits, counting from 0.
    pub fn index(self) -> u32 {
        self.unit * self.target.bits_per_unit() + self.bit
    }

    /// The address in the target's notation (`I0.1`, `%QX0.1`, `E0.1`).
    pub fn display(self, mnemonic: Mnemonic) -> String {
        let letter = match (self.target, self.area, mnemonic) {
            (Target::Festo, Area::Input, _) => "I",
            (Target::Festo, Area::Output, _) => "O",
            (Target::Festo, Area::Memory, _) => "F",
            (Target::Iec, Area::Input, _) => "%IX",
            (Target::Iec, Area::Output, _) => "%QX",
            (Target::Iec, Area::Memory, _) => "%MX",
            (Target::Siemens, Area::Input, Mnemonic::En) => "I",
            (Target::Siemens, Area::Input, Mnemonic::De) => "E",
            (Target::Siemens, Area::Output, Mnemonic::En) => "Q",
            (Target::Siemens, Area::Output, Mnemonic::De) => "A",
            (Target::Siemens, Area::Memory, _) => "M",
            (Target::Iec, Area::Timer, _) => "%MW",
            (Target::Festo | Target::Siemens, Area::Timer, _) => "T",
        };
        if self.area == Area::Timer {
            return format!("{letter}{}", self.unit);
        }
        format!("{letter}{}.{}", self.unit, self.bit)
    }

    /// The physical byte and bit (a 16-bit Festo word is two bytes, low
    /// byte first), as Siemens and IEC addresses count them.
    pub fn byte_bit(self) -> (u32, u32) {
        match self.target {
            Target::Festo => (self.unit * 2 + self.bit / 8, self.bit % 8),
            Target::Iec | Target::Siemens => (self.unit, self.bit),
        }
    }

    /// The same physical bit as an IEC direct address (`%IX1.2`), for the
    /// located variables of Structured Text. A 16-bit Festo word is two bytes,
    /// low byte first: `I0.10` is `%IX1.2`.
    pub fn iec(self) -> String {
        let (byte, bit) = self.byte_bit();
        let prefix = match self.area {
            Area::Input => "%IX",
            Area::Output => "%QX",
            Area::Memory | Area::Timer => "%MX",
        };
        format!("{prefix}{byte}.{bit}")
    }
}

/// The highest word or byte a pinned address may name: far beyond any
/// machine's I/O, and below where Festo's and Siemens' input images end.
pub const MAX_PINNED_UNIT: u32 = 255;

/// The width of the word an HMI reads the criteria analysis as: a Festo
/// output word, an S7 output word (two bytes), two OpenPLC coil bytes.
const MISS_WORD_BITS: u32 = 16;

/// Lays out `default` (in address order) around the pinned signals: a
/// pinned signal keeps its address, the others keep their order and take
/// the free bits from where the layout starts.
fn around_pins(default: Vec<Assigned>, pins: &[Assigned]) -> Vec<Assigned> {
    let Some(first) = default.first() else {
        return default;
    };
    let (area, target) = (first.address.area, first.address.target);
    // Every pin names a signal of the program (`convert::pins` checks), so
    // the area tells which of them are laid out here.
    let pinned: Vec<Assigned> = pins
        .iter()
        .filter(|p| p.address.area == area)
        .copied()
        .collect();
    if pinned.is_empty() {
        return default;
    }
    let taken: std::collections::BTreeSet<u32> = pinned.iter().map(|p| p.address.index()).collect();
    let mut next = first.address.index();
    let mut laid = pinned.clone();
    for a in default
        .iter()
        .filter(|d| !pinned.iter().any(|p| p.signal == d.signal))
    {
        while taken.contains(&next) {
            next += 1;
        }
        laid.push(Assigned {
            signal: a.signal,
            address: Address::from_index(area, target, next),
        });
        next += 1;
    }
    laid.sort_by_key(|a| a.address);
    laid
}

/// One signal with its address.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Assigned {
    pub signal: Signal,
    pub address: Address,
}

/// The complete I/O and memory allocation of one table for one target.
#[derive(Debug, Clone, PartialEq)]
pub struct Allocation {
    pub target: Target,
    pub mnemonic: Mnemonic,
    /// In address order: START, then each actuator's sensors.
    pub inputs: Vec<Assigned>,
    /// In address order.
    pub outputs: Vec<Assigned>,
    /// Internal memory bits of the program (middle-stop requests, safety).
    pub memories: Vec<Assigned>,
    /// Timers (the step watchdog, the dwells).
    pub timers: Vec<Assigned>,
}

/// Consecutive bits of one area, in the given order.
fn lay_out(area: Area, target: Target, signals: impl Iterator<Item = Signal>) -> Vec<Assigned> {
    signals
        .zip(0..)
        .map(|(signal, index)| Assigned {
            signal,
            address: Address::from_index(area, target, index),
        })
        .collect()
}

impl Allocation {
    /// Lays out every signal `program` uses.
    ///
    /// Inputs: START first, then for each actuator in ascending number its
    /// sensors 0…pmax, packed densely, then machine inputs and the mode
    /// buttons. Outputs on Festo follow the paper: all `+` coils from `O0.1`
    /// on, all `-` coils from bit 1 of the next free word. On IEC and Siemens
    /// targets each valve's two coils sit side by side (`+` then `-`), as they
    /// do on a valve terminal. A single-solenoid valve's one coil takes the
    /// place its `+` coil would have; its `-` place stays free, so no other
    /// address moves when a valve type changes. Machine outputs and alarms
    /// follow the coils.
    pub fn new(program: &StepProgram, target: Target, mnemonic: Mnemonic) -> Self {
        Self::pinned(program, target, mnemonic, &[])
    }

    /// Like [`Allocation::new`], with `pins` (inputs and outputs at the
    /// addresses the wiring gives them, in `target`'s notation) kept where
    /// they are and every other signal of their area laid out around them.
    /// The caller has checked that no two pins share an address.
    pub fn pinned(
        program: &StepProgram,
        target: Target,
        mnemonic: Mnemonic,
        pins: &[Assigned],
    ) -> Self {
        let signals = &program.signals;
        let inputs = lay_out(Area::Input, target, signals.inputs.iter().copied());

        let count = signals.valves.len() as u32;
        let width = target.bits_per_unit();
        let mut outputs = Vec::with_capacity(2 * signals.valves.len() + signals.outputs.len());
        for (rank, valve) in signals.valves.iter().enumerate() {
            let rank = rank as u32;
            let (plus, minus) = match target {
                Target::Festo => {
                    let minus_base = (count + 1).div_ceil(width) * width;
                    (rank + 1, minus_base + rank + 1)
                }
                Target::Iec | Target::Siemens => (2 * rank, 2 * rank + 1),
            };
            let place = |signal, index| Assigned {
                signal,
                address: Address::from_index(Area::Output, target, index),
            };
            outputs.push(place(valve.extend(), plus));
            if let Some(retract) = valve.retract() {
                outputs.push(place(retract, minus));
            }
        }
        outputs.sort_by_key(|a| a.address);
        let next_output = outputs
            .last()
            .map(|a| a.address.unit * width + a.address.bit + 1)
            .unwrap_or(0);
        let mut index = next_output;
        for &signal in &signals.outputs {
            // The criteria analysis starts a word of its own, so that an
            // HMI reads it as whole words (bit k of the first = miss(k+1)).
            if signal == Signal::Missing(1) {
                index = index.div_ceil(MISS_WORD_BITS) * MISS_WORD_BITS;
            }
            outputs.push(Assigned {
                signal,
                address: Address::from_index(Area::Output, target, index),
            });
            index += 1;
        }

        let memories = lay_out(Area::Memory, target, signals.memories.iter().copied());
        // T0 is the watchdog's; dwell n gets timer n, run-on n the n-th
        // timer after the dwells'.
        let dwells = program
            .timers
            .iter()
            .filter(|t| matches!(t, Signal::Dwell(_)))
            .count() as u32;
        let timers = program
            .timers
            .iter()
            .map(|&signal| Assigned {
                signal,
                address: Address {
                    area: Area::Timer,
                    target,
                    unit: match signal {
                        Signal::Dwell(n) => n as u32,
                        Signal::RunOn(n) => dwells + n as u32,
                        _ => 0,
                    },
                    bit: 0,
                },
            })
            .collect();

        Allocation {
            target,
            mnemonic,
            inputs: around_pins(inputs, pins),
            outputs: around_pins(outputs, pins),
            memories,
            timers,
        }
    }

    /// The layout on an OpenPLC board: IEC addresses, each area packed from
    /// its first bit (a board's pins are few, and unlike a valve terminal's
    /// places none is kept free for a coil a valve does not have), around
    /// `pins`. Whether it fits the board is the caller's to check.
    pub fn on_board(program: &StepProgram, mnemonic: Mnemonic, pins: &[Assigned]) -> Self {
        let mut allocation = Self::new(program, Target::Iec, mnemonic);
        let packed = |area, laid: &[Assigned]| {
            around_pins(
                lay_out(area, Target::Iec, laid.iter().map(|a| a.signal)),
                pins,
            )
        };
        allocation.inputs = packed(Area::Input, &allocation.inputs);
        allocation.outputs = packed(Area::Output, &allocation.outputs);
        allocation
    }

    /// The address of a signal.
    pub fn address_of(&self, signal: Signal) -> Option<Address> {
        self.inputs
            .iter()
            .chain(&self.outputs)
            .chain(&self.memories)
            .chain(&self.timers)
            .find(|a| a.signal == signal)
            .map(|a| a.address)
    }

    /// The address of a signal in the target's notation, or `?` if it has none
    /// (which the program builder never lets happen).
    pub fn display(&self, signal: Signal) -> String {
        self.address_of(signal)
            .map(|a| a.display(self.mnemonic))
            .unwrap_or_else(|| "?".to_string())
    }
}

impl Target {
    /// Every target, as `--target` and the SETTINGS sheet name them.
    pub const ALL: [Target; 3] = [Target::Festo, Target::Iec, Target::Siemens];
    /// Every name a target goes by: `openplc` is OpenPLC's name for `iec`.
    pub const NAMES: [&str; 4] = ["festo", "iec", "openplc", "siemens"];
}

impl std::str::FromStr for Target {
    type Err = String;

    /// `festo`, `iec` (or `openplc`) or `siemens`, in any case.
    fn from_str(text: &str) -> Result<Self, String> {
        let lower = text.trim().to_ascii_lowercase();
        if lower == "openplc" {
            return Ok(Target::Iec);
        }
        Target::ALL
            .into_iter()
            .find(|t| t.name() == lower)
            .ok_or_else(|| {
                format!(
                    "\"{text}\" is not a target (expected {})",
                    crate::diag::or_list(&Target::NAMES)
                )
            })
    }
}

impl Mnemonic {
    pub const ALL: [Mnemonic; 2] = [Mnemonic::En, Mnemonic::De];

    /// Every mnemonic's name, as `--mnemonic` and the SETTINGS sheet write it.
    pub fn names() -> Vec<&'static str> {
        Mnemonic::ALL.map(Mnemonic::name).to_vec()
    }

    pub fn name(self) -> &'static str {
        match self {
            Mnemonic::En => "en",
            Mnemonic::De => "de",
        }
    }
}

impl std::str::FromStr for Mnemonic {
    type Err = String;

    /// `en` (I/Q) or `de` (E/A), in any case.
    fn from_str(text: &str) -> Result<Self, String> {
        let lower = text.trim().to_ascii_lowercase();
        Mnemonic::ALL
            .into_iter()
            .find(|m| m.name() == lower)
            .ok_or_else(|| {
                format!(
                    "\"{text}\" is not a mnemonic (expected {})",
                    crate::diag::or_list(&Mnemonic::names())
                )
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn allocate(rows: &[&[&str]], target: Target) -> Allocation {
        let table = crate::table::from_rows("t.csv", rows).expect("valid table");
        let program = crate::program::build(
            &table,
            &crate::program::ProgramOptions::default(),
            &crate::actuator::Valves::default(),
            &crate::stroke::Strokes::default(),
        );
        Allocation::new(&program, target, Mnemonic::En)
    }

    #[test]
    fn festo_outputs_follow_the_paper() {
        let alloc = allocate(&[&["C1+1", "C2+1"], &["C1-0", "C2-0"]], Target::Festo);
        let outs: Vec<String> = alloc
            .outputs
            .iter()
            .map(|a| format!("{} {}", a.address.display(Mnemonic::En), a.signal.symbol()))
            .collect();
        assert_eq!(outs, ["O0.1 y1+", "O0.2 y2+", "O1.1 y1-", "O1.2 y2-"]);
    }

    #[test]
    fn forty_actuators_get_unique_valid_addresses() {
        let plus: Vec<String> = (1..=40).map(|i| format!("C{i}+1")).collect();
        let minus: Vec<String> = (1..=40).map(|i| format!("C{i}-0")).collect();
        let plus_ref: Vec<&str> = plus.iter().map(String::as_str).collect();
        let minus_ref: Vec<&str> = minus.iter().map(String::as_str).collect();
        for target in [Target::Festo, Target::Iec, Target::Siemens] {
            let alloc = allocate(&[&plus_ref, &minus_ref], target);
            let mut seen = std::collections::BTreeSet::new();
            for a in alloc.inputs.iter().chain(&alloc.outputs) {
                assert!(a.address.bit < target.bits_per_unit());
                assert!(
                    seen.insert(a.address),
                    "{}: duplicate {:?}",
                    target.name(),
                    a.address
                );
            }
            assert_eq!(alloc.inputs.len(), 81);
            assert_eq!(alloc.outputs.len(), 80);
        }
    }

    /// The paper's layout: `+` coils from bit 1 of word 0, `-` coils from
    /// bit 1 of the first word the `+` coils leave free.
    #[test]
    fn festo_minus_coils_start_in_the_next_free_word() {
        let first_minus = |count: usize| {
            let plus: Vec<String> = (1..=count).map(|i| format!("C{i}+1")).collect();
            let minus: Vec<String> = (1..=count).map(|i| format!("C{i}-0")).collect();
            let plus: Vec<&str> = plus.iter().map(String::as_str).collect();
            let minus: Vec<&str> = minus.iter().map(String::as_str).collect();
            let alloc = allocate(&[&plus, &minus], Target::Festo);
            alloc
                .outputs
                .iter()
                .find(|a| a.signal.symbol() == "y1-")
                .map(|a| a.address.display(Mnemonic::En))
        };
        assert_eq!(first_minus(1).as_deref(), Some("O1.1"));
        assert_eq!(first_minus(15).as_deref(), Some("O1.1"));
        // Sixteen + coils fill O0.1 to O1.0: the - coils begin in word 2.
        assert_eq!(first_minus(16).as_deref(), Some("O2.1"));
    }

    #[test]
    fn targets_parse_from_their_names() {
        for target in Target::ALL {
            assert_eq!(target.name().parse::<Target>(), Ok(target));
        }
        for mnemonic in Mnemonic::ALL {
            assert_eq!(
                mnemonic.name().to_uppercase().parse::<Mnemonic>(),
                Ok(mnemonic)
            );
        }
    }

    /// A pinned address is digits, a dot and digits in the target's
    /// spelling; a sign, a letter or a sixth digit is not a number, and a
    /// byte or word past 255 is out of range.
    #[test]
    fn pinned_addresses_are_digits_within_range() {
        let parse = |text: &str| Address::parse(text, Target::Siemens);
        assert_eq!(parse("Q255.7").map(|a| (a.unit, a.bit)), Ok((255, 7)));
        assert_eq!(
            parse("E1.2").map(|a| (a.area, a.unit)),
            Ok((Area::Input, 1))
        );
        let out_of_range = parse("Q256.0").unwrap_err();
        assert!(
            out_of_range.contains("256 is out of range (0 to 255)"),
            "{out_of_range}"
        );
        for bad in [
            "I+1.0",
            "I1.+0",
            "I.0",
            "I0.",
            "I1a.0",
            "I123456.0",
            "I000001.0",
        ] {
            let message = parse(bad).unwrap_err();
            assert!(
                message.contains("is not an input or output address"),
                "{bad}: {message}"
            );
        }
        assert!(parse("I0.8").unwrap_err().contains("bit 8 is out of range"));
    }

    /// Pins on the first bits push the others along, past every taken bit.
    #[test]
    fn unpinned_signals_step_over_every_pinned_bit() {
        let table = crate::table::from_rows("t.csv", &[&["C1+1"], &["C1-0"]]).expect("valid");
        let program = crate::program::build(
            &table,
            &crate::program::ProgramOptions::default(),
            &crate::actuator::Valves::default(),
            &crate::stroke::Strokes::default(),
        );
        let sensor = |position| Signal::Sensor {
            actuator: 1,
            position,
        };
        let pin = |signal, text| Assigned {
            signal,
            address: Address::parse(text, Target::Siemens).expect("an address"),
        };
        let pins = [pin(sensor(1), "I0.0"), pin(sensor(0), "I0.1")];
        let allocation = Allocation::pinned(&program, Target::Siemens, Mnemonic::En, &pins);
        let inputs: Vec<String> = allocation
            .inputs
            .iter()
            .map(|a| format!("{} {}", a.signal.symbol(), a.address.display(Mnemonic::En)))
            .collect();
        assert_eq!(inputs, ["x11 I0.0", "x10 I0.1", "START I0.2"]);
    }

    #[test]
    fn festo_words_map_to_iec_bytes() {
        let addr = Address {
            area: Area::Input,
            target: Target::Festo,
            unit: 0,
            bit: 10,
        };
        assert_eq!(addr.display(Mnemonic::En), "I0.10");
        assert_eq!(addr.iec(), "%IX1.2");
        let q = Address {
            area: Area::Output,
            target: Target::Siemens,
            unit: 3,
            bit: 7,
        };
        assert_eq!(q.display(Mnemonic::De), "A3.7");
        assert_eq!(q.iec(), "%QX3.7");
    }
}
