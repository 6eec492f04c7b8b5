//! A progress bar for long work inside one file (the fault analysis): on a
//! terminal only, and only once the work has taken a second, so a quick run
//! prints nothing extra.

use std::io::IsTerminal;
use std::sync::OnceLock;
use std::time::{Duration, Instant};

pub(crate) struct Progress {
    started: Instant,
    what: &'static str,
    shown: bool,
    bar: OnceLock<indicatif::ProgressBar>,
}

impl Progress {
    /// A bar counting `what` ("fault cases"); hidden when stderr is not a
    /// terminal or `quiet`.
    pub(crate) fn new(what: &'static str, quiet: bool) -> Self {
        Progress {
            started: Instant::now(),
            what,
            shown: !quiet && std::io::stderr().is_terminal(),
            bar: OnceLock::new(),
        }
    }

    /// `done` of `total` finished; safe to call from any thread.
    pub(crate) fn update(&self, done: usize, total: usize) {
        if !self.shown || self.started.elapsed() < Duration::from_secs(1) {
            return;
        }
        let bar = self.bar.get_or_init(|| {
            let bar = indicatif::ProgressBar::new(total as u64);
            bar.set_style(
                indicatif::ProgressStyle::with_template(&format!(
                    "{{bar:30}} {{pos}}/{{len}} {}, {{elapsed}}, about {{eta}} left (Ctrl-C stops)",
                    self.what
                ))
                .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
            );
            bar
        });
        bar.set_position(done as u64);
    }

    /// Clears the bar, if it was shown.
    pub(crate) fn finish(&self) {
        if let Some(bar) = self.bar.get() {
            bar.finish_and_clear();
        }
    }
}
