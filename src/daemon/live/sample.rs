//! A rig worker's clubhead samples: a zenoh payload is parsed and checked (a bad one is counted, logged and
//! recorded beside its reason, within the budget); a decoded sample from the rig's own client is used as it is.
//! Either way the sample's JSON is recorded as it arrived (a decoded one as the bridge would have sent it, so a
//! recording and its replay are the same whichever way the samples came), then the pipeline runs it.

use super::sinks;
use super::{Stamp, Worker};
use crate::daemon::stats::REJECTED_KEEP_BYTES;
use crate::wire::{self, ClubheadSampleMsg};

/// Whether JSON carries every number of `msg` as it is: a NaN or an infinity becomes `null`, which a parse
/// refuses (or, in an optional field, reads as absent).
fn json_exact(msg: &ClubheadSampleMsg) -> bool {
    let q = &msg.orientation;
    let optional = [msg.fit_residual_m, msg.system_latency_us];
    msg.position_m.iter().chain(&[q.x, q.y, q.z, q.w]).all(|v| v.is_finite())
        && optional.iter().flatten().all(|v| v.is_finite())
}

impl Worker {
    /// A sample's payload from zenoh: parsed and checked, then run.
    pub(super) fn on_sample(&mut self, at: Stamp, payload: Vec<u8>, encoding: &str) {
        let msg = match wire::parse_sample(&self.rig, &payload, encoding) {
            Ok(m) => m,
            Err(e) => {
                if let Some(p) = self.pipeline.as_mut() {
                    p.counts.rejected.add(e.rejection());
                    p.counts.samples += 1;
                }
                let bytes = payload.len();
                self.warn(e.key(), || format!("rejected sample: {e}"));
                // The raw payload goes to the recording beside the reason, within the budget; beyond it the
                // payload is counted (status `rejected_not_recorded`), so a flood cannot fill the disk.
                let keep = &payload[..bytes.min(REJECTED_KEEP_BYTES)];
                if !self.sinks.recorder().enabled() || !self.budget.allow(keep.len()) {
                    return;
                }
                let rejected = wire::RejectedInput {
                    reason: e.to_string(),
                    bytes,
                    payload: String::from_utf8_lossy(keep).into_owned(),
                };
                self.sinks.rejected(at.log_time_ns, &rejected);
                return;
            }
        };
        self.sinks.sample(at.log_time_ns, msg.t_ns, payload);
        self.run_sample(at, &msg);
    }

    /// A sample decoded by the rig's client: recorded as the JSON a bridge would send, then run. One whose numbers
    /// JSON cannot carry goes the way of its JSON (refused as a bridge's would be).
    pub(super) fn on_decoded_sample(&mut self, at: Stamp, msg: &ClubheadSampleMsg) {
        if !json_exact(msg) {
            let payload = serde_json::to_vec(msg).unwrap_or_default();
            return self.on_sample(at, payload, &wire::MessageType::ClubheadSample.encoding());
        }
        if self.sinks.recorder().enabled() {
            self.sinks.sample(at.log_time_ns, msg.t_ns, serde_json::to_vec(msg).unwrap_or_default());
        }
        self.run_sample(at, msg);
    }

    /// Runs an accepted sample through the pipeline, publishing its events as they come.
    fn run_sample(&mut self, at: Stamp, msg: &ClubheadSampleMsg) {
        let rig = self.rig.clone();
        let sample = msg.to_sample();
        let mut any_event = false;
        let received = at.received;
        // Out of its slot while it runs the sample (its events are published as they come, by `self`); it is
        // only ever taken here, so it is always back between samples.
        let Some(mut pipeline) = self.pipeline.take() else { return };
        pipeline.on_body_sample_with(msg.body.as_deref(), &sample, &mut |event| {
            any_event = true;
            self.on_event(&rig, event, received);
        });
        self.pipeline = Some(pipeline);
        // A shot whose every model refused still has its impact published (a launch releases it sooner).
        self.release_impact();
        if self.sinks.recorder().enabled() && !sample.occluded && !any_event {
            if let Some(world_from_club) = self.pipeline.as_ref().and_then(|p| sinks::world_from_club(p, &sample)) {
                self.sinks.club_pose(sample.t_ns, at.log_time_ns, world_from_club);
            }
        }
    }
}
