//! How signals are designated: the published method's `x10` / `y1+`, the
//! ISO 1219-2 designations of a circuit diagram (`1A1` cylinder, `1B1` /
//! `1B2` sensors, `1M1` / `1M2` solenoids), or the engineer's own names
//! (`clamp_home`, `clamp_out`) from the SETTINGS actuator table.

use std::collections::BTreeMap;

use crate::cell::Sign;
use crate::diag::Location;
use crate::program::Signal;
use crate::table::StepTable;

/// The designation scheme (`--designations`, SETTINGS `designations`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
pub enum Scheme {
    /// The published method's: `x10`, `x11`, `y1+`, `y1-`.
    #[default]
    Paper,
    /// ISO 1219-2: cylinder `1A1`, sensors `1B1` (home), `1B2` (end), then
    /// the middle positions in order; solenoids `1M1` (+) and `1M2` (-).
    /// They lead the comments and fill the lists; identifiers, which may
    /// not begin with a digit, stay the paper's.
    Iso,
    /// The engineer's: an actuator named `clamp` in the SETTINGS actuator
    /// table has `clamp_home`, `clamp_end`, `clamp_pos1` (middle position
    /// 1), `clamp_out` and `clamp_in` as identifiers and designations.
    Names,
}

impl Scheme {
    pub const ALL: [Scheme; 3] = [Scheme::Paper, Scheme::Iso, Scheme::Names];

    pub fn name(self) -> &'static str {
        match self {
            Scheme::Paper => "paper",
            Scheme::Iso => "iso",
            Scheme::Names => "names",
        }
    }

    /// Every value, for messages and `--help`.
    pub fn list() -> String {
        Scheme::ALL.map(Scheme::name).join(", ")
    }
}

impl std::str::FromStr for Scheme {
    type Err = String;

    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let lower = text.trim().to_ascii_lowercase();
        Scheme::ALL
            .into_iter()
            .find(|s| s.name() == lower)
            .ok_or_else(|| format!("expected one of {}", Scheme::list()))
    }
}

/// An actuator's name as the SETTINGS actuator table gives it (`C1
/// (clamp)`), with its cell.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ActuatorName {
    /// The comment as written (`clamp`, `gripper arm`).
    pub text: String,
    pub at: Location,
}

impl ActuatorName {
    /// The name as an identifier stem: lower case, every run of other
    /// characters one `_` (`Gripper arm` → `gripper_arm`); `None` when
    /// that is empty, begins with a digit or holds a letter outside ASCII.
    pub fn stem(&self) -> Option<String> {
        stem(&self.text)
    }
}

/// See [`ActuatorName::stem`].
pub fn stem(text: &str) -> Option<String> {
    let mut out = String::new();
    for c in text.trim().chars() {
        if c.is_ascii_alphanumeric() {
            out.push(c.to_ascii_lowercase());
        } else if c.is_alphanumeric() {
            return None;
        } else if !out.ends_with('_') {
            out.push('_');
        }
    }
    let out = out.trim_matches('_').to_string();
    out.chars()
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic())
        .then_some(out)
}

/// The naming settings of one conversion.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Naming {
    pub scheme: Scheme,
    /// The engineer's names of actuators, by number.
    pub actuators: BTreeMap<u32, ActuatorName>,
}

impl Naming {
    /// The identifier stem of actuator `n` under the names scheme.
    fn own_stem(&self, n: u32) -> Option<String> {
        match self.scheme {
            Scheme::Names => self.actuators.get(&n).and_then(ActuatorName::stem),
            _ => None,
        }
    }

    /// The actuator the engineer named `name` (as written, in any case, or
    /// as its identifier stem: `Gripper Arm`, `gripper_arm`).
    pub fn actuator_named(&self, name: &str) -> Option<u32> {
        // In any case and composed, as the duplicate-name check (E025)
        // compares them: `ölpumpe` is `Ölpumpe`.
        let lower = crate::cell::folded(name);
        self.actuators
            .iter()
            .find(|(_, a)| {
                crate::cell::folded(&a.text) == lower || a.stem().as_deref() == Some(&lower)
            })
            .map(|(n, _)| *n)
    }

