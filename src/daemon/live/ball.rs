//! A rig worker's tracked ball: each sample on `mocap/<rig>/ball` joins the rig's queue behind the clubhead
//! samples before it, is recorded, and moves the ball position of the rig's next impact when the ball is at rest
//! (`kinematics::ball_tracker`). A payload that is not a ball sample is logged and changes nothing.

use super::{Stamp, Worker};
use crate::wire::{keys, BallSampleMsg};

impl Worker {
    /// A ball sample's payload from zenoh: parsed and checked, recorded as it came, then used.
    pub(super) fn on_ball(&mut self, at: Stamp, payload: Vec<u8>) {
        let msg = match BallSampleMsg::parse(&payload) {
            Ok(m) => m,
            Err(e) => return self.refuse_ball(e),
        };
        self.sinks.ball(at.log_time_ns, msg.t_ns, payload);
        self.use_ball(&msg);
    }

    /// A ball sample decoded by the rig's client: checked as a payload is, recorded as the JSON a bridge would
    /// send, then used. One whose numbers JSON cannot carry goes the way of its JSON.
    pub(super) fn on_decoded_ball(&mut self, at: Stamp, msg: BallSampleMsg) {
        if msg.position_m.iter().any(|v| !v.is_finite()) {
            return self.on_ball(at, serde_json::to_vec(&msg).unwrap_or_default());
        }
        let msg = match msg.checked() {
            Ok(m) => m,
            Err(e) => return self.refuse_ball(e),
        };
        if self.sinks.recorder().enabled() {
            self.sinks.ball(at.log_time_ns, msg.t_ns, serde_json::to_vec(&msg).unwrap_or_default());
        }
        self.use_ball(&msg);
    }

    fn refuse_ball(&mut self, e: String) {
        let key = keys::ball(&self.rig);
        self.warn("bad_ball", || format!("sample on {key} refused: {e}"));
    }

    fn use_ball(&mut self, msg: &BallSampleMsg) {
        let position = (!msg.occluded).then_some(msg.position_m);
        if let Some(p) = self.pipeline.as_mut() {
            if let Ok(true) = p.on_ball(position) {
                let used = p.ball_used().position_m;
                tracing::debug!("rig {}: ball at rest at {used:?} (world, m)", self.rig);
            }
        }
    }
}
