//! Where the ground is (seed section 4.3, ARCHITECTURE.md section 2): the ball rests on the turf, so the ground is the
//! plane one ball radius below the ball's centre; the impact location on the face fixes the ball's centre
//! relative to the club ("changing the ball's position and ground height", seed 4.3), hence where the club's
//! sole meets the ground along the swing's undisturbed motion.

use crate::equipment::{BallSpec, ClubSpec};
use crate::impact::continuous::ground::SoilGround;
use crate::impact::continuous::shaft::grip::ConstantTwist;
use crate::impact::{ImpactError, ImpactState};
use crate::math::{Real, Vector3};

/// How the club met the turf.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Strike {
    /// The sole reaches the ground only after [`GOOD_WINDOW_S`] past the ball's first contact, or never.
    Thin,
    /// Ball first, then the ground within [`GOOD_WINDOW_S`]: the divot starts under the ball.
    Good,
    /// The ground before the ball.
    Fat,
    /// No ground at all: the ball on a tee (`--soil none`).
    Teed,
}

/// Ground contact this soon after the ball's (about two ball-contact times) still counts as a good strike.
pub const GOOD_WINDOW_S: Real = 1e-3;

/// The ball's centre (world) when it first touches the face at the impact location, the club at its delivered
/// pose (a flat face: the ball sits one radius out along the normal from the contact point).
pub fn ball_centre_m(state: &ImpactState, club: &ClubSpec, ball: &BallSpec) -> Result<Vector3, ImpactError> {
    if !club.on_face(state.impact_h_m, state.impact_v_m) {
        return Err(ImpactError::OffFace { h_mm: state.impact_h_m * 1e3, v_mm: state.impact_v_m * 1e3 });
    }
    let c = club.face.contact(state.impact_h_m, state.impact_v_m)?;
    Ok((state.world_from_club * crate::math::Point3::from(c.point_m + ball.radius_m * c.normal)).coords)
}

/// The ground's height under a ball resting on it (m, world).
pub fn ground_y_m(ball_centre_m: &Vector3, ball: &BallSpec) -> Real {
    ball_centre_m.y - ball.radius_m
}

/// The first instant (s from ball contact) in `[t_from, t_to]` when the undisturbed club's sole touches the
/// ground, to 1 ns; `None` if it stays clear.
pub fn first_ground_contact_s(ground: &SoilGround, motion: &ConstantTwist, t_from: Real, t_to: Real) -> Option<Real> {
    let sinkage = |t: Real| ground.placed(&motion.world_from_club(t)).max_sinkage_m();
    if sinkage(t_from) > 0.0 {
        return Some(t_from);
    }
    let dt: Real = 100e-6; // the sole descends ~0.2 mm in this time: no contact is missed between samples
                           // No sole point (all within 0.5 m of the CG) moves faster than this, so a sole `d` above the ground cannot
                           // touch it within d / speed: the scan skips that far when it is longer than its sample.
    let speed_bound_mps = motion.cg_velocity_mps.norm() + 0.5 * motion.angular_velocity_radps.norm();
    let mut t = t_from;
    let mut above_m = -sinkage(t_from);
    while t < t_to {
        let skip = if speed_bound_mps > 0.0 { above_m / speed_bound_mps } else { Real::INFINITY };
        let next = (t + dt.max(0.999 * skip)).min(t_to);
        let depth = sinkage(next);
        above_m = -depth;
        if depth > 0.0 {
            let (mut lo, mut hi) = (t, next);
            while hi - lo > 1e-9 {
                let mid = 0.5 * (lo + hi);
                if sinkage(mid) > 0.0 {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            return Some(hi);
        }
        t = next;
    }
    None
}

/// The strike from when the ground is first touched (s from the ball's first contact).
pub fn classify(first_ground_s: Option<Real>) -> Strike {
    match first_ground_s {
        Some(t) if t < 0.0 => Strike::Fat,
        Some(t) if t <= GOOD_WINDOW_S => Strike::Good,
        _ => Strike::Thin,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::equipment::soil::SoilSpec;
    use crate::equipment::sole::SoleSpec;
    use crate::impact::{Delivery, Equipment};

    fn delivery(v_mm: Real) -> Delivery {
        Delivery {
            club_speed_mps: 40.0,
            attack_angle_rad: (-4.0f64).to_radians(),
            club_path_rad: 0.0,
            face_angle_rad: 0.0,
            dynamic_loft_rad: 25f64.to_radians(),
            impact_h_m: 0.0,
            impact_v_m: v_mm * 1e-3,
            club_angular_velocity_radps: Vector3::zeros(),
        }
    }

    /// The ball of a delivery rests at the world origin, so the ground is the plane y = −21.3 mm (ARCHITECTURE.md 2).
    #[test]
    fn the_ground_is_one_radius_below_the_ball() {
        let eq = Equipment::new(ClubSpec::iron7());
        let state = delivery(5.0).to_state(&eq).unwrap();
        let c = ball_centre_m(&state, &eq.club, &eq.ball).unwrap();
        assert!(c.norm() < 1e-12, "{c:?}");
        assert!((ground_y_m(&c, &eq.ball) + 0.0213).abs() < 1e-15);
    }

    /// Closed form for a club that does not turn: the sole's deepest point moves with the CG, so it meets the
    /// ground at t = s₀ / v_y (s₀ its sinkage at the ball's contact, v_y < 0 descending); negative t is fat.
    #[test]
    fn first_contact_of_a_translating_club() {
        let eq = Equipment::new(ClubSpec::iron7());
        for v_mm in [-15.0, 0.0, 15.0] {
            let state = delivery(v_mm).to_state(&eq).unwrap();
            let c = ball_centre_m(&state, &eq.club, &eq.ball).unwrap();
            let ground = SoilGround::new(SoilSpec::firm(), SoleSpec::IRON7, &eq.club, ground_y_m(&c, &eq.ball));
            let motion = ConstantTwist {
                world_from_club: state.world_from_club,
                cg_velocity_mps: state.cg_velocity_mps,
                angular_velocity_radps: Vector3::zeros(),
            };
            let s0 = ground.placed(&state.world_from_club).max_sinkage_m();
            let want = s0 / state.cg_velocity_mps.y;
            let got = first_ground_contact_s(&ground, &motion, -0.03, 0.03).unwrap();
            assert!((got - want).abs() < 2e-9, "{v_mm}: {got} vs {want}");
            assert_eq!(classify(Some(got)) == Strike::Fat, s0 > 0.0);
        }
        assert_eq!(classify(None), Strike::Thin);
        assert_eq!(classify(Some(0.5e-3)), Strike::Good);
        assert_eq!(classify(Some(5e-3)), Strike::Thin);
    }
}
