//! A rig worker's tracked ball: each sample on `mocap/<rig>/ball` joins the rig's queue behind the clubhead
//! samples before it, is recorded, and moves the ball position of the rig's next impact when the ball is at rest
//! (`kinematics::ball_tracker`). A payload that is not a ball sample is logged and changes nothing.

use super::{Incoming, Worker};
use crate::wire::{keys, BallSampleMsg};

impl Worker {
    pub(super) fn on_ball(&mut self, incoming: Incoming) {
        let msg = match BallSampleMsg::parse(&incoming.payload) {
            Ok(m) => m,
            Err(e) => {
                let key = keys::ball(&self.rig);
                return self.warn("bad_ball", || format!("sample on {key} refused: {e}"));
            }
        };
        self.sinks.ball(incoming.log_time_ns, msg.t_ns, incoming.payload);
        let position = (!msg.occluded).then_some(msg.position_m);
        if let Some(p) = self.pipeline.as_mut() {
            if let Ok(true) = p.on_ball(position) {
                let used = p.ball_used().position_m;
                tracing::debug!("rig {}: ball at rest at {used:?} (world, m)", self.rig);
            }
        }
    }
}
