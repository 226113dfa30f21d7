//! A rig worker's status, once per `status_period_s`: its pipeline's counts and latency, its club now (name and
//! club file SHA-256), and the health of each edge (simulator, launch monitor, mocap input, comparisons, live
//! view, bay screen), published and recorded.

use std::sync::atomic::Ordering;

use super::sinks::{self, StatusInputs};
use super::Worker;
use crate::daemon::bridges::open_connect::SimulatorClient;
use crate::daemon::bridges::web::WebStatusSource;
use crate::wire;

impl Worker {
    pub(super) fn publish_status(&mut self) -> wire::StatusMessage {
        // The pipeline is out of its slot only while it runs a sample, never when the status is made.
        let no_counts = crate::pipeline::Counts::default();
        let inputs = StatusInputs {
            counts: self.pipeline.as_ref().map_or(&no_counts, |p| &p.counts),
            queue_dropped: self.queue_dropped.load(Ordering::Relaxed),
            latency: &self.latency,
            uptime_s: self.clock.since(self.started).as_secs_f64(),
            t_ns: self.clock.wall_ns(),
            unknown_rig_samples: self.unknown.load(Ordering::Relaxed),
            rejected_not_recorded: self.budget.refused,
            recorder_error: self.sinks.recorder().error(),
        };
        let mut status = sinks::status_message(&self.rig, inputs, self.sinks.recorder().dropped());
        status.simulator = self.simulator.as_ref().map(SimulatorClient::status);
        status.launch_monitor = self.launch_monitor.as_ref().and_then(|s| s.lock().ok().map(|s| s.clone()));
        status.input = self.input.lock().ok().and_then(|s| s.as_ref().map(|s| s.status()));
        status.comparison = Some(self.pairer.status());
        status.live_view = self.live_view.as_ref().map(|v| v.status());
        status.web = self.web.as_ref().map(WebStatusSource::status);
        status.club = self.pipeline.as_ref().map(|p| p.club_ref());
        self.sinks.status(&status);
        status
    }
}
