//! Where a continuous run starts: the ball at rest touching the face surface at the impact location, the face
//! approaching it, and the direction the friction first pushes the ball's cover (for traces).

use super::surface::FaceSurface;
use crate::impact::{Equipment, ImpactError, ImpactState};
use crate::math::Vector3;

/// The start of a continuous run (world frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Start {
    /// The ball's centre at first contact, touching the face (m).
    pub ball_centre_m: Vector3,
    /// Unit direction of the face's tangential motion at the contact (up the face if there is none).
    pub slip0: Vector3,
}

impl Start {
    /// Checks the impact location and the approach, and places the ball.
    pub fn new(state: &ImpactState, equipment: &Equipment) -> Result<Self, ImpactError> {
        let club = &equipment.club;
        if !club.on_face(state.impact_h_m, state.impact_v_m) {
            return Err(ImpactError::OffFace { h_mm: state.impact_h_m * 1e3, v_mm: state.impact_v_m * 1e3 });
        }
        let contact = club.face.contact(state.impact_h_m, state.impact_v_m)?;
        let ball_club = match FaceSurface::of_club(club) {
            FaceSurface::Plane { .. } => contact.point_m + equipment.ball.radius_m * contact.normal,
            FaceSurface::Sphere { centre, radius_m } => {
                let dir = (contact.point_m - centre).normalize();
                centre + (radius_m + equipment.ball.radius_m) * dir
            }
        };
        let iso = state.world_from_club;
        let rot = iso.rotation;
        let n0 = rot * contact.normal;
        let v_contact0 = state.cg_velocity_mps + state.angular_velocity_radps.cross(&(rot * contact.point_m));
        if v_contact0.dot(&n0) <= 0.0 {
            return Err(ImpactError::NotApproaching);
        }
        let t = v_contact0 - v_contact0.dot(&n0) * n0;
        let slip0 = if t.norm() > 1e-9 { t.normalize() } else { rot * club.face.u0() };
        Ok(Start { ball_centre_m: iso.translation.vector + rot * ball_club, slip0 })
    }
}
