//! The connections of one TCP surface (an Open Connect listener, the Foxglove live view), bounded: at most
//! `max_connections` open at once, and at the cap the connection idle the longest is closed to admit the
//! newcomer, so an honest peer that arrives behind a crowd of idle ones is answered at once and the daemon's
//! descriptors (zenoh's, the mocap inputs') are never starved. A connection that says nothing useful within
//! the handshake timeout, or then goes quiet for the idle timeout, is closed. Rejections are counted by kind
//! and logged at most once a second per kind.
//!
//! Written here rather than taken from a crate: tower's limits refuse the newcomer at the cap (the opposite of
//! what keeps an honest connector served) and would bring an HTTP service stack for two raw TCP loops.

use std::collections::{BTreeMap, HashMap};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use tokio::sync::Notify;

use crate::daemon::stats::RateLimiter;

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

/// Why a connection was refused, cut or a message rejected: the keys of the `rejected` counts.
pub mod kind {
    pub const EVICTED: &str = "evicted_at_cap";
    pub const HANDSHAKE_TIMEOUT: &str = "handshake_timeout";
    pub const IDLE_TIMEOUT: &str = "idle_timeout";
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
    rejected: BTreeMap<String, u64>,
    limiter: RateLimiter,
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
    pub fn kind(self) -> &'static str {
        match self {
            Cut::Evicted => kind::EVICTED,
            Cut::HandshakeTimeout => kind::HANDSHAKE_TIMEOUT,
            Cut::IdleTimeout => kind::IDLE_TIMEOUT,
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
                rejected: BTreeMap::new(),
                limiter: RateLimiter::new(Duration::from_secs(1)),
            })),
        }
    }

    pub fn limits(&self) -> PeerLimits {
        self.limits
    }

    fn now_ms(&self) -> u64 {
        u64::try_from(self.started.elapsed().as_millis()).unwrap_or(u64::MAX)
    }

    /// Admits a connection, closing the longest-idle one first when the surface is at its cap.
    pub fn admit(&self, peer: &str) -> PeerSlot {
        let state = Arc::new(PeerState {
            last_active_ms: AtomicU64::new(self.now_ms()),
            greeted: AtomicBool::new(false),
            closed: Notify::new(),
        });
        let mut evicted = false;
        let id = match self.inner.lock() {
            Ok(mut inner) => {
                while inner.open.len() >= self.limits.max_connections.max(1) {
                    let oldest = inner
                        .open
                        .iter()
                        .min_by_key(|(id, s)| (s.last_active_ms.load(Ordering::Relaxed), **id))
                        .map(|(id, _)| *id);
                    let Some(oldest) = oldest else { break };
                    if let Some(s) = inner.open.remove(&oldest) {
                        // A stored permit: the connection sees it even if it is not waiting right now.
                        s.closed.notify_one();
                        evicted = true;
                    }
                }
                inner.next_id += 1;
                let id = inner.next_id;
                inner.open.insert(id, state.clone());
                id
            }
            Err(_) => 0,
        };
        if evicted {
            self.reject(Cut::Evicted.kind(), || {
                format!(
                    "at the cap of {} connections: the longest idle was closed for {peer}",
                    self.limits.max_connections
                )
            });
        }
        PeerSlot { id, state, peers: self.clone(), connected: Instant::now() }
    }

    /// Counts a rejection of this kind and logs it, at most once a second per kind.
    pub fn reject(&self, kind: &str, message: impl FnOnce() -> String) {
        let Ok(mut inner) = self.inner.lock() else { return };
        *inner.rejected.entry(kind.to_string()).or_default() += 1;
        if let Some(n) = inner.limiter.allow(kind) {
            let what = &self.what;
            if n > 0 {
                tracing::warn!("{what}: {} ({n} more {kind} since the last)", message());
            } else {
                tracing::warn!("{what}: {}", message());
            }
        }
    }

    /// Connections open now.
    pub fn open(&self) -> usize {
        self.inner.lock().map(|i| i.open.len()).unwrap_or(0)
    }

    /// Rejections so far, by kind.
    pub fn rejected(&self) -> BTreeMap<String, u64> {
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
        assert_eq!(peers.rejected().get(kind::EVICTED), Some(&1));
        drop(b);
        assert_eq!(peers.open(), 2);
        drop((a, c));
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
