//! How sure an impact estimate is: the covariance of the delivery it gives, propagated from the frames' noise
//! (the fits' residuals), the frame rate and span (the fits' normal matrices), the impact instant's uncertainty
//! (the contact solve) and the calibration's residuals.
//!
//! The motion at the contact instant `t*` is `x = (f, v, φ, ω)`: the face centre's position and velocity, the
//! head's orientation (a world-frame rotation vector about the estimate) and angular velocity. Its covariance
//! `Σ_x` comes from the fits, each least squares with white noise of the variance its residual shows:
//!
//! - the face centre's path: the arc's parameters `σ² (JᵀJ)⁻¹` (`ArcFit::position_velocity_covariance`), or the
//!   polynomial's `σ² (AᵀA)⁻¹` per axis evaluated at `t*` (value and slope, extrapolated);
//! - the club speed, where the path-length fit gives it: the velocity's direction from the path, its magnitude
//!   with the path-length fit's variance and its bias: a low degree over a long span follows the speed's change
//!   only so far, so the fit one degree higher over the same frames measures what the lower one misses: their
//!   difference `d` at `t*` adds `d²` to the speed's variance;
//! - the arc's bias, where the arc fits: its departure from the polynomial path at `t*` plus the polynomial's own
//!   bias on the arc's path (what the polynomial misses of a path the arc's shape), less the departure's noise
//!   along its own direction;
//! - the orientation: the rotation vector's polynomial the same way (`R = R_ref Exp(θ)`, so a change `δθ` turns
//!   the head by `R J_r(θ) δθ`, within a few per cent of `δθ` for the few degrees it turns past the newest frame);
//! - the calibration, where the rig's calibration reports its residuals: a constant error of the face centre's
//!   place (`σ_p² I` on `f`) and of the head's orientation (`σ_a² I` on `φ`, and on the velocity's direction).
//!   Zero when it reports none.
//!
//! The contact instant moves with the state: the gap `G(f, φ)` between face and ball is zero at `t*`, so
//! `δt* = −(∂G/∂f δf + ∂G/∂φ δφ) / Ġ` with `Ġ = ∂G/∂f v + ∂G/∂φ ω` the closing rate, and the state at the moved
//! contact is `x + ẋ δt*` with `ẋ = (v, a, ω, α)` (`a`, `α`: the fits' accelerations). The impact location
//! `(h, v)` is where the face meets the ball at the moved contact; `∂G` and `∂(h, v)` are forward differences of
//! the face's gap (six evaluations). The delivery's numbers (speed, attack and path from the velocity, face angle
//! and loft from the face normal `n = R n₀`, dynamic lie from the shaft) are then linear in the moved state, and
//! `Σ_d = D E Σ_x Eᵀ Dᵀ` with `E = I + ẋ ∂t*/∂x`.

use super::estimate::{ImpactEstimate, Scene};
use super::so3;
use crate::equipment::ClubSpec;
use crate::impact::uncertainty::{DeliveryCovariance, DELIVERY_PARAMETERS};
use crate::math::{skew, Isometry3, Matrix3, Point3, Real, SMatrix, Translation3Ext, Vector3};

/// The calibration's residuals, one sigma: the face centre's place on the tracked body and the lab's axes
/// (zero: the calibration reported none).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct CalibrationSigma {
    /// The face centre's place, per axis (m): `σ_p`.
    pub position_m: Real,
    /// The head's orientation, per axis of its rotation vector (rad): `σ_a`.
    pub angle_rad: Real,
}

/// The uncertainty of one estimate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EstimateUncertainty {
    /// The covariance `Σ_d = D E Σ_x Eᵀ Dᵀ` of the delivery's eleven parameters (SI units).
    pub delivery: DeliveryCovariance,
    /// The impact instant's standard deviation (s).
    pub t_impact_sigma_s: Real,
}

type M12 = SMatrix<12, 12>;

