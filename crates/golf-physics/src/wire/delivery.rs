//! The JSONL forms of `impactd predict`: a TrackMan-style delivery in, the launch out.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::impact::{Delivery, DeliveryMetrics, Equipment, ImpactError, Launch, LaunchMetrics};
use crate::math::{mirror_z_axial, Real, Vector3};
use crate::units::{deg_to_rad, mm_to_m, mph_to_mps};

/// Which hand the golfer plays. Left-handed deliveries are mirrored (z -> -z) into a right-handed world before
/// any model runs, and the launch is mirrored back. Every angle and vector in and out is in the world frame
/// (x toward the target, y up, z right of the target line seen from behind the ball) for either hand: a
/// left-hander's `club_path_deg` > 0 and `launch_direction_deg` > 0 are right of the target, as for anyone.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Handedness {
    /// A right-handed golfer: the world as it is.
    #[default]
    Right,
    /// A left-handed golfer: mirrored z -> -z before the models and back after.
    Left,
}

/// A TrackMan-style delivery as read by `impactd predict`: flat fields with units in their names. Missing numbers
/// default to 0, except `dynamic_loft_deg`, which defaults to the loft tour players deliver with the club (its
/// static loft less their shaft lean and de-lofting, `impact::delivered_loft`). Other fields are not read
/// (`impactd predict` passes them through to its answer).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct DeliveryInput {
    /// Clubhead speed at the face centre (mph).
    #[serde(default)]
    pub club_speed_mph: Real,
    /// Attack angle (deg): the head's path above (+) or below (−) the horizontal.
    #[serde(default)]
    pub attack_angle_deg: Real,
    /// Club path (deg): the head's path right (+) or left (−) of the target line.
    #[serde(default)]
    pub club_path_deg: Real,
    /// Face angle (deg): the face normal right (+, open for a right-hander) or left of the target line.
    #[serde(default)]
    pub face_angle_deg: Real,
    /// Dynamic loft (deg): the face normal's angle above the horizontal; default the tour players' loft for the club.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dynamic_loft_deg: Option<Real>,
    /// Impact location across the face from its centre (mm, toward the toe +).
    #[serde(default)]
    pub impact_h_mm: Real,
    /// Impact location up the face from its centre (mm, up +).
    #[serde(default)]
    pub impact_v_mm: Real,
    /// Angular velocity of the head, rad/s, world frame.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub club_angular_velocity_radps: Option<[Real; 3]>,
    /// Which hand the golfer plays (default right).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub handedness: Option<Handedness>,
    /// TrackMan's dynamic lie (deg, the shaft's angle above the ground at impact): fixes the head's turn about
    /// the face normal; default the club's static lie turned by loft and face alone.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dynamic_lie_deg: Option<Real>,
}

/// The largest angular velocity of a clubhead `predict` accepts (rad/s): a driver's head turns at about 30-60
/// rad/s through impact; ten times that is no swing.
pub const MAX_CLUB_ANGULAR_VELOCITY_RADPS: Real = 500.0;

/// A number of an input outside what any swing could give.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[error("field `{field}`: {value} is outside {min} to {max}")]
pub struct OutOfBounds {
    /// The input's field.
    pub field: &'static str,
    /// What it was.
    pub value: Real,
    /// The smallest value accepted.
    pub min: Real,
    /// The largest value accepted.
    pub max: Real,
}

impl DeliveryInput {
    /// The fields a delivery reads (the others of a line pass through `impactd predict`).
    pub const FIELDS: [&'static str; 10] = [
        "club_speed_mph",
        "attack_angle_deg",
        "club_path_deg",
        "face_angle_deg",
        "dynamic_loft_deg",
        "impact_h_mm",
        "impact_v_mm",
        "club_angular_velocity_radps",
        "handedness",
        "dynamic_lie_deg",
    ];

