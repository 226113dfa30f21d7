//! The rig worker's queue. Clubhead samples come from zenoh (`mocap/<rig>/clubhead`, JSON) or from the rig's own
//! motion-capture client (`[rig.input]`, decoded); measured launches (`lm/<rig>/launch`), session labels
//! (`golf/<rig>/session`), shot exclusions (`golf/<rig>/exclude`), a synthetic rig's truth (`sim/<rig>/truth`),
//! a tracked ball (`mocap/<rig>/ball`) and a loaded club (`golf/<rig>/club`) join it behind the samples that came
//! before them, so each is handled in order by the rig's one worker.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::SyncSender;
use std::sync::Arc;

use crate::daemon::clock::Clock;
use crate::daemon::DaemonError;
use crate::wire::{BallSampleMsg, ClubheadSampleMsg};

/// What arrived, with the payload of its kind.
pub(super) enum Arrival {
    /// A clubhead sample as zenoh delivered it (`mocap/<rig>/clubhead`): JSON, with its encoding.
    Sample { payload: Vec<u8>, encoding: String },
    /// A clubhead sample decoded by the rig's motion-capture client (`[rig.input]`).
    DecodedSample(Box<ClubheadSampleMsg>),
    /// A measured launch (`lm/<rig>/launch`).
    Measured(Vec<u8>),
    /// Session labels (`golf/<rig>/session`).
    Labels(Vec<u8>),
    /// A synthetic rig's truth (`sim/<rig>/truth`).
    Truth(Vec<u8>),
    /// A club put (`golf/<rig>/club`), loaded and ready.
    Club(Box<crate::pipeline::ClubSwitch>),
    /// A tracked ball's sample as zenoh delivered it (`mocap/<rig>/ball`).
    Ball(Vec<u8>),
    /// A tracked ball's sample decoded by the rig's motion-capture client (`[rig.input] ball_body`).
    DecodedBall(BallSampleMsg),
    /// A shot left out of the session or taken back (`golf/<rig>/exclude`).
    Exclusion(Vec<u8>),
}

/// When something arrived (on the daemon's [`Clock`]): the instant its latency is measured from, and its recording's log time.
#[derive(Debug, Clone, Copy)]
pub(super) struct Stamp {
    pub(super) received: std::time::Instant,
    pub(super) log_time_ns: u64,
}

/// An arrival in the rig's queue, with when it arrived.
pub(super) struct Incoming {
    pub(super) at: Stamp,
    pub(super) arrival: Arrival,
}

impl Incoming {
    /// Arrived now, on `clock`.
    pub(super) fn now(clock: &Clock, arrival: Arrival) -> Self {
        Incoming { at: Stamp { received: clock.now(), log_time_ns: clock.wall_ns() }, arrival }
    }
}

/// Subscribes to `key`; each payload joins the rig's queue as `kind` makes it (a full queue is counted in
/// `dropped`).
pub(super) async fn subscribe(
    session: &zenoh::Session,
    key: String,
    kind: fn(Vec<u8>) -> Arrival,
    (tx, dropped): (SyncSender<Incoming>, Arc<AtomicU64>),
    clock: Clock,
) -> Result<zenoh::pubsub::Subscriber<()>, DaemonError> {
    session
        .declare_subscriber(key)
        .callback(move |sample| {
            let incoming = Incoming::now(&clock, kind(sample.payload().to_bytes().into_owned()));
            if tx.try_send(incoming).is_err() {
                dropped.fetch_add(1, Ordering::Relaxed);
            }
        })
        .await
        .map_err(DaemonError::zenoh)
}
