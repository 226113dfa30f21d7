//! An iron's sole and shaft mount (seed section 4.2, Figure 4.7): the geometry the ground model needs that the
//! seed does not give, with typical 7-iron values.
//!
//! The sole is a cylindrical section (Figure 4.7): its axis runs heel to toe (the club frame's z), its radius is
//! the sole radius, and its arc spans the sole width from the leading edge back to the trailing edge; the
//! tangent at the leading edge makes the bounce angle with the ground at a square address. In the club frame
//! (CG origin, x forward, y up, z toward the toe), the leading edge lies `leading_edge_below_face_centre_m` down
//! the face from the face centre: `p_LE = c − d u0`.
//!
//! | field | 7-iron value | source |
//! |---|---|---|
//! | `lie_deg` | 62.5 | typical 7-iron lie (makers' spec sheets: 61.5-63°) |
//! | `sole_width_m` | 0.020 | leading to trailing edge; 7-iron soles are 17-22 mm wide |
//! | `sole_length_m` | 0.060 | heel-toe length of the sole's cylinder (`w` of eq. 4.4-4.13); blade ~75 mm |
//! | `bounce_deg` | 4.0 | 7-iron bounce is 2-5° |
//! | `sole_radius_m` | 0.10 | front-to-back sole camber, ~4 in |
//! | `leading_edge_below_face_centre_m` | 0.012 | see below |
//! | `shaft_tip_from_cg_m` | (0.008, 0.050, −0.068) | hosel top: shaft axis 38 mm from the CG (irons: 35-40 mm) |
//! | `toe_down_deg` | 0.0 | the sole's heel-toe tilt at delivery, toe down + (see below) |
//!
//! The leading edge's distance below the face centre decides which strikes meet the ground first. The seed
//! finds that strikes below the face centre meet the ball before the ground (section 4.3, Figure 4.11): for a
//! ball resting on the ground against a 30° face, the contact lies `r (1 − sin 30°) = 10.7 mm` above the
//! ground, so a leading edge 12 mm down the face (10.3 mm vertically) puts the centred strike's leading edge at
//! the ground. A measured 7-iron's scoreline centre sits 18-22 mm above the leading edge; with 20 mm, strikes
//! 5 mm below the centre are already fat (docs/ground.md).
//!
//! The delivery fixes the face's direction but not the head's roll about the face normal: whether the sole meets
//! the turf level, heel first or toe first. `toe_down_deg` turns the sole (and the leading edge with it) about
//! the face normal through the face centre, toe down for positive angles. A shaft bowed toe-down at impact
//! ("droop", a few degrees for a steel iron) or a lie flatter than the golfer's delivery puts the toe down;
//! hands higher at impact than at address put it up. With no measured typical value of either sign, the level
//! sole (0) is the default; research/ground-findings.md measures what the tilt does to the seed's findings.

use super::EquipmentError;
use crate::math::{Real, UnitQuaternion, Vector3};

/// The sole, lie and shaft mount of an iron.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SoleSpec {
    /// Lie angle: the shaft's angle above the ground at a square address (deg).
    pub lie_deg: Real,
    /// Leading to trailing edge (m).
    pub sole_width_m: Real,
    /// Heel-toe length of the sole's cylinder (m).
    pub sole_length_m: Real,
    /// Angle between the ground and the sole's tangent at the leading edge, square address (deg).
    pub bounce_deg: Real,
    /// Radius of the sole's cylinder (m).
    pub sole_radius_m: Real,
    /// Distance from the face centre down the face to the leading edge (m).
    pub leading_edge_below_face_centre_m: Real,
    /// The shaft's tip (top of the hosel, on the shaft axis) from the CG, club frame (m).
    pub shaft_tip_from_cg_m: [Real; 3],
    /// The sole's heel-toe tilt at delivery, toe down + (deg): a turn about the face normal through the face
    /// centre.
    #[serde(default)]
    pub toe_down_deg: Real,
}

impl SoleSpec {
    /// Typical 7-iron values (table above).
    pub const IRON7: SoleSpec = SoleSpec {
        lie_deg: super::ClubSpec::IRON_LIE_DEG,
        sole_width_m: 0.020,
        sole_length_m: 0.060,
        bounce_deg: 4.0,
        sole_radius_m: 0.10,
        leading_edge_below_face_centre_m: 0.012,
        shaft_tip_from_cg_m: [0.008, 0.050, -0.068],
        toe_down_deg: 0.0,
    };

