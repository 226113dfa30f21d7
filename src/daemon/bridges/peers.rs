//! The connections of one TCP surface (an Open Connect listener, the Foxglove live view, the bay screen),
//! bounded: at most `max_connections` open at once. At the cap an unfinished handshake (a connection that has
//! said nothing useful yet, the one connected longest ago) is closed first to admit the newcomer, else the
//! connection idle the longest, so an honest peer that arrives behind a crowd of idle ones is answered at once and
//! the daemon's descriptors (zenoh's, the mocap inputs') are never starved; a surface whose clients retry (the bay
//! screen's pages) may instead refuse the newcomer when every connection is live ([`Peers::admit_unless_full`]),
//! so live clients are not pushed out in turn. A connection that says nothing useful within the handshake
//! timeout, or then goes quiet for the idle timeout, is closed. Rejections are counted by kind and logged at most
//! once a second per kind ([`PeerLog`]).
//!
//! Written here rather than taken from a crate: tower's limits refuse the newcomer at the cap (the opposite of
//! what keeps an honest connector served) and would bring an HTTP service stack for two raw TCP loops.

use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use tokio::sync::Notify;

use super::peer_rejection::{CounterKind, PeerRejection, Tally};
use crate::daemon::peer_log::PeerLog;

/// The bounds of one surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PeerLimits {
    /// Connections open at once; at the cap the longest-idle one is closed for a newcomer.
    pub max_connections: usize,
    /// Time from connecting to the first useful message (a handshake, a first shot or heartbeat).
    pub handshake: Duration,
    /// Time without a useful message after which a connection is closed.
    pub idle: Duration,
}

/// One open connection's shared state.
struct PeerState {
    /// Milliseconds since the surface started, at the last useful message (or the connection).
    last_active_ms: AtomicU64,
    /// Whether it has sent a useful message yet.
    greeted: AtomicBool,
    closed: Notify,
}

struct Inner {
    next_id: u64,
    open: HashMap<u64, Arc<PeerState>>,
    rejected: Tally<PeerRejection>,
    log: PeerLog,
}

/// The connections of one surface and their rejection counts.
#[derive(Clone)]
pub struct Peers {
    /// What is being served, for the log: `rig bay1: Open Connect`, `Foxglove live view`.
    what: Arc<str>,
    limits: PeerLimits,
    started: Instant,
    inner: Arc<Mutex<Inner>>,
}

/// An admitted connection; dropping it frees its place.
pub struct PeerSlot {
    id: u64,
    state: Arc<PeerState>,
    peers: Peers,
    connected: Instant,
}

/// How a connection's wait ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Cut {
    /// Closed for a newcomer at the cap.
    Evicted,
    HandshakeTimeout,
    IdleTimeout,
}

impl Cut {
    pub fn kind(self) -> PeerRejection {
        match self {
            Cut::Evicted => PeerRejection::EvictedAtCap,
            Cut::HandshakeTimeout => PeerRejection::HandshakeTimeout,
            Cut::IdleTimeout => PeerRejection::IdleTimeout,
        }
    }
}

impl Peers {
    pub fn new(what: &str, limits: PeerLimits) -> Self {
        Peers {
            what: Arc::from(what),
            limits,
            started: Instant::now(),
            inner: Arc::new(Mutex::new(Inner {
                next_id: 0,
                open: HashMap::new(),
                rejected: Tally::default(),
                log: PeerLog::new(),
            })),
        }
    }

    pub fn limits(&self) -> PeerLimits {
        self.limits
    }

    fn now_ms(&self) -> u64 {
        u64::try_from(self.started.elapsed().as_millis()).unwrap_or(u64::MAX)
    }

    /// Admits a connection; at the cap it closes an unfinished handshake first (the one connected longest
    /// ago), else the connection idle the longest.
    pub fn admit(&self, peer: &str) -> PeerSlot {
        // Never refused: every open connection has been idle for at least zero.
        self.admit_within(peer, Duration::ZERO).unwrap_or_else(|| self.slot(0, self.state()))
    }

    /// Admits a connection; at the cap it closes an unfinished handshake first, else a connection idle for
    /// `stale` or more, else it refuses the newcomer (`None`, counted as `refused_at_cap`): a crowd of live
    /// connections is never thinned for one more (the bay screen's pages, which back off when refused).
    pub fn admit_unless_full(&self, peer: &str, stale: Duration) -> Option<PeerSlot> {
        self.admit_within(peer, stale)
    }

