//! The face centre's path as an arc: a circle in a plane whose radius and angle change smoothly in time, plus a
//! small departure from the plane. Near impact a clubhead swings on an arc of 1-2 m about the hands (100-200 g of
//! centripetal acceleration, 60-80 deg of turn over the last 40 ms), which a Cartesian polynomial follows only at
//! degree 5 and above; in the arc's own coordinates the same motion is a cubic angle and a quadratic radius, so
//! fewer coefficients span the same frames and the position at contact carries less of the frames' noise.
//!
//! Model, with `τ` the time scaled to the window: `p(τ) = c + r(τ) (cos φ(τ) e₁ + sin φ(τ) e₂) + z(τ) n`, with
//! `φ` cubic, `r` quadratic and `z` linear in `τ`, `n` the normal of the best-fitting plane and `c` in it. The
//! plane comes from the scatter of the points, the circle from Kåsa's algebraic fit, and then Levenberg-Marquardt
//! refines centre, radius and angle polynomials together.

use crate::math::{Real, Vector3};

type M9 = crate::math::SMatrix<9, 9>;
type V9 = crate::math::SVector<9>;

/// Levenberg-Marquardt iterations at most. The benchmark's noisy swings take two or three accepted steps; a
/// few take a dozen or more: centre and radius trade against each other along a shallow valley (a centre moved
/// along the arc's mid-radius is almost a change of the quadratic radius), where the Gauss-Newton steps overshoot
/// and alternate with damped ones.
const MAX_ITERATIONS: usize = 200;

/// The fewest frames an arc fit accepts (nine in-plane coefficients and two out of the plane).
pub const MIN_FRAMES: usize = 8;

/// A fitted arc.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArcFit {
    t_ref_s: Real,
    scale_s: Real,
    origin: Vector3,
    e1: Vector3,
    e2: Vector3,
    n: Vector3,
    /// `[c_x, c_y, r₀, r₁, r₂, φ₀, φ₁, φ₂, φ₃]` in the plane's coordinates.
    p: V9,
    /// Departure from the plane: `z₀ + z₁ τ`.
    z: [Real; 2],
    /// RMS distance of the frames from the fitted path (m).
    pub residual_rms_m: Real,
    /// The in-plane fit's `JᵀJ` at the solution, for the parameters' covariance; and the moments of the departure
    /// from the plane's two stages: the plane through the frames' centroid (its tilt, `β₁ x + β₂ y` in the plane's
    /// coordinates), then `z₀ + z₁ τ`: `Σ (x, y)(x, y)ᵀ`, `Σ (1, τ)(1, τ)ᵀ` and `Σ (1, τ)(x, y)ᵀ`.
    jtj: M9,
    plane_moments: [crate::math::SMatrix<2, 2>; 3],
    frames: usize,
}

#[inline]
fn in_plane(p: &V9, tau: Real) -> (Real, Real, Real, Real) {
    let r = p[2] + tau * (p[3] + tau * p[4]);
    let phi = p[5] + tau * (p[6] + tau * (p[7] + tau * p[8]));
    let dr = p[3] + 2.0 * tau * p[4];
    let dphi = p[6] + tau * (2.0 * p[7] + 3.0 * tau * p[8]);
    (r, phi, dr, dphi)
}

