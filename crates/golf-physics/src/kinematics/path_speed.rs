//! The speed along a path from its chords, fitted in time (the club speed of `kinematics::estimate`).

use super::fit::{eval_derivative, poly_fit, TimedPose};
use super::normal_factor::{NormalFactor, MAX_DEGREE};
use crate::math::{Real, Vector3};

/// The speed along a path from its chords: the cumulative chord length `s_k = Σ |p_i − p_{i−1}|` of the frames
/// (oldest first) is fitted with a polynomial in time and differentiated. The speed of a clubhead near impact
/// changes slowly while its direction turns fast (100-200 g of centripetal acceleration), so a low degree fits
/// `s(t)` over a long span where a Cartesian fit needs a high degree to follow the curvature; the long span and
/// low degree average the noise along the path. A chord is shorter than its arc by `Δφ²/24` for a turn of `Δφ`
/// (5e-5 at 720 Hz on a 1.5 m arc, 7e-4 at 240 Hz), so each chord is lengthened by that factor, with `Δφ` the
/// mean turning angle between it and its neighbours; the noise across the path lengthens a chord by about
/// `σ²/|Δp|` (1e-5 at 720 Hz), far below the noise averaged away.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathSpeedFit {
    t_ref_s: Real,
    scale_s: Real,
    coeffs: [Vector3; MAX_DEGREE + 1],
    degree: usize,
    /// RMS residual of the arc-length fit (m).
    pub residual_rms_m: Real,
    /// The fit's normal factor, for its covariance.
    pub factor: NormalFactor,
}

impl PathSpeedFit {
    /// Fits `degree` to the chords of `poses` (oldest first, at least `degree + 2` of them).
    pub fn fit(poses: &[TimedPose], degree: usize) -> Option<PathSpeedFit> {
        let n = poses.len();
        if n < degree + 2 || n > 64 || degree > MAX_DEGREE {
            return None;
        }
        let t_ref_s = poses[n - 1].t_s;
        let scale_s = (t_ref_s - poses[0].t_s).max(1e-6);
        let mut tau = [0.0; 64];
        let mut s = [Vector3::zeros(); 64];
        // chords[i] from frame i to i + 1, its length, and turns[i] between chords i and i + 1 (at frame i + 1).
        let mut chords = [Vector3::zeros(); 64];
        let mut lengths = [0.0; 64];
        let mut turns = [0.0; 64];
        for i in 0..n - 1 {
            chords[i] = poses[i + 1].position_m - poses[i].position_m;
            lengths[i] = chords[i].norm();
        }
        for i in 0..n.saturating_sub(2) {
            let norms = lengths[i] * lengths[i + 1];
            let (sin, cos) = (chords[i].cross(&chords[i + 1]).norm() / norms, chords[i].dot(&chords[i + 1]) / norms);
            // A few degrees between frames: asin by its series (to 2e-6 relative below 0.3).
            turns[i] = if cos > 0.0 && sin < 0.3 {
                let s2 = sin * sin;
                sin * (1.0 + s2 * (1.0 / 6.0 + s2 * (3.0 / 40.0 + s2 * 15.0 / 336.0)))
            } else {
                sin.atan2(cos)
            };
        }
        let mut length = 0.0;
        for i in 0..n {
            if i > 0 {
                // Chord i − 1 joins frames i − 1 and i; its turning angle is the mean of the turns at its ends.
                let dphi = match (i > 1, i + 1 < n) {
                    (true, true) => 0.5 * (turns[i - 2] + turns[i - 1]),
                    (true, false) => turns[i - 2],
                    (false, true) => turns[i - 1],
                    (false, false) => 0.0,
                };
                length += lengths[i - 1] * (1.0 + dphi * dphi / 24.0);
            }
            tau[i] = (poses[i].t_s - t_ref_s) / scale_s;
            s[i] = Vector3::new(length, 0.0, 0.0);
        }
        let mut coeffs = [Vector3::zeros(); MAX_DEGREE + 1];
        let mut factor = NormalFactor::EMPTY;
        let residual_rms_m = poly_fit(&tau[..n], &s[..n], degree, &mut coeffs, &mut factor)?;
        Some(PathSpeedFit { t_ref_s, scale_s, coeffs, degree, residual_rms_m, factor })
    }

    /// Speed along the path (m/s) at `t_s`.
    pub fn speed_mps(&self, t_s: Real) -> Real {
        eval_derivative(&self.coeffs, self.degree, (t_s - self.t_ref_s) / self.scale_s).x / self.scale_s
    }

    /// The speed's variance per unit noise variance along the path at `t_s` (1/s²).
    pub fn speed_form(&self, t_s: Real) -> Real {
        self.factor.value_slope((t_s - self.t_ref_s) / self.scale_s)[2] / (self.scale_s * self.scale_s)
    }

    /// The noise variance along the path from the fit's residual (m²; white, the chords' shared first endpoint
    /// being the constant coefficient's) and its degrees of freedom.
    pub fn noise(&self) -> (Real, usize) {
        let dof = self.factor.dof();
        let ss = self.residual_rms_m.powi(2) * self.factor.frames() as Real;
        (if dof > 0 { ss / dof as Real } else { 0.0 }, dof)
    }
}
