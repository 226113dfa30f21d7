//! The rig worker's queue fed from zenoh: measured launches (`lm/<rig>/launch`), session labels
//! (`golf/<rig>/session`), shot exclusions (`golf/<rig>/exclude`), a synthetic rig's truth (`sim/<rig>/truth`)
//! and a tracked ball (`mocap/<rig>/ball`) join it behind the samples that came before them, so each is handled
//! in order by the rig's one worker.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::SyncSender;
use std::sync::Arc;
use std::time::Instant;

use crate::daemon::{wall_ns, DaemonError};

/// What a queued payload is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum InputKind {
    /// A clubhead sample (`mocap/<rig>/clubhead`).
    Sample,
    /// A measured launch (`lm/<rig>/launch`).
    Measured,
    /// Session labels (`golf/<rig>/session`).
    Labels,
    /// A synthetic rig's truth (`sim/<rig>/truth`).
    Truth,
    /// A club put (`golf/<rig>/club`), loaded and ready in `club`.
    Club,
    /// A tracked ball's sample (`mocap/<rig>/ball`).
    Ball,
    /// A shot left out of the session or taken back (`golf/<rig>/exclude`).
    Exclusion,
}

/// A payload in the rig's queue, with when it arrived.
pub(super) struct Incoming {
    pub(super) kind: InputKind,
    pub(super) received: Instant,
    pub(super) log_time_ns: u64,
    pub(super) payload: Vec<u8>,
    pub(super) encoding: String,
    /// A loaded club ([`InputKind::Club`]).
    pub(super) club: Option<Box<crate::pipeline::ClubSwitch>>,
}

/// Subscribes to `key`; each payload joins the rig's queue as `kind` (a full queue is counted in `dropped`).
pub(super) async fn subscribe(
    session: &zenoh::Session,
    key: String,
    kind: InputKind,
    tx: SyncSender<Incoming>,
    dropped: Arc<AtomicU64>,
) -> Result<zenoh::pubsub::Subscriber<()>, DaemonError> {
    session
        .declare_subscriber(key)
        .callback(move |sample| {
            let incoming = Incoming {
                kind,
                received: Instant::now(),
                log_time_ns: wall_ns(),
                payload: sample.payload().to_bytes().into_owned(),
                encoding: sample.encoding().to_string(),
                club: None,
            };
            if tx.try_send(incoming).is_err() {
                dropped.fetch_add(1, Ordering::Relaxed);
            }
        })
        .await
        .map_err(DaemonError::zenoh)
}
