//! Log lines a peer can drive (a page's control, a put on the bus, a mocap server's model, a connection):
//! at most one a second per kind ([`RateLimiter`]), the count suppressed said on the kind's next line or, when
//! the flood stops, in a summary line of its own ([`PeerLog::flush`]), and each line's text cut to
//! [`PEER_LINE_BYTES`] with control characters escaped, so a peer's string can neither fill the log nor start a
//! line of its own. docs/limits.md states the rule.

use std::collections::HashMap;
use std::time::{Duration, Instant};

use tracing::Level;

use crate::daemon::clock::Clock;
use crate::daemon::stats::RateLimiter;

/// The most of a peer-driven line's text that is logged (what the daemon says plus what it quotes), in bytes;
/// the cut is marked `… (N bytes in all)`.
pub const PEER_LINE_BYTES: usize = 512;
/// The most of one list of peer names (a mocap model's bodies) quoted in a line, in bytes.
pub const PEER_LIST_BYTES: usize = 256;

/// One surface's peer-driven lines (a rig's worker, the bay screen, a mocap client).
#[derive(Debug)]
pub struct PeerLog {
    limiter: RateLimiter,
    clock: Clock,
    /// Each kind's level, for its summary line (kinds are the program's names, never a peer's).
    levels: HashMap<&'static str, Level>,
    last_flush: Instant,
}

impl Default for PeerLog {
    fn default() -> Self {
        PeerLog::new()
    }
}

impl PeerLog {
    /// One line a second per kind.
    pub fn new() -> Self {
        PeerLog::with_clock(Clock::system())
    }

    /// One line a second of `clock` per kind.
    pub fn with_clock(clock: Clock) -> Self {
        let last_flush = clock.now();
        PeerLog { limiter: RateLimiter::with_clock(PERIOD, clock.clone()), clock, levels: HashMap::new(), last_flush }
    }

    pub fn warn(&mut self, kind: &'static str, message: impl FnOnce() -> String) {
        self.log(Level::WARN, kind, message);
    }

    pub fn info(&mut self, kind: &'static str, message: impl FnOnce() -> String) {
        self.log(Level::INFO, kind, message);
    }

    /// Logs `message` (built only when it is logged) unless this kind had its line within the last second.
    pub fn log(&mut self, level: Level, kind: &'static str, message: impl FnOnce() -> String) {
        if self.clock.since(self.last_flush) >= PERIOD {
            self.flush();
        }
        let Some(n) = self.limiter.allow(kind) else { return };
        if self.levels.len() < crate::daemon::stats::RATE_LIMITER_KEYS {
            self.levels.insert(kind, level);
        }
        let text = cut(&message());
        if n > 0 {
            emit(level, format_args!("{text} ({n} more {kind} since the last)"));
        } else {
            emit(level, format_args!("{text}"));
        }
    }

    /// Says what was suppressed of each kind whose flood stopped a second or more ago (a caller with a clock
    /// calls it every second or so; any later line calls it too, and so does dropping the log).
    pub fn flush(&mut self) {
        self.last_flush = self.clock.now();
        for (kind, n) in self.limiter.overdue() {
            self.summary(kind, n);
        }
    }

    fn summary(&self, kind: Option<String>, n: u64) {
        let level = kind.as_deref().and_then(|k| self.levels.get(k).copied()).unwrap_or(Level::WARN);
        let kind = kind.as_deref().unwrap_or("lines of other kinds");
        emit(level, format_args!("{n} more {kind} since the last (suppressed: one line a second per kind)"));
    }
}

impl Drop for PeerLog {
    fn drop(&mut self) {
        // Whatever is still owed, however recent.
        for (kind, n) in self.limiter.owed() {
            self.summary(kind, n);
        }
    }
}

const PERIOD: Duration = Duration::from_secs(1);

fn emit(level: Level, args: std::fmt::Arguments<'_>) {
    match level {
        Level::ERROR => tracing::error!("{args}"),
        Level::WARN => tracing::warn!("{args}"),
        Level::INFO => tracing::info!("{args}"),
        Level::DEBUG => tracing::debug!("{args}"),
        Level::TRACE => tracing::trace!("{args}"),
    }
}

/// `text` with control characters escaped, cut to [`PEER_LINE_BYTES`] (at a character) and the cut marked.
pub fn cut(text: &str) -> String {
    escaped(text, PEER_LINE_BYTES)
}

/// A peer's string as a line quotes it: escaped and cut to `max` bytes, the cut marked `… (N bytes in all)`.
pub fn escaped(text: &str, max: usize) -> String {
    let mut out = String::with_capacity(text.len().min(max) + 16);
    for c in text.chars() {
        let before = out.len();
        if c.is_control() {
            out.extend(c.escape_debug());
        } else {
            out.push(c);
        }
        if out.len() > max {
            out.truncate(before);
            out.push_str(&format!("… ({} bytes in all)", text.len()));
            return out;
        }
    }
    out
}

/// A list of peer names as a line quotes it: each in backquotes, escaped, while they fit in
/// [`PEER_LIST_BYTES`], then how many more: `` `a`, `b` and 9998 more (10000 in all) ``.
pub fn list<'a>(names: impl IntoIterator<Item = &'a str>) -> String {
    let names: Vec<&str> = names.into_iter().collect();
    let mut out = String::new();
    for (i, name) in names.iter().enumerate() {
        let quoted = format!("`{}`", escaped(name, 64));
        if out.len() + quoted.len() + 2 > PEER_LIST_BYTES {
            out.push_str(&format!(" and {} more ({} in all)", names.len() - i, names.len()));
            return out;
        }
        if i > 0 {
            out.push_str(", ");
        }
        out.push_str(&quoted);
    }
    if names.is_empty() {
        out.push_str("none");
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_peers_text_is_escaped_and_cut() {
        assert_eq!(escaped("club\nWARN forged", 100), "club\\nWARN forged");
        let long = "x".repeat(1 << 20);
        let c = cut(&long);
        assert!(c.len() <= PEER_LINE_BYTES + 32, "{}", c.len());
        assert!(c.ends_with("… (1048576 bytes in all)"), "{}", &c[500..]);
        // Cut at a character, never inside one.
        let wide = "é".repeat(400);
        assert!(escaped(&wide, 101).starts_with(&"é".repeat(50)));
        assert_eq!(escaped("short", 100), "short");
    }

    #[test]
    fn a_long_list_is_quoted_in_part_with_its_count() {
        let names: Vec<String> = (0..10_000).map(|i| format!("body{i}")).collect();
        let l = list(names.iter().map(String::as_str));
        assert!(l.len() <= PEER_LIST_BYTES + 40, "{l}");
        assert!(l.starts_with("`body0`, `body1`") && l.ends_with("more (10000 in all)"), "{l}");
        assert_eq!(list(["a", "b"]), "`a`, `b`");
        assert_eq!(list([]), "none");
        let huge = "n".repeat(1 << 20);
        assert!(list([huge.as_str()]).len() < 100);
    }
}
