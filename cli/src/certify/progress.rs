//! Certify's progress display: live bars on a terminal, the plain report lines everywhere else.
//!
//! On a terminal (stderr, else stdout) each implementation gets a bar of rules done and each rule
//! in flight a line with its ID, the cases its child has announced and its time; the report's
//! lines print above them. Elsewhere (CI, a pipe, a file) nothing is animated and the lines are
//! exactly those of a run without the display.

use std::io::IsTerminal;
use std::time::Duration;

use indicatif::{MultiProgress, ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::say;

/// How often a line in flight redraws its clock, so a slow rule still shows it is alive.
const TICK: Duration = Duration::from_millis(200);

/// Where certify's lines and bars go.
pub struct Progress {
    /// The live bars; `None` when neither stderr nor stdout is a terminal.
    multi: Option<MultiProgress>,
}

impl Progress {
    /// Bars when stderr (else stdout) is a terminal, so that logs and pipes get plain lines.
    pub fn detect() -> Self {
        let target = if std::io::stderr().is_terminal() {
            Some(ProgressDrawTarget::stderr())
        } else if std::io::stdout().is_terminal() {
            Some(ProgressDrawTarget::stdout())
        } else {
            None
        };
        Self {
            multi: target.map(MultiProgress::with_draw_target),
        }
    }

    /// Prints one line of the report, above the bars when there are some.
    pub fn line(&self, text: &str) {
        match &self.multi {
            Some(multi) => multi.suspend(|| say(text)),
            None => say(text),
        }
    }

    /// Prints a warning on stderr, above the bars when there are some.
    pub fn warn(&self, text: &str) {
        match &self.multi {
            Some(multi) => multi.suspend(|| eprintln!("{text}")),
            None => eprintln!("{text}"),
        }
    }

    /// A bar of `rules` rules for one implementation; hidden (every call a no-op) off a terminal.
    pub fn implementation(&self, name: &str, rules: usize) -> ProgressBar {
        let Some(multi) = &self.multi else {
            return ProgressBar::hidden();
        };
        let bar = multi.add(ProgressBar::new(rules as u64));
        bar.set_style(style(
            "{prefix:30!} [{bar:32}] {pos:>3}/{len} rules {msg}",
            ProgressStyle::default_bar(),
        ));
        bar.set_prefix(name.to_owned());
        bar
    }

    /// A line for a rule in flight: its ID, the cases of `planned` announced so far (0 when they
    /// cannot be seen), its time.
    pub fn rule(&self, implementation: &str, id: &str, planned: u32) -> ProgressBar {
        let Some(multi) = &self.multi else {
            return ProgressBar::hidden();
        };
        let bar = multi.add(ProgressBar::new(u64::from(planned)));
        let template = if planned == 0 {
            "  {spinner} {prefix:60!} {elapsed:>4}"
        } else {
            "  {spinner} {prefix:60!} {pos:>6}/{len} cases {elapsed:>4}"
        };
        bar.set_style(style(template, ProgressStyle::default_spinner()));
        bar.set_prefix(format!("{id} ({implementation})"));
        bar.enable_steady_tick(TICK);
        bar
    }

    /// Takes a rule's line away once it is done.
    pub fn done(&self, bar: &ProgressBar) {
        bar.finish_and_clear();
        if let Some(multi) = &self.multi {
            multi.remove(bar);
        }
    }

    /// Takes every bar away, leaving the report's lines.
    pub fn clear(&self) {
        if let Some(multi) = &self.multi {
            let _ = multi.clear();
        }
    }
}

/// A style from a template known to parse, else `fallback` (never a panic).
fn style(template: &str, fallback: ProgressStyle) -> ProgressStyle {
    fallback.clone().template(template).unwrap_or(fallback)
}
