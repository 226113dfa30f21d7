//! Progress of a long command on stderr: a bar (indicatif) when stderr is a terminal, else a plain line every
//! tenth of the work, each ending in a newline, so a log or a pipe reads line by line.

use std::io::{IsTerminal, Write};

use indicatif::{ProgressBar, ProgressStyle};

/// Progress over `total` steps.
pub struct Progress {
    bar: Option<ProgressBar>,
    what: &'static str,
    total: u64,
    /// Plain lines: the next step at which one is printed.
    next_line: u64,
}

impl Progress {
    /// Progress over `total` steps of `what` ("swings", "stages").
    pub fn new(total: u64, what: &'static str) -> Self {
        let bar = std::io::stderr().is_terminal().then(|| {
            let bar = ProgressBar::new(total);
            if let Ok(style) = ProgressStyle::with_template("{bar:40} {pos}/{len} {msg} ({elapsed}, {eta} left)") {
                bar.set_style(style);
            }
            bar.set_message(what);
            bar
        });
        Progress { bar, what, total, next_line: 0 }
    }

    /// `done` of the steps are done; `note` says what is under way (a stage's name), if anything.
    pub fn set(&mut self, done: u64, note: Option<&str>) {
        match &self.bar {
            Some(bar) => {
                bar.set_position(done);
                if let Some(n) = note {
                    bar.set_message(format!("{}: {n}", self.what));
                }
            }
            None if done >= self.next_line || done == self.total || note.is_some() => {
                let mut err = std::io::stderr().lock();
                let _ = match note {
                    Some(n) => writeln!(err, "{done}/{} {}: {n}", self.total, self.what),
                    None => writeln!(err, "{done}/{} {}", self.total, self.what),
                };
                self.next_line = done + (self.total / 10).max(1);
            }
            None => {}
        }
    }

    /// Clears the bar (plain lines stay).
    pub fn finish(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}