impl ArcFit {
    /// Fits positions `(t_s, p)` (oldest first), times relative to any reference; `None` when there are too few
    /// frames or the points do not describe an arc (a straight or degenerate path).
    pub fn fit(points: &[(Real, Vector3)]) -> Option<ArcFit> {
        let n_pts = points.len();
        if n_pts < MIN_FRAMES {
            return None;
        }
        let t_ref_s = points[n_pts - 1].0;
        let scale_s = (t_ref_s - points[0].0).max(1e-6);
        let taus: Vec<Real> = points.iter().map(|(t, _)| (t - t_ref_s) / scale_s).collect();
        // The sums of powers of τ (to the tenth) do not depend on the parameters: the normal equations of every
        // polynomial fit below are made of them (the refinement's angle-angle block too, `Σ r² τᵏ⁺ˡ` with `r²` a
        // quartic in τ).
        let mut pow_sum = [0.0; 11]; // Σ τᵐ
        for &tau in &taus {
            let mut tk = 1.0;
            for ps in pow_sum.iter_mut() {
                *ps += tk;
                tk *= tau;
            }
        }
        let origin = points.iter().map(|(_, p)| p).sum::<Vector3>() / n_pts as Real;
        let mut scatter = crate::math::Matrix3::zeros();
        for (_, p) in points {
            let d = p - origin;
            scatter += d * d.transpose();
        }
        let eig = crate::math::SymmetricEigen::new(scatter);
        let (mut i_min, mut i_max) = (0, 0);
        for i in 1..3 {
            if eig.eigenvalues[i] < eig.eigenvalues[i_min] {
                i_min = i;
            }
            if eig.eigenvalues[i] > eig.eigenvalues[i_max] {
                i_max = i;
            }
        }
        if i_min == i_max {
            return None;
        }
        let n = eig.eigenvectors.column(i_min).into_owned().normalize();
        let e1 = eig.eigenvectors.column(i_max).into_owned().normalize();
        let e2 = n.cross(&e1);
        let xy: Vec<(Real, Real)> =
            points.iter().map(|(_, p)| ((p - origin).dot(&e1), (p - origin).dot(&e2))).collect();

        // Kåsa's algebraic fit, with the radius free to change along the arc: x² + y² + D x + E y + F(τ) = 0,
        // F quadratic in τ (r² = cx² + cy² − F), by linear least squares.
        type V5 = crate::math::SVector<5>;
        let mut a = crate::math::SMatrix::<5, 5>::zeros();
        let mut b = V5::zeros();
        for (&tau, &(x, y)) in taus.iter().zip(&xy) {
            let row = V5::new(x, y, 1.0, tau, tau * tau);
            a += row * row.transpose();
            b -= row * (x * x + y * y);
        }
        let def = a.cholesky()?.solve(&b);
        let (cx, cy) = (-0.5 * def[0], -0.5 * def[1]);
        let r2 = cx * cx + cy * cy - def[2];
        if r2.is_nan() || r2 <= 0.0 {
            return None;
        }

        // Starting angle and radius polynomials from the polar coordinates about that centre. Each angle is the
        // previous one plus the turn between neighbouring frames (a few degrees), so the angles come unwrapped
        // and the turns from a short series instead of a full atan2. The frames' own sines and cosines seed the
        // angle cache of the refinement below.
        let (mut r_moments, mut phi_moments) = ([0.0; 4], [0.0; 4]); // Σ r τᵏ, Σ φ τᵏ
        let mut trig: Vec<(Real, Real, Real)> = Vec::with_capacity(n_pts); // (φ, sin φ, cos φ)
        let mut last: Option<(Real, Real, Real)> = None;
        for &(x, y) in &xy {
            let (dx, dy) = (x - cx, y - cy);
            let r = (dx * dx + dy * dy).sqrt();
            let (c, s) = (dx / r, dy / r);
            let phi = match last {
                None => dy.atan2(dx),
                Some((phi_prev, s_prev, c_prev)) => {
                    phi_prev + turn_angle(c_prev * s - s_prev * c, c_prev * c + s_prev * s)
                }
            };
            let tau = taus[trig.len()];
            let (mut tr, mut tphi) = (r, phi);
            for k in 0..4 {
                r_moments[k] += tr;
                phi_moments[k] += tphi;
                tr *= tau;
                tphi *= tau;
            }
            trig.push((phi, s, c));
            last = Some((phi, s, c));
        }
        let mut p = V9::zeros();
        p[0] = cx;
        p[1] = cy;
        let r_coeffs = poly_from_moments(&pow_sum, &r_moments, 2)?;
        for k in 0..3 {
            p[2 + k] = r_coeffs[k];
        }
        let phi_coeffs = poly_from_moments(&pow_sum, &phi_moments, 3)?;
        for k in 0..4 {
            p[5 + k] = phi_coeffs[k];
        }

        // Levenberg-Marquardt on the in-plane residuals (the algebraic circle is biased when the radius changes
        // along the arc, so the first steps can be long). One pass gives the cost and the normal equations.
        //
        // `trig` keeps the angles' sines and cosines at the accepted parameters: a step changes each angle a
        // little, and the angle-addition formulas with short series for the change are far cheaper than a fresh
        // sin_cos.
        let mut trial_trig = trig.clone();
        let normal_equations =
            |p: &V9, trig: &[(Real, Real, Real)], out: &mut [(Real, Real, Real)]| -> (Real, M9, V9) {
                // JᵀJ and Jᵀr from moments: with `(c, s) = (cos φ, sin φ)`, the radius columns are `τᵏ (c, s)` and
                // the angle columns `r τᵏ (−s, c)`, so the radius-angle block vanishes and the rest are sums of
                // powers of τ weighted by c or s (`Σ r c τᵏ` expands the quadratic r into `Σ c τᵏ⁺ʲ`).
                let mut cost = 0.0;
                let mut jtj = M9::zeros();
                let mut jtr = V9::zeros();
                let (mut c_sum, mut s_sum) = ([0.0; 6], [0.0; 6]); // Σ c τᵏ, Σ s τᵏ
                for (i, (&tau, &(x, y))) in taus.iter().zip(&xy).enumerate() {
                    let (r, phi, _, _) = in_plane(p, tau);
                    let (phi_old, s_old, c_old) = trig[i];
                    let d = phi - phi_old;
                    let (s, c) = if d.abs() < 1e-2 {
                        // sin and cos of d to 1e-18.
                        let d2 = d * d;
                        let sd = d * (1.0 - d2 / 6.0 * (1.0 - d2 / 20.0));
                        let cd = 1.0 - d2 / 2.0 * (1.0 - d2 / 12.0 * (1.0 - d2 / 30.0));
                        (s_old * cd + c_old * sd, c_old * cd - s_old * sd)
                    } else {
                        phi.sin_cos()
                    };
                    out[i] = (phi, s, c);
                    let (rx, ry) = (x - (p[0] + r * c), y - (p[1] + r * s));
                    cost += rx * rx + ry * ry;
                    let radial = c * rx + s * ry;
                    let tangential = r * (c * ry - s * rx);
                    let (mut tc, mut ts, mut tr, mut tt) = (c, s, radial, tangential);
                    for k in 0..6 {
                        c_sum[k] += tc;
                        s_sum[k] += ts;
                        if k < 3 {
                            jtr[2 + k] += tr;
                            tr *= tau;
                        }
                        if k < 4 {
                            jtr[5 + k] += tt;
                            tt *= tau;
                        }
                        tc *= tau;
                        ts *= tau;
                    }
                    jtr[0] += rx;
                    jtr[1] += ry;
                }
                let n_f = taus.len() as Real;
                // r² = Σ q_j τʲ.
                let q =
                    [p[2] * p[2], 2.0 * p[2] * p[3], p[3] * p[3] + 2.0 * p[2] * p[4], 2.0 * p[3] * p[4], p[4] * p[4]];
                jtj[(0, 0)] = n_f;
                jtj[(1, 1)] = n_f;
                for k in 0..3 {
                    jtj[(0, 2 + k)] = c_sum[k];
                    jtj[(1, 2 + k)] = s_sum[k];
                    for l in 0..3 {
                        jtj[(2 + k, 2 + l)] = pow_sum[k + l];
                    }
                }
                for k in 0..4 {
                    jtj[(0, 5 + k)] = -(p[2] * s_sum[k] + p[3] * s_sum[k + 1] + p[4] * s_sum[k + 2]);
                    jtj[(1, 5 + k)] = p[2] * c_sum[k] + p[3] * c_sum[k + 1] + p[4] * c_sum[k + 2];
                    for l in 0..4 {
                        jtj[(5 + k, 5 + l)] = (0..5).map(|j| q[j] * pow_sum[k + l + j]).sum();
                    }
                }
                for i in 0..9 {
                    for j in 0..i {
                        jtj[(i, j)] = jtj[(j, i)];
                    }
                }
                (cost, jtj, jtr)
            };
        let (mut cost, mut jtj, mut jtr) = normal_equations(&p, &trig, &mut trial_trig);
        std::mem::swap(&mut trig, &mut trial_trig);
        let mut lambda = 1e-6;
        for _ in 0..MAX_ITERATIONS {
            // The loop ends when a step is shorter than 0.1 um (or 0.1 urad), when the Gauss-Newton model
            // predicts that the squared residuals can fall by less than 1e-4 of their sum (the parameters are then
            // within a tenth of their standard error of the minimum; the evaluation's errors equal full
            // convergence's to three digits), or when no damping makes a step downhill (the minimum is reached to
            // rounding).
            let mut done = true;
            while lambda < 1e3 {
                let mut damped = jtj;
                for i in 0..9 {
                    damped[(i, i)] *= 1.0 + lambda;
                }
                let step = damped.cholesky()?.solve(&jtr);
                // The Gauss-Newton model's predicted fall of the squared residuals (stopping on it saves the last
                // steps, which would be rejected one by one as the damping climbs, each a pass over the frames).
                let predicted = step.dot(&jtr);
                if step.norm() < 1e-7 || predicted < 1e-4 * cost {
                    break;
                }
                let trial = p + step;
                let (trial_cost, trial_jtj, trial_jtr) = normal_equations(&trial, &trig, &mut trial_trig);
                if trial_cost <= cost {
                    (p, cost, jtj, jtr) = (trial, trial_cost, trial_jtj, trial_jtr);
                    std::mem::swap(&mut trig, &mut trial_trig);
                    lambda = (lambda * 0.1).max(1e-9);
                    done = false;
                    break;
                }
                lambda *= 10.0;
            }
            if done {
                break;
            }
        }

        let zs: Vec<Real> = points.iter().map(|(_, q)| (q - origin).dot(&n)).collect();
        let z_moments = taus.iter().zip(&zs).fold([0.0; 4], |m, (&tau, &z)| [m[0] + z, m[1] + z * tau, 0.0, 0.0]);
        let zc = poly_from_moments(&pow_sum, &z_moments, 1)?;
        // The in-plane squared residuals are the last accepted cost; the plane's are added to them.
        let ss_out_of_plane: Real = taus.iter().zip(&zs).map(|(&tau, &z)| (z - (zc[0] + zc[1] * tau)).powi(2)).sum();
        let residual_rms_m = ((cost + ss_out_of_plane) / n_pts as Real).sqrt();
        residual_rms_m.is_finite().then_some(ArcFit {
            t_ref_s,
            scale_s,
            origin,
            e1,
            e2,
            n,
            p,
            z: [zc[0], zc[1]],
            residual_rms_m,
            jtj,
            plane_moments: taus.iter().zip(&xy).fold(
                [crate::math::SMatrix::<2, 2>::zeros(); 3],
                |m, (&tau, &(x, y))| {
                    let (q, t) = (crate::math::SVector::<2>::new(x, y), crate::math::SVector::<2>::new(1.0, tau));
                    [m[0] + q * q.transpose(), m[1] + t * t.transpose(), m[2] + t * q.transpose()]
                },
            ),
            frames: n_pts,
        })
    }