/// Steps of the gap's forward differences (m, rad): the gap is smooth on this scale and far above rounding.
const GAP_STEP: Real = 1e-6;
/// Step of the accelerations' central differences (s).
const ACCEL_STEP_S: Real = 1e-4;

/// The per-axis covariance `[var x, cov(x, ẋ), var ẋ]` as a 6x6 block (x first).
fn isotropic(c: [Real; 3]) -> SMatrix<6, 6> {
    let mut m = SMatrix::<6, 6>::zeros();
    for i in 0..3 {
        m[(i, i)] = c[0];
        m[(i, 3 + i)] = c[1];
        m[(3 + i, i)] = c[1];
        m[(3 + i, 3 + i)] = c[2];
    }
    m
}

/// The arc's bias where it fits: an arc is the head's path only so far (the wrists uncock, the radius changes).
/// The polynomial path over the same frames measures it: at the contact the arc is off the truth by `b_arc` and
/// the polynomial by its own bias `b_poly`, so their departure `d = arc − poly` is `b_arc − b_poly` plus noise,
/// and `b_arc = d + b_poly`. `b_poly` is the polynomial's bias on the arc's own path (`bias_on_arc`,
/// [`PoseFit::position_bias_on`](super::fit::PoseFit::position_bias_on)): large at 240 Hz, where a low degree
/// spans few frames over the same 44 ms, and of the same sign as the arc's where both miss the uncocking, so the
/// departure alone overstated the bias at 240 Hz and understated it at 720 Hz. The estimate `b = d + b_poly`
/// holds the departure's noise `Σ_e = Σ_poly − Σ_arc` (the arc the efficient fit, the difference's covariance is
/// the difference of the covariances); the bias enters as `b bᵀ`, along one direction, where that noise is
/// `b̂ᵀ Σ_e b̂`, not `tr Σ_e` (all three axes'): `b bᵀ max(0, 1 − bᵀ Σ_e b / |b|⁴)`, in position and velocity
/// apart (`noise`: `Σ_e` as a 6x6 block).
fn arc_bias(departure: (Vector3, Vector3), bias_on_arc: (Vector3, Vector3), noise: &SMatrix<6, 6>) -> SMatrix<6, 6> {
    let shrink = |b: Vector3, k: usize| {
        let b2 = b.norm_squared();
        if b2 == 0.0 {
            return b;
        }
        let along = (b.transpose() * noise.fixed_view::<3, 3>(k, k) * b)[(0, 0)] / (b2 * b2);
        b * (1.0 - along).clamp(0.0, 1.0).sqrt()
    };
    outer(&shrink(departure.0 + bias_on_arc.0, 0), &shrink(departure.1 + bias_on_arc.1, 3))
}

/// `b bᵀ` of a bias in position and velocity, as a 6x6 block.
fn outer(bp: &Vector3, bv: &Vector3) -> SMatrix<6, 6> {
    let b = SMatrix::<6, 1>::from_column_slice(&[bp.x, bp.y, bp.z, bv.x, bv.y, bv.z]);
    b * b.transpose()
}

/// The polynomial path's bias on the osculating circle of the fitted motion at the contact (`t`, s from the
/// revealing frame; `frames` the fitted frames' times): the head swings on an arc, whose higher derivatives
/// (`|f⁽ᵏ⁾| = sᵏ / ρᵏ⁻¹` at speed `s` on radius `ρ`) a polynomial of degree five or less over 40 ms misses; fitted
/// to that circle at the frames' times, the polynomial is off at the contact by this much in position and
/// velocity (the circle carries the fitted tangential acceleration too).
fn circle_bias(fit: &super::fit::PoseFit, frames: &[Real], t: Real, accel: Vector3) -> (Vector3, Vector3) {
    let at = fit.at(t);
    let (f0, v0) = (at.position_m, at.velocity_mps);
    let s = v0.norm();
    let v_hat = v0 / s;
    let a_t = accel.dot(&v_hat);
    let a_n = accel - a_t * v_hat;
    let curvature = a_n.norm() / (s * s);
    if !(curvature > 1e-3 && s > 0.1) {
        return (Vector3::zeros(), Vector3::zeros());
    }
    let (rho, n_hat) = (1.0 / curvature, a_n.normalize());
    let centre = f0 + rho * n_hat;
    let path = |time: Real| {
        let d = time - t;
        let phi = (s * d + 0.5 * a_t * d * d) / rho;
        let dphi = (s + a_t * d) / rho;
        let (sin, cos) = phi.sin_cos();
        (centre + rho * (v_hat * sin - n_hat * cos), rho * dphi * (v_hat * cos + n_hat * sin))
    };
    fit.position_bias_on(frames, path, t)
}

