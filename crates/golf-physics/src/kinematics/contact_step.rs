//! The impact instant from the head's own motion: the ball takes momentum from the head during the contact
//! (about 0.5 ms), so the head's speed steps down there. Fitting a line of path length against time to the frames
//! before the contact and another to the frames after it, the lines cross at the momentum transfer's centre: an
//! instant measured from the capture, beside the geometric contact of the face with the configured or tracked
//! ball (docs/estimation.md).
//!
//! How big the step is, by the impulse-momentum model (seed section 3.1): a normal impulse `P` on a head of
//! effective mass `m_eff` at the contact point and a ball of mass `m_b` at rest, with the restitution `e` of eq.
//! 3.6 along the normal, gives from eqs. 3.2, 3.4 and 3.6 `P = (1 + e) m_b m_eff / (m_b + m_eff) v`, so the head
//! loses `P / m_eff = (1 + e) m_b / (m_b + m_eff)` of its normal speed ([`im_speed_drop_fraction`]): 34 % for
//! the seed's driver (0.204 kg head, 45.9 g ball, e = 0.83) struck at its centre, more off centre (a smaller
//! `m_eff`).

use crate::math::{Real, SMatrix, SVector, Vector3};

/// The contact's duration the frames are kept away from (s): a frame within it is neither before nor after.
pub const CONTACT_S: Real = 0.0005;

/// The frames fitted on each side of the geometric contact: those within this time of it (s), at most
/// [`MAX_FRAMES_PER_SIDE`]. Over it the head's acceleration is one number (the model's `c`); its jerk is not
/// modelled.
pub const WINDOW_S: Real = 0.015;

/// The most frames fitted on a side.
pub const MAX_FRAMES_PER_SIDE: usize = 12;

/// The fewest frames on a side: a line and its noise.
pub const MIN_FRAMES_PER_SIDE: usize = 3;

/// The step must be this many of its standard deviations to be a step.
pub const MIN_STEP_SIGMAS: Real = 5.0;

/// The crossing's standard deviation must be at most this fraction of the frame interval: the instant is then
/// within one frame interval at two sigma.
pub const MAX_SIGMA_OF_INTERVAL: Real = 0.5;

/// The fraction of its normal speed a head of effective mass `m_eff_kg` loses to a ball of `m_ball_kg` at
/// restitution `e` (impulse-momentum model, seed eqs. 3.2, 3.4, 3.6).
pub fn im_speed_drop_fraction(m_ball_kg: Real, m_eff_kg: Real, e: Real) -> Real {
    (1.0 + e) * m_ball_kg / (m_ball_kg + m_eff_kg)
}

/// The step found: where the speed lines cross and how much the speed dropped.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpeedStep {
    /// The crossing, from the geometric contact (s; positive: after it).
    pub t_from_contact_s: Real,
    /// Its standard deviation (s).
    pub sigma_s: Real,
    /// The face centre's speed along its path before the step, at the geometric contact (m/s): the slope there
    /// of the line fitted to the frames before the split.
    pub speed_before_mps: Real,
    /// The same after the step (m/s): the slope at the geometric contact of the line fitted to the frames after
    /// the split.
    pub speed_after_mps: Real,
    /// The frame interval (s).
    pub interval_s: Real,
}

impl SpeedStep {
    /// The drop as a percentage of the speed before.
    pub fn drop_pct(&self) -> Real {
        100.0 * (self.speed_before_mps - self.speed_after_mps) / self.speed_before_mps
    }

    /// Whether the two instants disagree by more than the frame interval.
    pub fn disagrees(&self) -> bool {
        self.t_from_contact_s.abs() > self.interval_s
    }
}

/// Why no step was placed.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum StepUnresolved {
    /// Fewer than [`MIN_FRAMES_PER_SIDE`] frames on a side of the geometric contact, or no split of the frames
    /// that the model could be fitted to.
    #[error("{before} frames before and {after} after the contact, need {MIN_FRAMES_PER_SIDE} on each side")]
    TooFewFrames {
        /// The frames within [`WINDOW_S`] before the geometric contact (at most [`MAX_FRAMES_PER_SIDE`]).
        before: usize,
        /// The frames within [`WINDOW_S`] after it and more than [`CONTACT_S`] past it.
        after: usize,
    },
    #[error(
        "the step is below the noise: the speed drops {drop_mps:.2} +- {sigma_mps:.2} m/s ({drop_pct:.1} %) and \
         the lines cross +-{sigma_ms:.2} ms, against a frame interval of {interval_ms:.2} ms (need a drop of \
         {MIN_STEP_SIGMAS} sigma and a crossing known to half the interval)"
    )]
    /// The best fit's speed drop is not above [`MIN_STEP_SIGMAS`] of its standard deviation, or the crossing's
    /// standard deviation is above [`MAX_SIGMA_OF_INTERVAL`] of the frame interval.
    BelowNoise {
        /// The speed drop across the step (m/s; the before line's slope less the after line's).
        drop_mps: Real,
        /// Its standard deviation (m/s).
        sigma_mps: Real,
        /// The drop as a percentage of the speed before it.
        drop_pct: Real,
        /// The standard deviation of the lines' crossing (ms).
        sigma_ms: Real,
        /// The frame interval: the median time between the frames used (ms).
        interval_ms: Real,
    },
}

/// The path length `s(t)` on both sides of a split: `a1 + b1 t + c t^2` before it and `a2 + b2 t + c t^2` after it
/// (one acceleration `2c` through the contact: the golfer's and the shaft's forces do not step in 0.5 ms; the
/// ball's does), fitted by least squares over the frames with their covariance per unit noise variance.
#[derive(Debug, Clone, Copy)]
struct StepFit {
    /// `[a1, b1, a2, b2, c]`.
    p: SVector<5>,
    cov: SMatrix<5, 5>,
    ssr: Real,
    dof: Real,
}

