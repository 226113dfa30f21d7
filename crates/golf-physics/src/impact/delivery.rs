//! TrackMan-style delivery <-> impact state (ARCHITECTURE.md section 2, "Delivery").
//!
//! - Club speed, attack angle (up +) and club path (right +) are the speed and direction of the face centre's
//!   velocity just before impact: `v_face = s (cos a cos p, sin a, cos a sin p)`.
//! - Face angle (open/right +) and dynamic loft are the azimuth and elevation of the face-centre normal. With no
//!   lie change, `world_from_club = Ry(-face_angle) Rz(dynamic_loft - static_loft)`, which turns
//!   `n0 = (cos L, sin L, 0)` into `(cos dl cos f, sin dl, cos dl sin f)`.
//! - The CG velocity is `v_cg = v_face - w x r(CG -> face centre)` (rigid body, seed eq. 3.7).
//! - Dynamic lie and closure rate (TrackMan's club data, docs/club-data.md) from the state alone: the shaft axis
//!   `a = R (0, sin λ, -cos λ)` at the static lie λ gives `dynamic_lie = asin(a_y)` (above the static lie: the shaft
//!   more upright and the toe down; below: toe up, as TrackMan reads it) and `closure_rate = ω · a` (closing +: the face turning left for a right-hander).
//! - A dynamic lie λ_d given with the delivery (TrackMan's club data) fixes the last degree of freedom of the
//!   orientation: `world_from_club` is turned about the face-centre normal `n` (which keeps face angle and loft)
//!   by the angle θ nearest zero with `(Rot(n, θ) a)_y = sin λ_d`, a closed form
//!   `A cos θ + B sin θ = sin λ_d - C` (A, B, C from `a`, `n`); a lie no turn reaches is refused.
//! - The ball rests at the world origin and touches the face at the contact point, so the contact point is at
//!   `-R_ball n` and the CG at `-R_ball n - r(CG -> contact)`.

use super::{Equipment, ImpactError, ImpactState};
use crate::face::FaceContact;
use crate::math::{rot_y, rot_z, Isometry3, Real, Rotation3, UnitQuaternion, Vector3};

/// A delivery in SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Delivery {
    /// Clubhead speed at the face centre (m/s).
    pub club_speed_mps: Real,
    /// Attack angle: the face centre's path above (+) or below the horizontal (rad).
    pub attack_angle_rad: Real,
    /// Club path: the face centre's path right (+) or left of the target line (rad).
    pub club_path_rad: Real,
    /// Face angle: the face normal right (+, open) or left of the target line (rad).
    pub face_angle_rad: Real,
    /// Dynamic loft: the face normal's angle above the horizontal (rad).
    pub dynamic_loft_rad: Real,
    /// Impact location across the face from its centre (m, toward the toe +).
    pub impact_h_m: Real,
    /// Impact location up the face from its centre (m, up +).
    pub impact_v_m: Real,
    /// Angular velocity of the head (rad/s, world).
    pub club_angular_velocity_radps: Vector3,
}

impl Delivery {
    /// Unit direction of the face centre's velocity.
    pub fn direction(&self) -> Vector3 {
        let (a, p) = (self.attack_angle_rad, self.club_path_rad);
        Vector3::new(a.cos() * p.cos(), a.sin(), a.cos() * p.sin())
    }

    /// Checks the fields a model relies on.
    pub fn validate(&self) -> Result<(), ImpactError> {
        let fields = [
            ("club_speed_mph", self.club_speed_mps),
            ("attack_angle_deg", self.attack_angle_rad),
            ("club_path_deg", self.club_path_rad),
            ("face_angle_deg", self.face_angle_rad),
            ("dynamic_loft_deg", self.dynamic_loft_rad),
            ("impact_h_mm", self.impact_h_m),
            ("impact_v_mm", self.impact_v_m),
            ("club_angular_velocity_radps", self.club_angular_velocity_radps.norm()),
        ];
        for (field, v) in fields {
            if !v.is_finite() {
                return Err(ImpactError::NotFinite { field });
            }
        }
        if !(1.0..=100.0).contains(&self.club_speed_mps) {
            return Err(ImpactError::SpeedOutOfRange { speed_mps: self.club_speed_mps });
        }
        Ok(())
    }