    /// The actuator `text` names where a setting names one (`--home-order`,
    /// its SETTINGS row, `--valve`, `--stroke`, `--load`): its paper number
    /// (`C1`), its ISO designation (`1A1`) or the engineer's name (`clamp`).
    /// Also as steptable prints an actuator, `C1 (clamp)` or `1A1(clamp)`:
    /// then the name in brackets must be that actuator's too.
    pub fn actuator_called(&self, text: &str) -> Option<u32> {
        // A name of its own first (`clamp (left)`): one that reads as an
        // actuator printed so (`1A1 (x)`) is refused at its cell (E015).
        if let Some(n) = self.actuator_plain(text) {
            return Some(n);
        }
        let (actuator, name) = crate::program::bracketed(text.trim());
        let n = self.actuator_plain(actuator)?;
        let Some(name) = name else {
            return Some(n);
        };
        let as_name = self
            .actuator_plain(name)
            .or_else(|| self.actuator_plain(&name.replace(' ', "_")));
        (as_name == Some(n)).then_some(n)
    }

    /// The actuator `text` names with no name in brackets.
    fn actuator_plain(&self, text: &str) -> Option<u32> {
        let text = text.trim();
        crate::cell::parse_actuator(text)
            .or_else(|| crate::cell::iso_actuator(text))
            .or_else(|| self.actuator_named(text))
    }

    /// The name among those of `actuators` (number, ISO designation, the
    /// engineer's name) closest to `text`, for a "did you mean": within one
    /// letter in four.
    pub fn actuator_like(&self, text: &str, actuators: &[u32]) -> Option<String> {
        let lower = text.trim().to_lowercase();
        actuators
            .iter()
            .flat_map(|&n| {
                let mut names = vec![format!("C{n}"), format!("{n}A1")];
                // A name beyond A-Z has no stem: it is offered as written.
                names.extend(
                    self.actuators
                        .get(&n)
                        .map(|a| a.stem().unwrap_or_else(|| a.text.clone())),
                );
                names
            })
            .map(|name| {
                (
                    crate::cell::edit_distance(&lower, &name.to_lowercase()),
                    name,
                )
            })
            .filter(|(distance, _)| *distance > 0 && *distance * 4 <= lower.chars().count().max(4))
            .min()
            .map(|(_, name)| name)
    }

    /// The identifier of `signal`.
    pub fn ident(&self, signal: Signal, table: &StepTable) -> String {
        named(signal, table, |n| self.own_stem(n)).unwrap_or_else(|| paper_ident(signal))
    }

    /// The designation of `signal`.
    pub fn designation(&self, signal: Signal, table: &StepTable) -> String {
        if self.scheme == Scheme::Iso
            && let Some(iso) = iso(signal, table)
        {
            return iso;
        }
        named(signal, table, |n| self.own_stem(n)).unwrap_or_else(|| signal.symbol())
    }

    /// Actuator `n` in an action's comment and a diagram: `C1` (`1A1`
    /// under ISO) and the engineer's name, if it has one.
    pub fn actuator_parts(&self, n: u32) -> (String, Option<String>) {
        let head = match self.scheme {
            Scheme::Iso => format!("{n}A1"),
            _ => format!("C{n}"),
        };
        (head, self.actuators.get(&n).map(|name| name.text.clone()))
    }

    /// Actuator `n` after `cylinder` in a comment: `1`, `1 (clamp)`, `1A1 (clamp)`.
    pub fn actuator_words(&self, n: u32) -> String {
        let head = match self.scheme {
            Scheme::Iso => format!("{n}A1"),
            _ => n.to_string(),
        };
        match self.actuators.get(&n) {
            Some(name) => format!("{head} ({})", name.text),
            None => head,
        }
    }

    /// Every name `signal` answers to where a setting names a signal: its
    /// paper symbol and identifier, and the engineer's names whatever the
    /// scheme (`clamp_out`).
    pub fn aliases(&self, signal: Signal, table: &StepTable) -> Vec<String> {
        self.aliases_by(signal, &|a| table.actuator(a).map_or(1, |x| x.max_position))
    }

    /// The engineer's name of `signal` whatever the scheme (`clamp_out`),
    /// if its actuator has a name.
    pub fn own_alias(&self, signal: Signal, table: &StepTable) -> Option<String> {
        let own = |n: u32| self.actuators.get(&n).and_then(ActuatorName::stem);
        named(signal, table, own)
    }

