//! Ground reaction on the clubhead (seed chapter 4): none for a ball on a tee or a club that never reaches the
//! turf ([`NoGround`]); an iron's sole in Bekker soil and its face below the surface ([`SoilGround`], section
//! 4.2, eq. 4.3-4.13).

mod bekker;
pub mod face_pressure;
pub mod sole;
mod sole_arc;

pub use bekker::{GroundForces, GroundPhase, SoilGround};
pub use face_pressure::{face_forces, FacePressure};
pub use sole::{sole_forces, SoleContact};
pub use sole_arc::{GaussRule, SoleArcWorld, MAX_GAUSS};

use super::club::Head;
use crate::math::Vector3;

/// A force the ground puts on the head, with its moment about the head's CG (world frame).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct GroundWrench {
    pub force_n: Vector3,
    pub torque_nm: Vector3,
}

/// Ground reaction on the head as a function of its motion.
pub trait GroundReaction {
    /// The wrench on the head at this instant.
    fn wrench(&self, head: &Head) -> GroundWrench;
    /// Whether the ground exists at all (lets the assembly skip it).
    const PRESENT: bool = true;
}

/// No ground: a ball on a tee, or a model without ground reaction.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct NoGround;

impl GroundReaction for NoGround {
    const PRESENT: bool = false;
    #[inline]
    fn wrench(&self, _: &Head) -> GroundWrench {
        GroundWrench::default()
    }
}

impl GroundReaction for SoilGround {
    fn wrench(&self, head: &Head) -> GroundWrench {
        let pose = crate::math::Isometry3::from_parts(
            crate::math::Translation3::from(head.position_m),
            crate::math::UnitQuaternion::from_rotation_matrix(&head.world_from_club),
        );
        let f = self.forces(&pose, &head.velocity_mps, &head.angular_velocity_radps);
        GroundWrench { force_n: f.force_n(), torque_nm: f.torque_nm() }
    }
}
