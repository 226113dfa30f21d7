//! Impact detection: the first frame in which the face has reached the ball (the revealing frame) triggers an
//! estimate from the frames before it.
//!
//! The detector watches the gap between the ball's surface and the face surface (see [`Scene::gap`]). It fires
//! when, while armed, the gap turns from positive to non-positive between two accepted frames, or when the
//! previous two frames, extrapolated linearly, put the contact before the new frame (the head may have rebounded
//! or spun after the impact, so the new frame alone can show a positive gap again); the face must have
//! approached faster than `min_approach_speed_mps` (an address or a waggle does not fire), and the crossing must
//! be on the face (within its extents plus a margin). It re-arms once the face centre is `rearm_distance_m`
//! away from the ball.

use super::estimate::{estimate, estimate_at, EstimateError, EstimatorSpec, ImpactEstimate, Scene};
use super::sample::ClubPose;
use super::track::Track;
use crate::equipment::ClubSpec;
use crate::math::{Real, Vector3};

/// Detector settings.
#[derive(Debug, Clone, PartialEq)]
pub struct DetectorConfig {
    /// The ball's centre (m, world).
    pub ball_position_m: Vector3,
    /// The ball's radius (m); the seed's ball by default.
    pub ball_radius_m: Real,
    /// How fast the face's gap to the ball must close between the frames at the crossing for the detector to
    /// fire (m/s): an address or a waggle is slower.
    pub min_approach_speed_mps: Real,
    /// The face centre's distance from the ball's centre (m, world) beyond which a disarmed detector re-arms.
    pub rearm_distance_m: Real,
    /// Tolerance around the face extents for accepting a crossing (m).
    pub face_margin_m: Real,
    /// An estimate may extrapolate at most this far past the newest pre-impact frame (s); see
    /// [`Scene::max_extrapolation_s`].
    pub max_extrapolation_s: Real,
    /// The impact instant the user gives (`--impact-frame`, `--impact-time`): the estimate is made there, once,
    /// instead of at the geometric contact with the ball, which is then not looked for.
    pub given_impact: Option<GivenImpact>,
}

/// An impact instant the user knows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GivenImpact {
    /// The instant of this frame (the rig's or the capture's frame number).
    Frame(u64),
    /// This capture time on the rig's clock (ns).
    TimeNs(u64),
}

impl Default for DetectorConfig {
    fn default() -> Self {
        DetectorConfig {
            ball_position_m: Vector3::zeros(),
            ball_radius_m: crate::equipment::BallSpec::SEED.radius_m,
            min_approach_speed_mps: 3.0,
            rearm_distance_m: 0.25,
            face_margin_m: 0.04,
            max_extrapolation_s: 0.010,
            given_impact: None,
        }
    }
}

/// A detected impact: the estimate (or why there is none) and the frame that revealed it.
#[derive(Debug, Clone, PartialEq)]
pub struct Detection {
    /// The rig's frame number of the revealing frame (with a [`GivenImpact`], the first pose at or after it).
    pub reveal_frame: u64,
    /// The revealing frame's capture time on the rig's clock (ns).
    pub reveal_t_ns: u64,
    /// One estimator's estimate from the frames before the impact, or why it refused.
    pub result: Result<ImpactEstimate, EstimateError>,
}

/// Watches one track for impacts.
#[derive(Debug, Clone)]
pub struct ImpactDetector {
    /// The settings it detects with.
    pub config: DetectorConfig,
    armed: bool,
    previous: Option<(u64, crate::face::FaceGap, Vector3)>,
    before_previous: Option<(u64, crate::face::FaceGap, Vector3)>,
    scratch: Vec<ClubPose>,
    /// The given instant has been estimated at.
    given_used: bool,
}

impl ImpactDetector {
    /// A detector with these settings, disarmed until the face centre is `rearm_distance_m` from the ball.
    pub fn new(config: DetectorConfig) -> Self {
        ImpactDetector {
            config,
            armed: false,
            previous: None,
            before_previous: None,
            scratch: Vec::with_capacity(64),
            given_used: false,
        }
    }

    /// The pre-impact poses of the latest detection (oldest first), for the club data of its path.
    pub fn pre_impact(&self) -> &[ClubPose] {
        &self.scratch
    }

    /// Whether the next crossing would fire.
    pub fn armed(&self) -> bool {
        self.armed
    }