    fn admit_within(&self, peer: &str, stale: Duration) -> Option<PeerSlot> {
        let now_ms = self.now_ms();
        let stale_ms = u64::try_from(stale.as_millis()).unwrap_or(u64::MAX);
        let state = self.state();
        let mut evicted = None;
        let id = match self.inner.lock() {
            Ok(mut inner) => {
                while inner.open.len() >= self.limits.max_connections.max(1) {
                    let active = |s: &PeerState| s.last_active_ms.load(Ordering::Relaxed);
                    let unfinished = inner
                        .open
                        .iter()
                        .filter(|(_, s)| !s.greeted.load(Ordering::Relaxed))
                        .min_by_key(|(id, s)| (active(s), **id))
                        .map(|(id, _)| (*id, "an unfinished handshake"));
                    let idle = || {
                        inner
                            .open
                            .iter()
                            .filter(|(_, s)| now_ms.saturating_sub(active(s)) >= stale_ms)
                            .min_by_key(|(id, s)| (active(s), **id))
                            .map(|(id, _)| (*id, "the longest idle"))
                    };
                    let Some((victim, which)) = unfinished.or_else(idle) else { break };
                    if let Some(s) = inner.open.remove(&victim) {
                        // A stored permit: the connection sees it even if it is not waiting right now.
                        s.closed.notify_one();
                        evicted = Some(which);
                    }
                }
                if inner.open.len() >= self.limits.max_connections.max(1) {
                    None
                } else {
                    inner.next_id += 1;
                    let id = inner.next_id;
                    inner.open.insert(id, state.clone());
                    Some(id)
                }
            }
            Err(_) => Some(0),
        };
        let max = self.limits.max_connections;
        if let Some(which) = evicted {
            self.reject(Cut::Evicted.kind(), || {
                format!("at the cap of {max} connections: {which} was closed for {peer}")
            });
        }
        let Some(id) = id else {
            self.reject(PeerRejection::RefusedAtCap, || {
                format!("at the cap of {max} live connections: {peer} refused (it may retry)")
            });
            return None;
        };
        Some(self.slot(id, state))
    }

    fn state(&self) -> Arc<PeerState> {
        Arc::new(PeerState {
            last_active_ms: AtomicU64::new(self.now_ms()),
            greeted: AtomicBool::new(false),
            closed: Notify::new(),
        })
    }

    fn slot(&self, id: u64, state: Arc<PeerState>) -> PeerSlot {
        PeerSlot { id, state, peers: self.clone(), connected: Instant::now() }
    }

    /// Counts a rejection of this kind and logs it, at most once a second per kind.
    pub fn reject(&self, kind: PeerRejection, message: impl FnOnce() -> String) {
        let Ok(mut inner) = self.inner.lock() else { return };
        inner.rejected.add(kind);
        let what = &self.what;
        inner.log.warn(kind.wire_name(), || format!("{what}: {}", message()));
    }

    /// Logs a connection's news (a page connected), at most once a second per kind.
    pub fn info(&self, kind: &'static str, message: impl FnOnce() -> String) {
        let Ok(mut inner) = self.inner.lock() else { return };
        let what = &self.what;
        inner.log.info(kind, || format!("{what}: {}", message()));
    }

    /// Says what the log suppressed of floods that stopped (called every second by a surface with a clock).
    pub fn flush_log(&self) {
        if let Ok(mut inner) = self.inner.lock() {
            inner.log.flush();
        }
    }

    /// Connections open now.
    pub fn open(&self) -> usize {
        self.inner.lock().map(|i| i.open.len()).unwrap_or(0)
    }

    /// Rejections so far, by kind.
    pub fn rejected(&self) -> Tally<PeerRejection> {
        self.inner.lock().map(|i| i.rejected.clone()).unwrap_or_default()
    }
}

impl PeerSlot {
    /// Marks a useful message: the connection is greeted and no longer idle.
    pub fn touch(&self) {
        self.state.greeted.store(true, Ordering::Relaxed);
        self.state.last_active_ms.store(self.peers.now_ms(), Ordering::Relaxed);
    }

