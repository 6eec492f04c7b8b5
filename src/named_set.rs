//! One reader for every comma-separated list of names a user gives
//! (`--formats`, `--safety`, `--modes` and their SETTINGS rows), so that
//! they all refuse the same mistakes the same way: an empty item, a name
//! given twice (`st,ST`), or a word that stands for the whole set (`all`,
//! `none`) beside another name (`all,st` could mean all, or st) is refused
//! rather than read one way silently. A leaf: it imports nothing.

/// What one list accepts.
pub struct NameList<'a> {
    /// The names, compared without regard to ASCII case.
    pub names: &'a [&'static str],
    /// The words that stand for a whole set and so stand alone (`all`,
    /// `none`); accepted like a name, but only as the list's one item.
    pub alone: &'a [&'static str],
    /// Everything the list accepts, for the message about an empty item.
    pub expected: &'a str,
}

impl NameList<'_> {
    /// The items of `text`, each as the list spells it, in the order given.
    /// Nothing at all (`--modes ""`, a script's empty variable) is no item:
    /// the caller says whether that is allowed. `unknown` words the error
    /// for an item that is no name (it gets the item as written).
    pub fn parse(
        &self,
        text: &str,
        unknown: impl Fn(&str) -> String,
    ) -> Result<Vec<&'static str>, String> {
        let mut items: Vec<&'static str> = Vec::new();
        if text.trim().is_empty() {
            return Ok(items);
        }
        // `and` and `&` separate items as a comma does (`estop and reset`,
        // `stop, estop, and reset`, as a SETTINGS cell is often written):
        // no name holds a space.
        let mut separated = String::with_capacity(text.len());
        let mut after_and = false;
        for word in text.replace('&', " and ").split(char::is_whitespace) {
            if word.is_empty() {
                continue;
            }
            let and = word.eq_ignore_ascii_case("and");
            // After a comma (`estop, and reset`) `and` separates nothing
            // more; after another `and` it leaves an empty item.
            if !and {
                separated.push_str(word);
                separated.push(' ');
            } else if after_and || !separated.trim_end().ends_with(',') {
                separated.push(',');
            }
            after_and = and;
        }
        for raw in separated.split(',') {
            let item = raw.trim();
            let known = self
                .names
                .iter()
                .chain(self.alone)
                .find(|name| name.eq_ignore_ascii_case(item));
            let Some(&name) = known else {
                return Err(if item.is_empty() {
                    format!(
                        "\"{}\" has an empty item; write each name once, the names apart by commas or `and` (expected {})",
                        text.trim(),
                        self.expected
                    )
                } else {
                    unknown(item)
                });
            };
            if items.contains(&name) {
                return Err(format!(
                    "\"{name}\" is given twice in \"{}\"; give each once",
                    text.trim()
                ));
            }
            items.push(name);
        }
        if items.len() > 1
            && let Some(alone) = items.iter().find(|name| self.alone.contains(name))
        {
            return Err(format!(
                "\"{alone}\" stands alone; \"{}\" also names others (write {alone}, or the names)",
                text.trim()
            ));
        }
        Ok(items)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const LIST: NameList = NameList {
        names: &["st", "awl"],
        alone: &["all"],
        expected: "st, awl or all",
    };

    fn parse(text: &str) -> Result<Vec<&'static str>, String> {
        LIST.parse(text, |item| format!("{item} is unknown"))
    }

    #[test]
    fn each_name_once_and_a_whole_set_alone() {
        assert_eq!(parse(" ST , awl").unwrap(), ["st", "awl"]);
        assert_eq!(parse("All").unwrap(), ["all"]);
        assert!(parse("  ").unwrap().is_empty());
        let err = parse("st,ST").unwrap_err();
        assert!(err.contains("\"st\" is given twice in \"st,ST\""), "{err}");
        let err = parse("all,st").unwrap_err();
        assert!(err.contains("\"all\" stands alone"), "{err}");
        let err = parse("st,,awl").unwrap_err();
        assert!(err.contains("has an empty item"), "{err}");
        assert!(err.contains("st, awl or all"), "{err}");
        assert_eq!(parse("st,pdf").unwrap_err(), "pdf is unknown");
    }

    #[test]
    fn and_separates_items_as_a_comma_does() {
        for text in [
            "st and awl",
            "ST AND awl",
            "st & awl",
            "st, and awl",
            "st&awl",
        ] {
            assert_eq!(parse(text).unwrap(), ["st", "awl"], "{text}");
        }
        assert!(parse("st and").unwrap_err().contains("has an empty item"));
        for text in [
            "st and and awl",
            "st & & awl",
            "st & and awl",
            "st,, and awl",
        ] {
            assert!(
                parse(text).unwrap_err().contains("has an empty item"),
                "{text}"
            );
        }
        assert!(parse("st and st").unwrap_err().contains("given twice"));
        assert_eq!(parse("standard").unwrap_err(), "standard is unknown");
    }
}
