//! Swings, whether or not they reach the ball: a run of frames in which the face centre moves faster than
//! [`SWING_SPEED_M_S`] and that reaches [`SWING_PEAK_M_S`]. A swing in which no impact was detected is reported when it ends ([`MissedSwing`]): how
//! close the face came to the ball and on which side, how far the ball was at address, and whether the head moved
//! faster than a golfer swings, so a capture that gives no prediction says why for each swing.

use super::guards::{Miss, MAX_BALL_FROM_FACE_AT_ADDRESS_M, MAX_HEAD_SPEED_M_S};
use crate::equipment::ClubSpec;
use crate::math::{Real, Vector3};

/// The face centre's speed that makes a swing (m/s): a waggle or a practice take-away stays below it.
pub const SWING_SPEED_M_S: Real = 10.0;

/// A swing at the ball reaches this speed (m/s): a back swing (about 10 m/s at the head) does not.
pub const SWING_PEAK_M_S: Real = 20.0;

/// Slower than this for [`ADDRESS_STILL_S`] or longer, the head is at address (m/s): the top of the back swing,
/// as slow, lasts a tenth of that.
pub const ADDRESS_SPEED_M_S: Real = 0.5;

/// How long a head at address stays still (s).
pub const ADDRESS_STILL_S: Real = 0.3;

/// A swing ends at a frame slower than [`SWING_SPEED_M_S`], or at a frame this long after the previous one (s).
pub const SWING_BREAK_S: Real = 0.1;

/// Points between two frames at which the face's miss is measured (the closest approach falls between frames).
const SUBSTEPS: usize = 8;

/// A swing that found no impact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MissedSwing {
    /// The rig's frame number of the swing's first frame faster than [`SWING_SPEED_M_S`].
    pub first_frame: u64,
    /// The rig's frame number of its last frame faster than [`SWING_SPEED_M_S`].
    pub last_frame: u64,
    /// The face centre's highest speed over the swing, from frame to frame (m/s).
    pub peak_speed_mps: Real,
    /// The frame at (or just after) the face's closest approach to the ball.
    pub closest_frame: u64,
    /// How far the face passed from the ball at its closest, and on which side.
    pub miss: Miss,
    /// The face centre's distance from the ball at address (the last frame of the last still stretch before the
    /// swing; m), when seen, with that frame's number.
    pub address: Option<(u64, Real)>,
}

impl std::fmt::Display for MissedSwing {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "a swing (frames {}-{}, head up to {:.1} m/s) did not reach the ball: {} (frame {})",
            self.first_frame, self.last_frame, self.peak_speed_mps, self.miss, self.closest_frame
        )?;
        if let Some((frame, d)) = self.address.filter(|a| a.1 > MAX_BALL_FROM_FACE_AT_ADDRESS_M) {
            write!(
                f,
                "; at address (frame {frame}) the face centre was {d:.2} m from the ball, more than the \
                 {MAX_BALL_FROM_FACE_AT_ADDRESS_M} m of a ball addressed: the ball position (ball_position_m, a ball \
                 marker) or the calibration (world_from_lab, club_from_body) is wrong"
            )?;
        }
        if self.peak_speed_mps > MAX_HEAD_SPEED_M_S {
            write!(
                f,
                "; the head moved faster than any golfer swings (bound {MAX_HEAD_SPEED_M_S:.0} m/s): the capture's \
                 units or frame rate are wrong"
            )?;
        }
        Ok(())
    }
}

#[derive(Debug, Clone, Copy)]
struct Current {
    first_frame: u64,
    last_frame: u64,
    peak_speed_mps: Real,
    closest: Option<(u64, Miss)>,
    impact: bool,
    address: Option<(u64, Real)>,
}

/// A pose as the watch sees it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeenPose {
    /// The rig's frame number of the pose.
    pub frame: u64,
    /// Its capture time on the rig's clock (ns).
    pub t_ns: u64,
    /// The face centre (world, m).
    pub centre_m: Vector3,
    /// The ball's centre in the club frame (m).
    pub ball_club_m: Vector3,
    /// The ball's centre (world, m).
    pub ball_world_m: Vector3,
}

/// Watches one track's poses for swings.
#[derive(Debug, Clone, Default)]
pub struct SwingWatch {
    current: Option<Current>,
    /// The previous pose: time, face centre (world) and the ball's centre in the club frame.
    last: Option<(u64, Vector3, Vector3)>,
    address: Option<(u64, Real)>,
    /// Since when the head has been slower than [`ADDRESS_SPEED_M_S`] (ns).
    still_since_ns: Option<u64>,
}

