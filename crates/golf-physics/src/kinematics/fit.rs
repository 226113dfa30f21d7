//! Least-squares polynomial fits in time of a rigid body's pose, evaluated (extrapolated) at any instant.
//!
//! Position: each axis a polynomial of degree `d_p` in `τ = (t − t_ref) / T`. Orientation: the rotation vector
//! `θ_k = Log(R_refᵀ R_k)` relative to the newest frame, a polynomial of degree `d_r`; `R(t) = R_ref Exp(θ(t))`
//! and the world angular velocity `ω = R(t) J_r(θ) θ'(t)`. With two frames and degree one this is exactly the
//! seed's two-point linear extrapolation (section 3.1.4).

use super::so3;
use crate::math::{Real, UnitQuaternion, Vector3};

pub use super::normal_factor::{NormalFactor, MAX_DEGREE};

/// One pose at a time relative to the fit's reference (s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimedPose {
    /// Time relative to the fit's reference (s; the estimator uses the revealing frame, so pre-impact frames
    /// are negative).
    pub t_s: Real,
    /// The fitted point's position (m; the estimator fits the face centre in the world).
    pub position_m: Vector3,
    /// The body's orientation (the estimator's `world_from_club` rotation).
    pub orientation: UnitQuaternion,
}

/// A fitted motion: position and orientation polynomials.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PoseFit {
    t_ref_s: Real,
    scale_s: Real,
    pos: [Vector3; MAX_DEGREE + 1],
    pos_degree: usize,
    rot: [Vector3; MAX_DEGREE + 1],
    rot_degree: usize,
    r_ref: UnitQuaternion,
    /// RMS over the frames of the position residual vectors' lengths (m).
    pub residual_rms_m: Real,
    /// RMS over the frames of the rotation-vector residuals' lengths (rad).
    pub residual_rms_rad: Real,
    /// The position fit's normal factor, for its covariance.
    pub position_factor: NormalFactor,
    /// The rotation fit's normal factor, for its covariance.
    pub rotation_factor: NormalFactor,
}

/// The state of the fitted motion at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PoseAt {
    /// The fitted point's position (m), in the frame of the fitted poses.
    pub position_m: Vector3,
    /// Its velocity, the position polynomial's derivative (m/s).
    pub velocity_mps: Vector3,
    /// The orientation `R(t) = R_ref Exp(θ(t))`.
    pub orientation: UnitQuaternion,
    /// The angular velocity `ω = R(t) J_r(θ) θ'(t)` in the frame the orientations map into (rad/s).
    pub angular_velocity_radps: Vector3,
}

/// Fits `values` (one per frame) at normalised times `tau` with a polynomial of `degree` by least squares
/// (normal equations; the times are scaled to [-1, 0] so they stay well conditioned for degree <= 5). Returns the
/// RMS residual; `factor` receives the normal matrix's Cholesky factor.
pub(super) fn poly_fit(
    tau: &[Real],
    values: &[Vector3],
    degree: usize,
    out: &mut [Vector3; MAX_DEGREE + 1],
    factor: &mut NormalFactor,
) -> Option<Real> {
    // One instance per size, so the small loops unroll.
    match degree {
        0 => poly_fit_sized::<1>(tau, values, out, factor),
        1 => poly_fit_sized::<2>(tau, values, out, factor),
        2 => poly_fit_sized::<3>(tau, values, out, factor),
        3 => poly_fit_sized::<4>(tau, values, out, factor),
        4 => poly_fit_sized::<5>(tau, values, out, factor),
        5 => poly_fit_sized::<6>(tau, values, out, factor),
        _ => None,
    }
}

