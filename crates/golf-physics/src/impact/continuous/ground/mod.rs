//! Ground reaction on the clubhead (seed chapter 4): none for a ball on a tee or a club that never reaches the
//! turf ([`NoGround`]); an iron's sole in Bekker soil and its face below the surface ([`SoilGround`], section
//! 4.2, eq. 4.3-4.13).

mod bekker;
pub mod face_pressure;
pub mod sole;
mod sole_arc;

pub use bekker::{GroundForces, GroundPhase, SoilGround};
pub use face_pressure::{face_forces, face_point_forces, FacePressure};
pub use sole::{sole_forces, sole_point_forces, SoleContact};
pub use sole_arc::{GaussRule, SoleArcWorld, MAX_GAUSS};

use super::club::Head;
use crate::math::Vector3;

/// A force the ground puts on the head, with its moment about the head's CG (world frame).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct GroundWrench {
    /// The resultant force (N, world).
    pub force_n: Vector3,
    /// Its moment about the head's CG (N m, world).
    pub torque_nm: Vector3,
}

/// A ground whose reaction at an instant is a value: the assembly's multi-rate stepping can evaluate it once and
/// hold it over several steps (it changes over milliseconds, a ball's contact over microseconds), and a model can
/// measure what it holds (sinkage, phase).
pub trait SampledGround {
    /// Everything the ground puts on the head at one instant.
    type Forces: Copy;
    /// The forces on the head as it moves at this instant.
    fn forces_on(&self, head: &Head) -> Self::Forces;
    /// Their resultant on the head, with its moment about the head's CG.
    fn wrench_of(forces: &Self::Forces) -> GroundWrench;
}

/// No ground: a ball on a tee, or a model without ground reaction.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct NoGround;

impl SampledGround for NoGround {
    type Forces = ();
    #[inline]
    fn forces_on(&self, _: &Head) {}
    #[inline]
    fn wrench_of(_: &()) -> GroundWrench {
        GroundWrench::default()
    }
}

impl SampledGround for SoilGround {
    type Forces = GroundForces;
    #[inline]
    fn forces_on(&self, head: &Head) -> GroundForces {
        self.forces_at(&head.world_from_club, &head.position_m, &head.velocity_mps, &head.angular_velocity_radps)
    }
    #[inline]
    fn wrench_of(forces: &GroundForces) -> GroundWrench {
        GroundWrench { force_n: forces.force_n(), torque_nm: forces.torque_nm() }
    }
}
