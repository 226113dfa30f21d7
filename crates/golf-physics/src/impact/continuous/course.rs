//! A continuous run in the seam's terms: its contact time and peak force, and its trace by column name
//! ([`crate::impact::report`]).

use super::assembly::{ContinuousResult, TracePoint};
use crate::impact::report::{Course, Fields, ModelRun, RunOptions, Trace, Value};

impl TracePoint {
    /// The point's values by name, as `predict --trace` writes them.
    pub fn fields(&self) -> Fields {
        Fields(vec![
            ("t_us", self.t_us.into()),
            ("normal_force_n", self.normal_force_n.into()),
            ("tangential_force_n", self.tangential_force_n.into()),
            ("ball_spin_rpm", self.ball_spin_rpm.into()),
            ("cover_spin_rpm", self.cover_spin_rpm.into()),
            ("compression_mm", self.compression_mm.into()),
            ("stuck_rings", self.stuck_rings.map_or(Value::Absent, |n| Value::Count(n as u64))),
        ])
    }
}

impl ContinuousResult {
    /// The run: no report on the wire (the launch says it all live); the course when `options` ask for one.
    pub fn into_run(self, options: &RunOptions) -> ModelRun {
        let course = (options.trace_every > 0).then(|| Course {
            summary: Fields(vec![
                ("contact_time_us", (self.contact_time_s * 1e6).into()),
                ("peak_normal_force_n", self.peak_normal_force_n.into()),
            ]),
            trace: Trace(self.trace.iter().map(TracePoint::fields).collect()),
        });
        ModelRun { launch: self.launch, report: None, course }
    }
}