    /// The impact state of this delivery on the given equipment, the ball at rest at the world origin.
    pub fn to_state(&self, equipment: &Equipment) -> Result<ImpactState, ImpactError> {
        self.to_state_with_lie(equipment, None)
    }

    /// [`Self::to_state`] with the shaft at `dynamic_lie_rad` above the ground (TrackMan's dynamic lie), when
    /// given; without it the lie is the club's static lie turned by the loft and face alone.
    pub fn to_state_with_lie(
        &self,
        equipment: &Equipment,
        dynamic_lie_rad: Option<Real>,
    ) -> Result<ImpactState, ImpactError> {
        Ok(StateParts::of(self, equipment, dynamic_lie_rad)?.assemble(self, equipment))
    }

    /// The head's orientation for this delivery's face angle and loft, turned to `dynamic_lie_rad` when given.
    fn orientation(
        &self,
        club: &crate::equipment::ClubSpec,
        dynamic_lie_rad: Option<Real>,
    ) -> Result<(Rotation3, UnitQuaternion), ImpactError> {
        let mut world_from_club_rot = rot_y(-self.face_angle_rad) * rot_z(self.dynamic_loft_rad - club.face.loft_rad);
        if let Some(lie) = dynamic_lie_rad {
            world_from_club_rot = lie_twist(&world_from_club_rot, club, lie)? * world_from_club_rot;
        }
        Ok((world_from_club_rot, UnitQuaternion::from_rotation_matrix(&world_from_club_rot)))
    }

    /// Refuses an impact location off the club's face.
    fn check_on_face(&self, club: &crate::equipment::ClubSpec) -> Result<(), ImpactError> {
        if !club.on_face(self.impact_h_m, self.impact_v_m) {
            return Err(ImpactError::OffFace { h_mm: self.impact_h_m * 1e3, v_mm: self.impact_v_m * 1e3 });
        }
        Ok(())
    }

    /// The contact point and normal on the face at this delivery's impact location (checked on the face).
    fn face_contact(&self, club: &crate::equipment::ClubSpec) -> Result<FaceContact, ImpactError> {
        Ok(club.face.contact(self.impact_h_m, self.impact_v_m)?)
    }
}

/// The parts of a delivery's impact state, each from the fields it rests on: the orientation (face angle, loft
/// and dynamic lie), the contact on the face (the impact location) and the path's direction (attack angle and
/// club path). [`Delivery::to_state_with_lie`] assembles them; a caller that moves one field recomputes its part
/// alone ([`uncertainty::LaunchJacobian`](super::uncertainty::LaunchJacobian): the same numbers, bit for bit, for
/// a third less).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StateParts {
    rot: Rotation3,
    quat: UnitQuaternion,
    contact: FaceContact,
    direction: Vector3,
}

/// Which part of a delivery's state a changed field moves ([`StateParts::with`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StatePart {
    /// Club speed or the head's angular velocity: none of the parts.
    None,
    /// Attack angle or club path: the direction.
    Direction,
    /// Face angle, loft or dynamic lie: the orientation.
    Orientation,
    /// The impact location: the contact.
    Contact,
}

impl StateParts {
    /// The parts of `delivery`'s state on `equipment` (its errors those of [`Delivery::to_state_with_lie`]).
    pub fn of(delivery: &Delivery, equipment: &Equipment, dynamic_lie_rad: Option<Real>) -> Result<Self, ImpactError> {
        delivery.validate()?;
        let club = &equipment.club;
        delivery.check_on_face(club)?;
        let (rot, quat) = delivery.orientation(club, dynamic_lie_rad)?;
        let contact = delivery.face_contact(club)?;
        Ok(StateParts { rot, quat, contact, direction: delivery.direction() })
    }