    /// `signal` in a message about a setting that names it: its paper
    /// symbol, and the engineer's name beside it where its actuator has
    /// one (`x11 (clamp_end)`), whatever the scheme.
    pub fn called_by(&self, signal: Signal, pmax: &dyn Fn(u32) -> u32) -> String {
        let own = |n: u32| self.actuators.get(&n).and_then(ActuatorName::stem);
        match named_by(signal, pmax, own) {
            Some(name) => format!("{} ({name})", signal.symbol()),
            None => signal.symbol(),
        }
    }

    /// [`Naming::aliases`], each actuator's end position given by `pmax`.
    pub fn aliases_by(&self, signal: Signal, pmax: &dyn Fn(u32) -> u32) -> Vec<String> {
        let mut names = vec![signal.symbol(), paper_ident(signal)];
        let own = |n: u32| self.actuators.get(&n).and_then(ActuatorName::stem);
        if let Some(name) = named_by(signal, pmax, own) {
            names.push(name);
        }
        if let Some(iso) = iso_by(signal, pmax) {
            names.push(iso);
        }
        names
    }
}

/// The engineer's name of an actuator's sensor or coil, when `stem` gives
/// its actuator one.
fn named(
    signal: Signal,
    table: &StepTable,
    stem: impl Fn(u32) -> Option<String>,
) -> Option<String> {
    named_by(
        signal,
        &|a| table.actuator(a).map_or(1, |x| x.max_position),
        stem,
    )
}

fn named_by(
    signal: Signal,
    pmax_of: &dyn Fn(u32) -> u32,
    stem: impl Fn(u32) -> Option<String>,
) -> Option<String> {
    match signal {
        Signal::Sensor { actuator, position } => {
            let name = stem(actuator)?;
            let pmax = pmax_of(actuator);
            Some(if position == 0 {
                format!("{name}_home")
            } else if position == pmax {
                format!("{name}_end")
            } else {
                format!("{name}_pos{position}")
            })
        }
        Signal::Coil { actuator, sign } => {
            let name = stem(actuator)?;
            Some(match sign {
                Sign::Plus => format!("{name}_out"),
                Sign::Minus => format!("{name}_in"),
            })
        }
        Signal::SingleCoil { actuator } => Some(format!("{}_out", stem(actuator)?)),
        Signal::Jog { actuator, sign } => {
            let name = stem(actuator)?;
            Some(match sign {
                Sign::Plus => format!("{name}_jog_out"),
                Sign::Minus => format!("{name}_jog_in"),
            })
        }
        _ => None,
    }
}

/// The ISO 1219-2 designation of an actuator's sensor or solenoid: sensors
/// `nB1` (home), `nB2` (end), then the middle positions in order from
/// `nB3`; solenoids `nM1` (+, the only one of a single-solenoid valve) and
/// `nM2` (-).
fn iso(signal: Signal, table: &StepTable) -> Option<String> {
    iso_by(signal, &|a| table.actuator(a).map_or(1, |x| x.max_position))
}

fn iso_by(signal: Signal, pmax_of: &dyn Fn(u32) -> u32) -> Option<String> {
    match signal {
        Signal::Sensor { actuator, position } => {
            let pmax = pmax_of(actuator);
            let number = if position == 0 {
                1
            } else if position == pmax {
                2
            } else {
                position + 2
            };
            Some(format!("{actuator}B{number}"))
        }
        Signal::Coil { actuator, sign } => Some(match sign {
            Sign::Plus => format!("{actuator}M1"),
            Sign::Minus => format!("{actuator}M2"),
        }),
        Signal::SingleCoil { actuator } => Some(format!("{actuator}M1")),
        _ => None,
    }
}

/// The published method's symbol as an identifier legal in every target
/// language: `+`/`-` become `p`/`m`.
pub fn paper_ident(signal: Signal) -> String {
    match signal {
        Signal::Coil { actuator, sign } => {
            format!("y{actuator}{}", if sign == Sign::Plus { 'p' } else { 'm' })
        }
        Signal::Jog { actuator, sign } => {
            format!(
                "jog{actuator}{}",
                if sign == Sign::Plus { 'p' } else { 'm' }
            )
        }
        other => other.symbol(),
    }
}
