//! A rig worker's session labels: each put on `golf/<rig>/session` joins the rig's queue behind the samples
//! before it, is recorded, and labels the shots after it (a bad put is logged and changes nothing). A put on
//! `golf/<rig>/exclude` is recorded, so `impactd session` leaves the shot out. Each is logged at most once a
//! second per kind: a flood of puts, from a page or a program, is counted in the kind's next line.

use super::{Stamp, Worker};
use crate::wire::{keys, ShotExclusion, ShotLabels};

impl Worker {
    /// New labels for the shots from now on: recorded, then set on the pipeline.
    pub(super) fn on_labels(&mut self, at: Stamp, payload: &[u8]) {
        let labels = match ShotLabels::parse(payload) {
            Ok(l) => l,
            Err(e) => {
                let key = keys::session(&self.rig);
                return self.warn("bad_labels", || format!("put on {key} refused: {e}"));
            }
        };
        self.sinks.labels(at.log_time_ns, &labels);
        self.info("labels", || format!("shots labelled {}", serde_json::to_string(&labels).unwrap_or_default()));
        if let Some(p) = self.pipeline.as_mut() {
            p.set_labels(labels);
        }
    }

    /// A shot left out of the session (or taken back): recorded as it came, once it parses.
    pub(super) fn on_exclusion(&mut self, at: Stamp, payload: &[u8]) {
        match ShotExclusion::parse(payload) {
            Ok(x) => {
                self.sinks.exclusion(at.log_time_ns, &x);
                let what = if x.excluded { "left out of" } else { "taken back into" };
                self.info("exclusion", || format!("shot {} {what} the session", x.shot));
            }
            Err(e) => {
                let key = keys::exclude(&self.rig);
                self.warn("bad_exclusion", || format!("put on {key} refused: {e}"));
            }
        }
    }
}
