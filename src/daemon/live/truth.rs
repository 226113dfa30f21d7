//! A rig worker's synthetic truth: what `impactd sim` really swung (`sim/<rig>/truth`) is recorded beside the
//! predictions, so a session made with the synthetic rig can be scored afterwards (`impactd compare FILE.mcap
//! --models ...` pairs each prediction with the truth of its impact).

use super::{Incoming, Worker};
use crate::wire::TruthMessage;

impl Worker {
    /// A synthetic rig's truth: recorded as it arrived when it is one (a bad payload is logged, not recorded).
    pub(super) fn on_truth(&mut self, incoming: Incoming) {
        match serde_json::from_slice::<TruthMessage>(&incoming.payload) {
            Ok(t) => self.sinks.truth(incoming.log_time_ns, t.t_impact_ns, incoming.payload),
            Err(e) => self.warn("bad_truth", || format!("truth refused: {e}")),
        }
    }
}
