//! STEP 7's S5TIME: the time a timer of the `.awl` is loaded with.

/// S5TIME literal for a duration, never shorter than asked: the finest time
/// base (10 ms, 100 ms, 1 s, 10 s) whose 999 steps reach it, rounded up to
/// a whole step (at most 2H46M30S).
pub fn s5time(ms: u32) -> String {
    let ms = s5_ms(ms);
    let (h, rest) = (ms / 3_600_000, ms % 3_600_000);
    let (m, rest) = (rest / 60_000, rest % 60_000);
    let (s, rest) = (rest / 1000, rest % 1000);
    let mut text = "S5T#".to_string();
    for (value, unit) in [(h, "H"), (m, "M"), (s, "S"), (rest, "MS")] {
        if value > 0 {
            text.push_str(&format!("{value}{unit}"));
        }
    }
    if text.len() == 4 {
        text.push_str("0MS");
    }
    text
}

/// The milliseconds an S5TIME of `ms` holds (see [`s5time`]).
pub fn s5_ms(ms: u32) -> u32 {
    let ms = ms.min(9_990_000);
    [10u32, 100, 1000, 10_000]
        .into_iter()
        .find(|base| ms.div_ceil(*base) <= 999)
        .map_or(9_990_000, |base| ms.div_ceil(base) * base)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The time base STEP 7 stores a duration with: the finest that holds it in
    /// 999 steps.
    fn base_of(ms: u32) -> u32 {
        [10u32, 100, 1000]
            .into_iter()
            .find(|base| ms <= 999 * base)
            .unwrap_or(10_000)
    }

    /// Milliseconds of an S5TIME literal, as STEP 7 reads it.
    fn literal_ms(text: &str) -> u32 {
        let mut rest = text.strip_prefix("S5T#").unwrap();
        let mut total = 0;
        for (unit, factor) in [("H", 3_600_000), ("M", 60_000), ("S", 1000), ("MS", 1)] {
            let digits: String = rest.chars().take_while(char::is_ascii_digit).collect();
            let after = &rest[digits.len()..];
            if !digits.is_empty()
                && after.starts_with(unit)
                && !after[unit.len()..].starts_with('S')
            {
                total += digits.parse::<u32>().unwrap() * factor;
                rest = &after[unit.len()..];
            }
        }
        assert!(rest.is_empty(), "{text}");
        total
    }

    #[test]
    fn s5time_literals() {
        assert_eq!(s5time(3000), "S5T#3S");
        assert_eq!(s5time(2400), "S5T#2S400MS");
        assert_eq!(s5time(0), "S5T#0MS");
        assert_eq!(s5time(u32::MAX), "S5T#2H46M30S");
        // Never shorter than asked, and no longer than one step of the
        // finest base that holds the time in 999 steps.
        assert_eq!(s5time(15), "S5T#20MS");
        assert_eq!(s5time(1005), "S5T#1S10MS");
        assert_eq!(s5time(9990), "S5T#9S990MS");
        assert_eq!(s5time(10_010), "S5T#10S100MS");
        assert_eq!(s5time(61_005), "S5T#1M1S100MS");
        assert_eq!(s5time(655_000), "S5T#10M55S");
        for ms in [
            10, 15, 999, 1005, 9990, 9999, 10_010, 99_901, 123_456, 655_000,
        ] {
            let got = literal_ms(&s5time(ms));
            // What W008 and the comment say the preset holds is what it holds.
            assert_eq!(s5_ms(ms), got);
            assert!(got >= ms && got - ms < base_of(got), "{ms} ms -> {got} ms");
            assert!(got / base_of(got) <= 999, "{ms} ms -> {got} ms");
        }
    }
}