// The normal equations and their Cholesky factor read as the textbook's indexed sums.
#[allow(clippy::needless_range_loop)]
fn poly_fit_sized<const M: usize>(
    tau: &[Real],
    values: &[Vector3],
    out: &mut [Vector3; MAX_DEGREE + 1],
    factor: &mut NormalFactor,
) -> Option<Real> {
    let mut ata = [[0.0; M]; M];
    let mut aty = [Vector3::zeros(); M];
    for (&t, y) in tau.iter().zip(values) {
        let mut p = [1.0; M];
        for k in 1..M {
            p[k] = p[k - 1] * t;
        }
        for i in 0..M {
            for j in 0..=i {
                ata[i][j] += p[i] * p[j];
            }
            aty[i] += p[i] * y;
        }
    }
    // Cholesky of the (M x M) normal matrix (its lower triangle).
    let mut l = [[0.0; M]; M];
    for i in 0..M {
        for j in 0..=i {
            let mut s = ata[i][j];
            for k in 0..j {
                s -= l[i][k] * l[j][k];
            }
            if i == j {
                if s.is_nan() || s <= 1e-300 {
                    return None;
                }
                l[i][i] = s.sqrt();
            } else {
                l[i][j] = s / l[j][j];
            }
        }
    }
    let mut z = [Vector3::zeros(); M];
    for i in 0..M {
        let mut s = aty[i];
        for k in 0..i {
            s -= l[i][k] * z[k];
        }
        z[i] = s / l[i][i];
    }
    for i in (0..M).rev() {
        let mut s = z[i];
        for k in i + 1..M {
            s -= l[k][i] * out[k];
        }
        out[i] = s / l[i][i];
    }
    for c in out.iter_mut().skip(M) {
        *c = Vector3::zeros();
    }
    factor.coefficients = M;
    factor.frames = tau.len();
    for i in 0..M {
        factor.l[i][..M].copy_from_slice(&l[i]);
    }
    let mut ss = 0.0;
    for (&t, y) in tau.iter().zip(values) {
        ss += (eval(out, M - 1, t) - y).norm_squared();
    }
    Some((ss / tau.len() as Real).sqrt())
}

#[inline]
fn eval(c: &[Vector3; MAX_DEGREE + 1], degree: usize, tau: Real) -> Vector3 {
    let mut v = c[degree];
    for k in (0..degree).rev() {
        v = v * tau + c[k];
    }
    v
}

#[inline]
pub(super) fn eval_derivative(c: &[Vector3; MAX_DEGREE + 1], degree: usize, tau: Real) -> Vector3 {
    if degree == 0 {
        return Vector3::zeros();
    }
    let mut v = c[degree] * degree as Real;
    for k in (1..degree).rev() {
        v = v * tau + c[k] * k as Real;
    }
    v
}

/// Poses prepared for fitting: times scaled to the window, positions relative to the newest frame and, for the
/// newest frames an orientation fit may use, rotation vectors relative to the newest frame. Several fits over
/// nested windows share one series, so each frame's logarithm is taken once.
#[derive(Debug, Clone)]
pub struct PoseSeries {
    n: usize,
    rot_frames: usize,
    t_ref_s: Real,
    scale_s: Real,
    tau: [Real; 64],
    p: [Vector3; 64],
    th: [Vector3; 64],
    newest: TimedPose,
}

impl PoseSeries {
    /// Prepares the poses (oldest first, at most 64) with rotation vectors for the newest `rot_frames`.
    pub fn new(poses: &[TimedPose], rot_frames: usize) -> Option<PoseSeries> {
        let n = poses.len();
        if n == 0 || n > 64 || rot_frames > n {
            return None;
        }
        let newest = poses[n - 1];
        let t_ref_s = newest.t_s;
        let scale_s = (t_ref_s - poses[0].t_s).max(1e-6);
        let mut tau = [0.0; 64];
        let mut p = [Vector3::zeros(); 64];
        let mut th = [Vector3::zeros(); 64];
        for (i, pose) in poses.iter().enumerate() {
            tau[i] = (pose.t_s - t_ref_s) / scale_s;
            p[i] = pose.position_m - newest.position_m;
        }
        // Rotation vectors relative to the newest frame, unwrapped from newest to oldest so that a window turning
        // through more than π stays continuous (θ and θ (1 − 2π/|θ|) are the same rotation).
        let r_ref_inv = newest.orientation.inverse();
        let mut previous = Vector3::zeros();
        for i in (n - rot_frames..n).rev() {
            let mut theta = so3::log(&(r_ref_inv * poses[i].orientation));
            let angle = theta.norm();
            // The other representative has a norm of 2π − |θ| >= π, so it can only be nearer the previous vector
            // when |θ| + |previous| > π.
            if angle > 1e-9 && angle + previous.norm() > std::f64::consts::PI {
                for k in [-1.0, 1.0] {
                    let alt = theta * (1.0 + k * 2.0 * std::f64::consts::PI / angle);
                    if (alt - previous).norm() < (theta - previous).norm() {
                        theta = alt;
                    }
                }
            }
            th[i] = theta;
            previous = theta;
        }
        Some(PoseSeries { n, rot_frames, t_ref_s, scale_s, tau, p, th, newest })
    }