    /// These parts with `part` recomputed for `delivery` (the delivery these were made of with one field moved).
    pub fn with(
        &self,
        part: StatePart,
        delivery: &Delivery,
        equipment: &Equipment,
        dynamic_lie_rad: Option<Real>,
    ) -> Result<Self, ImpactError> {
        delivery.validate()?;
        let mut parts = *self;
        match part {
            StatePart::None => {}
            StatePart::Direction => parts.direction = delivery.direction(),
            StatePart::Orientation => {
                (parts.rot, parts.quat) = delivery.orientation(&equipment.club, dynamic_lie_rad)?
            }
            StatePart::Contact => {
                delivery.check_on_face(&equipment.club)?;
                parts.contact = delivery.face_contact(&equipment.club)?
            }
        }
        Ok(parts)
    }

    /// The impact state of `delivery` (the one these parts were made of), the ball at rest at the world origin.
    pub fn assemble(&self, delivery: &Delivery, equipment: &Equipment) -> ImpactState {
        let club = &equipment.club;
        let rot = self.rot.matrix();
        let v_face = delivery.club_speed_mps * self.direction;
        let w = delivery.club_angular_velocity_radps;
        let r_face_world = rot * club.face.center_m;
        let cg_velocity_mps = v_face - w.cross(&r_face_world);
        let contact_world = -equipment.ball.radius_m * (rot * self.contact.normal);
        let cg_position = contact_world - rot * self.contact.point_m;
        ImpactState {
            world_from_club: Isometry3::from_parts(cg_position.into(), self.quat),
            cg_velocity_mps,
            angular_velocity_radps: w,
            impact_h_m: delivery.impact_h_m,
            impact_v_m: delivery.impact_v_m,
        }
    }
}

/// The turn about the face-centre normal that brings the shaft to `lie_rad` above the ground.
fn lie_twist(
    world_from_club_rot: &crate::math::Rotation3,
    club: &crate::equipment::ClubSpec,
    lie_rad: Real,
) -> Result<crate::math::Rotation3, ImpactError> {
    if !lie_rad.is_finite() {
        return Err(ImpactError::NotFinite { field: "dynamic_lie_deg" });
    }
    let n = world_from_club_rot * club.face.n0();
    let a = world_from_club_rot * club.shaft_axis_up();
    let na = n.dot(&a);
    let (big_a, big_b, big_c) = (a.y - n.y * na, n.cross(&a).y, n.y * na);
    let rho = big_a.hypot(big_b);
    let c = (lie_rad.sin() - big_c) / rho;
    if !(rho > 1e-12 && c.abs() <= 1.0) {
        return Err(ImpactError::LieUnreachable { lie_deg: lie_rad.to_degrees() });
    }
    let phi = big_b.atan2(big_a);
    let wrap = |t: Real| (t + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI) - std::f64::consts::PI;
    let (t1, t2) = (wrap(phi + c.acos()), wrap(phi - c.acos()));
    let theta = if t1.abs() <= t2.abs() { t1 } else { t2 };
    Ok(crate::math::Rotation3::from_axis_angle(&crate::math::Unit::new_normalize(n), theta))
}

/// Delivery numbers read back from any impact state, plus spin loft and face-to-path.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
pub struct DeliveryMetrics {
    /// Clubhead speed at the face centre (m/s).
    pub club_speed_mps: Real,
    /// The same in mph.
    pub club_speed_mph: Real,
    /// Attack angle (deg, up +).
    pub attack_angle_deg: Real,
    /// Club path (deg, right of the target line +).
    pub club_path_deg: Real,
    /// Face angle (deg, open +).
    pub face_angle_deg: Real,
    /// Dynamic loft (deg).
    pub dynamic_loft_deg: Real,
    /// The angle between the face centre's path and the face normal (deg).
    pub spin_loft_deg: Real,
    /// Face angle less club path (deg).
    pub face_to_path_deg: Real,
    /// Impact location across the face from its centre (mm, toward the toe +).
    pub impact_h_mm: Real,
    /// Impact location up the face from its centre (mm, up +).
    pub impact_v_mm: Real,
    /// The head's angular velocity (rad/s, world).
    pub club_angular_velocity_radps: [Real; 3],
    /// The shaft's angle above the ground at impact (deg), TrackMan's dynamic lie: the static lie at a square
    /// address; above it the shaft is more upright and the toe down (toe first into the turf), below it the toe
    /// is up (heel first).
    #[serde(default)]
    pub dynamic_lie_deg: Real,
    /// The head's rotation rate about the shaft axis at impact (deg/s, closing +), TrackMan's closure rate.
    #[serde(default)]
    pub closure_rate_degps: Real,
    /// Swing direction, swing plane and low point from the clubhead's path over the frames before impact
    /// (`kinematics::club_data`); absent where there is no path (a delivery typed in, a path that fits no arc).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub swing_arc: Option<SwingArc>,
    /// One-sigma standard deviations of these numbers, propagated from the frames (`kinematics::uncertainty`;
    /// docs/estimation.md): on every impact a rig estimates from frames; absent for a delivery typed in, an
    /// estimator that leaves no residual (`linear2`) and recordings made before it was published.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub uncertainty: Option<super::sigmas::DeliveryUncertainty>,
}