impl StepFit {
    /// Fits `path` (time, path length) with the frames before `split` on the first line and those from `from` on
    /// the second.
    fn fit(path: &[(Real, Real)], split: usize, from: usize) -> Option<StepFit> {
        let row = |i: usize, t: Real| {
            if i < split {
                SVector::<5>::new(1.0, t, 0.0, 0.0, t * t)
            } else {
                SVector::<5>::new(0.0, 0.0, 1.0, t, t * t)
            }
        };
        let (mut ata, mut atb) = (SMatrix::<5, 5>::zeros(), SVector::<5>::zeros());
        let used = || path.iter().enumerate().filter(|(i, _)| *i < split || *i >= from);
        for (i, &(t, s)) in used() {
            let r = row(i, t);
            ata += r * r.transpose();
            atb += r * s;
        }
        let cov = ata.try_inverse()?;
        let p = cov * atb;
        let ssr = used().map(|(i, &(t, s))| (s - row(i, t).dot(&p)).powi(2)).sum();
        let dof = used().count() as Real - 5.0;
        (dof >= 1.0).then_some(StepFit { p, cov, ssr, dof })
    }
}

/// Places the speed step in the face centre's path: `frames` are (time from the geometric contact in s, face
/// centre in m), oldest first, the frames around the contact (those within [`WINDOW_S`] of it are used);
/// `noise_floor_m` the frames' position noise as their fit reported it (the estimate's residual): the noise the
/// step is measured against is the larger of it and the model's own residual, so a fit of few frames that
/// happens to pass through its points is not taken for a noiseless one. The split between the frames before and after the step is searched, not
/// assumed: the split (and a frame taken during the contact left out) that the model fits best, so a geometric
/// contact that is frames off does not move the step with it.
pub fn find(frames: &[(Real, Vector3)], noise_floor_m: Real) -> Result<SpeedStep, StepUnresolved> {
    let first_after = frames.iter().position(|f| f.0 >= 0.0).unwrap_or(frames.len());
    let within = |f: &&(Real, Vector3)| f.0.abs() <= WINDOW_S;
    let lo = first_after - frames[..first_after].iter().rev().take(MAX_FRAMES_PER_SIDE).filter(within).count();
    let hi = first_after + frames[first_after..].iter().take(MAX_FRAMES_PER_SIDE).filter(within).count();
    let frames = &frames[lo..hi];
    let before = frames.iter().filter(|f| f.0 < 0.0).count();
    let after = frames.iter().filter(|f| f.0 > CONTACT_S).count();
    if before < MIN_FRAMES_PER_SIDE || after < MIN_FRAMES_PER_SIDE {
        return Err(StepUnresolved::TooFewFrames { before, after });
    }
    // The path length along the frames, through the contact: the chords' sum follows the arc, which the head's
    // speed steps along, however the path curves.
    let mut s = 0.0;
    let path: Vec<(Real, Real)> = frames
        .iter()
        .enumerate()
        .map(|(i, f)| {
            if i > 0 {
                s += (f.1 - frames[i - 1].1).norm();
            }
            (f.0, s)
        })
        .collect();
    let n = path.len();
    let interval_s = {
        let mut d: Vec<Real> = frames.windows(2).map(|w| w[1].0 - w[0].0).collect();
        d.sort_by(|a, b| a.total_cmp(b));
        d[d.len() / 2]
    };
    let mut best: Option<StepFit> = None;
    for split in MIN_FRAMES_PER_SIDE..=n - MIN_FRAMES_PER_SIDE {
        for from in [split, split + 1] {
            if n < from + MIN_FRAMES_PER_SIDE {
                continue;
            }
            if let Some(fit) = StepFit::fit(&path, split, from) {
                if best.as_ref().is_none_or(|b| fit.ssr / fit.dof < b.ssr / b.dof) {
                    best = Some(fit);
                }
            }
        }
    }
    let Some(fit) = best else {
        return Err(StepUnresolved::TooFewFrames { before, after });
    };
    let noise_var = (fit.ssr / fit.dof).max(noise_floor_m * noise_floor_m);
    let [a1, b1, a2, b2, _] = [fit.p[0], fit.p[1], fit.p[2], fit.p[3], fit.p[4]];
    let drop = b1 - b2;
    let c = &fit.cov;
    let sigma_drop = (noise_var * (c[(1, 1)] + c[(3, 3)] - 2.0 * c[(1, 3)])).max(0.0).sqrt();
    let t = if drop != 0.0 { (a2 - a1) / drop } else { 0.0 };
    // dt/d[a1, b1, a2, b2, c]
    let g = SVector::<5>::new(-1.0, -t, 1.0, t, 0.0) / drop.abs().max(1e-12) * drop.signum();
    let sigma_t = (noise_var * (g.transpose() * c * g)[(0, 0)]).max(0.0).sqrt();
    if !(drop > MIN_STEP_SIGMAS * sigma_drop && sigma_t <= MAX_SIGMA_OF_INTERVAL * interval_s) {
        return Err(StepUnresolved::BelowNoise {
            drop_mps: drop,
            sigma_mps: sigma_drop,
            drop_pct: 100.0 * drop / b1,
            sigma_ms: sigma_t * 1e3,
            interval_ms: interval_s * 1e3,
        });
    }
    Ok(SpeedStep { t_from_contact_s: t, sigma_s: sigma_t, speed_before_mps: b1, speed_after_mps: b2, interval_s })
}

#[cfg(test)]
#[path = "contact_step_tests.rs"]
mod tests;