    /// Fits position over the newest `pos_frames` and orientation over the newest `rot_frames` (at most the
    /// series' own); `None` for a window too short for its degree or a singular fit.
    pub fn fit(&self, pos_frames: usize, pos_degree: usize, rot_frames: usize, rot_degree: usize) -> Option<PoseFit> {
        let n = self.n;
        if pos_frames > n
            || rot_frames > self.rot_frames
            || pos_frames <= pos_degree
            || rot_frames <= rot_degree
            || pos_degree > MAX_DEGREE
            || rot_degree > MAX_DEGREE
        {
            return None;
        }
        let mut pos = [Vector3::zeros(); MAX_DEGREE + 1];
        let mut rot = [Vector3::zeros(); MAX_DEGREE + 1];
        let (mut position_factor, mut rotation_factor) = (NormalFactor::EMPTY, NormalFactor::EMPTY);
        let (tau_p, p) = (&self.tau[n - pos_frames..n], &self.p[n - pos_frames..n]);
        let rp = poly_fit(tau_p, p, pos_degree, &mut pos, &mut position_factor)?;
        let (tau_r, th) = (&self.tau[n - rot_frames..n], &self.th[n - rot_frames..n]);
        let rr = poly_fit(tau_r, th, rot_degree, &mut rot, &mut rotation_factor)?;
        pos[0] += self.newest.position_m;
        Some(PoseFit {
            t_ref_s: self.t_ref_s,
            scale_s: self.scale_s,
            pos,
            pos_degree,
            rot,
            rot_degree,
            r_ref: self.newest.orientation,
            residual_rms_m: rp,
            residual_rms_rad: rr,
            position_factor,
            rotation_factor,
        })
    }
}

impl PoseFit {
    /// Fits the poses (oldest first; at least `max(d_p, d_r) + 1` of them). Returns `None` for a singular fit.
    /// Windows over the newest frames: [`PoseSeries::fit`].
    pub fn fit(poses: &[TimedPose], pos_degree: usize, rot_degree: usize) -> Option<PoseFit> {
        PoseSeries::new(poses, poses.len())?.fit(poses.len(), pos_degree, poses.len(), rot_degree)
    }

    /// This fit's position with `other`'s orientation (both fitted to the same poses).
    pub fn with_rotation_of(mut self, other: &PoseFit) -> PoseFit {
        debug_assert!(self.t_ref_s == other.t_ref_s && self.scale_s == other.scale_s);
        self.rot = other.rot;
        self.rot_degree = other.rot_degree;
        self.residual_rms_rad = other.residual_rms_rad;
        self.rotation_factor = other.rotation_factor;
        self
    }

    /// Position (m) at time `t_s`.
    #[inline]
    pub fn position(&self, t_s: Real) -> Vector3 {
        eval(&self.pos, self.pos_degree, (t_s - self.t_ref_s) / self.scale_s)
    }

    /// Orientation at time `t_s`.
    #[inline]
    pub fn orientation(&self, t_s: Real) -> UnitQuaternion {
        self.r_ref * so3::exp(&eval(&self.rot, self.rot_degree, (t_s - self.t_ref_s) / self.scale_s))
    }

    /// Full state at time `t_s`.
    pub fn at(&self, t_s: Real) -> PoseAt {
        let tau = (t_s - self.t_ref_s) / self.scale_s;
        let theta = eval(&self.rot, self.rot_degree, tau);
        let dtheta = eval_derivative(&self.rot, self.rot_degree, tau) / self.scale_s;
        let orientation = self.r_ref * so3::exp(&theta);
        let w_body: Vector3 = so3::right_jacobian(&theta) * dtheta;
        PoseAt {
            position_m: eval(&self.pos, self.pos_degree, tau),
            velocity_mps: eval_derivative(&self.pos, self.pos_degree, tau) / self.scale_s,
            orientation,
            angular_velocity_radps: orientation * w_body,
        }
    }

    /// The newest frame's time (s).
    pub fn t_ref_s(&self) -> Real {
        self.t_ref_s
    }

    /// The window's span (s): times are normalised as `τ = (t − t_ref) / span`.
    pub fn scale_s(&self) -> Real {
        self.scale_s
    }

