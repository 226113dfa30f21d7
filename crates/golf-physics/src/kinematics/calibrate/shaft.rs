//! Two markers on the shaft at address: the shaft's lean and lie in the world, and the shaft's direction that
//! fixes a face known only by its normal.

use crate::math::{Real, Vector3};

use super::CalibrationError;

/// Shaft markers closer than this give no direction worth reporting (m).
pub const MIN_SHAFT_SPAN_M: Real = 0.1;

/// The shaft at address, in the world (x toward the target, y up, z right of the target line).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShaftReading {
    /// Unit vector along the shaft from the head up toward the grip (world).
    pub up_world: Vector3,
    /// Forward lean: the shaft's angle from vertical seen face-on (down the toe axis), positive with the hands
    /// ahead of the head toward the target (deg): `atan2(s_x, s_y)`.
    pub lean_deg: Real,
    /// Lie: the shaft's angle above the ground seen down the target line (deg): `atan2(s_y, -s_z)`.
    pub lie_deg: Real,
}

/// The shaft through two of its markers (world, m; either order: the direction taken is the one going up).
/// Both must sit on the same side of the shaft, so the line through them is parallel to its axis.
pub fn shaft_reading(a_world: &Vector3, b_world: &Vector3) -> Result<ShaftReading, CalibrationError> {
    let d = b_world - a_world;
    if d.norm() < MIN_SHAFT_SPAN_M {
        return Err(CalibrationError::Geometry(format!(
            "the shaft markers are {:.0} mm apart: put them at least {:.0} mm apart along the shaft",
            d.norm() * 1e3,
            MIN_SHAFT_SPAN_M * 1e3
        )));
    }
    let s = if d.y < 0.0 { -d.normalize() } else { d.normalize() };
    Ok(ShaftReading { up_world: s, lean_deg: s.x.atan2(s.y).to_degrees(), lie_deg: s.y.atan2(-s.z).to_degrees() })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lean_and_lie_of_a_shaft() {
        // At the driver's 58 deg lie, 4 deg of forward lean.
        let (lie, lean) = (58f64.to_radians(), 4f64.to_radians());
        let s = Vector3::new(lean.tan() * lie.sin(), lie.sin(), -lie.cos());
        let r = shaft_reading(&Vector3::zeros(), &(-s * 0.4)).unwrap();
        assert!((r.lie_deg - 58.0).abs() < 1e-9 && (r.lean_deg - 4.0).abs() < 1e-9, "{r:?}");
        assert!(shaft_reading(&Vector3::zeros(), &(s * 0.05)).is_err());
    }
}