    /// The time left before the handshake or idle timeout.
    fn remaining(&self) -> (Duration, Cut) {
        let limits = self.peers.limits;
        if !self.state.greeted.load(Ordering::Relaxed) {
            return (limits.handshake.saturating_sub(self.connected.elapsed()), Cut::HandshakeTimeout);
        }
        let idle_ms = self.peers.now_ms().saturating_sub(self.state.last_active_ms.load(Ordering::Relaxed));
        (limits.idle.saturating_sub(Duration::from_millis(idle_ms)), Cut::IdleTimeout)
    }

    /// Completes when the connection must close: evicted at the cap, or a timeout. Cancel-safe: call it again
    /// in every `select!` round.
    pub async fn cut(&self) -> Cut {
        loop {
            let (left, cut) = self.remaining();
            if left.is_zero() {
                return cut;
            }
            tokio::select! {
                _ = self.state.closed.notified() => return Cut::Evicted,
                _ = tokio::time::sleep(left) => {}
            }
        }
    }

    /// Counts and logs the cut as a rejection of its kind.
    pub fn report(&self, cut: Cut, peer: &str) {
        let message = match cut {
            Cut::Evicted => return, // counted when the newcomer was admitted
            Cut::HandshakeTimeout => format!("{peer} closed: nothing useful within {:?}", self.peers.limits.handshake),
            Cut::IdleTimeout => format!("{peer} closed: idle for {:?}", self.peers.limits.idle),
        };
        self.peers.reject(cut.kind(), || message);
    }
}

impl Drop for PeerSlot {
    fn drop(&mut self) {
        if let Ok(mut inner) = self.peers.inner.lock() {
            inner.open.remove(&self.id);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn limits(max: usize) -> PeerLimits {
        PeerLimits { max_connections: max, handshake: Duration::from_millis(50), idle: Duration::from_millis(80) }
    }

    #[tokio::test]
    async fn at_the_cap_the_longest_idle_connection_goes() {
        let peers = Peers::new("test", limits(2));
        let a = peers.admit("a");
        tokio::time::sleep(Duration::from_millis(5)).await;
        let b = peers.admit("b");
        tokio::time::sleep(Duration::from_millis(5)).await;
        a.touch();
        let c = peers.admit("c");
        assert_eq!(peers.open(), 2);
        assert_eq!(b.cut().await, Cut::Evicted);
        assert_eq!(peers.rejected().get(PeerRejection::EvictedAtCap), 1);
        drop(b);
        assert_eq!(peers.open(), 2);
        drop((a, c));
        assert_eq!(peers.open(), 0);
    }

    #[tokio::test]
    async fn at_the_cap_an_unfinished_handshake_goes_first_and_live_connections_may_refuse_the_newcomer() {
        let peers = Peers::new("test", limits(2));
        let live = peers.admit("live");
        live.touch();
        tokio::time::sleep(Duration::from_millis(5)).await;
        // Connected later (so idle for less), but it has said nothing yet: it goes first.
        let head = peers.admit("slow head");
        let next = peers.admit("next");
        assert_eq!(head.cut().await, Cut::Evicted);
        next.touch();
        // Both live: a newcomer is refused rather than one of them closed...
        assert!(peers.admit_unless_full("third", Duration::from_secs(30)).is_none());
        assert_eq!(peers.rejected().get(PeerRejection::RefusedAtCap), 1);
        assert_eq!(peers.open(), 2);
        // ...unless one has been idle for the stale time.
        tokio::time::sleep(Duration::from_millis(10)).await;
        live.touch();
        let fourth = peers.admit_unless_full("fourth", Duration::from_millis(5)).expect("a stale one makes room");
        assert_eq!(next.cut().await, Cut::Evicted);
        assert_eq!(peers.rejected().get(PeerRejection::EvictedAtCap), 2);
        drop((live, head, next, fourth));
        assert_eq!(peers.open(), 0);
    }

    #[tokio::test]
    async fn silent_connections_time_out_and_active_ones_idle_out() {
        let peers = Peers::new("test", limits(4));
        let quiet = peers.admit("quiet");
        let t0 = Instant::now();
        assert_eq!(quiet.cut().await, Cut::HandshakeTimeout);
        assert!(t0.elapsed() >= Duration::from_millis(50));
        let talker = peers.admit("talker");
        talker.touch();
        let t0 = Instant::now();
        assert_eq!(talker.cut().await, Cut::IdleTimeout);
        assert!(t0.elapsed() >= Duration::from_millis(80));
    }
}
