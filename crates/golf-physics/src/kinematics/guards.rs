//! Guards that speak: the bounds a capture must keep for its launches to be trusted, and how a swing that did not
//! reach the ball missed it. Each bound is checked where its numbers exist (the pipeline for the head's speed and
//! the frames, `impactd replay`/`import` for a capture's markers); a value beyond one is a refusal or a warning
//! with its reason (docs/estimation.md), never silent.

use crate::face::FaceGap;
use crate::math::Real;

/// No golfer swings a club head faster than this (m/s; 156.6 mph). Long-drive champions reach about 67 m/s
/// (150 mph); a faster head is a capture read in the wrong units (inches as centimetres gives 2.54 times the
/// speed) or a wrong frame rate.
pub const MAX_HEAD_SPEED_M_S: Real = 70.0;

/// The club lengths a golfer swings, from the head's markers to a grip marker (m): a putter's 0.8 m to a long
/// driver's 1.3 m (the rules' limit is 48 in, 1.22 m, plus the hosel to the markers). Outside it the markers
/// are of another object, or the capture's units are wrong.
pub const CLUB_LENGTH_M: (Real, Real) = (0.8, 1.3);

/// The refusal of a grip marker `label` at `distance_m` from the head's markers (`seen`: where it was measured, a
/// frame or a trial) outside [`CLUB_LENGTH_M`], said for a person; `None` within it.
pub fn club_length_refusal(label: &str, distance_m: Real, seen: &str) -> Option<String> {
    let (lo, hi) = CLUB_LENGTH_M;
    (!(lo..=hi).contains(&distance_m)).then(|| {
        format!(
            "the grip marker {label} is {distance_m:.2} m from the head's markers ({seen}), outside the {lo}-{hi} m \
             of a golf club: the markers are of another object, the marker named as the grip is not at the grip, \
             or the capture's units are wrong"
        )
    })
}

/// The face centre is on the head: further than this from the nearest marker of the head's set (m), the
/// calibration (`club_from_body`) is wrong.
pub const MAX_FACE_FROM_MARKERS_M: Real = 0.3;

/// At address the face is behind the ball: a ball further than this from the face centre there (m) is not the
/// ball the golfer addressed (a wrong `ball_position_m`, `world_from_lab` or calibration).
pub const MAX_BALL_FROM_FACE_AT_ADDRESS_M: Real = 0.5;

/// A gap in the frames before impact this many frame intervals long or longer is reported (a missing frame
/// makes 2).
pub const GAP_INTERVALS: Real = 1.5;

/// The refusal of a head faster than [`MAX_HEAD_SPEED_M_S`], said for a person; `None` within the bound.
pub fn head_speed_refusal(speed_m_s: Real) -> Option<String> {
    (speed_m_s > MAX_HEAD_SPEED_M_S).then(|| {
        format!(
            "the club head moves at {speed_m_s:.1} m/s ({:.0} mph) at impact, faster than any golfer swings (bound \
             {MAX_HEAD_SPEED_M_S:.0} m/s): the capture's units or frame rate are wrong (inches read as centimetres \
             give 2.54 times the speed); check the C3D's POINT:UNITS or the samples' units and the rate",
            crate::units::mps_to_mph(speed_m_s)
        )
    })
}

/// Where the ball was, seen from the face, when a swing missed it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum MissSide {
    /// Above the face's top edge (the face passed under it).
    Above,
    /// Below the face's bottom edge (the face passed over it).
    Below,
    /// Beyond the heel.
    Heel,
    /// Beyond the toe.
    Toe,
    /// In front of the face: the motion stopped short of the ball.
    Short,
}

impl MissSide {
    /// The side's name, as it is serialized: `above`, `below`, `heel`, `toe` or `short`.
    pub fn as_str(self) -> &'static str {
        match self {
            MissSide::Above => "above",
            MissSide::Below => "below",
            MissSide::Heel => "heel",
            MissSide::Toe => "toe",
            MissSide::Short => "short",
        }
    }
}

/// How far a face passed from the ball at its closest, and on which side.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Miss {
    /// How far the ball's surface stayed from the face (mm): beyond the face's edge for a heel, toe, above or
    /// below miss, in front of the face for a short one.
    pub distance_mm: Real,
    /// Where the ball was, seen from the face.
    pub side: MissSide,
}

impl Miss {
    /// The miss of a face gap (the ball centre's gap, before subtracting the radius) against a face of these
    /// half extents (m).
    pub fn of(gap: &FaceGap, ball_radius_m: Real, half_width_m: Real, half_height_m: Real) -> Miss {
        let beyond_h = gap.h_m.abs() - half_width_m;
        let beyond_v = gap.v_m.abs() - half_height_m;
        let in_front = gap.distance_m - ball_radius_m;
        if beyond_h <= 0.0 && beyond_v <= 0.0 {
            return Miss { distance_mm: in_front.max(0.0) * 1e3, side: MissSide::Short };
        }
        let (beyond, side) = if beyond_h >= beyond_v {
            (beyond_h, if gap.h_m > 0.0 { MissSide::Toe } else { MissSide::Heel })
        } else {
            (beyond_v, if gap.v_m > 0.0 { MissSide::Above } else { MissSide::Below })
        };
        // Beside the face and in front of its plane both count: the distance from the face's edge.
        Miss { distance_mm: beyond.hypot(in_front.max(0.0)) * 1e3, side }
    }

    /// A score to minimise over a swing: the same distance, metres.
    pub fn metric_m(&self) -> Real {
        self.distance_mm * 1e-3
    }
}

impl std::fmt::Display for Miss {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.side {
            MissSide::Short => write!(f, "the face stopped {:.0} mm short of the ball", self.distance_mm),
            MissSide::Above | MissSide::Below => {
                write!(f, "the ball was {:.0} mm {} the face", self.distance_mm, self.side.as_str())
            }
            MissSide::Heel | MissSide::Toe => {
                write!(f, "the ball was {:.0} mm beyond the face's {}", self.distance_mm, self.side.as_str())
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_speed_bound_names_itself_and_passes_a_golfers_swing() {
        assert!(head_speed_refusal(60.0).is_none());
        let why = head_speed_refusal(132.3).unwrap();
        assert!(why.contains("70 m/s") && why.contains("296 mph"), "{why}");
    }

    #[test]
    fn a_miss_says_its_side() {
        let (r, hw, hh) = (0.02135, 0.05, 0.025);
        let toe = Miss::of(&FaceGap { distance_m: r, h_m: 0.09, v_m: 0.0 }, r, hw, hh);
        assert_eq!(toe.side, MissSide::Toe);
        assert!((toe.distance_mm - 40.0).abs() < 1e-9);
        let heel = Miss::of(&FaceGap { distance_m: r, h_m: -0.06, v_m: 0.01 }, r, hw, hh);
        assert_eq!(heel.side, MissSide::Heel);
        let above = Miss::of(&FaceGap { distance_m: r, h_m: 0.0, v_m: 0.045 }, r, hw, hh);
        assert_eq!((above.side, above.distance_mm.round()), (MissSide::Above, 20.0));
        let below = Miss::of(&FaceGap { distance_m: r, h_m: 0.0, v_m: -0.045 }, r, hw, hh);
        assert_eq!(below.side, MissSide::Below);
        let short = Miss::of(&FaceGap { distance_m: r + 0.012, h_m: 0.0, v_m: 0.0 }, r, hw, hh);
        assert_eq!((short.side, short.distance_mm.round()), (MissSide::Short, 12.0));
        assert!(short.to_string().contains("12 mm short"), "{short}");
    }
}
