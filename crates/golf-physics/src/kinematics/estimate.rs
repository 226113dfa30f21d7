//! Impact-state estimators: fit the pre-impact frames, solve for the first contact between the face surface
//! and the ball sphere on the fitted motion, and extrapolate the full state to that instant.
//!
//! - `linear2`: the seed's method (section 3.1.4): the two frames before impact, extrapolated linearly (position
//!   in R³, orientation along the geodesic of SO(3)).
//! - `poly`: a least-squares polynomial in time over the last frames for position (cubic) and for the rotation
//!   vector relative to the newest frame (cubic), so curvature of the arc (100-200 g of centripetal
//!   acceleration) and the face's angular acceleration are modelled and noise is averaged; the club speed from
//!   a cubic in time of the path length (the speed changes slowly while the direction turns fast).
//! - `arc` (the default): `poly`, with the face centre's path from an arc in the swing's plane ([`ArcFit`]) over a
//!   longer span, kept while it fits the frames about as well as `poly`'s path (on a double pendulum's path, as
//!   the wrist uncocks, it may not).

use super::arc::ArcFit;
use super::fit::{PoseFit, PoseSeries, TimedPose};
use super::path_speed::PathSpeedFit;
use super::sample::ClubPose;
use crate::face::Face;
use crate::impact::ImpactState;
use crate::math::{Isometry3, Real, Translation3Ext, Vector3};

pub use super::spec::{EstimatorSpec, EstimatorSpecError, PathSpeedSpec};

/// A long window's residual this many times the half window's means the long model lacks fit. With white noise
/// alone the ratio is about sqrt((N - p) / N) / sqrt((N/2 - p) / (N/2)), 1.1-1.2 for the default spans.
const LACK_OF_FIT_RATIO: Real = 1.5;

/// The arc is dropped for the polynomial path when its RMS residual exceeds the polynomial's by this factor. With
/// noise alone the ratio is 1.05 (99 % of the evaluation's arc swings below 1.21); on double-pendulum paths the
/// median is 1.24 and a twentieth are above 3.8. Shots between keep the arc: its small misfit there costs less than
/// the polynomial's noise.
const ARC_LACK_OF_FIT_RATIO: Real = 1.3;

/// Why an estimator refused.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EstimateError {
    /// Fewer pre-impact frames than the estimator fits.
    #[error("too few good pre-impact frames: {have}, need {need}")]
    TooFewFrames {
        /// The pre-impact frames there are (for a windowed estimator, those within its rotation window).
        have: usize,
        /// The frames the estimator needs: its `frames`, or [`EstimatorSpec::MIN_WINDOW_FRAMES`] for a window.
        need: usize,
    },
    /// The contact is further from the newest pre-impact frame than [`Scene::max_extrapolation_s`].
    #[error("the newest pre-impact frame is {gap_ms:.1} ms before contact (limit {limit_ms:.1} ms)")]
    StaleFrames {
        /// The time from the newest pre-impact frame to the contact (ms).
        gap_ms: Real,
        /// The scene's [`Scene::max_extrapolation_s`] (ms).
        limit_ms: Real,
    },
    /// The least-squares fit of the pre-impact poses has no unique solution.
    #[error("the fit of the pre-impact frames is singular")]
    SingularFit,
    /// The fitted motion's gap to the ball stays positive (it stops short), or is already closed at the newest
    /// frame before impact (`past`); the gap is the ball surface's from the face surface where it was smallest,
    /// and `h_mm`, `v_mm` the face point nearest the ball there (toward the toe, up the face).
    #[error(
        "the fitted motion does not reach the ball: {}, the face's nearest point {h_mm:+.0} mm toward the toe and \
         {v_mm:+.0} mm up from its centre",
        if *past {
            format!("the face is already {:.0} mm through it at the newest frame before impact", -gap_mm)
        } else {
            format!("it stops {gap_mm:.0} mm short of it")
        }
    )]
    NoContact {
        /// The ball surface's gap from the face surface (mm): positive when the motion stops short, not positive
        /// when it is `past`.
        gap_mm: Real,
        /// The face point nearest the ball, toward the toe from the face centre (mm).
        h_mm: Real,
        /// The face point nearest the ball, up the face from its centre (mm).
        v_mm: Real,
        /// The gap is already closed at the newest pre-impact frame (and up to four frame intervals before it).
        past: bool,
    },
}

