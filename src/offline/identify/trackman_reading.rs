//! TrackMan's club data read by TrackMan's own definitions ("TrackMan Data Parameter Definitions", TrackMan's
//! support pages): dynamic loft and face angle are "the vertical angle of the club face" and "the direction the
//! club face is pointing" *at the centre-point of contact between the club and ball*, where a delivery
//! (ARCHITECTURE.md section 2) gives them at the face centre.
//!
//! On a planar face (irons, wedges) the two are the same normal. On a curved face (a wood's bulge and roll) the
//! normal at the contact point `(h, v)` is the face-centre normal turned by `phi = asin(h / (R_bulge - R_roll +
//! R_roll cos psi))` toward the toe and `psi = asin(v / R_roll)` up the face (the torus of ARCHITECTURE.md section
//! 2): taking TrackMan's angles as the face centre's would turn the face twice, a heel strike's face closed by
//! about `h / R_bulge` (5 deg at 27 mm on a 305 mm bulge) more than TrackMan saw it.
//!
//! [`at_face_centre`] finds the face-centre loft and face angle whose contact-point normal has TrackMan's
//! elevation and azimuth: a fixed-point iteration on the delivery's own orientation (the dynamic lie applied
//! when given), which converges in a few steps because the correction is nearly a constant turn.
//!
//! TrackMan's loft and face are themselves computed from its ball data: on every measured shot of
//! tests/data/trackman its spin is [`TRACKMAN_SPIN_RATIO`] times `2.5 v sin(a) / R`, `a` the angle between its
//! face normal and the ball's direction, where a homogeneous ball (`I = 0.4 m R^2`, the seed's) leaves any face
//! with exactly `2.5 v sin(a) / R` (`I w = m R v_t`). [`through_spin_relation`] reads TrackMan's normal through
//! that relation: the normal the seed's ball needs to leave in TrackMan's direction with TrackMan's spin, turned
//! from TrackMan's, in the plane of its normal and the ball's direction, to `asin(1.136 sin a)` from the
//! ball's direction. The measured launch then enters the delivery, so launch and spin are no longer an
//! independent test.

use crate::impact::{Equipment, ImpactError};
use crate::math::Real;
use crate::wire::{DeliveryInput, Handedness, LaunchFields};

/// TrackMan's measured spin over `2.5 v sin(a) / R` on all 32 measured shots of tests/data/trackman (two players,
/// 5-iron to driver): 1.136 within 0.002 (research/tests/tour_iron_spin.rs). A property of TrackMan's software, not of
/// a model.
pub const TRACKMAN_SPIN_RATIO: Real = 1.136;

/// Iterations at most, and the residual (deg) at which the angles are taken as found.
const MAX_ITERATIONS: usize = 50;
const TOLERANCE_DEG: Real = 1e-9;

/// Elevation and azimuth (deg, right +, in the golfer's own frame) of the face normal at the delivery's impact
/// location on `equipment`.
pub fn contact_normal_angles_deg(d: &DeliveryInput, equipment: &Equipment) -> Result<(Real, Real), ImpactError> {
    let state = d.to_state(equipment)?;
    let contact = equipment.club.face.contact(d.impact_h_mm * 1e-3, d.impact_v_mm * 1e-3)?;
    let n = state.world_from_club.rotation * contact.normal;
    let azimuth = n.z.atan2(n.x).to_degrees();
    let mirrored = d.handedness == Some(Handedness::Left);
    Ok((n.y.clamp(-1.0, 1.0).asin().to_degrees(), if mirrored { -azimuth } else { azimuth }))
}

/// The delivery with TrackMan's dynamic loft and face angle (the contact point's) turned into the face centre's
/// on `equipment`'s face. A planar face, or a row without a dynamic loft, is returned as it is.
pub fn at_face_centre(d: &DeliveryInput, equipment: &Equipment) -> Result<DeliveryInput, ImpactError> {
    let Some(loft_deg) = d.dynamic_loft_deg else { return Ok(d.clone()) };
    if !equipment.club.face.shape.is_curved() {
        return Ok(d.clone());
    }
    let (target_loft, target_face) = (loft_deg, d.face_angle_deg);
    let mut out = d.clone();
    for _ in 0..MAX_ITERATIONS {
        let (loft, face) = contact_normal_angles_deg(&out, equipment)?;
        let (e_loft, e_face) = (target_loft - loft, target_face - face);
        out.dynamic_loft_deg = Some(out.dynamic_loft_or_delivered(equipment.club.loft_deg()) + e_loft);
        out.face_angle_deg += e_face;
        if e_loft.abs().max(e_face.abs()) < TOLERANCE_DEG {
            return Ok(out);
        }
    }
    Err(ImpactError::NotConverged {
        model: "TrackMan's contact-point loft and face",
        reason: format!("no face-centre orientation within {TOLERANCE_DEG} deg after {MAX_ITERATIONS} steps"),
    })
}

