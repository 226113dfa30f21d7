//! A rig worker's synthetic truth: what `impactd sim` really swung (`sim/<rig>/truth`) is recorded beside the
//! predictions, so a session made with the synthetic rig can be scored afterwards (`impactd compare FILE.mcap
//! --models ...` pairs each prediction with the truth of its impact).

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::SyncSender;
use std::sync::Arc;
use std::time::Instant;

use super::{Incoming, InputKind, Worker};
use crate::daemon::{wall_ns, DaemonError};
use crate::wire::{keys, TruthMessage};

/// Subscribes to `sim/<rig>/truth`; each payload joins the rig's queue (a full queue is counted in `dropped`).
pub(super) async fn subscribe(
    session: &zenoh::Session,
    rig: &str,
    tx: SyncSender<Incoming>,
    dropped: Arc<AtomicU64>,
) -> Result<zenoh::pubsub::Subscriber<()>, DaemonError> {
    session
        .declare_subscriber(keys::truth(rig))
        .callback(move |sample| {
            let incoming = Incoming {
                kind: InputKind::Truth,
                received: Instant::now(),
                log_time_ns: wall_ns(),
                payload: sample.payload().to_bytes().into_owned(),
                encoding: sample.encoding().to_string(),
            };
            if tx.try_send(incoming).is_err() {
                dropped.fetch_add(1, Ordering::Relaxed);
            }
        })
        .await
        .map_err(DaemonError::zenoh)
}

impl Worker {
    /// A synthetic rig's truth: recorded as it arrived when it is one (a bad payload is logged, not recorded).
    pub(super) fn on_truth(&mut self, incoming: Incoming) {
        match serde_json::from_slice::<TruthMessage>(&incoming.payload) {
            Ok(t) => self.sinks.truth(incoming.log_time_ns, t.t_impact_ns, incoming.payload),
            Err(e) => self.warn("bad_truth", || format!("truth refused: {e}")),
        }
    }
}
