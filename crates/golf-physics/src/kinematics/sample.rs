//! Motion-capture samples of the clubhead and the calibration that turns them into club poses in the world.

use crate::math::{Isometry3, Real, UnitQuaternion, Vector3};

/// One motion-capture frame of the tracked body on the clubhead, in the lab frame, as the rig reports it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClubheadSample {
    /// The rig's frame number (increasing; gaps are dropped frames).
    pub frame: u64,
    /// Capture time on the rig's clock (ns).
    pub t_ns: u64,
    /// Position of the tracked body (m, lab frame).
    pub position_m: Vector3,
    /// Orientation of the tracked body, quaternion `[x, y, z, w]` as sent (checked for unit norm).
    pub orientation_xyzw: [Real; 4],
    /// The rig could not see the body in this frame; its pose is meaningless.
    pub occluded: bool,
}

/// From the lab to the world frame, and from the tracked body to the club frame (CG, ARCHITECTURE.md section 2).
/// Identity by default: the rig reports the club's CG pose in the world frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Calibration {
    /// The lab frame's pose in the world frame: takes lab coordinates (m) to world coordinates.
    pub world_from_lab: Isometry3,
    /// The tracked body's pose in the club frame.
    pub club_from_body: Isometry3,
}

impl Default for Calibration {
    fn default() -> Self {
        Calibration { world_from_lab: Isometry3::identity(), club_from_body: Isometry3::identity() }
    }
}

impl Calibration {
    /// `world_from_club = world_from_lab * lab_from_body * body_from_club`.
    #[inline]
    pub fn world_from_club(&self, lab_from_body: &Isometry3) -> Isometry3 {
        self.world_from_lab * lab_from_body * self.club_from_body.inverse()
    }

    /// The inverse: the tracked body's pose in the lab for a club pose in the world.
    #[inline]
    pub fn lab_from_body(&self, world_from_club: &Isometry3) -> Isometry3 {
        self.world_from_lab.inverse() * world_from_club * self.club_from_body
    }
}

/// A sample after validation and calibration: the club frame's pose in the world.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClubPose {
    /// The rig's frame number of the sample.
    pub frame: u64,
    /// Capture time on the rig's clock (ns).
    pub t_ns: u64,
    /// The club frame's pose (origin at the head's CG) in the world frame (m).
    pub world_from_club: Isometry3,
}

impl ClubPose {
    /// The sample as the tracked body's pose in the lab (what a rig would send), for a club pose.
    pub fn to_sample(&self, calibration: &Calibration) -> ClubheadSample {
        let lab = calibration.lab_from_body(&self.world_from_club);
        let q = lab.rotation;
        ClubheadSample {
            frame: self.frame,
            t_ns: self.t_ns,
            position_m: lab.translation.vector,
            orientation_xyzw: [q.i, q.j, q.k, q.w],
            occluded: false,
        }
    }
}

/// The unit quaternion of `[x, y, z, w]`, if its norm is within `tol` of 1.
pub fn unit_quaternion(xyzw: &[Real; 4], tol: Real) -> Option<UnitQuaternion> {
    let q = crate::math::Quaternion::new(xyzw[3], xyzw[0], xyzw[1], xyzw[2]);
    let n = q.norm();
    if (n - 1.0).abs() <= tol {
        Some(UnitQuaternion::new_normalize(q))
    } else {
        None
    }
}
