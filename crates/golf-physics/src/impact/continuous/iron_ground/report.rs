//! The ground model's run in the seam's terms: its `ground` report (how the club met the turf, published with every
//! launch) and its trace of ground forces, face angle and loft by column name ([`crate::impact::report`]).

use super::{GroundResult, GroundTracePoint, Strike};
use crate::impact::continuous::ground::GroundPhase;
use crate::impact::report::{Course, Fields, ModelRun, Report, RunOptions, Trace};

/// The key the report is published under.
pub const GROUND_REPORT: &str = "ground";

impl Strike {
    /// The strike's name in the report (`thin`, `good`, `fat`, `teed`).
    pub fn as_str(self) -> &'static str {
        match self {
            Strike::Thin => "thin",
            Strike::Good => "good",
            Strike::Fat => "fat",
            Strike::Teed => "teed",
        }
    }
}

impl GroundPhase {
    /// The phase's name in traces (`clear`, `compression`, `divot`).
    pub fn as_str(self) -> &'static str {
        match self {
            GroundPhase::Clear => "clear",
            GroundPhase::Compression => "compression",
            GroundPhase::Divot => "divot",
        }
    }
}

impl GroundTracePoint {
    /// The point's values by name, as `predict --trace` writes them.
    pub fn fields(&self) -> Fields {
        Fields(vec![
            ("t_ms", self.t_ms.into()),
            ("sole_vertical_n", self.sole_vertical_n.into()),
            ("sole_horizontal_n", self.sole_horizontal_n.into()),
            ("face_horizontal_n", self.face_horizontal_n.into()),
            ("ground_vertical_n", self.ground_vertical_n.into()),
            ("ground_horizontal_n", self.ground_horizontal_n.into()),
            ("ball_normal_n", self.ball_normal_n.into()),
            ("face_angle_deg", self.face_angle_deg.into()),
            ("dynamic_loft_deg", self.dynamic_loft_deg.into()),
            ("phase", crate::impact::report::Value::Text(self.phase.as_str())),
        ])
    }
}

impl GroundResult {
    /// The `ground` report a prediction carries (names as on the wire, seed section 4.3).
    pub fn report(&self) -> Report {
        Report {
            key: GROUND_REPORT,
            fields: Fields(vec![
                ("strike", crate::impact::report::Value::Text(self.strike.as_str())),
                ("ground_contact_before_ball_ms", self.ground_contact_before_ball_ms.into()),
                ("club_speed_loss_mph", self.club_speed_loss_mph.into()),
                ("face_angle_change_deg", self.face_angle_change_deg.into()),
                ("dynamic_loft_change_deg", self.dynamic_loft_change_deg.into()),
                ("divot_depth_mm", self.divot_depth_mm.into()),
                ("divot_length_mm", self.divot_length_mm.into()),
                ("peak_ground_force_n", self.peak_ground_force_n.into()),
                ("ground_contact_ms", self.ground_contact_ms.into()),
                ("ball_contact_us", self.ball_contact_us.into()),
            ]),
        }
    }

    /// The run: the `ground` report, and the trace when `options` ask for one.
    pub fn into_run(self, options: &RunOptions) -> ModelRun {
        let report = Some(self.report());
        let course = (options.trace_every > 0).then(|| Course {
            summary: Fields::default(),
            trace: Trace(self.trace.iter().map(|p| p.fields()).collect()),
        });
        ModelRun { launch: self.launch, report, course }
    }
}
