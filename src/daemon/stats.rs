//! Latency percentiles over a window of recent shots, a rate limiter for log lines and a recording budget: what
//! the live loop, replay and the bridges share.

use std::time::{Duration, Instant};

use crate::daemon::clock::Clock;

/// The last `capacity` latencies (us).
#[derive(Debug, Clone)]
pub struct LatencyWindow {
    values: Vec<f64>,
    next: usize,
    capacity: usize,
}

impl LatencyWindow {
    pub fn new(capacity: usize) -> Self {
        LatencyWindow { values: Vec::with_capacity(capacity), next: 0, capacity }
    }

    pub fn push(&mut self, us: f64) {
        if self.values.len() < self.capacity {
            self.values.push(us);
        } else {
            self.values[self.next] = us;
        }
        self.next = (self.next + 1) % self.capacity;
    }

    /// The `q` quantile (0..1) by nearest rank, 0 when empty.
    pub fn quantile(&self, q: f64) -> f64 {
        if self.values.is_empty() {
            return 0.0;
        }
        let mut v = self.values.clone();
        v.sort_by(f64::total_cmp);
        let rank = ((q * v.len() as f64).ceil() as usize).clamp(1, v.len());
        v[rank - 1]
    }
}

/// Allows one event per `period` per key and counts what it suppressed.
#[derive(Debug)]
pub struct RateLimiter {
    period: Duration,
    clock: Clock,
    last: std::collections::HashMap<String, (Instant, u64)>,
    /// Events of kinds not tracked because the table was full, reported with the next allowed line.
    untracked: u64,
}

/// Kinds a [`RateLimiter`] tracks at once: keys are kinds (a reason, `unknown_rig`), never what a peer chose,
/// and entries older than the period are pruned when the table fills.
pub const RATE_LIMITER_KEYS: usize = 256;

impl RateLimiter {
    pub fn new(period: Duration) -> Self {
        RateLimiter::with_clock(period, Clock::system())
    }

    /// A limiter whose periods pass on `clock`.
    pub fn with_clock(period: Duration, clock: Clock) -> Self {
        RateLimiter { period, clock, last: Default::default(), untracked: 0 }
    }

    /// `Some(suppressed since the last allowed)` when this event may be logged.
    pub fn allow(&mut self, key: &str) -> Option<u64> {
        let now = self.clock.now();
        match self.last.get_mut(key) {
            Some((t, n)) if now.duration_since(*t) < self.period => {
                *n += 1;
                None
            }
            Some((t, n)) => {
                let suppressed = *n + std::mem::take(&mut self.untracked);
                *t = now;
                *n = 0;
                Some(suppressed)
            }
            None => {
                if self.last.len() >= RATE_LIMITER_KEYS {
                    // A stale kind's suppressed events are not forgotten: they are said with the next line.
                    let (period, mut owed) = (self.period, 0);
                    self.last.retain(|_, (t, n)| {
                        let keep = now.duration_since(*t) < period;
                        if !keep {
                            owed += *n;
                        }
                        keep
                    });
                    self.untracked += owed;
                }
                if self.last.len() >= RATE_LIMITER_KEYS {
                    self.untracked += 1;
                    return None;
                }
                self.last.insert(key.to_string(), (now, 0));
                Some(std::mem::take(&mut self.untracked))
            }
        }
    }

    /// Kinds tracked now (bounded by [`RATE_LIMITER_KEYS`]).
    pub fn tracked(&self) -> usize {
        self.last.len()
    }

    /// The summaries a flood that stopped is owed: each kind with events suppressed and none allowed for a whole
    /// period since, with its count (then reset, and the kind's period started again, so a summary is a line of
    /// the kind's one a period). Events of kinds not tracked come last, under `None`.
    pub fn overdue(&mut self) -> Vec<(Option<String>, u64)> {
        self.take_suppressed(self.period)
    }

    /// Every count of events suppressed and not yet said, however recent (when the log ends).
    pub fn owed(&mut self) -> Vec<(Option<String>, u64)> {
        self.take_suppressed(Duration::ZERO)
    }

    fn take_suppressed(&mut self, min_age: Duration) -> Vec<(Option<String>, u64)> {
        let now = self.clock.now();
        let mut out = Vec::new();
        for (kind, (t, n)) in &mut self.last {
            if *n > 0 && now.duration_since(*t) >= min_age {
                out.push((Some(kind.clone()), std::mem::take(n)));
                *t = now;
            }
        }
        if self.untracked > 0 {
            out.push((None, std::mem::take(&mut self.untracked)));
        }
        out
    }
}

