//! What `replay` and `import` say of a capture's swings: `--impact-frame`/`--impact-time` (an impact instant the
//! user knows), each swing's reason when it gave no prediction, the impact instants measured beside the geometric
//! contact, and the exit code of a capture whose swings predicted nothing (docs/estimation.md).

use std::process::ExitCode;

use clap::Args;
use impactd::kinematics::GivenImpact;
use impactd::pipeline::{Event, RigSetup};

/// How `quality` and `frames_used` read, for the `--help` of `replay` and `import`.
pub const QUALITY_HELP: &str = "\
Each launch line carries `frames_used`, the frames before the impact the estimator fitted (the arc estimator \
takes those within about 44 ms of the impact, up to 64), and `quality`, a score in (0, 1]: 1 / (1 + residual_mm / 1 \
+ residual_deg / 0.5 + extrapolation_ms / 5), from the fit's RMS position residual (mm), its RMS orientation \
residual (deg) and the time from the newest fitted frame to the impact (ms): 1 for a perfect fit at the impact, 0.5 \
for 1 mm of residual alone. `warnings` names what the estimate bridged (`frame_gap_before_impact`, with \
`impact_timing.frame_gap`) beside the launch's sanity flags. A swing that gives no prediction says why on stderr; \
when a capture's swings give none at all the command exits 2. docs/estimation.md has each guard and its bound.";

/// An impact instant the user knows.
#[derive(Debug, Clone, Args)]
pub struct ImpactArgs {
    /// The impact is at this frame (the capture's or the samples' frame number): the estimate is made there, from
    /// the frames before it, instead of at the geometric contact with the ball.
    #[arg(long, value_name = "N", conflicts_with = "impact_time")]
    pub impact_frame: Option<u64>,
    /// The impact is at this capture time (s, the samples' clock: `t_ns` / 1e9; a C3D capture's first frame is at
    /// 0), as --impact-frame.
    #[arg(long, value_name = "S")]
    pub impact_time: Option<f64>,
}

impl ImpactArgs {
    /// The given instant, checked.
    pub fn given(&self) -> anyhow::Result<Option<GivenImpact>> {
        match (self.impact_frame, self.impact_time) {
            (Some(n), _) => Ok(Some(GivenImpact::Frame(n))),
            (None, Some(s)) if (0.0..1.8e10).contains(&s) => Ok(Some(GivenImpact::TimeNs((s * 1e9).round() as u64))),
            (None, Some(s)) => anyhow::bail!("--impact-time must be a non-negative number of seconds, got {s}"),
            (None, None) => Ok(None),
        }
    }

    /// Sets the given instant on every rig.
    pub fn apply(&self, setups: &mut [RigSetup]) -> anyhow::Result<()> {
        if let Some(given) = self.given()? {
            for s in setups {
                s.detector.given_impact = Some(given);
            }
        }
        Ok(())
    }

    /// What the output says of the instant.
    pub fn describe(&self) -> Option<String> {
        match (self.impact_frame, self.impact_time) {
            (Some(n), _) => Some(format!("--impact-frame {n}")),
            (None, Some(s)) => Some(format!("--impact-time {s}")),
            _ => None,
        }
    }
}

/// The line an event gives on stderr, if any (`losses`: what the capture's markers say before a frame).
pub fn describe(e: &Event, losses: &dyn Fn(u64) -> Vec<String>) -> Vec<String> {
    match e {
        Event::Failed { shot, frame, reason, .. } => {
            let mut lines = vec![format!("shot {shot} (frame {frame}): no prediction: {reason}")];
            lines.extend(losses(*frame).into_iter().map(|l| format!("shot {shot}: {l}")));
            lines
        }
        Event::Missed(m) => {
            let mut lines = vec![format!("no prediction: {m}")];
            lines.extend(losses(m.closest_frame).into_iter().map(|l| format!("the swing: {l}")));
            lines
        }
        Event::ImpactTiming(t) => vec![t.to_string()],
        Event::Launch(l) => {
            let mut lines = Vec::new();
            if let Some(timing) = &l.impact_timing {
                if timing.instant == impactd::wire::ImpactInstant::Given {
                    lines.push(format!("shot {}: the estimate is at the given impact instant", l.shot));
                }
                if let Some(gap) = &timing.frame_gap {
                    lines.push(format!("shot {} (frame {}): warning: {gap}", l.shot, l.frame));
                    lines.extend(losses(l.frame).into_iter().map(|m| format!("shot {}: {m}", l.shot)));
                }
                if let Some(d) = timing.address_ball_distance_m {
                    lines.push(format!(
                        "shot {}: warning: at address the face centre was {d:.2} m from the ball (more than 0.5 m)",
                        l.shot
                    ));
                }
            }
            lines
        }
        _ => Vec::new(),
    }
}

/// Exit 2, saying so, when swings were found and none predicted; `None` otherwise.
pub fn nothing_predicted(predictions: u64, failed: u64, missed: u64) -> Option<ExitCode> {
    if predictions > 0 || failed + missed == 0 {
        return None;
    }
    eprintln!(
        "{} swings found ({failed} impacts refused, {missed} swings that did not reach the ball) and no prediction: \
         each swing's reason is above (exit 2; docs/estimation.md says what to do for each)",
        failed + missed
    );
    Some(ExitCode::from(super::args::BAD_INPUT_EXIT))
}
