//! The daemon's clock: the wall time its records are stamped with (ns since the Unix epoch) and the monotonic
//! instant its periods are measured on (a peer's log lines a second, the recording budget of rejected
//! payloads, the status period, a prediction's latency). The live daemon runs on [`Clock::system`]; a test
//! steps a [`Clock::manual`] forward with [`Clock::advance`], so what depends on time passing is checked without
//! sleeping.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

/// The system's clocks, or a manual clock that moves only when told (cloning shares it).
#[derive(Debug, Clone, Default)]
pub struct Clock(Option<Arc<Manual>>);

#[derive(Debug)]
struct Manual {
    start: Instant,
    wall_start_ns: u64,
    elapsed_ns: AtomicU64,
}

impl Clock {
    /// The system's wall clock and monotonic clock.
    pub fn system() -> Self {
        Clock(None)
    }

    /// A clock standing at `wall_start_ns` (ns since the Unix epoch) until [`Clock::advance`] moves it.
    pub fn manual(wall_start_ns: u64) -> Self {
        let manual = Manual { start: Instant::now(), wall_start_ns, elapsed_ns: AtomicU64::new(0) };
        Clock(Some(Arc::new(manual)))
    }

    /// Moves a manual clock (and every clone of it) forward by `by`; the system's clock moves on its own, so
    /// this does nothing to it.
    pub fn advance(&self, by: Duration) {
        if let Some(m) = &self.0 {
            m.elapsed_ns.fetch_add(u64::try_from(by.as_nanos()).unwrap_or(u64::MAX), Ordering::Relaxed);
        }
    }

    /// Nanoseconds since the Unix epoch, now.
    pub fn wall_ns(&self) -> u64 {
        match &self.0 {
            None => SystemTime::now().duration_since(UNIX_EPOCH).map(|d| d.as_nanos() as u64).unwrap_or(0),
            Some(m) => m.wall_start_ns + m.elapsed_ns.load(Ordering::Relaxed),
        }
    }

    /// The monotonic instant now.
    pub fn now(&self) -> Instant {
        match &self.0 {
            None => Instant::now(),
            Some(m) => m.start + Duration::from_nanos(m.elapsed_ns.load(Ordering::Relaxed)),
        }
    }

    /// The time since `earlier` on this clock (zero if `earlier` is later).
    pub fn since(&self, earlier: Instant) -> Duration {
        self.now().saturating_duration_since(earlier)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_manual_clock_moves_only_when_told_and_its_clones_with_it() {
        let clock = Clock::manual(1_000);
        let (t0, clone) = (clock.now(), clock.clone());
        assert_eq!((clock.wall_ns(), clock.since(t0)), (1_000, Duration::ZERO));
        clone.advance(Duration::from_millis(1500));
        assert_eq!((clock.wall_ns(), clock.since(t0)), (1_500_001_000, Duration::from_millis(1500)));
    }
}