/// TrackMan's club data of the path (docs/club-data.md): the plane of the face centre's path over the last
/// frames before impact, and that path's lowest point.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
pub struct SwingArc {
    /// Horizontal direction of the swing plane's base line (its intersection with the ground) from the target
    /// line (deg, right +).
    pub swing_direction_deg: Real,
    /// The swing plane's angle to the ground (deg; 90 is vertical).
    pub swing_plane_deg: Real,
    /// From the face centre at impact to the path's lowest point, horizontally along the swing direction (mm;
    /// + after impact, toward the target: TrackMan's "A"; - before: "B").
    pub low_point_distance_mm: Real,
    /// The lowest point's height above the ball's bottom (the ground under a ball on the turf) (mm).
    pub low_point_height_mm: Real,
}

impl DeliveryMetrics {
    /// The delivery numbers of `state` on `club`.
    pub fn from_state(state: &ImpactState, club: &crate::equipment::ClubSpec) -> Self {
        let rot = state.world_from_club.rotation;
        let w = state.angular_velocity_radps;
        let v_face = state.cg_velocity_mps + w.cross(&(rot * club.face.center_m));
        let n = rot * club.face.n0();
        let speed = v_face.norm();
        let attack = v_face.y.atan2(v_face.x.hypot(v_face.z));
        let path = v_face.z.atan2(v_face.x);
        let face = n.z.atan2(n.x);
        let loft = n.y.atan2(n.x.hypot(n.z));
        let spin_loft = v_face.cross(&n).norm().atan2(v_face.dot(&n));
        let shaft = rot * club.shaft_axis_up();
        DeliveryMetrics {
            club_speed_mps: speed,
            club_speed_mph: crate::units::mps_to_mph(speed),
            attack_angle_deg: attack.to_degrees(),
            club_path_deg: path.to_degrees(),
            face_angle_deg: face.to_degrees(),
            dynamic_loft_deg: loft.to_degrees(),
            spin_loft_deg: spin_loft.to_degrees(),
            face_to_path_deg: (face - path).to_degrees(),
            impact_h_mm: state.impact_h_m * 1e3,
            impact_v_mm: state.impact_v_m * 1e3,
            club_angular_velocity_radps: [w.x, w.y, w.z],
            dynamic_lie_deg: shaft.y.clamp(-1.0, 1.0).asin().to_degrees(),
            closure_rate_degps: w.dot(&shaft).to_degrees(),
            swing_arc: None,
            uncertainty: None,
        }
    }