impl EstimateError {
    /// The refusal's name for counts and warnings keyed by reason: `too_few_frames`, `stale_frames`,
    /// `singular_fit` or `no_contact`.
    pub fn key(&self) -> &'static str {
        match self {
            EstimateError::TooFewFrames { .. } => "too_few_frames",
            EstimateError::StaleFrames { .. } => "stale_frames",
            EstimateError::SingularFit => "singular_fit",
            EstimateError::NoContact { .. } => "no_contact",
        }
    }
}

/// How much to trust an estimate.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
pub struct Quality {
    /// The pre-impact frames the estimate spans (for a windowed estimator, the longest of its position, arc and
    /// speed windows).
    pub frames_used: usize,
    /// RMS residual of the position fit (mm); 0 for an exact fit (linear2).
    pub residual_rms_mm: Real,
    /// RMS residual of the orientation fit (deg).
    pub residual_rms_deg: Real,
    /// Time from the newest pre-impact frame to the contact (ms).
    pub extrapolation_ms: Real,
    /// A summary in (0, 1]: 1 for a perfect fit with no extrapolation, falling with residuals and extrapolation.
    pub score: Real,
}

/// The estimated impact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpactEstimate {
    /// Contact time on the rig's clock (ns).
    pub t_impact_ns: u64,
    /// The same, as a fraction of a nanosecond-exact offset from the revealing frame (s, negative).
    pub t_from_reveal_s: Real,
    /// The clubhead at the contact (world frame): its pose, velocities and impact location.
    pub state: ImpactState,
    /// How much to trust it.
    pub quality: Quality,
    /// The face centre's arc the estimate used (`arc` estimator, while it fits the frames), with times from the
    /// revealing frame: the club data of the path reuse it (`club_data::swing_arc`).
    pub arc: Option<ArcFit>,
    /// The polynomial fits the estimate used (times from the revealing frame), for its uncertainty
    /// (`kinematics::uncertainty`).
    pub fits: EstimateFits,
}

/// The fits behind an estimate: the pose polynomials (the orientation's, and the face centre's path where there
/// is no arc) and the path-length fit of the club speed, the frames' times, and the noise an arc that was fitted
/// but not kept showed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EstimateFits {
    /// The face centre's position and the orientation fitted over the frames (times from the revealing frame).
    pub pose: PoseFit,
    /// The path-length fit the club speed came from: a windowed estimator's `path_speed` fit, when it succeeded.
    pub speed: Option<PathSpeedFit>,
    /// The path-length fit one degree higher over the same frames, where they allow it: the club speed's bias
    /// (`kinematics::uncertainty`).
    pub speed_check: Option<PathSpeedFit>,
    /// The fitted frames' times from the revealing frame, oldest first (s; the first `frames`).
    pub frame_t_s: [Real; 64],
    /// How many of `frame_t_s` are the fitted frames' (the estimate's [`Quality::frames_used`]).
    pub frames: usize,
    /// An arc fitted and dropped for the polynomial path.
    pub dropped_arc: Option<ArcFit>,
}

/// What an estimate needs to know of the scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scene<'a> {
    /// The club's face (club frame).
    pub face: &'a Face,
    /// The ball's centre (m, world).
    pub ball_position_m: Vector3,
    /// The ball's radius (m).
    pub ball_radius_m: Real,
    /// Extrapolating further than this from the newest pre-impact frame is refused (s).
    pub max_extrapolation_s: Real,
}

impl Scene<'_> {
    /// Gap between the ball surface and the face for a club pose (m), and the nearest face location.
    #[inline]
    pub fn gap(&self, world_from_club: &Isometry3) -> crate::face::FaceGap {
        let ball_club = world_from_club.inverse_transform_point(&self.ball_position_m.into());
        let mut g = self.face.gap(&ball_club.coords);
        g.distance_m -= self.ball_radius_m;
        g
    }
}