/// Whether a variance estimate `a` is above `b` by more than noise explains: the F ratio beyond its 95th
/// percentile (Paulson's normal approximation of the cube root of F, within 0.01 of the table from 10 degrees of
/// freedom up).
fn exceeds_f95((a, d1): (Real, usize), (b, d2): (Real, usize)) -> bool {
    if d1 == 0 || d2 == 0 || b.is_nan() || b <= 0.0 {
        return false;
    }
    let (g1, g2) = (2.0 / (9.0 * d1 as Real), 2.0 / (9.0 * d2 as Real));
    let x = (a / b).cbrt();
    let z = ((1.0 - g2) * x - (1.0 - g1)) / (g2 * x * x + g1).sqrt();
    z > 1.645
}

/// The variance of a Student t with `dof` degrees of freedom over its scale's, `ν / (ν − 2)`; `None` below
/// three.
fn student(dof: usize) -> Option<Real> {
    (dof > 2).then(|| dof as Real / (dof - 2) as Real)
}

/// Gradients of the elevation `atan2(u_y, hypot(u_x, u_z))` and of the azimuth `atan2(u_z, u_x)` of `u`.
fn angle_gradients(u: &Vector3) -> (Vector3, Vector3) {
    let rho2 = u.x * u.x + u.z * u.z;
    let rho = rho2.sqrt();
    let n2 = u.norm_squared();
    let elevation = Vector3::new(-u.x * u.y / rho, rho, -u.z * u.y / rho) / n2;
    let azimuth = Vector3::new(-u.z, 0.0, u.x) / rho2;
    (elevation, azimuth)
}