    /// Position (m) at `t_s`.
    pub fn position(&self, t_s: Real) -> Vector3 {
        let tau = (t_s - self.t_ref_s) / self.scale_s;
        let (r, phi, _, _) = in_plane(&self.p, tau);
        let (s, c) = phi.sin_cos();
        self.origin
            + self.e1 * (self.p[0] + r * c)
            + self.e2 * (self.p[1] + r * s)
            + self.n * (self.z[0] + self.z[1] * tau)
    }

    /// The covariance of the fitted position and velocity at `t_s` (m, m/s; a 6x6 matrix, position first), from
    /// the parameters' covariance `σ² (JᵀJ)⁻¹` per unit noise variance (the caller scales it by the frames'
    /// noise); `None` for a singular fit. The departure from the plane is counted with the plane's tilt, as the
    /// fit makes it in two stages (the plane, then `z₀ + z₁ τ` of what it leaves: block-diagonal, `(XᵀX)⁻¹` for the
    /// tilt and `(TᵀT)⁻¹ Tᵀ(I − P_X)T (TᵀT)⁻¹` for the line): the frames span a metre or more of the plane, so a tilt
    /// within the noise moves the contact across the face by a tenth of a millimetre.
    pub fn position_velocity_covariance(&self, t_s: Real) -> Option<crate::math::SMatrix<6, 6>> {
        let tau = (t_s - self.t_ref_s) / self.scale_s;
        let (r, phi, dr, dphi) = in_plane(&self.p, tau);
        let (s, c) = phi.sin_cos();
        let u_r = self.e1 * c + self.e2 * s;
        let u_t = self.e2 * c - self.e1 * s;
        let t = self.scale_s;
        // Rows: position (3) and velocity (3); columns: the nine in-plane coefficients, then z₀, z₁, β₁, β₂.
        let mut g = crate::math::SMatrix::<6, 13>::zeros();
        let mut set = |col: usize, dp: Vector3, dv: Vector3| {
            for i in 0..3 {
                g[(i, col)] = dp[i];
                g[(3 + i, col)] = dv[i];
            }
        };
        set(0, self.e1, Vector3::zeros());
        set(1, self.e2, Vector3::zeros());
        let pow = |k: usize| tau.powi(k as i32);
        let dpow = |k: usize| if k == 0 { 0.0 } else { k as Real * tau.powi(k as i32 - 1) };
        for k in 0..3 {
            set(2 + k, u_r * pow(k), (u_r * dpow(k) + u_t * (pow(k) * dphi)) / t);
        }
        for k in 0..4 {
            let dv = u_t * (dr * pow(k) + r * dpow(k)) - u_r * (r * dphi * pow(k));
            set(5 + k, u_t * (r * pow(k)), dv / t);
        }
        // The in-plane place and velocity, for the plane's tilt.
        let (x, y) = (self.p[0] + r * c, self.p[1] + r * s);
        let (vx, vy) = ((dr * c - r * s * dphi) / t, (dr * s + r * c * dphi) / t);
        set(9, self.n, Vector3::zeros());
        set(10, self.n * tau, self.n / t);
        set(11, self.n * x, self.n * vx);
        set(12, self.n * y, self.n * vy);
        let in_plane_cov = self.jtj.cholesky()?.inverse();
        let [sxx, stt, stx] = self.plane_moments;
        let (sxx_inv, stt_inv) = (sxx.try_inverse()?, stt.try_inverse()?);
        let line_cov = stt_inv * (stt - stx * sxx_inv * stx.transpose()) * stt_inv;
        let mut cov = crate::math::SMatrix::<13, 13>::zeros();
        cov.fixed_view_mut::<9, 9>(0, 0).copy_from(&in_plane_cov);
        cov.fixed_view_mut::<2, 2>(9, 9).copy_from(&line_cov);
        cov.fixed_view_mut::<2, 2>(11, 11).copy_from(&sxx_inv);
        Some(g * cov * g.transpose())
    }