/// Estimates the impact from the pre-impact poses (oldest first, all before `reveal_t_ns`).
pub fn estimate(
    spec: &EstimatorSpec,
    pre_impact: &[ClubPose],
    reveal_t_ns: u64,
    scene: &Scene,
) -> Result<ImpactEstimate, EstimateError> {
    estimate_at(spec, pre_impact, reveal_t_ns, scene, None)
}

/// [`estimate`], at a given instant (`given_t_s` from the revealing frame, the user's `--impact-frame` or
/// `--impact-time`) instead of the geometric contact with the ball when one is given: the fitted motion is
/// evaluated there, and the impact location is the face point nearest the ball at that instant.
pub fn estimate_at(
    spec: &EstimatorSpec,
    pre_impact: &[ClubPose],
    reveal_t_ns: u64,
    scene: &Scene,
    given_t_s: Option<Real>,
) -> Result<ImpactEstimate, EstimateError> {
    let (need, pos_frames, pos_degree, rot_frames, rot_degree) = match spec.window_ms {
        None => {
            if pre_impact.len() < spec.frames {
                return Err(EstimateError::TooFewFrames { have: pre_impact.len(), need: spec.frames });
            }
            (spec.frames, spec.frames, spec.position_degree, spec.rotation_frames, spec.rotation_degree)
        }
        Some(window_ms) => {
            let newest = pre_impact.last().map(|p| p.t_ns).unwrap_or(0);
            let within = |ms: Real, cap: usize| {
                let span_ns = (ms * 1e6) as u64;
                pre_impact.iter().rev().take_while(|p| newest - p.t_ns <= span_ns).count().min(cap).min(64)
            };
            let n_p = within(window_ms, spec.frames);
            let n_r = within(spec.rotation_window_ms.unwrap_or(window_ms), spec.rotation_frames).min(n_p);
            if n_r < EstimatorSpec::MIN_WINDOW_FRAMES {
                return Err(EstimateError::TooFewFrames { have: n_r, need: EstimatorSpec::MIN_WINDOW_FRAMES });
            }
            let cap = |n: usize, d: usize| d.min(n / 2 - 1);
            let n_s = spec.path_speed.map_or(0, |ps| within(ps.window_ms, 64));
            let n_a = spec.arc_window_ms.map_or(0, |ms| within(ms, 64));
            (n_p.max(n_s).max(n_a), n_p, cap(n_p, spec.position_degree), n_r, cap(n_r, spec.rotation_degree))
        }
    };
    let used = &pre_impact[pre_impact.len() - need..];
    // Times relative to the revealing frame keep full precision in f64.
    let rel = |t_ns: u64| -((reveal_t_ns - t_ns) as Real) * 1e-9;
    let mut poses = [TimedPose { t_s: 0.0, position_m: Vector3::zeros(), orientation: Default::default() }; 64];
    // The position fit follows the face centre, not the CG: the contact velocity then comes straight from the
    // fitted path instead of through the (noisier) differentiated orientation, v_cg + w x r.
    let r_fit = scene.face.center_m;
    for (dst, p) in poses.iter_mut().zip(used) {
        *dst = TimedPose {
            t_s: rel(p.t_ns),
            position_m: (p.world_from_club * crate::math::Point3::from(r_fit)).coords,
            orientation: p.world_from_club.rotation,
        };
    }
    let arc = spec.arc_window_ms.filter(|_| spec.window_ms.is_some()).and_then(|ms| {
        let span_s = ms * 1e-3;
        let t_newest = poses[need - 1].t_s;
        let points: Vec<(Real, Vector3)> =
            poses[..need].iter().filter(|p| t_newest - p.t_s <= span_s + 1e-9).map(|p| (p.t_s, p.position_m)).collect();
        ArcFit::fit(&points)
    });
    let series = PoseSeries::new(&poses[..need], rot_frames).ok_or(EstimateError::SingularFit)?;
    let mut fit = series.fit(pos_frames, pos_degree, rot_frames, rot_degree).ok_or(EstimateError::SingularFit)?;
    // The arc is kept only while it fits the frames about as well as the polynomial path does: a path of another
    // shape leaves the arc a residual well above the noise, and its extrapolation a bias (README).
    let kept = arc.as_ref().is_some_and(|a| a.residual_rms_m <= ARC_LACK_OF_FIT_RATIO * fit.residual_rms_m);
    let dropped_arc = arc.filter(|_| !kept);
    let arc = arc.filter(|_| kept);
    // A windowed fit spans enough frames to average noise. Half the span has less bias from the motion's higher
    // derivatives: where the long fit's residual is well above the short one's (noise alone makes them nearly
    // equal), the long model lacks fit and the short one is used, for position and orientation separately.
    if spec.window_ms.is_some() {
        let (p2, r2) = (pos_frames / 2, rot_frames / 2);
        let cap = |n: usize, d: usize| d.min((n / 2).saturating_sub(1));
        if r2 >= EstimatorSpec::MIN_WINDOW_FRAMES {
            // With an arc the polynomial path is not used: its short window is not needed.
            let (p2, short_pos_degree) = if arc.is_some() { (1, 0) } else { (p2, cap(p2, pos_degree)) };
            if let Some(short) = series.fit(p2, short_pos_degree, r2, cap(r2, spec.rotation_degree)) {
                let pos_short = arc.is_none() && fit.residual_rms_m > LACK_OF_FIT_RATIO * short.residual_rms_m;
                let rot_short = fit.residual_rms_rad > LACK_OF_FIT_RATIO * short.residual_rms_rad;
                fit = match (pos_short, rot_short) {
                    (false, false) => fit,
                    (true, true) => short,
                    (true, false) => short.with_rotation_of(&fit),
                    (false, true) => fit.with_rotation_of(&short),
                };
            }
        }
    }
    let position_at = |t: Real| arc.as_ref().map_or_else(|| fit.position(t), |a| a.position(t));
    let club_pose = |face_centre: Vector3, orientation: crate::math::UnitQuaternion| {
        Isometry3::from_parts((face_centre - orientation * r_fit).into_translation(), orientation)
    };
    let gap_at = |t: Real| scene.gap(&club_pose(position_at(t), fit.orientation(t))).distance_m;
    let t_last = fit.t_ref_s();
    let t = match given_t_s {
        Some(t) => t,
        None => {
            let dt = if need >= 2 { (t_last - poses[need - 2].t_s).max(1e-5) } else { 1.0 / 720.0 };
            first_contact(&gap_at, t_last, dt).map_err(|(t, past)| {
                let g = scene.gap(&club_pose(position_at(t), fit.orientation(t)));
                EstimateError::NoContact { gap_mm: g.distance_m * 1e3, h_mm: g.h_m * 1e3, v_mm: g.v_m * 1e3, past }
            })?
        }
    };
    let extrapolation_s = t - t_last;
    if extrapolation_s > scene.max_extrapolation_s {
        return Err(EstimateError::StaleFrames {
            gap_ms: extrapolation_s * 1e3,
            limit_ms: scene.max_extrapolation_s * 1e3,
        });
    }
    let mut at = fit.at(t);
    if let Some(a) = &arc {
        at.position_m = a.position(t);
        at.velocity_mps = a.velocity(t);
    }
    let (mut speed_fit, mut speed_check) = (None, None);
    if let Some(ps) = spec.path_speed.filter(|_| spec.window_ms.is_some()) {
        let n_s = {
            let span_ns = (ps.window_ms * 1e6) as u64;
            let newest = used[need - 1].t_ns;
            used.iter().rev().take_while(|p| newest - p.t_ns <= span_ns).count()
        };
        let degree = ps.degree.min(n_s / 2 - 1);
        if let Some(speed) = PathSpeedFit::fit(&poses[need - n_s..need], degree) {
            at.velocity_mps = at.velocity_mps.normalize() * speed.speed_mps(t);
            speed_fit = Some(speed);
            if n_s >= degree + 4 {
                speed_check = PathSpeedFit::fit(&poses[need - n_s..need], degree + 1);
            }
        }
    }
    let world_from_club = club_pose(at.position_m, at.orientation);
    let cg_velocity_mps = at.velocity_mps - at.angular_velocity_radps.cross(&(at.orientation * r_fit));
    let g = scene.gap(&world_from_club);
    let residual_rms_mm = arc.as_ref().map_or(fit.residual_rms_m, |a| a.residual_rms_m) * 1e3;
    let residual_rms_deg = fit.residual_rms_rad.to_degrees();
    let extrapolation_ms = extrapolation_s.max(0.0) * 1e3;
    let score = 1.0 / (1.0 + residual_rms_mm / 1.0 + residual_rms_deg / 0.5 + extrapolation_ms / 5.0);
    let t_impact_ns = (reveal_t_ns as i128 + (t * 1e9).round() as i128).max(0) as u64;
    Ok(ImpactEstimate {
        t_impact_ns,
        t_from_reveal_s: t,
        state: ImpactState {
            world_from_club,
            cg_velocity_mps,
            angular_velocity_radps: at.angular_velocity_radps,
            impact_h_m: g.h_m,
            impact_v_m: g.v_m,
        },
        quality: Quality { frames_used: need, residual_rms_mm, residual_rms_deg, extrapolation_ms, score },
        arc,
        fits: EstimateFits {
            pose: fit,
            speed: speed_fit,
            speed_check,
            frame_t_s: std::array::from_fn(|i| if i < need { poses[i].t_s } else { 0.0 }),
            frames: need,
            dropped_arc,
        },
    })
}