/// Unit vector at `elevation_deg` above the horizon and `azimuth_deg` right of the target line.
fn direction(elevation_deg: Real, azimuth_deg: Real) -> crate::math::Vector3 {
    let (e, a) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
    crate::math::Vector3::new(e.cos() * a.cos(), e.sin(), e.cos() * a.sin())
}

/// TrackMan's dynamic loft and face angle read through its spin relation (module doc): the normal turned away
/// from the measured ball direction `b` to `a' = asin(1.136 sin a)` in the plane of `b` and TrackMan's normal
/// `n`, so that the seed's ball leaving along `b` spins TrackMan's spin. A row without a loft, or whose normal is
/// along the ball's direction, is returned as it is.
pub fn through_spin_relation(d: &DeliveryInput, measured: &LaunchFields) -> DeliveryInput {
    let Some(loft_deg) = d.dynamic_loft_deg else { return d.clone() };
    let n = direction(loft_deg, d.face_angle_deg);
    let b = direction(measured.launch_angle_deg, measured.launch_direction_deg);
    let along = n.dot(&b).clamp(-1.0, 1.0);
    let across = n - along * b;
    if across.norm() < 1e-9 {
        return d.clone();
    }
    let a = (TRACKMAN_SPIN_RATIO * along.acos().sin()).min(1.0).asin();
    let turned = a.cos() * b + a.sin() * across.normalize();
    DeliveryInput {
        dynamic_loft_deg: Some(turned.y.clamp(-1.0, 1.0).asin().to_degrees()),
        face_angle_deg: turned.z.atan2(turned.x).to_degrees(),
        ..d.clone()
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use crate::equipment::ClubSpec;

    fn driver_row(h_mm: Real, v_mm: Real) -> DeliveryInput {
        DeliveryInput {
            club_speed_mph: 100.0,
            attack_angle_deg: 2.0,
            club_path_deg: -1.0,
            face_angle_deg: 1.5,
            dynamic_loft_deg: Some(13.0),
            impact_h_mm: h_mm,
            impact_v_mm: v_mm,
            club_angular_velocity_radps: None,
            handedness: None,
            dynamic_lie_deg: Some(57.0),
        }
    }

    /// On the seed's driver (bulge and roll 305 mm, Table 3.1) at its static lie, a strike 20 mm toward the heel
    /// and 8 mm up read at the face centre has the torus' contact normal (ARCHITECTURE.md section 2: `psi =
    /// asin(v / R_roll)`, `phi = asin(h / (R_roll cos psi))` at equal radii) turned by the loft `dl` and face `f`:
    /// azimuth `f + atan2(cos psi sin phi, cos psi cos phi cos dl - sin psi sin dl)`, elevation `asin(cos psi cos
    /// phi sin dl + sin psi cos dl)`, about 3.9 deg closed and 1.5 deg lofted. Read by TrackMan's definition the
    /// contact normal has TrackMan's angles to 1e-6 deg, the face centre turned the other way.
    #[test]
    fn a_heel_strike_on_a_driver_keeps_trackmans_contact_normal() {
        let equipment = Equipment::new(ClubSpec::driver());
        let row = DeliveryInput { dynamic_lie_deg: None, ..driver_row(-20.0, 8.0) };
        let (psi, dl) = ((8.0_f64 / 305.0).asin(), 13.0_f64.to_radians());
        let phi = (-20.0 / (305.0 * psi.cos())).asin();
        let azimuth =
            1.5 + (psi.cos() * phi.sin()).atan2(psi.cos() * phi.cos() * dl.cos() - psi.sin() * dl.sin()).to_degrees();
        let elevation = (psi.cos() * phi.cos() * dl.sin() + psi.sin() * dl.cos()).asin().to_degrees();
        let (loft, face) = contact_normal_angles_deg(&row, &equipment).unwrap();
        assert!((face - azimuth).abs() < 1e-9 && (face - 1.5) < -3.8, "contact face {face:.4} deg, {azimuth:.4}");
        assert!((loft - elevation).abs() < 1e-9 && loft - 13.0 > 1.4, "contact loft {loft:.4} deg, {elevation:.4}");
        let read = at_face_centre(&row, &equipment).unwrap();
        let (loft, face) = contact_normal_angles_deg(&read, &equipment).unwrap();
        assert!((face - 1.5).abs() < 1e-6 && (loft - 13.0).abs() < 1e-6, "{loft} {face}");
        assert!(read.face_angle_deg - 1.5 > 3.8, "face centre {:.3}", read.face_angle_deg);
        assert!(read.dynamic_loft_deg.unwrap() - 13.0 < -1.4);
        // With TrackMan's dynamic lie the same holds: the lie turns the head about the face-centre normal.
        let lie = at_face_centre(&driver_row(-20.0, 8.0), &equipment).unwrap();
        let (loft, face) = contact_normal_angles_deg(&lie, &equipment).unwrap();
        assert!((face - 1.5).abs() < 1e-6 && (loft - 13.0).abs() < 1e-6, "{loft} {face}");
    }

    /// Through the relation, the seed's ball leaving along the measured direction spins TrackMan's spin: on the
    /// validation session's first 8-iron row (tests/data/trackman: 118.95 mph, launch 16.60 deg, direction 0.62
    /// deg, loft 22.11 deg, face 1.58 deg, 6,589 rpm measured), `2.5 v sin(a') / R` is 6,589 rpm within 0.1 %
    /// (the row's own ratio is 1.1359), the normal stays in the plane of TrackMan's normal and the ball's
    /// direction, and loft and face each move away from the ball's direction by about 0.136 times their gap to it
    /// (small angles: `sin a' = 1.136 sin a`), 0.75 and 0.13 deg.
    #[test]
    fn the_relation_gives_the_seeds_ball_trackmans_spin() {
        let row = DeliveryInput {
            club_speed_mph: 90.84,
            face_angle_deg: 1.583,
            dynamic_loft_deg: Some(22.114),
            ..driver_row(0.0, 0.0)
        };
        let measured = LaunchFields {
            ball_speed_mph: 118.95,
            launch_angle_deg: 16.602,
            launch_direction_deg: 0.6239,
            backspin_rpm: 6588.9,
            sidespin_rpm: 0.0,
            carry_yd: None,
        };
        let read = through_spin_relation(&row, &measured);
        let (n0, b) = (direction(22.114, 1.583), direction(16.602, 0.6239));
        let n1 = direction(read.dynamic_loft_deg.unwrap(), read.face_angle_deg);
        assert!(n1.dot(&n0.cross(&b)).abs() < 1e-12, "out of the plane");
        let spin_rpm = 2.5 * 118.95 * 0.44704 * n1.dot(&b).acos().sin() / 0.0213 * 60.0 / std::f64::consts::TAU;
        assert!((spin_rpm / 6588.9 - 1.0).abs() < 1e-3, "{spin_rpm:.0} rpm");
        let (rise, turn) = (read.dynamic_loft_deg.unwrap() - 22.114, read.face_angle_deg - 1.583);
        assert!((rise - 0.136 * (22.114 - 16.602)).abs() < 0.02, "{read:?}");
        assert!((turn - 0.136 * (1.583 - 0.6239)).abs() < 0.02, "{read:?}");
    }

    /// An iron's face is a plane: the reading changes nothing. A left-hander's row is the right-hander's mirror
    /// image (its face angle negated at the boundary), so it reads as the mirror of the right-hander's.
    #[test]
    fn a_planar_face_is_unchanged_and_a_left_hander_mirrors() {
        let iron = Equipment::new(ClubSpec::iron7());
        let row = DeliveryInput { dynamic_loft_deg: Some(25.0), ..driver_row(-10.0, 5.0) };
        assert_eq!(at_face_centre(&row, &iron).unwrap(), row);
        let driver = Equipment::new(ClubSpec::driver());
        let mirror = DeliveryInput { face_angle_deg: -1.5, club_path_deg: 1.0, ..driver_row(-20.0, 8.0) };
        let right = at_face_centre(&mirror, &driver).unwrap();
        let left_row = DeliveryInput { handedness: Some(Handedness::Left), ..driver_row(-20.0, 8.0) };
        let left = at_face_centre(&left_row, &driver).unwrap();
        assert!((left.face_angle_deg + right.face_angle_deg).abs() < 1e-6, "{left:?} {right:?}");
        assert!((left.dynamic_loft_deg.unwrap() - right.dynamic_loft_deg.unwrap()).abs() < 1e-6);
    }
}