    /// The residual's pooled variance per coordinate, `Σ r² / (3 n − 13)` (two in-plane coordinates for nine
    /// coefficients, one out of the plane for four), and its degrees of freedom.
    pub fn noise_variance(&self) -> (Real, usize) {
        let dof = (3 * self.frames).saturating_sub(13);
        let ss = self.residual_rms_m.powi(2) * self.frames as Real;
        (if dof > 0 { ss / dof as Real } else { 0.0 }, dof)
    }

    /// The unit normal of the arc's plane (the frames' best-fitting plane; its sign is arbitrary).
    pub fn normal(&self) -> Vector3 {
        self.n
    }

    /// Velocity (m/s) at `t_s`.
    pub fn velocity(&self, t_s: Real) -> Vector3 {
        let tau = (t_s - self.t_ref_s) / self.scale_s;
        let (r, phi, dr, dphi) = in_plane(&self.p, tau);
        let (s, c) = phi.sin_cos();
        (self.e1 * (dr * c - r * s * dphi) + self.e2 * (dr * s + r * c * dphi) + self.n * self.z[1]) / self.scale_s
    }
}

/// The angle whose sine and cosine are proportional to `sin` and `cos` (an atan2), by a series when it is small.
#[inline]
fn turn_angle(sin: Real, cos: Real) -> Real {
    if cos > 0.0 && sin.abs() < 0.25 * cos {
        // atan x = x − x³/3 + x⁵/5 − …, to 2e-10 for |x| < 0.25.
        let x = sin / cos;
        let x2 = x * x;
        x * (1.0
            - x2 * (1.0 / 3.0
                - x2 * (1.0 / 5.0 - x2 * (1.0 / 7.0 - x2 * (1.0 / 9.0 - x2 / 11.0 * (1.0 - x2 * 11.0 / 13.0))))))
    } else {
        sin.atan2(cos)
    }
}