    /// Every angle and the angular velocity within plausible bounds (a model would answer nonsense beyond them;
    /// club speed and impact location are checked by the models, which name them).
    pub fn check_plausible(&self) -> Result<(), OutOfBounds> {
        let within = |field: &'static str, value: Real, min: Real, max: Real| {
            if (min..=max).contains(&value) {
                Ok(())
            } else {
                Err(OutOfBounds { field, value, min, max })
            }
        };
        within("attack_angle_deg", self.attack_angle_deg, -60.0, 60.0)?;
        within("club_path_deg", self.club_path_deg, -60.0, 60.0)?;
        within("face_angle_deg", self.face_angle_deg, -60.0, 60.0)?;
        if let Some(l) = self.dynamic_loft_deg {
            within("dynamic_loft_deg", l, -30.0, 90.0)?;
        }
        if let Some(l) = self.dynamic_lie_deg {
            within("dynamic_lie_deg", l, 0.0, 90.0)?;
        }
        if let Some(w) = self.club_angular_velocity_radps {
            let m = MAX_CLUB_ANGULAR_VELOCITY_RADPS;
            within("club_angular_velocity_radps", Vector3::from(w).norm(), 0.0, m)?;
        }
        Ok(())
    }

    /// The dynamic loft (deg): the given one, else the loft tour players deliver with a club of this static loft
    /// (`impact::delivered_loft`).
    pub fn dynamic_loft_or_delivered(&self, static_loft_deg: Real) -> Real {
        self.dynamic_loft_deg.unwrap_or_else(|| crate::impact::delivered_loft::delivered_loft_deg(static_loft_deg))
    }

    /// The delivery in SI for a club of the given static loft, mirrored into the right-handed world for a
    /// left-handed golfer.
    pub fn to_delivery(&self, static_loft_deg: Real) -> Delivery {
        let w = self.club_angular_velocity_radps.map(Vector3::from).unwrap_or_else(Vector3::zeros);
        let left = self.handedness == Some(Handedness::Left);
        let s = if left { -1.0 } else { 1.0 };
        Delivery {
            club_speed_mps: mph_to_mps(self.club_speed_mph),
            attack_angle_rad: deg_to_rad(self.attack_angle_deg),
            club_path_rad: s * deg_to_rad(self.club_path_deg),
            face_angle_rad: s * deg_to_rad(self.face_angle_deg),
            dynamic_loft_rad: deg_to_rad(self.dynamic_loft_or_delivered(static_loft_deg)),
            impact_h_m: mm_to_m(self.impact_h_mm),
            impact_v_m: mm_to_m(self.impact_v_mm),
            club_angular_velocity_radps: if left { mirror_z_axial(&w) } else { w },
        }
    }

    /// The impact state of this delivery on `equipment` (the dynamic lie applied when given).
    pub fn to_state(&self, equipment: &crate::impact::Equipment) -> Result<crate::impact::ImpactState, ImpactError> {
        let delivery = self.to_delivery(equipment.club.face.loft_rad.to_degrees());
        delivery.to_state_with_lie(equipment, self.dynamic_lie_deg.map(deg_to_rad))
    }

    /// The first non-finite field, named.
    pub fn check_finite(&self) -> Result<(), ImpactError> {
        let mut fields = vec![
            ("club_speed_mph", self.club_speed_mph),
            ("attack_angle_deg", self.attack_angle_deg),
            ("club_path_deg", self.club_path_deg),
            ("face_angle_deg", self.face_angle_deg),
            ("impact_h_mm", self.impact_h_mm),
            ("impact_v_mm", self.impact_v_mm),
        ];
        if let Some(l) = self.dynamic_loft_deg {
            fields.push(("dynamic_loft_deg", l));
        }
        if let Some(l) = self.dynamic_lie_deg {
            fields.push(("dynamic_lie_deg", l));
        }
        if let Some(w) = self.club_angular_velocity_radps {
            fields.extend(w.iter().map(|v| ("club_angular_velocity_radps", *v)));
        }
        match fields.into_iter().find(|(_, v)| !v.is_finite()) {
            Some((field, _)) => Err(ImpactError::NotFinite { field }),
            None => Ok(()),
        }
    }
}