    /// The delivery these numbers describe.
    pub fn to_delivery(&self) -> Delivery {
        Delivery {
            club_speed_mps: self.club_speed_mps,
            attack_angle_rad: self.attack_angle_deg.to_radians(),
            club_path_rad: self.club_path_deg.to_radians(),
            face_angle_rad: self.face_angle_deg.to_radians(),
            dynamic_loft_rad: self.dynamic_loft_deg.to_radians(),
            impact_h_m: self.impact_h_mm * 1e-3,
            impact_v_m: self.impact_v_mm * 1e-3,
            club_angular_velocity_radps: Vector3::from(self.club_angular_velocity_radps),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::equipment::ClubSpec;

    #[test]
    fn delivery_round_trips_through_the_state() {
        for club in [ClubSpec::driver(), ClubSpec::iron7()] {
            let eq = Equipment::new(club.clone());
            let d = Delivery {
                club_speed_mps: 45.0,
                attack_angle_rad: (-3.0f64).to_radians(),
                club_path_rad: 2.5f64.to_radians(),
                face_angle_rad: (-1.2f64).to_radians(),
                dynamic_loft_rad: 14.0f64.to_radians(),
                impact_h_m: 0.012,
                impact_v_m: -0.006,
                club_angular_velocity_radps: Vector3::new(3.0, -40.0, 8.0),
            };
            let s = d.to_state(&eq).unwrap();
            let m = DeliveryMetrics::from_state(&s, &club);
            assert!((m.club_speed_mps - 45.0).abs() < 1e-12);
            assert!((m.attack_angle_deg + 3.0).abs() < 1e-12);
            assert!((m.club_path_deg - 2.5).abs() < 1e-12);
            assert!((m.face_angle_deg + 1.2).abs() < 1e-12);
            assert!((m.dynamic_loft_deg - 14.0).abs() < 1e-12);
            assert!((m.face_to_path_deg + 3.7).abs() < 1e-12);
            // The ball (radius R at the origin) touches the face at the contact point.
            let g = s.contact(&club).unwrap();
            let contact = s.world_from_club.translation.vector + g.r_club_m;
            assert!((contact.norm() - eq.ball.radius_m).abs() < 1e-12);
            assert!((contact + eq.ball.radius_m * g.world_from_impact.column(0)).norm() < 1e-12);
        }
    }

    /// A dynamic lie given with the delivery is the lie read back from the state, and face angle, loft, speed,
    /// attack and path stay as given; a lie no turn about the face normal reaches is refused.
    #[test]
    fn a_given_dynamic_lie_is_the_lie_of_the_state() {
        for club in [ClubSpec::driver(), ClubSpec::iron7()] {
            let eq = Equipment::new(club.clone());
            let d = Delivery {
                club_speed_mps: 45.0,
                attack_angle_rad: (-3.0f64).to_radians(),
                club_path_rad: 2.5f64.to_radians(),
                face_angle_rad: (-1.2f64).to_radians(),
                dynamic_loft_rad: 14.0f64.to_radians(),
                impact_h_m: 0.012,
                impact_v_m: -0.006,
                club_angular_velocity_radps: Vector3::new(3.0, -40.0, 8.0),
            };
            let free = DeliveryMetrics::from_state(&d.to_state(&eq).unwrap(), &club).dynamic_lie_deg;
            for lie_deg in [free - 4.0, free, free + 3.0] {
                let s = d.to_state_with_lie(&eq, Some(lie_deg.to_radians())).unwrap();
                let m = DeliveryMetrics::from_state(&s, &club);
                assert!((m.dynamic_lie_deg - lie_deg).abs() < 1e-9, "{lie_deg} -> {}", m.dynamic_lie_deg);
                assert!((m.face_angle_deg + 1.2).abs() < 1e-9 && (m.dynamic_loft_deg - 14.0).abs() < 1e-9);
                assert!((m.club_path_deg - 2.5).abs() < 1e-9 && (m.attack_angle_deg + 3.0).abs() < 1e-9);
                assert!((m.club_speed_mps - 45.0).abs() < 1e-9);
            }
            assert!(matches!(
                d.to_state_with_lie(&eq, Some(89.0f64.to_radians())),
                Err(ImpactError::LieUnreachable { .. })
            ));
        }
    }

    /// Spin loft of a square face on a level path is the dynamic loft minus the attack angle.
    #[test]
    fn spin_loft_in_the_plane() {
        let club = ClubSpec::iron7();
        let d = Delivery {
            club_speed_mps: 40.0,
            attack_angle_rad: (-4.0f64).to_radians(),
            club_path_rad: 0.0,
            face_angle_rad: 0.0,
            dynamic_loft_rad: 25.0f64.to_radians(),
            impact_h_m: 0.0,
            impact_v_m: 0.0,
            club_angular_velocity_radps: Vector3::zeros(),
        };
        let s = d.to_state(&Equipment::new(club.clone())).unwrap();
        let m = DeliveryMetrics::from_state(&s, &club);
        assert!((m.spin_loft_deg - 29.0).abs() < 1e-12);
    }
}