    /// Call after each pose the track accepted; returns a detection when this pose revealed an impact.
    pub fn on_pose(&mut self, track: &Track, club: &ClubSpec, estimators: &[EstimatorSpec]) -> Option<Vec<Detection>> {
        let newest = *track.latest()?;
        let scene = Scene {
            face: &club.face,
            ball_position_m: self.config.ball_position_m,
            ball_radius_m: self.config.ball_radius_m,
            max_extrapolation_s: self.config.max_extrapolation_s,
        };
        if let Some(given) = self.config.given_impact {
            return self.at_given(given, track, &newest, &scene, estimators);
        }
        let g = scene.gap(&newest.world_from_club);
        let face_centre = newest.world_from_club * crate::math::Point3::from(club.face.center_m);
        let distance = (face_centre.coords - self.config.ball_position_m).norm();
        let previous = self.previous.replace((newest.t_ns, g, face_centre.coords));
        let before_previous = std::mem::replace(&mut self.before_previous, previous);
        if !self.armed {
            if distance > self.config.rearm_distance_m {
                self.armed = true;
            }
            return None;
        }
        let (t_prev, prev, centre_prev) = previous?;
        if prev.distance_m <= 0.0 {
            return None;
        }
        let secs = |a: u64, b: u64| b.saturating_sub(a) as Real * 1e-9;
        let dt = secs(t_prev, newest.t_ns);
        // The crossing as the new frame shows it, or as the two frames before it predict it.
        let crossing = if g.distance_m <= 0.0 && dt > 0.0 {
            Some((prev, g, (prev.distance_m - g.distance_m) / dt))
        } else if let Some((t_old, old, _)) = before_previous {
            let dt_old = secs(t_old, t_prev);
            // The face must really have travelled at least the remaining gap since the previous frame.
            if dt_old <= 0.0 || (face_centre.coords - centre_prev).norm() < prev.distance_m {
                None
            } else {
                let k = dt / dt_old;
                let predicted = crate::face::FaceGap {
                    distance_m: prev.distance_m + k * (prev.distance_m - old.distance_m),
                    h_m: prev.h_m + k * (prev.h_m - old.h_m),
                    v_m: prev.v_m + k * (prev.v_m - old.v_m),
                };
                (predicted.distance_m <= 0.0).then_some((prev, predicted, (old.distance_m - prev.distance_m) / dt_old))
            }
        } else {
            None
        };
        let (prev, g, approach_mps) = crossing?;
        if approach_mps < self.config.min_approach_speed_mps {
            return None;
        }
        // Roughly where on the face the crossing happened, interpolated between the two frames: a coarse filter
        // against swings that pass beside the ball. The estimator finds the exact location, and a model refuses
        // a contact off the face.
        let f = prev.distance_m / (prev.distance_m - g.distance_m);
        let (h, v) = (prev.h_m + f * (g.h_m - prev.h_m), prev.v_m + f * (g.v_m - prev.v_m));
        let m = self.config.face_margin_m;
        if h.abs() > club.face_half_width_m + m || v.abs() > club.face_half_height_m + m {
            return None;
        }
        self.armed = false;
        self.scratch.clear();
        self.scratch.extend(track.poses().iter().filter(|p| p.t_ns < newest.t_ns).copied());
        Some(
            estimators
                .iter()
                .map(|spec| Detection {
                    reveal_frame: newest.frame,
                    reveal_t_ns: newest.t_ns,
                    result: estimate(spec, &self.scratch, newest.t_ns, &scene),
                })
                .collect(),
        )
    }

    /// A detection at the given instant, from the first pose at or after it.
    fn at_given(
        &mut self,
        given: GivenImpact,
        track: &Track,
        newest: &ClubPose,
        scene: &Scene,
        estimators: &[EstimatorSpec],
    ) -> Option<Vec<Detection>> {
        if self.given_used {
            return None;
        }
        let t_given_ns = match given {
            GivenImpact::TimeNs(t) => (newest.t_ns >= t).then_some(t)?,
            GivenImpact::Frame(n) if newest.frame == n => newest.t_ns,
            GivenImpact::Frame(n) if newest.frame > n => {
                // The frame is missing: its instant between the poses around it.
                let before = track.poses().iter().rev().find(|p| p.frame < n)?;
                let f = (n - before.frame) as Real / (newest.frame - before.frame) as Real;
                before.t_ns + (f * newest.t_ns.saturating_sub(before.t_ns) as Real).round() as u64
            }
            GivenImpact::Frame(_) => return None,
        };
        self.given_used = true;
        self.scratch.clear();
        self.scratch.extend(track.poses().iter().filter(|p| p.t_ns < t_given_ns).copied());
        let given_t_s = -(newest.t_ns.saturating_sub(t_given_ns) as Real) * 1e-9;
        Some(
            estimators
                .iter()
                .map(|spec| Detection {
                    reveal_frame: newest.frame,
                    reveal_t_ns: newest.t_ns,
                    result: estimate_at(spec, &self.scratch, newest.t_ns, scene, Some(given_t_s)),
                })
                .collect(),
        )
    }
}