/// Least-squares polynomial of `degree` (at most 3) from the moments of its samples: `pow_sum[m] = Σ τᵐ` and
/// `moments[k] = Σ vᵢ τᵢᵏ`.
fn poly_from_moments(pow_sum: &[Real; 11], moments: &[Real; 4], degree: usize) -> Option<[Real; 4]> {
    let mut ata = crate::math::Matrix4::identity();
    let mut aty = crate::math::Vector4::zeros();
    for i in 0..=degree {
        for j in 0..=degree {
            ata[(i, j)] = pow_sum[i + j];
        }
        aty[i] = moments[i];
    }
    let c = ata.cholesky()?.solve(&aty);
    Some([c[0], c[1], c[2], c[3]])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An exact arc (cubic angle, quadratic radius, tilted plane) is reproduced to rounding, position and velocity.
    #[test]
    fn an_exact_arc_is_reproduced() {
        let n = Vector3::new(0.2, 0.9, -0.4).normalize();
        let e1 = n.cross(&Vector3::x()).normalize();
        let e2 = n.cross(&e1);
        let centre = Vector3::new(0.3, 1.4, -0.7);
        let truth = |t: Real| {
            let r = 1.5 * (1.0 + 12.0 * t * t);
            let phi = -1.2 + (45.0 * t + 0.5 * 150.0 * t * t + 4000.0 * t * t * t / 6.0) / 1.5;
            centre + e1 * (r * phi.cos()) + e2 * (r * phi.sin())
        };
        let points: Vec<(Real, Vector3)> =
            (0..32).map(|i| (-0.044 + i as Real / 720.0, truth(-0.044 + i as Real / 720.0))).collect();
        let fit = ArcFit::fit(&points).unwrap();
        let t = 0.002;
        assert!((fit.position(t) - truth(t)).norm() < 1e-9, "{}", (fit.position(t) - truth(t)).norm());
        let h = 1e-6;
        let v = (truth(t + h) - truth(t - h)) / (2.0 * h);
        assert!((fit.velocity(t) - v).norm() < 1e-6);
        assert!(fit.residual_rms_m < 1e-9);
    }
}