    /// Checks every field, naming a bad one.
    pub fn validate(&self) -> Result<(), EquipmentError> {
        let invalid = |field, reason: String| Err(EquipmentError::Invalid { field, reason });
        for (field, v) in [
            ("sole.sole_width_m", self.sole_width_m),
            ("sole.sole_length_m", self.sole_length_m),
            ("sole.sole_radius_m", self.sole_radius_m),
            ("sole.leading_edge_below_face_centre_m", self.leading_edge_below_face_centre_m),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return invalid(field, format!("must be positive, got {v}"));
            }
        }
        if !(self.lie_deg > 30.0 && self.lie_deg < 80.0) {
            return invalid("sole.lie_deg", format!("must lie in (30, 80), got {}", self.lie_deg));
        }
        if !(self.toe_down_deg > -15.0 && self.toe_down_deg < 15.0) {
            return invalid("sole.toe_down_deg", format!("must lie in (-15, 15), got {}", self.toe_down_deg));
        }
        if !(self.bounce_deg > -10.0 && self.bounce_deg < 30.0) {
            return invalid("sole.bounce_deg", format!("must lie in (-10, 30), got {}", self.bounce_deg));
        }
        let sin_te = self.bounce_deg.to_radians().sin() - self.sole_width_m / self.sole_radius_m;
        if sin_te <= -1.0 {
            return invalid("sole.sole_radius_m", "is too small for the sole width".into());
        }
        if self.shaft_tip_from_cg_m.iter().any(|v| !v.is_finite()) {
            return invalid("sole.shaft_tip_from_cg_m", "must be finite".into());
        }
        Ok(())
    }

    /// The shaft's axis from tip toward the butt, club frame: up and toward the heel at the lie angle.
    pub fn shaft_axis_up(&self) -> Vector3 {
        let lie = self.lie_deg.to_radians();
        Vector3::new(0.0, lie.sin(), -lie.cos())
    }

    /// The shaft's tip in the club frame (m).
    pub fn shaft_tip_m(&self) -> Vector3 {
        Vector3::from(self.shaft_tip_from_cg_m)
    }

    /// The sole's arc in the club frame: the cylinder's axis point (x, y) and the trailing- and leading-edge
    /// angles (rad), measured from straight down, positive toward the front: a sole point is
    /// `centre + R (sin θ, −cos θ)`.
    pub fn arc(&self, face_centre_m: &Vector3, loft_rad: Real) -> SoleArc {
        let u0 = Vector3::new(-loft_rad.sin(), loft_rad.cos(), 0.0);
        let le = face_centre_m - self.leading_edge_below_face_centre_m * u0;
        let theta_le = self.bounce_deg.to_radians();
        let r = self.sole_radius_m;
        let level = Vector3::new(le.x - r * theta_le.sin(), le.y + r * theta_le.cos(), face_centre_m.z);
        let theta_te = (theta_le.sin() - self.sole_width_m / r).asin();
        // Toe down: a turn about the face normal n0 = (cos loft, sin loft, 0) takes the toe (+z) toward -u0.
        let n0 = crate::math::Unit::new_normalize(Vector3::new(loft_rad.cos(), loft_rad.sin(), 0.0));
        let axes = UnitQuaternion::from_axis_angle(&n0, self.toe_down_deg.to_radians());
        SoleArc {
            centre_m: face_centre_m + axes * (level - face_centre_m),
            axes,
            radius_m: r,
            theta_te_rad: theta_te,
            theta_le_rad: theta_le,
            length_m: self.sole_length_m,
        }
    }
}

/// The sole's cylinder placed in the club frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SoleArc {
    /// A point on the cylinder's axis, at the sole's heel-toe middle (club frame, m).
    pub centre_m: Vector3,
    /// The cylinder's frame in the club frame (identity for a level sole): its x forward, y up, z (the axis)
    /// toward the toe.
    pub axes: UnitQuaternion,
    /// The cylinder's radius (m).
    pub radius_m: Real,
    /// Angle of the trailing edge on the cylinder from straight below its axis (rad).
    pub theta_te_rad: Real,
    /// Angle of the leading edge on the cylinder (rad): the sole's bounce.
    pub theta_le_rad: Real,
    /// Heel-toe length (m).
    pub length_m: Real,
}

