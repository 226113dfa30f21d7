//! What the NatNet and QTM clients' threads share: the counts behind each rig's `MocapInputStatus`, the sample
//! hand-off, the polling period and the reconnection back-off.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Mutex, MutexGuard};
use std::time::{Duration, Instant};

use super::counters::{InputRejection, Reconnect, Tally};
use crate::daemon::peer_log::PeerLog;
use crate::daemon::stats::LatencyWindow;
use crate::mocap::track::BodySample;
use crate::wire::{ConnectionState, MocapInputStatus};

/// How long a blocking socket read waits before looking at the stop flag: a client stops within this.
pub const POLL: Duration = Duration::from_millis(100);
/// Reconnection back-off: from the first to the last, doubling.
pub const BACKOFF_FIRST: Duration = Duration::from_millis(250);
pub const BACKOFF_LAST: Duration = Duration::from_secs(4);
/// A connected server silent this long is connected to again (every protocol's client).
pub const QUIET: Duration = Duration::from_secs(3);

/// Hands a body's sample on (to a rig's queue, or to zenoh); `route` indexes the client's bodies.
pub type Deliver = Box<dyn FnMut(usize, &BodySample, Instant) + Send>;

/// Connection-wide state and counts.
#[derive(Debug)]
pub struct Conn {
    pub state: ConnectionState,
    pub connects: u64,
    /// Sessions the client ended itself, by reason (`quiet`, `undecodable`).
    pub reconnects: Tally<Reconnect>,
    pub server_version: Option<String>,
    /// Packets refused, by reason.
    pub rejected: Tally<InputRejection>,
    pub last_error: Option<String>,
    pub exposure_to_transmit_us: LatencyWindow,
}

impl Conn {
    pub fn reject(&mut self, reason: InputRejection) {
        self.rejected.add(reason);
    }

    /// The client ends the session itself for `reason` and connects again; said in `last_error`.
    pub fn reconnect(&mut self, reason: Reconnect, why: String) {
        self.reconnects.add(reason);
        self.state = ConnectionState::Disconnected;
        self.last_error = Some(why);
    }
}

/// The counts a client keeps; one [`MocapInputStatus`] per body (route).
pub struct Shared {
    pub conn: Conn,
    pub bodies: Vec<MocapInputStatus>,
    pub deliver: Deliver,
    /// The lines the server's answers drive (a body not in its model): one a second per kind, names cut.
    pub log: PeerLog,
}

/// Locks the counts, whatever a panicking holder left (they are counts: still worth reporting).
pub fn lock(shared: &Mutex<Shared>) -> MutexGuard<'_, Shared> {
    shared.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// Sleeps up to `d`, waking early when `stop` is set; false when stopped.
pub fn sleep_unless_stopped(d: Duration, stop: &AtomicBool) -> bool {
    let end = Instant::now() + d;
    while !stop.load(Ordering::Relaxed) {
        let now = Instant::now();
        if now >= end {
            return true;
        }
        std::thread::sleep((end - now).min(POLL));
    }
    false
}
