//! Sanity flags on a prediction: numbers no golf shot produces, reported beside the prediction (never dropped
//! or hidden).
//!
//! - `spin_axis_beyond_45_deg`: `|spin_axis| > 45 deg` (TrackMan's spin axis, ARCHITECTURE.md section 2). A 45 deg
//!   axis is a hard hook or slice; launch monitors report golfers' full shots within about +-30 deg.
//! - `negative_backspin`: the ball leaves with topspin, which a lofted face cannot give a centred ball.
//! - `frame_gap_before_impact`, `ball_far_from_address`: raised by the pipeline from the frames
//!   (`kinematics::guards`), not by the launch's numbers.
//! - `smash_out_of_range`: smash factor outside the club's physical range [`smash_range`]. The upper bound is
//!   the point-mass limit of the impulse-momentum model at the rules' COR, `(1 + e) M / (M + m)` (seed eq. 3.6
//!   with a free head of mass M and a ball of mass m, the head's face normal along its velocity); no club gives
//!   more. The lower bound is half of it: the normal component at a 60 deg spin loft, beyond any full shot.

use super::{Equipment, LaunchMetrics};
use crate::math::Real;

/// The rules' limit on the coefficient of restitution (USGA/R&A), the largest a conforming club has.
pub const RULES_COR: Real = 0.83;

/// Spin axes beyond this are flagged (deg).
pub const SPIN_AXIS_LIMIT_DEG: Real = 45.0;

/// One sanity flag.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum LaunchWarning {
    /// `|spin_axis| > 45 deg`.
    #[serde(rename = "spin_axis_beyond_45_deg")]
    SpinAxisBeyond45Deg,
    /// The ball leaves with topspin.
    NegativeBackspin,
    /// The smash factor outside the club's physical range ([`smash_range`]).
    SmashOutOfRange,
    /// Frames were missing before the impact and the fit bridged them (`impact_timing.frame_gap` says how many
    /// and how long; `kinematics::frame_gap`).
    FrameGapBeforeImpact,
    /// The face centre was more than 0.5 m from the ball at the address before the swing
    /// (`impact_timing.address_ball_distance_m`; `kinematics::guards`).
    BallFarFromAddress,
}

impl LaunchWarning {
    /// The name on the wire and in status counts.
    pub fn as_str(self) -> &'static str {
        match self {
            LaunchWarning::SpinAxisBeyond45Deg => "spin_axis_beyond_45_deg",
            LaunchWarning::NegativeBackspin => "negative_backspin",
            LaunchWarning::SmashOutOfRange => "smash_out_of_range",
            LaunchWarning::FrameGapBeforeImpact => "frame_gap_before_impact",
            LaunchWarning::BallFarFromAddress => "ball_far_from_address",
        }
    }
}

impl std::fmt::Display for LaunchWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// The smash factors a club can physically give: `[u/2, u]` with `u = (1 + e) M / (M + m)` at the rules' COR.
pub fn smash_range(equipment: &Equipment) -> (Real, Real) {
    let (m_club, m_ball) = (equipment.club.mass_kg, equipment.ball.mass_kg);
    let upper = (1.0 + RULES_COR) * m_club / (m_club + m_ball);
    (0.5 * upper, upper)
}

/// The flags a launch raises; `smash` is ball speed over club speed.
pub fn warnings(launch: &LaunchMetrics, smash: Real, equipment: &Equipment) -> Vec<LaunchWarning> {
    let mut out = Vec::new();
    if launch.spin_axis_deg.abs() > SPIN_AXIS_LIMIT_DEG {
        out.push(LaunchWarning::SpinAxisBeyond45Deg);
    }
    if launch.backspin_rpm < 0.0 {
        out.push(LaunchWarning::NegativeBackspin);
    }
    let (lo, hi) = smash_range(equipment);
    if !(lo..=hi).contains(&smash) {
        out.push(LaunchWarning::SmashOutOfRange);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::equipment::ClubSpec;
    use crate::math::Vector3;

    fn metrics(axis_deg: Real, back_rpm: Real) -> LaunchMetrics {
        let (s, c) = axis_deg.to_radians().sin_cos();
        let total = crate::units::rpm_to_radps(back_rpm.abs().max(1.0));
        let sign = back_rpm.signum();
        LaunchMetrics::from_ball(&Vector3::new(60.0, 10.0, 0.0), &(Vector3::new(0.0, -s * total, sign * c * total)))
    }

    /// The driver's upper smash bound is (1 + 0.83) 0.204 / (0.204 + 0.0459) = 1.4938 (Table 3.1 masses).
    #[test]
    fn the_drivers_smash_range_is_the_point_mass_limit() {
        let (lo, hi) = smash_range(&Equipment::new(ClubSpec::driver()));
        assert!((hi - 1.83 * 0.204 / 0.2499).abs() < 1e-12 && (hi - 1.4938).abs() < 1e-4);
        assert!((lo - hi / 2.0).abs() < 1e-12);
    }

    #[test]
    fn each_flag_is_raised_by_its_own_condition() {
        let eq = Equipment::new(ClubSpec::driver());
        assert!(warnings(&metrics(10.0, 2500.0), 1.45, &eq).is_empty());
        assert_eq!(warnings(&metrics(50.0, 2500.0), 1.45, &eq), vec![LaunchWarning::SpinAxisBeyond45Deg]);
        assert!(warnings(&metrics(0.0, -500.0), 1.45, &eq).contains(&LaunchWarning::NegativeBackspin));
        assert_eq!(warnings(&metrics(0.0, 2500.0), 1.52, &eq), vec![LaunchWarning::SmashOutOfRange]);
        assert_eq!(warnings(&metrics(0.0, 2500.0), 0.7, &eq), vec![LaunchWarning::SmashOutOfRange]);
        // The wire names are the status counts' names.
        for w in [LaunchWarning::SpinAxisBeyond45Deg, LaunchWarning::NegativeBackspin, LaunchWarning::SmashOutOfRange] {
            assert_eq!(serde_json::to_string(&w).unwrap(), format!("\"{}\"", w.as_str()));
        }
    }
}
