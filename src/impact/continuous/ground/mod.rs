//! Ground reaction on the clubhead (seed chapter 4): none for a ball on a tee or a club that never reaches the
//! turf ([`NoGround`]).

use super::club::Head;
use crate::math::Vector3;

/// A force the ground puts on the head, with its moment about the head's CG (world frame).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct GroundWrench {
    pub force_n: Vector3,
    pub torque_nm: Vector3,
}

/// Ground reaction on the head as a function of its motion.
pub trait Ground {
    /// The wrench on the head at this instant.
    fn wrench(&self, head: &Head) -> GroundWrench;
    /// Whether the ground exists at all (lets the assembly skip it).
    const PRESENT: bool = true;
}

/// No ground: a ball on a tee, or a model without ground reaction.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct NoGround;

impl Ground for NoGround {
    const PRESENT: bool = false;
    #[inline]
    fn wrench(&self, _: &Head) -> GroundWrench {
        GroundWrench::default()
    }
}
