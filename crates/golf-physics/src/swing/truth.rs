//! The exact club data of a synthetic swing (docs/club-data.md): the approach path continued past impact, its
//! plane and lowest point, and the head turned about its face normal (a dynamic lie other than the static one).

use super::Swing;
use crate::equipment::ClubSpec;
use crate::impact::{Delivery, Equipment, ImpactError, ImpactState, SwingArc};
use crate::math::{Isometry3, Real, UnitQuaternion, Vector3};

/// `rotation` turned about its face-centre normal by `roll_deg`, toe up +: the normal (face angle, dynamic loft)
/// stays and the shaft flattens (for a small roll the dynamic lie falls by about the roll).
pub(super) fn rolled(rotation: UnitQuaternion, club: &ClubSpec, roll_deg: Real) -> UnitQuaternion {
    if roll_deg == 0.0 {
        return rotation;
    }
    // About the outward normal a positive turn carries the toe (club z) down; toe up is the negative turn.
    let n = crate::math::Unit::new_normalize(rotation * club.face.n0());
    UnitQuaternion::from_axis_angle(&n, -roll_deg.to_radians()) * rotation
}

/// [`Delivery::to_state`] with the head's orientation given (`rotation` has the delivery's face normal): the
/// ball at rest at the world origin touches the face at the delivery's impact location.
pub(super) fn state(d: &Delivery, equipment: &Equipment, rotation: UnitQuaternion) -> Result<ImpactState, ImpactError> {
    let plain = d.to_state(equipment)?;
    if plain.world_from_club.rotation == rotation {
        return Ok(plain);
    }
    let club = &equipment.club;
    let contact = club.face.contact(d.impact_h_m, d.impact_v_m)?;
    let contact_world = -equipment.ball.radius_m * (rotation * contact.normal);
    let cg_position = contact_world - rotation * contact.point_m;
    let w = d.club_angular_velocity_radps;
    Ok(ImpactState {
        world_from_club: Isometry3::from_parts(cg_position.into(), rotation),
        cg_velocity_mps: d.club_speed_mps * d.direction() - w.cross(&(rotation * club.face.center_m)),
        ..plain
    })
}

impl Swing {
    /// The unit vector of the swing plane at `angle` from the bottom of the arc toward the target.
    pub(super) fn in_plane(&self, angle: Real) -> Vector3 {
        -self.n_c * angle.cos() + self.v_hat * angle.sin()
    }

    /// The face centre on the approach's law at `tau_s` from impact, continued past impact as if there were no
    /// ball (the path a launch monitor's low point refers to).
    pub fn approach_face_centre(&self, tau_s: Real) -> Vector3 {
        let sp = &self.spec;
        let rho0 = sp.arc_radius_m;
        let t2 = tau_s * tau_s;
        let arc = self.delivery.club_speed_mps * tau_s
            + 0.5 * sp.tangential_accel_mps2 * t2
            + sp.tangential_jerk_mps3 * t2 * tau_s / 6.0;
        let phi = arc / rho0;
        match sp.double_pendulum {
            Some(dp) => {
                let (l1, l2) = (dp.arm_share * rho0, (1.0 - dp.arm_share) * rho0);
                let w1 = self.delivery.club_speed_mps / (l1 + dp.rate_ratio * l2);
                let w2 = dp.rate_ratio * w1;
                let theta1 = w1 * tau_s + 0.5 * dp.arm_accel_radps2 * tau_s * tau_s;
                let theta2 = w2 * tau_s + 0.5 * dp.club_accel_radps2 * tau_s * tau_s;
                self.centre + l1 * self.in_plane(theta1) + l2 * self.in_plane(theta2)
            }
            None => {
                let rho = rho0 * (1.0 + sp.radius_curvature_per_s2 * tau_s * tau_s);
                self.centre + rho * self.in_plane(phi)
            }
        }
    }

    /// The exact swing direction, swing plane and low point of this swing for a ball of `ball_radius_m` at
    /// `ball_position_m`: the approach path lies in the plane through the arc's centre spanned by `n_c` and the
    /// club's direction at impact, and its lowest point, the one nearest impact, is where the height's rate turns
    /// positive (found by bisection on a central difference of the height, to rounding).
    pub fn swing_arc_truth(&self, ball_position_m: &Vector3, ball_radius_m: Real) -> Option<SwingArc> {
        let normal = self.v_hat.cross(&self.n_c);
        let h = 1e-6;
        let rate = |t: Real| (self.approach_face_centre(t + h).y - self.approach_face_centre(t - h).y) / (2.0 * h);
        let lowest = self.approach_face_centre(crate::kinematics::club_data::lowest_time(rate, 0.0)?);
        crate::kinematics::club_data::swing_arc_of(&normal, &self.f_i, &lowest, ball_position_m, ball_radius_m)
    }
}
