//! The refusals of a scenario as a whole, before anything runs: each event
//! is read with the ones written before it. An event at a moment another
//! of its signal has (written twice, contradicting), an absolute time
//! before the event before it, an event past [`LATEST_MS`], and an event
//! that could do nothing (a release of a button not held, a hold of one
//! held already, a press of a button a stuck input hides) are E042: a
//! scenario prints what it did, and an event printed as done that did
//! nothing would mislead.

use std::collections::BTreeMap;

use super::events::{Act, Event, LATEST_MS, When};
use crate::program::Signal;

/// When an event happens, as far as it is known before the run: at a scan
/// of the run, or this long after the event of a step (which happens when
/// the program enters that step, unknown before it runs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Moment {
    At(u64),
    AfterStepEvent(usize, u64),
}

/// The refusals of `events`, their times resolved to the scans (`scan_ms`)
/// they happen in.
pub fn check(events: &[Event], scan_ms: u32) -> Vec<String> {
    let mut refused = timing(events, scan_ms);
    for (k, why) in without_effect(events) {
        // One refusal an event is enough: a moment shared says it already.
        if !refused.iter().any(|r| r.starts_with(&events[k].written)) {
            refused.push(why);
        }
    }
    refused.extend(super::events::too_many_jogs(events));
    refused
}

/// The refusals of times: the order written, the latest moment, and one
/// signal twice at one moment.
fn timing(events: &[Event], scan_ms: u32) -> Vec<String> {
    let scan = u64::from(scan_ms.max(1));
    let on_scan = |t: u64| t.div_ceil(scan) * scan;
    let mut refused = Vec::new();
    // The moment of the event before (power-up for the first), and how far
    // `+` times reach past the last step's event.
    let mut before = (Moment::At(0), "");
    let mut moments: Vec<Moment> = Vec::new();
    let mut reach = 0;
    for (k, event) in events.iter().enumerate() {
        let at = match event.when {
            When::At(t) => {
                if let (Moment::At(b), written) = before
                    && !written.is_empty()
                    && b > on_scan(t)
                {
                    refused.push(format!(
                        "{}: {} s is before the event written before it ({written}, at {} s): events happen in the order written",
                        event.written,
                        t as f64 / 1000.0,
                        b as f64 / 1000.0
                    ));
                }
                reach = 0;
                Moment::At(on_scan(t))
            }
            When::After(d) => {
                reach += d;
                match before.0 {
                    Moment::At(b) => Moment::At(on_scan(b + d)),
                    Moment::AfterStepEvent(s, o) => Moment::AfterStepEvent(s, on_scan(o + d)),
                }
            }
            // Never the scan of the event before: the step is entered anew.
            When::Step(_) => {
                reach = 0;
                Moment::AfterStepEvent(k, 0)
            }
        };
        let late = matches!(at, Moment::At(t) if t > u64::from(LATEST_MS));
        if late || reach > u64::from(LATEST_MS) {
            refused.push(format!(
                "{}: happens after {} s, the latest an event may name",
                event.written,
                LATEST_MS / 1000
            ));
        }
        for (o, other) in events[..k].iter().enumerate() {
            if moments[o] != at || other.act.signal() != event.act.signal() {
                continue;
            }
            refused.push(if other.act == event.act {
                format!(
                    "{}: written twice for one scan; the second would do nothing",
                    event.written
                )
            } else if contradicts(other.act, event.act) {
                format!(
                    "{}: contradicts {} at the same scan",
                    event.written, other.written
                )
            } else {
                format!(
                    "{}: one signal twice with {} at the same scan",
                    event.written, other.written
                )
            });
        }
        moments.push(at);
        before = (at, event.written.as_str());
    }
    refused
}

/// The events that could do nothing, by index, with why: each signal's
/// state (held, stuck) followed through the events in the order they
/// happen, which is the order written.
fn without_effect(events: &[Event]) -> Vec<(usize, String)> {
    let mut held: BTreeMap<Signal, &str> = BTreeMap::new();
    let mut stuck: BTreeMap<Signal, (bool, &str)> = BTreeMap::new();
    let mut refused = Vec::new();
    for (k, event) in events.iter().enumerate() {
        let signal = event.act.signal();
        let name = signal.symbol();
        let why = match (event.act, stuck.get(&signal), held.get(&signal)) {
            (Act::Stick(_, v), Some((w, by)), _) if v == *w => Some(format!(
                "does nothing: {name} is stuck at {} already ({by})",
                u8::from(v)
            )),
            (Act::Stick(..), ..) => None,
            (_, Some((v, by)), _) => Some(format!(
                "does nothing: {name} reads {} from {by} on, whatever the button does",
                u8::from(*v)
            )),
            (Act::Release(_), _, None) => Some(format!(
                "does nothing: {name} is not held (a --hold before it holds a button; a --press lets go by itself)"
            )),
            (Act::Hold(_) | Act::Press(_), _, Some(by)) => Some(format!(
                "does nothing: {name} is held already ({by}); release it first"
            )),
            _ => None,
        };
        if let Some(why) = why {
            refused.push((k, format!("{}: {why}", event.written)));
        }
        match event.act {
            Act::Hold(s) => {
                held.entry(s).or_insert(&event.written);
            }
            Act::Release(s) => {
                held.remove(&s);
            }
            Act::Stick(s, v) => {
                stuck.insert(s, (v, &event.written));
            }
            Act::Press(_) => {}
        }
    }
    refused
}

/// Two acts on one signal that cannot both hold at one moment: a press
/// and a release, stuck at 0 and at 1, a button pressed and stuck.
fn contradicts(a: Act, b: Act) -> bool {
    if a.signal() != b.signal() {
        return false;
    }
    match (a, b) {
        (Act::Release(_), Act::Release(_)) => false,
        (Act::Release(_), _) | (_, Act::Release(_)) => true,
        (Act::Stick(_, x), Act::Stick(_, y)) => x != y,
        (Act::Stick(..), _) | (_, Act::Stick(..)) => true,
        _ => false,
    }
}
