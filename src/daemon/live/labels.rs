//! A rig worker's session labels: each put on `golf/<rig>/session` joins the rig's queue behind the samples
//! before it, is recorded, and labels the shots after it (a bad put is logged and changes nothing).

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::SyncSender;
use std::sync::Arc;
use std::time::Instant;

use super::{Incoming, InputKind, Worker};
use crate::daemon::{wall_ns, DaemonError};
use crate::wire::{keys, ShotLabels};

/// Subscribes to `golf/<rig>/session`; each payload joins the rig's queue (a full queue is counted in `dropped`).
pub(super) async fn subscribe(
    session: &zenoh::Session,
    rig: &str,
    tx: SyncSender<Incoming>,
    dropped: Arc<AtomicU64>,
) -> Result<zenoh::pubsub::Subscriber<()>, DaemonError> {
    session
        .declare_subscriber(keys::session(rig))
        .callback(move |sample| {
            let incoming = Incoming {
                kind: InputKind::Labels,
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
    /// New labels for the shots from now on: recorded, then set on the pipeline.
    pub(super) fn on_labels(&mut self, incoming: Incoming) {
        let labels = match ShotLabels::parse(&incoming.payload) {
            Ok(l) => l,
            Err(e) => {
                let key = keys::session(&self.rig);
                return self.warn("bad_labels", || format!("put on {key} refused: {e}"));
            }
        };
        self.sinks.labels(incoming.log_time_ns, &labels);
        tracing::info!("rig {}: shots labelled {}", self.rig, serde_json::to_string(&labels).unwrap_or_default());
        if let Some(p) = self.pipeline.as_mut() {
            p.set_labels(labels);
        }
    }
}