/// The first contact on a fitted motion whose ball gap is `gap_at(t)` (t from the revealing frame), bracketed from
/// the newest pre-impact frame at `t_last`, frames `dt` apart; else the instant to describe the miss at and whether
/// the face is already past the ball there.
fn first_contact(gap_at: &dyn Fn(Real) -> Real, t_last: Real, dt: Real) -> Result<Real, (Real, bool)> {
    // Bracket the first contact: the fitted gap is positive at the newest pre-impact frame (stepping back if
    // noise says otherwise) and not positive by the revealing frame (stepping on a little if the extrapolation
    // falls short).
    let mut lo = t_last;
    let mut g_lo = gap_at(lo);
    let mut steps = 0;
    while g_lo <= 0.0 && steps < 4 {
        lo -= dt;
        g_lo = gap_at(lo);
        steps += 1;
    }
    let mut hi = 0.0;
    let mut g_hi = gap_at(hi);
    steps = 0;
    while g_hi > 0.0 && steps < 4 {
        hi += dt;
        g_hi = gap_at(hi);
        steps += 1;
    }
    if g_lo <= 0.0 {
        return Err((lo, true));
    }
    if g_hi > 0.0 {
        // Where the fitted gap is smallest over the frames' span and the steps beyond it.
        let (mut t_min, mut g_min) = (hi, g_hi);
        for k in 0..=64 {
            let t = lo + (hi - lo) * k as Real / 64.0;
            let g = gap_at(t);
            if g < g_min {
                (t_min, g_min) = (t, g);
            }
        }
        return Err((t_min, false));
    }
    // Illinois false position: superlinear and safe.
    let (mut a, mut fa, mut b, mut fb) = (lo, g_lo, hi, g_hi);
    let mut side = 0i8;
    let mut t = a;
    for _ in 0..60 {
        t = (a * fb - b * fa) / (fb - fa);
        let ft = gap_at(t);
        // A nanometre of gap is a few hundredths of a nanosecond of approach: far below the frames' noise.
        if ft.abs() < 1e-9 || (b - a).abs() < 1e-12 {
            break;
        }
        if ft > 0.0 {
            a = t;
            fa = ft;
            if side == 1 {
                fb *= 0.5;
            }
            side = 1;
        } else {
            b = t;
            fb = ft;
            if side == -1 {
                fa *= 0.5;
            }
            side = -1;
        }
    }
    Ok(t)
}
