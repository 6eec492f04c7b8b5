//! Times the engineer gives: stroke times per actuator and durations such as
//! `1.5s` or `800ms`. Used by the program (watchdog presets) and the plant.

use std::collections::BTreeMap;

/// Extend and retract stroke times of one actuator, in milliseconds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Stroke {
    pub extend_ms: u32,
    pub retract_ms: u32,
}

impl Default for Stroke {
    fn default() -> Self {
        Stroke {
            extend_ms: 1000,
            retract_ms: 1000,
        }
    }
}

/// Stroke times of every actuator: a default and the ones given explicitly.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Strokes {
    pub default: Stroke,
    pub per_actuator: BTreeMap<u32, Stroke>,
}

impl Strokes {
    pub fn of(&self, actuator: u32) -> Stroke {
        self.per_actuator
            .get(&actuator)
            .copied()
            .unwrap_or(self.default)
    }
}

/// Parses a duration such as `1.5s`, `800ms` or `2 s` into milliseconds,
/// from 1 ms to an hour. A bare number means seconds.
pub fn parse_duration_ms(text: &str) -> Option<u32> {
    // `1 5s`, `0, 8s`: 15 s or 1.5 s or two values, which is not ours to
    // guess (white space is dropped everywhere else).
    if crate::cell::split_number(text) {
        return None;
    }
    let t: String = text.chars().filter(|c| !c.is_whitespace()).collect();
    crate::cell::parse_duration_in(&t, 1..=3_600_000)
}

/// Parses a scan time (`--scan`, the SETTINGS sheet's `scan time`): 1 ms to 1 s.
pub fn parse_scan(text: &str) -> Result<u32, String> {
    if crate::cell::thousands_comma(text) {
        return Err(crate::cell::thousands_comma_words(text));
    }
    parse_duration_ms(text)
        .filter(|ms| *ms <= 1000)
        .ok_or_else(|| format!("\"{text}\" is not a scan time from 1ms to 1s, such as 10ms"))
}

/// An option's list that gives one actuator twice (`--valve
/// C1=52mono,C1=52bi`): refused, as the SETTINGS sheet refuses a row twice,
/// rather than the later value silently winning.
pub fn given_twice(item: &str, actuator: u32) -> String {
    format!("\"{item}\": C{actuator} is given twice; give each actuator once")
}

/// Parses `--stroke` values: `C2=1.5s/0.8s,C3=2s` (extend/retract, or one
/// time for both). Returns the map or a message saying what is wrong.
pub fn parse_strokes(text: &str) -> Result<BTreeMap<u32, Stroke>, String> {
    let mut strokes = BTreeMap::new();
    for item in text.split(',').map(str::trim).filter(|i| !i.is_empty()) {
        let (name, times) = item.split_once('=').ok_or_else(|| {
            format!("\"{item}\": expected C<number>=<extend>/<retract>, e.g. C2=1.5s/0.8s")
        })?;
        let actuator = crate::cell::parse_actuator(name)
            .ok_or_else(|| format!("\"{item}\": expected an actuator such as C2 before ="))?;
        let (extend, retract) = times.split_once('/').unwrap_or((times, times));
        let parse = |t: &str| {
            parse_duration_ms(t).ok_or_else(|| {
                format!("\"{item}\": \"{t}\" is not a stroke time such as 1.5s or 800ms")
            })
        };
        let stroke = Stroke {
            extend_ms: parse(extend)?,
            retract_ms: parse(retract)?,
        };
        if strokes.insert(actuator, stroke).is_some() {
            return Err(given_twice(item, actuator));
        }
    }
    Ok(strokes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn durations_in_engineering_units() {
        assert_eq!(parse_duration_ms("1.5s"), Some(1500));
        assert_eq!(parse_duration_ms("800ms"), Some(800));
        assert_eq!(parse_duration_ms("2 S"), Some(2000));
        assert_eq!(parse_duration_ms("0,5s"), Some(500));
        assert_eq!(parse_duration_ms("2"), Some(2000));
        // A comma before three digits may group thousands: no reading.
        for bad in [
            "", "s", "-1s", "0ms", "fast", "nan", "inf s", "1,000ms", "1,500s",
        ] {
            assert_eq!(parse_duration_ms(bad), None, "{bad}");
        }
    }

    #[test]
    fn stroke_options_parse() {
        let strokes = parse_strokes("C2=1.5s/0.8s, c3 = 2s").unwrap();
        assert_eq!(
            strokes[&2],
            Stroke {
                extend_ms: 1500,
                retract_ms: 800
            }
        );
        assert_eq!(
            strokes[&3],
            Stroke {
                extend_ms: 2000,
                retract_ms: 2000
            }
        );
        assert!(
            parse_strokes("C2")
                .unwrap_err()
                .contains("expected C<number>=")
        );
        assert!(parse_strokes("X2=1s").unwrap_err().contains("actuator"));
        assert!(
            parse_strokes("C2=quick")
                .unwrap_err()
                .contains("not a stroke time")
        );
    }
}