/// The covariance of the delivery `estimate` gives on `club` (`scene` its face and ball). `None` when the fits
/// leave no residual to measure the noise by (`linear2`'s two frames) or the contact is not closing.
pub fn estimate_uncertainty(
    estimate: &ImpactEstimate,
    scene: &Scene,
    club: &ClubSpec,
    calibration: &CalibrationSigma,
) -> Option<EstimateUncertainty> {
    let t = estimate.t_from_reveal_s;
    let fit = &estimate.fits.pose;
    let r_fc = scene.face.center_m;
    let state = &estimate.state;
    let rot = state.world_from_club.rotation;
    let f = (state.world_from_club * Point3::from(r_fc)).coords;
    let w = state.angular_velocity_radps;
    let v = state.cg_velocity_mps + w.cross(&(rot * r_fc));

    // The frames' noise, pooled over the fits that show noise alone: the polynomial path's residual, the
    // path-length fit's (the same noise along the path) and the arc's (kept or dropped) unless an F test says it
    // holds more than noise (a path of another shape). A polynomial path kept over an arc that fitted worse was
    // often kept because its own residual came out low by chance; the arc's residual corrects that. Where the
    // path-length fit is there, it is the reference: a smooth one-dimensional cubic, its residual is the noise
    // alone at every rate, while the path's fits over the same 40 ms also hold what their shape misses of the
    // head's path (at 240 Hz their residual was 0.32 mm rms against the frames' 0.2 mm, the path length's
    // 0.21 mm). That misfit is already counted at the contact as the fits' bias, so a path fit whose residual
    // an F test finds above the path length's is left out of the noise. The orientation's noise is its own
    // fit's. A variance estimated with ν degrees of freedom leaves the error a Student t, whose variance is
    // ν / (ν − 2) times the estimate's.
    let poly_noise = fit.position_noise();
    let arc = estimate.arc.as_ref().or(estimate.fits.dropped_arc.as_ref());
    let arc_fits = arc.filter(|a| !exceeds_f95(a.noise_variance(), poly_noise));
    let speed_noise = estimate.fits.speed.map(|s| s.noise());
    let shows_noise = |v: (Real, usize)| speed_noise.is_none_or(|s| !exceeds_f95(v, s));
    let pooled = [
        Some(poly_noise).filter(|&p| shows_noise(p)),
        speed_noise,
        arc_fits.map(|a| a.noise_variance()).filter(|&a| shows_noise(a)),
    ];
    let (ss, dof) = pooled.iter().flatten().fold((0.0, 0), |(ss, dof), (v, d)| (ss + v * *d as Real, dof + d));
    let position_var = ss / dof.max(1) as Real * student(dof)?;
    let (rotation_noise, rotation_dof) = fit.rotation_noise();
    let rotation_var = rotation_noise * student(rotation_dof)?;

    // The face centre's position and velocity. The arc's covariance where it is the estimate and fits as noise
    // alone would; else the polynomial path's, with its bias on the reference path (the arc where it fits, else
    // the osculating circle), and, where the arc is the estimate all the same, the arc's departure from the
    // polynomial path: its error is that departure plus the polynomial's.
    let poly_at = fit.at(t);
    let poly_accel =
        (fit.at(t + ACCEL_STEP_S).velocity_mps - fit.at(t - ACCEL_STEP_S).velocity_mps) / (2.0 * ACCEL_STEP_S);
    let (mut s_fv, velocity_fit, accel) = match (&estimate.arc, arc_fits) {
        (Some(a), Some(_)) => (
            {
                let frames = &estimate.fits.frame_t_s[..estimate.fits.frames];
                let departure = (a.position(t) - poly_at.position_m, a.velocity(t) - poly_at.velocity_mps);
                let bias_on_arc = fit.position_bias_on(frames, |time| (a.position(time), a.velocity(time)), t);
                let s_arc = a.position_velocity_covariance(t)? * position_var;
                let s_poly = isotropic(fit.position_form(t).map(|c| c * position_var));
                s_arc + arc_bias(departure, bias_on_arc, &(s_poly - s_arc))
            },
            a.velocity(t),
            (a.velocity(t + ACCEL_STEP_S) - a.velocity(t - ACCEL_STEP_S)) / (2.0 * ACCEL_STEP_S),
        ),
        (reported, reference) => {
            let frames = &estimate.fits.frame_t_s[..estimate.fits.frames];
            let (bp, bv) = match reference {
                Some(a) => fit.position_bias_on(frames, |time| (a.position(time), a.velocity(time)), t),
                None => circle_bias(fit, frames, t, poly_accel),
            };
            let mut s_fv = isotropic(fit.position_form(t).map(|c| c * position_var)) + outer(&bp, &bv);
            if let Some(a) = reported {
                s_fv += outer(&(a.position(t) - poly_at.position_m), &(a.velocity(t) - poly_at.velocity_mps));
            }
            (s_fv, reported.map_or(poly_at.velocity_mps, |a| a.velocity(t)), poly_accel)
        }
    };
    let v_hat = v.normalize();
    let across = Matrix3::identity() - v_hat * v_hat.transpose();
    if let Some(speed) = &estimate.fits.speed {
        // The velocity is the path's direction at the path-length fit's speed: δv = k P δv_path + v̂ δs.
        let k = v.norm() / velocity_fit.norm();
        let mut t6 = SMatrix::<6, 6>::identity();
        t6.fixed_view_mut::<3, 3>(3, 3).copy_from(&(across * k));
        s_fv = t6 * s_fv * t6.transpose();
        let along = v_hat * v_hat.transpose() * (speed.speed_form(t) * position_var + speed_bias_var(estimate, t));
        let vv = s_fv.fixed_view::<3, 3>(3, 3) + along;
        s_fv.fixed_view_mut::<3, 3>(3, 3).copy_from(&vv);
    }
    let s_rw = isotropic(fit.rotation_form(t).map(|c| c * rotation_var));

    let mut s_x = M12::zeros();
    s_x.fixed_view_mut::<6, 6>(0, 0).copy_from(&s_fv);
    s_x.fixed_view_mut::<6, 6>(6, 6).copy_from(&s_rw);
    // The face centre's path and the orientation share each frame's turn: the face centre is the tracked pose
    // moved by `R_k r_fc`, so a frame's orientation noise `δφ_k` moves it by `δφ_k × R_k r_fc` too. Through the
    // fits' weights at the contact (`a_k`, `b_k`, and their rates), `cov(δf, δφ) = −σ_a² Σ a_k b_k [R_k r_fc]×
    // R_k R(t)ᵀ`, the rotation fit's world-frame error being its frames' `R(t) R_kᵀ δφ_k`. The path's weights are
    // the polynomial path's, the arc's too where it is the estimate (its linear response to a frame is of the
    // same reach). Without it, the fields that move with both (launch angle with loft and impact height, launch
    // direction with face and heel-toe place) were covered more than the fields alone (docs/uncertainty.md).
    let frames = &estimate.fits.frame_t_s[..estimate.fits.frames];
    let mut cross = SMatrix::<6, 6>::zeros();
    let rot_t = rot.to_rotation_matrix().into_inner().transpose();
    for (t_k, a, da, b, db) in fit.shared_weights(frames, t) {
        let r_k = fit.orientation(t_k).to_rotation_matrix().into_inner();
        let m = -(skew(&(r_k * r_fc)) * r_k * rot_t) * rotation_var;
        for (row, col, w) in [(0, 0, a * b), (0, 3, a * db), (3, 0, da * b), (3, 3, da * db)] {
            let block = cross.fixed_view::<3, 3>(row, col) + m * w;
            cross.fixed_view_mut::<3, 3>(row, col).copy_from(&block);
        }
    }
    if estimate.fits.speed.is_some() {
        // The velocity's across-path part, as above (its along-path part is the path-length fit's).
        let k = v.norm() / velocity_fit.norm();
        let rows = across * k * cross.fixed_view::<3, 6>(3, 0);
        cross.fixed_view_mut::<3, 6>(3, 0).copy_from(&rows);
    }
    s_x.fixed_view_mut::<6, 6>(0, 6).copy_from(&cross);
    s_x.fixed_view_mut::<6, 6>(6, 0).copy_from(&cross.transpose());
    let (sp2, sa2) = (calibration.position_m.powi(2), calibration.angle_rad.powi(2));
    for i in 0..3 {
        s_x[(i, i)] += sp2;
        s_x[(6 + i, 6 + i)] += sa2;
    }
    let dir = across * (v.norm_squared() * sa2);
    let vv = s_x.fixed_view::<3, 3>(3, 3) + dir;
    s_x.fixed_view_mut::<3, 3>(3, 3).copy_from(&vv);

    // The contact solve: the gap and the impact location against the face centre's place and the head's turn.
    let gap_of = |df: &Vector3, dphi: &Vector3| {
        let r = so3::exp(dphi) * rot;
        scene.gap(&Isometry3::from_parts((f + df - r * r_fc).into_translation(), r))
    };
    let g0 = gap_of(&Vector3::zeros(), &Vector3::zeros());
    let mut grad = SMatrix::<3, 6>::zeros(); // rows: gap, h, v; columns: f, φ
    for i in 0..6 {
        let mut d = [Vector3::zeros(), Vector3::zeros()];
        d[i / 3][i % 3] = GAP_STEP;
        let g = gap_of(&d[0], &d[1]);
        grad[(0, i)] = (g.distance_m - g0.distance_m) / GAP_STEP;
        grad[(1, i)] = (g.h_m - g0.h_m) / GAP_STEP;
        grad[(2, i)] = (g.v_m - g0.v_m) / GAP_STEP;
    }
    let alpha = (fit.at(t + ACCEL_STEP_S).angular_velocity_radps - fit.at(t - ACCEL_STEP_S).angular_velocity_radps)
        / (2.0 * ACCEL_STEP_S);
    let g_f = Vector3::new(grad[(0, 0)], grad[(0, 1)], grad[(0, 2)]);
    let g_phi = Vector3::new(grad[(0, 3)], grad[(0, 4)], grad[(0, 5)]);
    let closing = g_f.dot(&v) + g_phi.dot(&w);
    if closing.is_nan() || closing >= -1e-3 {
        return None;
    }
    // δt* = T x, and the state at the moved contact E x = x + ẋ δt*.
    let mut t_row = SMatrix::<1, 12>::zeros();
    let mut x_dot = SMatrix::<12, 1>::zeros();
    for i in 0..3 {
        t_row[(0, i)] = -g_f[i] / closing;
        t_row[(0, 6 + i)] = -g_phi[i] / closing;
        x_dot[i] = v[i];
        x_dot[3 + i] = accel[i];
        x_dot[6 + i] = w[i];
        x_dot[9 + i] = alpha[i];
    }
    let e = M12::identity() + x_dot * t_row;

    // The delivery's parameters against the moved state.
    let mut d = SMatrix::<DELIVERY_PARAMETERS, 12>::zeros();
    let set_row = |d: &mut SMatrix<DELIVERY_PARAMETERS, 12>, row: usize, col: usize, g: &Vector3| {
        for i in 0..3 {
            d[(row, col + i)] = g[i];
        }
    };
    let (attack, path) = angle_gradients(&v);
    set_row(&mut d, 0, 3, &v_hat);
    set_row(&mut d, 1, 3, &attack);
    set_row(&mut d, 2, 3, &path);
    // A turn δφ moves a body vector u by δφ × u = −[u]× δφ.
    let n = rot * scene.face.n0();
    let (loft, face) = angle_gradients(&n);
    set_row(&mut d, 3, 6, &(-skew(&n).transpose() * face));
    set_row(&mut d, 4, 6, &(-skew(&n).transpose() * loft));
    for (row, g) in [(5, 1), (6, 2)] {
        for i in 0..6 {
            d[(row, if i < 3 { i } else { 3 + i })] = grad[(g, i)];
        }
    }
    for i in 0..3 {
        d[(7 + i, 9 + i)] = 1.0;
    }
    let shaft = rot * club.shaft_axis_up();
    let lie_cos = (1.0 - shaft.y * shaft.y).max(1e-12).sqrt();
    set_row(&mut d, 10, 6, &(-skew(&shaft).transpose() * Vector3::y() / lie_cos));

    let de = d * e;
    let cov = de * s_x * de.transpose();
    let t_var = (t_row * s_x * t_row.transpose())[(0, 0)];
    cov.iter().all(|c| c.is_finite()).then_some(EstimateUncertainty {
        delivery: DeliveryCovariance { cov },
        t_impact_sigma_s: t_var.max(0.0).sqrt(),
    })
}

/// The path-length fit's bias at `t` (m²/s²): the square of what the fit one degree higher over the same frames
/// finds at `t`. That difference also holds the noise the higher degree adds; it is kept, not subtracted, since
/// one difference is a one-degree-of-freedom estimate of the bias and subtracting its expected noise leaves the
/// shots whose bias came out low by chance uncovered (`impactd eval extrapolation` measures the coverage).
fn speed_bias_var(estimate: &ImpactEstimate, t: Real) -> Real {
    let (Some(lo), Some(hi)) = (&estimate.fits.speed, &estimate.fits.speed_check) else { return 0.0 };
    (hi.speed_mps(t) - lo.speed_mps(t)).powi(2)
}
