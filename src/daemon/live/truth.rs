//! A rig worker's synthetic truth: what `impactd sim` really swung (`sim/<rig>/truth`) is recorded beside the
//! predictions, so a session made with the synthetic rig can be scored afterwards (`impactd compare FILE.mcap
//! --models ...` pairs each prediction with the truth of its impact).

use super::{Stamp, Worker};
use crate::wire::TruthMessage;

impl Worker {
    /// A synthetic rig's truth: recorded as it arrived when it is one (a bad payload is logged, not recorded).
    pub(super) fn on_truth(&mut self, at: Stamp, payload: Vec<u8>) {
        match serde_json::from_slice::<TruthMessage>(&payload) {
            Ok(t) => self.sinks.truth(at.log_time_ns, t.t_impact_ns, payload),
            Err(e) => self.warn("bad_truth", || format!("truth refused: {e}")),
        }
    }
}
