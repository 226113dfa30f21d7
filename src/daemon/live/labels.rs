//! A rig worker's session labels: each put on `golf/<rig>/session` joins the rig's queue behind the samples
//! before it, is recorded, and labels the shots after it (a bad put is logged and changes nothing).

use super::{Incoming, Worker};
use crate::wire::{keys, ShotLabels};

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