impl SoleArc {
    /// The sole point at angle `theta` and heel-toe offset `s` from the middle (club frame, m).
    #[inline]
    pub fn point(&self, theta: Real, s_m: Real) -> Vector3 {
        self.centre_m + self.axes * Vector3::new(self.radius_m * theta.sin(), -self.radius_m * theta.cos(), s_m)
    }

    /// The leading edge at heel-toe offset `s` (club frame, m).
    pub fn leading_edge(&self, s_m: Real) -> Vector3 {
        self.point(self.theta_le_rad, s_m)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The arc's ends: the leading edge is `d` down the face from the face centre, the trailing edge one sole
    /// width behind it, and the tangent at the leading edge rises at the bounce angle.
    #[test]
    fn arc_geometry() {
        let s = SoleSpec::IRON7;
        s.validate().unwrap();
        let c = Vector3::new(0.00361, 0.00485, 0.00112);
        let loft = 30.5f64.to_radians();
        let arc = s.arc(&c, loft);
        let le = arc.leading_edge(0.0);
        let want = c - 0.012 * Vector3::new(-loft.sin(), loft.cos(), 0.0);
        assert!((le - want).norm() < 1e-15);
        let te = arc.point(arc.theta_te_rad, 0.0);
        assert!((le.x - te.x - 0.020).abs() < 1e-12);
        let h = 1e-6;
        let d = arc.point(arc.theta_le_rad + h, 0.0) - arc.point(arc.theta_le_rad - h, 0.0);
        assert!(((d.y / d.x).atan().to_degrees() - 4.0).abs() < 1e-6);
        // The lowest point (θ = 0) lies on the arc, R (1 − cos 4°) = 0.24 mm below the leading edge.
        assert!(arc.theta_te_rad < 0.0 && arc.theta_le_rad > 0.0);
        assert!((le.y - arc.point(0.0, 0.0).y - 0.1 * (1.0 - 4f64.to_radians().cos())).abs() < 1e-15);
    }

    /// A toe-down sole, turned by `a` about the face normal through the face centre c: its leading edge at
    /// heel-toe offset s is `c + (−d u0 + s z)` turned, so along the face the toe end (s = +L/2) lies `L sin a`
    /// below the heel end, the middle stays `d` from the face centre, and the level sole is the unturned one.
    #[test]
    fn toe_down_tilts_the_sole_about_the_face_normal() {
        let c = Vector3::new(0.00361, 0.00485, 0.00112);
        let loft = 30.5f64.to_radians();
        let level = SoleSpec::IRON7.arc(&c, loft);
        let tilted = SoleSpec { toe_down_deg: 5.0, ..SoleSpec::IRON7 }.arc(&c, loft);
        let u0 = Vector3::new(-loft.sin(), loft.cos(), 0.0);
        let (toe, heel) = (tilted.leading_edge(0.03), tilted.leading_edge(-0.03));
        assert!(((toe - heel).dot(&u0) + 0.06 * 5f64.to_radians().sin()).abs() < 1e-12, "{toe:?} {heel:?}");
        assert!(((tilted.leading_edge(0.0) - c).norm() - 0.012).abs() < 1e-12);
        assert!((level.leading_edge(0.03) - level.leading_edge(-0.03)).dot(&u0).abs() < 1e-15);
        let mut bad = SoleSpec::IRON7;
        bad.toe_down_deg = 20.0;
        assert!(bad.validate().unwrap_err().to_string().contains("toe_down_deg"));
    }

    /// The shaft axis leaves the tip at the lie angle: its elevation is 62.5° and it leans toward the heel.
    #[test]
    fn shaft_axis_at_lie() {
        let a = SoleSpec::IRON7.shaft_axis_up();
        assert!((a.y.asin().to_degrees() - 62.5).abs() < 1e-12 && a.z < 0.0 && a.x == 0.0);
        let mut bad = SoleSpec::IRON7;
        bad.sole_radius_m = 0.005;
        assert!(bad.validate().unwrap_err().to_string().contains("sole_radius_m"));
    }
}
