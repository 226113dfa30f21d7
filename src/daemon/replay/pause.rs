//! Pausing a replay, as rosbag2's `play` does (`--start-paused`, space to pause and resume): a shared switch that
//! whoever controls the replay (a terminal's keys, lines on stdin) flips, and that the replay checks before each
//! sample. A paused replay sends nothing and its pace (`--rate`) resumes where it stopped.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// The switch a replay checks before each sample.
#[derive(Debug, Default)]
pub struct PauseControl {
    paused: AtomicBool,
    /// The capture time (ns) of the sample the replay is at, for messages such as "paused at 12.3 s".
    position_ns: AtomicU64,
    /// The capture time of the replay's first sample (ns).
    first_ns: AtomicU64,
}

/// How often a paused replay looks at the switch.
const POLL: Duration = Duration::from_millis(10);

impl PauseControl {
    /// A switch, paused or running.
    pub fn new(paused: bool) -> Self {
        PauseControl { paused: AtomicBool::new(paused), ..Default::default() }
    }

    pub fn is_paused(&self) -> bool {
        self.paused.load(Ordering::Acquire)
    }

    /// Pauses (`true`) or resumes; whether that changed anything.
    pub fn set(&self, paused: bool) -> bool {
        self.paused.swap(paused, Ordering::AcqRel) != paused
    }

    /// Pauses a running replay or resumes a paused one; whether it is paused now.
    pub fn toggle(&self) -> bool {
        !self.paused.fetch_xor(true, Ordering::AcqRel)
    }

    /// Capture time from the replay's first sample to the sample it is at (s).
    pub fn position_s(&self) -> f64 {
        let (at, first) = (self.position_ns.load(Ordering::Relaxed), self.first_ns.load(Ordering::Relaxed));
        at.saturating_sub(first) as f64 * 1e-9
    }

    /// Called by the replay before the sample at `t_ns`: waits while paused and returns how long it waited.
    pub async fn checkpoint(&self, t_ns: u64) -> Duration {
        if self.first_ns.load(Ordering::Relaxed) == 0 {
            self.first_ns.store(t_ns, Ordering::Relaxed);
        }
        self.position_ns.store(t_ns, Ordering::Relaxed);
        if !self.is_paused() {
            return Duration::ZERO;
        }
        let since = Instant::now();
        while self.is_paused() {
            tokio::time::sleep(POLL).await;
        }
        since.elapsed()
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use std::sync::Arc;

    #[test]
    fn toggles_and_sets() {
        let p = PauseControl::new(true);
        assert!(p.is_paused());
        assert!(!p.toggle());
        assert!(p.toggle());
        assert!(!p.set(true), "already paused");
        assert!(p.set(false));
        assert!(!p.is_paused());
    }

    /// A paused checkpoint returns only once resumed, and says how long it waited.
    #[tokio::test]
    async fn a_paused_checkpoint_waits_for_resume() {
        let p = Arc::new(PauseControl::new(true));
        let q = p.clone();
        let resume = tokio::spawn(async move {
            tokio::time::sleep(Duration::from_millis(100)).await;
            q.set(false);
        });
        let waited = p.checkpoint(5_000_000_000).await;
        resume.await.unwrap();
        assert!(waited >= Duration::from_millis(90), "{waited:?}");
        assert_eq!(p.checkpoint(7_500_000_000).await, Duration::ZERO);
        assert!((p.position_s() - 2.5).abs() < 1e-12);
    }
}
