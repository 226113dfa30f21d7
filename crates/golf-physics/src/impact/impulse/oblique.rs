//! Cross's tangential restitution rising with the impact's obliquity: the slip model's optional law (club file
//! `[slip]`: `oblique_from_deg`, `oblique_full_deg`, `oblique_e_t`).
//!
//! The seed (chapter 2, citing Cross) reports the tangential ("horizontal") coefficient of restitution of eq. 2.4
//! as negative for grazing impacts (the ball slides throughout), between 0.2 and 0.3 for premium balls at 50 deg
//! of incidence (the ball "grips" the face: its contact point reverses and it leaves spinning faster than rolling),
//! and close to 0 as the impact nears perpendicular. Cross's incidence angles are measured from the surface (Cross,
//! "Grip-slip behavior of a bouncing ball", Am. J. Phys. 70, 2002: "at low angles of incidence to the
//! horizontal, a ball incident without spin will slide throughout the bounce"), so 50 deg of incidence is 40 deg
//! from the face normal, the obliquity of a wedge's strike (its spin loft).
//!
//! The law: with `θ` the angle between the contact point's closing velocity and the face normal (the spin loft of
//! a strike without head rotation), each tangential restitution of Table 3.4 (`e_y`, `e_z`, eq. 3.11-3.12) rises
//! linearly to the one grip value `e_t` between `θ_from` and `θ_full`:
//!
//! `e(θ) = e_seed + (e_t − e_seed) s`, `s = clamp((θ − θ_from) / (θ_full − θ_from), 0, 1)`
//!
//! so below `θ_from` the seed's identified values hold and from `θ_full` on the ball grips alike in both tangential
//! directions (the grip is a property of the ball's cover against the face, not of a direction on the face).
//! Grazing impacts, where Cross's e_t turns negative, lie beyond any club's spin loft and are not modelled.

use crate::impact::ImpactError;
use crate::math::Real;

/// The rise of the tangential restitution with obliquity (angles in degrees from the face normal).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ObliqueRise {
    /// Below this obliquity the seed's e_y and e_z hold.
    pub from_deg: Real,
    /// From this obliquity on both tangential restitutions are `e_t`.
    pub full_deg: Real,
    /// The grip's tangential restitution (Cross: 0.2-0.3 for premium balls at 50 deg to the surface).
    pub e_t: Real,
}

impl ObliqueRise {
    /// Checked: finite angles with `0 <= from < full <= 90` and `e_t` within -1 and 1.
    pub fn new(from_deg: Real, full_deg: Real, e_t: Real) -> Result<Self, ImpactError> {
        let invalid = |field: &str, reason: &str| ImpactError::InvalidParameter {
            field: format!("slip.{field}"),
            reason: reason.to_string(),
        };
        if ![from_deg, full_deg, e_t].iter().all(|v| v.is_finite()) {
            return Err(invalid("oblique_*", "must be finite numbers"));
        }
        if !(0.0..90.0).contains(&from_deg) {
            return Err(invalid("oblique_from_deg", "must be within 0 and 90 (deg from the face normal)"));
        }
        if full_deg <= from_deg || full_deg > 90.0 {
            return Err(invalid(
                "oblique_full_deg",
                "the angles must satisfy 0 <= oblique_from_deg < oblique_full_deg <= 90",
            ));
        }
        if !(-1.0..=1.0).contains(&e_t) {
            return Err(invalid("oblique_e_t", "must be within -1 and 1"));
        }
        Ok(ObliqueRise { from_deg, full_deg, e_t })
    }

    /// The tangential restitution `e_seed` becomes at obliquity `theta_deg`.
    pub fn at(&self, e_seed: Real, theta_deg: Real) -> Real {
        // A rise built without `new` with `full <= from` is a step at `from` (no 0/0).
        let span = self.full_deg - self.from_deg;
        let s = if span > 0.0 {
            ((theta_deg - self.from_deg) / span).clamp(0.0, 1.0)
        } else if theta_deg >= self.from_deg {
            1.0
        } else {
            0.0
        };
        e_seed + (self.e_t - e_seed) * s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_seeds_value_below_the_rise_and_the_grip_beyond_it() {
        let r = ObliqueRise::new(30.0, 40.0, 0.25).unwrap();
        assert_eq!(r.at(0.0183, 12.0), 0.0183);
        assert_eq!(r.at(0.0183, 30.0), 0.0183);
        assert!((r.at(0.0183, 35.0) - (0.0183 + 0.5 * (0.25 - 0.0183))).abs() < 1e-12);
        assert_eq!(r.at(0.0423, 40.0), 0.25);
        assert_eq!(r.at(-0.2, 60.0), 0.25);
    }

    #[test]
    fn bad_angles_and_restitutions_are_named() {
        for (from, full, e, field) in [
            (40.0, 30.0, 0.2, "slip.oblique_full_deg"),
            (-1.0, 30.0, 0.2, "slip.oblique_from_deg"),
            (90.0, 95.0, 0.2, "slip.oblique_from_deg"),
            (10.0, 95.0, 0.2, "slip.oblique_full_deg"),
            (10.0, 40.0, 1.5, "slip.oblique_e_t"),
        ] {
            let e = ObliqueRise::new(from, full, e).unwrap_err().to_string();
            assert!(e.contains(field), "{e}");
        }
        let step = ObliqueRise { from_deg: 30.0, full_deg: 30.0, e_t: 0.25 };
        assert_eq!((step.at(0.0183, 29.0), step.at(0.0183, 31.0)), (0.0183, 0.25));
        assert!(ObliqueRise::new(Real::NAN, 40.0, 0.2).is_err());
    }
}