impl SwingWatch {
    /// Takes a pose ([`SeenPose`]) of `club`; returns the swing that ended before it without an impact.
    pub fn on_pose(&mut self, pose: &SeenPose, club: &ClubSpec, ball_radius_m: Real) -> Option<MissedSwing> {
        let SeenPose { frame, t_ns, centre_m, ball_club_m, ball_world_m } = *pose;
        let (t_prev, centre_prev, ball_prev) = self.last.replace((t_ns, centre_m, ball_club_m))?;
        let dt = t_ns.saturating_sub(t_prev) as Real * 1e-9;
        if dt > SWING_BREAK_S || dt <= 0.0 {
            return self.end();
        }
        let speed = (centre_m - centre_prev).norm() / dt;
        if speed < ADDRESS_SPEED_M_S {
            let since = *self.still_since_ns.get_or_insert(t_prev);
            if t_ns.saturating_sub(since) as Real * 1e-9 >= ADDRESS_STILL_S {
                self.address = Some((frame, (centre_m - ball_world_m).norm()));
            }
        } else {
            self.still_since_ns = None;
        }
        if speed < SWING_SPEED_M_S {
            return self.end();
        }
        let address = self.address;
        let current = self.current.get_or_insert(Current {
            first_frame: frame,
            last_frame: frame,
            peak_speed_mps: 0.0,
            closest: None,
            impact: false,
            address,
        });
        current.last_frame = frame;
        current.peak_speed_mps = current.peak_speed_mps.max(speed);
        // A swing that found its impact is never reported as a miss: its closest approach is not needed.
        if current.impact {
            return None;
        }
        // The ball's place in the club frame, between the two frames.
        for k in 1..=SUBSTEPS {
            let f = k as Real / SUBSTEPS as Real;
            let gap = club.face.gap(&(ball_prev + f * (ball_club_m - ball_prev)));
            let miss = Miss::of(&gap, ball_radius_m, club.face_half_width_m, club.face_half_height_m);
            if current.closest.is_none_or(|(_, m)| miss.metric_m() < m.metric_m()) {
                current.closest = Some((frame, miss));
            }
        }
        None
    }

    /// The swing in progress found an impact.
    pub fn note_impact(&mut self) {
        if let Some(c) = &mut self.current {
            c.impact = true;
        }
    }

    /// The face centre's distance from the ball at the address before the swing in progress (or the last
    /// address seen), with its frame.
    pub fn address(&self) -> Option<(u64, Real)> {
        self.current.map_or(self.address, |c| c.address)
    }

    /// Ends the swing in progress (the input ended, or the track broke): the missed swing, if it was one.
    pub fn end(&mut self) -> Option<MissedSwing> {
        let c = self.current.take()?;
        let (closest_frame, miss) = c.closest?;
        (!c.impact && c.peak_speed_mps >= SWING_PEAK_M_S).then_some(MissedSwing {
            first_frame: c.first_frame,
            last_frame: c.last_frame,
            peak_speed_mps: c.peak_speed_mps,
            closest_frame,
            miss,
            address: c.address,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A head still 0.8 m from the ball for 0.5 s, a pause of 0.1 s at the top, then 45 m/s past the ball 0.12 m
    /// above the face: the swing is missed, the address is the still stretch's, not the top's.
    #[test]
    fn a_missed_swing_says_its_address_and_its_side() {
        let club = ClubSpec::driver();
        let (ball, r) = (Vector3::zeros(), 0.02135);
        let mut watch = SwingWatch::default();
        let mut missed = None;
        let mut feed = |frame: u64, t_s: Real, centre: Vector3, watch: &mut SwingWatch| {
            // The club frame is the world shifted so the face centre is at `centre`.
            let ball_club = ball - centre + club.face.center_m;
            let pose = SeenPose {
                frame,
                t_ns: (t_s * 1e9) as u64,
                centre_m: centre,
                ball_club_m: ball_club,
                ball_world_m: ball,
            };
            if let Some(m) = watch.on_pose(&pose, &club, r) {
                missed = Some(m);
            }
        };
        let address = Vector3::new(-0.8, 0.0, 0.0);
        let top = Vector3::new(-1.5, 1.5, 0.0);
        for k in 0..360 {
            feed(k, k as Real / 720.0, address, &mut watch);
        }
        for k in 0..72 {
            feed(360 + k, (360 + k) as Real / 720.0, top, &mut watch);
        }
        for k in 0..40 {
            let x = -0.5 + 45.0 * k as Real / 720.0;
            feed(432 + k, (432 + k) as Real / 720.0, Vector3::new(x, 0.12, 0.0), &mut watch);
        }
        let m = missed.or_else(|| watch.end()).expect("a missed swing");
        assert_eq!(m.address.map(|a| a.0), Some(359), "{m:?}");
        assert!((m.address.unwrap().1 - 0.8).abs() < 1e-9);
        let text = m.to_string();
        assert!(text.contains("at address (frame 359) the face centre was 0.80 m from the ball"), "{text}");
        assert!(m.peak_speed_mps > 40.0 && m.miss.distance_mm > 50.0, "{m:?}");
    }
}