/// One answer of `impactd predict`: the launch (TrackMan names) and the delivery numbers that explain it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct PredictOutput {
    /// The ball's launch, TrackMan's numbers.
    #[serde(flatten)]
    pub launch: LaunchMetrics,
    /// Ball speed over club speed.
    pub smash_factor: Real,
    /// The angle between the head's path and the face normal at impact (deg).
    pub spin_loft_deg: Real,
    /// Face angle less club path (deg; closed to the path −).
    pub face_to_path_deg: Real,
    /// TrackMan's dynamic lie: the shaft's angle above the ground at impact (deg; docs/club-data.md).
    #[serde(default)]
    pub dynamic_lie_deg: Real,
    /// TrackMan's closure rate: the head's rotation rate about the shaft at impact (deg/s, closing +; 0 for a
    /// delivery given without its angular velocity).
    #[serde(default)]
    pub closure_rate_degps: Real,
    /// The ball's velocity (m/s) in the world frame: x toward the target, y up, z right of the target line seen
    /// from behind the ball. The same frame for left- and right-handed golfers (a left-hander's shot is mirrored
    /// back into it), so a ball starting right of the target has z > 0 whoever hit it.
    pub ball_velocity_mps: [Real; 3],
    /// The ball's spin (rad/s) in the world frame of `ball_velocity_mps`, for either hand; backspin points
    /// along -z for a ball flying toward +x.
    pub ball_spin_radps: [Real; 3],
    /// Sanity flags (`impact::sanity`): empty for a shot a golfer could hit.
    #[serde(default)]
    pub warnings: Vec<crate::impact::LaunchWarning>,
    /// One-sigma standard deviations of the launch numbers, propagated from the frames (`impact::uncertainty`;
    /// docs/estimation.md): on every launch a rig predicts from frames; absent for a delivery typed in and in
    /// recordings made before it was published.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub uncertainty: Option<crate::impact::uncertainty::LaunchUncertainty>,
}

impl PredictOutput {
    /// Builds the answer with its sanity flags, mirroring back into the golfer's world for a left-hander.
    pub fn new(launch: &Launch, delivery: &DeliveryMetrics, handedness: Handedness, equipment: &Equipment) -> Self {
        let (v, w) = match handedness {
            Handedness::Right => (launch.ball_velocity_mps, launch.ball_spin_radps),
            Handedness::Left => {
                (crate::math::mirror_z(&launch.ball_velocity_mps), mirror_z_axial(&launch.ball_spin_radps))
            }
        };
        let metrics = LaunchMetrics::from_ball(&v, &w);
        let sign = if handedness == Handedness::Left { -1.0 } else { 1.0 };
        let smash_factor = metrics.ball_speed_mps / delivery.club_speed_mps;
        PredictOutput {
            warnings: crate::impact::sanity::warnings(&metrics, smash_factor, equipment),
            smash_factor,
            launch: metrics,
            spin_loft_deg: delivery.spin_loft_deg,
            face_to_path_deg: sign * delivery.face_to_path_deg,
            dynamic_lie_deg: delivery.dynamic_lie_deg,
            closure_rate_degps: delivery.closure_rate_degps,
            ball_velocity_mps: [v.x, v.y, v.z],
            ball_spin_radps: [w.x, w.y, w.z],
            uncertainty: None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `DeliveryInput::FIELDS` names every field of the struct, so none is passed through as unknown.
    #[test]
    fn fields_name_every_field() {
        let full = DeliveryInput {
            dynamic_loft_deg: Some(1.0),
            club_angular_velocity_radps: Some([0.0; 3]),
            handedness: Some(Handedness::Left),
            dynamic_lie_deg: Some(57.0),
            ..Default::default()
        };
        let value = serde_json::to_value(full).unwrap();
        let mut keys: Vec<&str> = value.as_object().unwrap().keys().map(String::as_str).collect();
        keys.sort_unstable();
        let mut fields = DeliveryInput::FIELDS.to_vec();
        fields.sort_unstable();
        assert_eq!(keys, fields);
    }
}