    /// Per axis and per unit noise variance: the variance of the fitted position at `t_s`, its covariance with
    /// the velocity and the velocity's variance (1, 1/s, 1/s²).
    pub fn position_form(&self, t_s: Real) -> [Real; 3] {
        Self::form(&self.position_factor, (t_s - self.t_ref_s) / self.scale_s, self.scale_s)
    }

    /// The same of the rotation vector and its rate.
    pub fn rotation_form(&self, t_s: Real) -> [Real; 3] {
        Self::form(&self.rotation_factor, (t_s - self.t_ref_s) / self.scale_s, self.scale_s)
    }

    /// The bias of the position fit on a path known exactly: the same polynomial fitted to `path` (position and
    /// velocity at a time, s) at the position fit's frames (`frame_t_s`, the newest of them), minus the path, in
    /// position and velocity at `t_s`.
    pub fn position_bias_on(
        &self,
        frame_t_s: &[Real],
        path: impl Fn(Real) -> (Vector3, Vector3),
        t_s: Real,
    ) -> (Vector3, Vector3) {
        let n = self.position_factor.frames.min(frame_t_s.len());
        let times = &frame_t_s[frame_t_s.len() - n..];
        let mut tau = [0.0; 64];
        let mut values = [Vector3::zeros(); 64];
        for (i, &t) in times.iter().enumerate() {
            tau[i] = (t - self.t_ref_s) / self.scale_s;
            values[i] = path(t).0;
        }
        let c = self.position_factor.solve(&tau[..n], &values[..n]);
        let (p, v) = path(t_s);
        let tau_s = (t_s - self.t_ref_s) / self.scale_s;
        let degree = self.position_factor.coefficients - 1;
        (eval(&c, degree, tau_s) - p, eval_derivative(&c, degree, tau_s) / self.scale_s - v)
    }

    /// The frames both fits share (the newest of `frame_t_s`, oldest first), each with its time and the position
    /// and rotation fits' weights at `t_s`: `(t_k, a_k, ȧ_k, b_k, ḃ_k)`, the fitted value's and rate's (per
    /// second) response to that frame's value.
    pub fn shared_weights(&self, frame_t_s: &[Real], t_s: Real) -> Vec<(Real, Real, Real, Real, Real)> {
        let tau = (t_s - self.t_ref_s) / self.scale_s;
        let taus: Vec<Real> = frame_t_s.iter().map(|t| (t - self.t_ref_s) / self.scale_s).collect();
        let weights = |f: &NormalFactor| {
            let n = f.frames.min(taus.len());
            let w: Vec<(Real, Real)> = f.weights(tau, &taus[taus.len() - n..]).collect();
            (n, w)
        };
        let ((np, wp), (nr, wr)) = (weights(&self.position_factor), weights(&self.rotation_factor));
        let shared = np.min(nr);
        let at = taus.len() - shared;
        (0..shared)
            .map(|i| {
                let (a, da) = wp[np - shared + i];
                let (b, db) = wr[nr - shared + i];
                (frame_t_s[at + i], a, da / self.scale_s, b, db / self.scale_s)
            })
            .collect()
    }

    /// The position fit's noise variance per axis from its residual (m²) and its degrees of freedom.
    pub fn position_noise(&self) -> (Real, usize) {
        Self::noise(&self.position_factor, self.residual_rms_m)
    }

    /// The rotation fit's noise variance per axis (rad²) and its degrees of freedom.
    pub fn rotation_noise(&self) -> (Real, usize) {
        Self::noise(&self.rotation_factor, self.residual_rms_rad)
    }

    fn form(factor: &NormalFactor, tau: Real, scale_s: Real) -> [Real; 3] {
        let [a, b, c] = factor.value_slope(tau);
        [a, b / scale_s, c / (scale_s * scale_s)]
    }

    /// The RMS is of the residual vectors' norms: per axis, `Σ|r|² / (3 (n − p))` with `3 (n − p)` degrees of
    /// freedom.
    fn noise(factor: &NormalFactor, residual_rms: Real) -> (Real, usize) {
        let dof = 3 * factor.dof();
        let ss = residual_rms * residual_rms * factor.frames() as Real;
        (if dof > 0 { ss / dof as Real } else { 0.0 }, dof)
    }
}

#[cfg(test)]
#[path = "fit_tests.rs"]
mod tests;