/// Rejected payloads recorded per rig (and for unknown rigs together), per second: beyond either bound they are
/// counted, not stored.
pub const REJECTED_RECORDS_PER_S: u32 = 20;
/// Bytes of rejected payloads recorded per rig per second.
pub const REJECTED_BYTES_PER_S: usize = 64 * 1024;
/// The most of one rejected payload that is kept.
pub const REJECTED_KEEP_BYTES: usize = 4 * 1024;

/// A recording budget: at most `max_records` records and `max_bytes` bytes per second; beyond it payloads are
/// counted, not stored (so a flood cannot fill the disk).
#[derive(Debug, Clone)]
pub struct Budget {
    max_records: u32,
    max_bytes: usize,
    clock: Clock,
    window: Instant,
    records: u32,
    bytes: usize,
    /// Payloads refused over the budget's life.
    pub refused: u64,
}

impl Budget {
    pub fn new(max_records: u32, max_bytes: usize) -> Self {
        Budget::with_clock(max_records, max_bytes, Clock::system())
    }

    /// A budget whose seconds pass on `clock`.
    pub fn with_clock(max_records: u32, max_bytes: usize, clock: Clock) -> Self {
        let window = clock.now();
        Budget { max_records, max_bytes, clock, window, records: 0, bytes: 0, refused: 0 }
    }

    /// Whether a record of `bytes` may be stored now; counts the refusal when not.
    pub fn allow(&mut self, bytes: usize) -> bool {
        let now = self.clock.now();
        if now.duration_since(self.window) >= Duration::from_secs(1) {
            self.window = now;
            self.records = 0;
            self.bytes = 0;
        }
        if self.records < self.max_records && self.bytes + bytes <= self.max_bytes {
            self.records += 1;
            self.bytes += bytes;
            true
        } else {
            self.refused += 1;
            false
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_limiter_fed_distinct_keys_stays_bounded() {
        let mut l = RateLimiter::new(Duration::from_secs(60));
        let allowed = (0..10_000).filter(|i| l.allow(&format!("k{i}")).is_some()).count();
        assert_eq!(allowed, RATE_LIMITER_KEYS);
        assert_eq!(l.tracked(), RATE_LIMITER_KEYS);
        let mut short = RateLimiter::new(Duration::ZERO);
        for i in 0..10_000 {
            short.allow(&format!("k{i}"));
        }
        assert!(short.tracked() <= RATE_LIMITER_KEYS);
    }

    #[test]
    fn a_flood_that_stopped_is_owed_its_count_once() {
        // Stepped by a manual clock: no sleeping, and a loaded machine cannot make a period pass early or late.
        let clock = Clock::manual(0);
        let mut l = RateLimiter::with_clock(Duration::from_millis(30), clock.clone());
        assert_eq!(l.allow("k"), Some(0));
        for _ in 0..9 {
            assert_eq!(l.allow("k"), None);
        }
        clock.advance(Duration::from_millis(29));
        assert!(l.overdue().is_empty(), "not yet a period since the last line");
        clock.advance(Duration::from_millis(1));
        assert_eq!(l.overdue(), vec![(Some("k".to_string()), 9)]);
        assert!(l.overdue().is_empty(), "said once");
        // The summary started the kind's period again.
        assert_eq!(l.allow("k"), None);
        clock.advance(Duration::from_millis(30));
        assert_eq!(l.allow("k"), Some(1));
    }

    #[test]
    fn the_recording_budget_is_renewed_each_second_of_its_clock() {
        let clock = Clock::manual(0);
        let mut b = Budget::with_clock(2, 100, clock.clone());
        assert_eq!([b.allow(10), b.allow(10), b.allow(10)], [true, true, false]);
        clock.advance(Duration::from_millis(999));
        assert!(!b.allow(10), "the same second");
        clock.advance(Duration::from_millis(1));
        assert_eq!([b.allow(60), b.allow(60), b.allow(40)], [true, false, true]);
        assert_eq!(b.refused, 3);
    }

    #[test]
    fn quantiles() {
        let mut w = LatencyWindow::new(100);
        for i in 1..=100 {
            w.push(i as f64);
        }
        assert_eq!(w.quantile(0.5), 50.0);
        assert_eq!(w.quantile(0.99), 99.0);
        w.push(1000.0);
        assert_eq!(w.quantile(1.0), 1000.0);
    }
}
