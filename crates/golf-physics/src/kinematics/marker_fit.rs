//! A body's pose from its markers: the least-squares rigid fit of the marker set onto the markers seen in one
//! frame, with a marker that jumps (a label swap, a ghost) rejected by its residual rather than averaged in.
//!
//! The fit is Horn's closed form (B. K. P. Horn, "Closed-form solution of absolute orientation using unit
//! quaternions", J. Opt. Soc. Am. A 4(4), 1987): with the body-frame positions `b_i` and the seen positions `l_i`
//! about their centroids, `S = Σ b_i l_iᵀ`; the rotation is the unit quaternion of the largest eigenvalue of the
//! symmetric 4x4 matrix N(S) (Horn's eq. 41), and the translation `l̄ - R b̄`. It minimises `Σ |R b_i + t - l_i|²`
//! over rotations (never a reflection), and needs at least 3 markers not on one line.
//!
//! Validity and rejection: a marker is valid when it is seen (finite coordinates the input did not flag) and not
//! rejected. While some valid marker sits more than `reject_m` from its fitted place, one marker is rejected and
//! the fit repeated over the rest: with more than 3 valid, the one whose removal leaves the best fit (the
//! smallest worst residual of the others: a ghost pulls the fit towards it, so the largest residual is not always
//! its own); with 3 valid, any of them, as 3 that disagree cannot say which is wrong. A rejected marker is not
//! valid, so a frame is `occluded` exactly when fewer than 3 markers are valid: fewer than 3 seen, or 3 seen and
//! one rejected, or 4 seen and two rejected. A frame of 4 markers with one ghost gives the pose of the other 3.
//! Any input (a C3D file, a live marker stream) calls [`MarkerFitter::fit`] once per frame; it does not
//! allocate.

use crate::math::{Isometry3, Matrix3, Real, Translation3, UnitQuaternion, Vector3};

use super::marker_set::MarkerSet;

/// How far a marker may sit from its fitted place before it is taken for a swap or a ghost (m). Tracking noise
/// is a fraction of a millimetre; a swapped marker on a clubhead is centimetres off.
pub const DEFAULT_REJECT_M: Real = 0.003;

/// A pose fitted from markers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyFit {
    /// The body's pose in the lab frame: takes the set's body-frame positions (m) onto the seen markers.
    pub lab_from_body: Isometry3,
    /// Root-mean-square distance of the markers used from their fitted places (m).
    pub residual_m: Real,
    /// The markers used (bit i: the set's marker i).
    pub used_mask: u64,
    /// Visible markers rejected by their residual.
    pub rejected: u32,
}

/// Why a frame gave no pose: fewer than 3 valid markers (the frame is occluded).
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum FitFailure {
    /// Fewer than 3 of the set's markers were seen.
    #[error("{seen} of the set's markers seen, a pose needs 3 valid")]
    TooFew {
        /// The set's markers seen (finite coordinates).
        seen: u32,
    },
    /// Enough markers were seen, but rejecting those off their fitted places left fewer than 3.
    #[error(
        "{seen} of the set's markers seen, {rejected} rejected by their residual ({worst_mm:.2} mm over the \
         {reject_mm:.2} mm limit): {} valid, a pose needs 3",
        seen - rejected
    )]
    Rejected {
        /// The set's markers seen (finite coordinates).
        seen: u32,
        /// The markers rejected by their residual, the last one with 3 valid included.
        rejected: u32,
        /// The largest residual of the last fit, over 3 markers (mm).
        worst_mm: Real,
        /// The limit it exceeded, [`MarkerFitter::reject_m`] (mm).
        reject_mm: Real,
    },
}

/// Fits one marker set, frame after frame.
#[derive(Debug, Clone)]
pub struct MarkerFitter {
    /// The body's markers and their body-frame positions.
    pub set: MarkerSet,
    /// How far a marker may sit from its fitted place before it is rejected (m).
    pub reject_m: Real,
}

impl MarkerFitter {
    /// A fitter of `set` rejecting markers more than [`DEFAULT_REJECT_M`] off their fitted places.
    pub fn new(set: MarkerSet) -> Self {
        MarkerFitter { set, reject_m: DEFAULT_REJECT_M }
    }

    /// The same fitter with another rejection distance (m).
    pub fn with_reject_m(mut self, reject_m: Real) -> Self {
        self.reject_m = reject_m;
        self
    }

    /// The pose from the markers seen in one frame: `lab_m[i]` is the set's marker i (lab frame, m), `None`
    /// when it is not seen (or not valid). Extra entries are ignored.
    pub fn fit(&self, lab_m: &[Option<Vector3>]) -> Result<BodyFit, FitFailure> {
        let n = self.set.len().min(lab_m.len());
        let mut mask: u64 = 0;
        for (i, p) in lab_m.iter().take(n).enumerate() {
            if p.is_some_and(|p| p.iter().all(|v| v.is_finite())) {
                mask |= 1 << i;
            }
        }
        let seen = mask.count_ones();
        if seen < 3 {
            return Err(FitFailure::TooFew { seen });
        }
        let limit_sq = self.reject_m * self.reject_m;
        let mut rejected = 0;
        loop {
            let lab_from_body = horn(&self.set.body_m, lab_m, mask);
            let (_, worst_sq, sum_sq) = residuals(&self.set.body_m, lab_m, mask, &lab_from_body);
            if worst_sq <= limit_sq {
                let residual_m = (sum_sq / Real::from(mask.count_ones())).sqrt();
                return Ok(BodyFit { lab_from_body, residual_m, used_mask: mask, rejected });
            }
            rejected += 1;
            if mask.count_ones() <= 3 {
                let (worst_mm, reject_mm) = (worst_sq.sqrt() * 1e3, self.reject_m * 1e3);
                return Err(FitFailure::Rejected { seen, rejected, worst_mm, reject_mm });
            }
            mask &= !(1 << self.worst_member(lab_m, mask));
        }
    }

    /// The marker of `mask` whose removal leaves the best fit of the others (the smallest worst residual).
    fn worst_member(&self, lab_m: &[Option<Vector3>], mask: u64) -> usize {
        let mut best = (0, Real::INFINITY);
        for i in (0..self.set.len().min(64)).filter(|i| mask & (1 << i) != 0) {
            let others = mask & !(1 << i);
            let pose = horn(&self.set.body_m, lab_m, others);
            let (_, worst_sq, _) = residuals(&self.set.body_m, lab_m, others, &pose);
            if worst_sq < best.1 {
                best = (i, worst_sq);
            }
        }
        best.0
    }
}

/// Horn's least-squares rotation and translation taking the set's markers in `mask` onto the seen ones.
fn horn(body_m: &[Vector3], lab_m: &[Option<Vector3>], mask: u64) -> Isometry3 {
    let mut body_mean = Vector3::zeros();
    let mut lab_mean = Vector3::zeros();
    let mut count = 0.0;
    for_each(body_m, lab_m, mask, |b, l| {
        body_mean += b;
        lab_mean += l;
        count += 1.0;
    });
    body_mean /= count;
    lab_mean /= count;
    // S = Σ (b - b̄)(l - l̄)ᵀ; S[(r, c)] is Horn's S_rc.
    let mut s = Matrix3::zeros();
    for_each(body_m, lab_m, mask, |b, l| {
        s += (b - body_mean) * (l - lab_mean).transpose();
    });
    let rotation = rotation_of(&s);
    let translation = lab_mean - rotation * body_mean;
    Isometry3::from_parts(Translation3::from(translation), rotation)
}

/// The unit quaternion maximising `Σ l·(R b)` for the cross-covariance `s` (Horn's eq. 41 matrix N).
fn rotation_of(s: &Matrix3) -> UnitQuaternion {
    largest_eigenvector(s).unwrap_or_else(|| {
        let n = horn_matrix(s);
        // Degenerate (markers nearly on one line, or all at one point): the general eigen-solver.
        let eigen = crate::math::SymmetricEigen::new(n);
        let mut best = 0;
        for i in 1..4 {
            if eigen.eigenvalues[i] > eigen.eigenvalues[best] {
                best = i;
            }
        }
        let q = eigen.eigenvectors.column(best);
        UnitQuaternion::new_normalize(crate::math::Quaternion::new(q[0], q[1], q[2], q[3]))
    })
}

/// Horn's eq. 41 matrix N of the cross-covariance `s` (`s[(r, c)]` = Horn's S_rc).
fn horn_matrix(s: &Matrix3) -> crate::math::Matrix4 {
    let (sxx, sxy, sxz) = (s[(0, 0)], s[(0, 1)], s[(0, 2)]);
    let (syx, syy, syz) = (s[(1, 0)], s[(1, 1)], s[(1, 2)]);
    let (szx, szy, szz) = (s[(2, 0)], s[(2, 1)], s[(2, 2)]);
    #[rustfmt::skip]
    let n = crate::math::Matrix4::new(
        sxx + syy + szz, syz - szy,        szx - sxz,        sxy - syx,
        syz - szy,       sxx - syy - szz,  sxy + syx,        szx + sxz,
        szx - sxz,       sxy + syx,        -sxx + syy - szz, syz + szy,
        sxy - syx,       szx + sxz,        syz + szy,        -sxx - syy + szz,
    );
    n
}

/// The unit eigenvector of N's largest eigenvalue by the quaternion characteristic polynomial (D. L. Theobald,
/// "Rapid calculation of RMSDs using a quaternion-based characteristic polynomial", Acta Cryst. A61, 2005): N is
/// symmetric and traceless, so `det(λI - N) = λ⁴ - tr(N²)/2 λ² - tr(N³)/3 λ + det N`; Newton's method from the
/// upper bound tr(N²)^½ (no eigenvalue is larger than the Frobenius norm) descends to the largest root, and the
/// eigenvector is the largest column of the adjugate of `N - λI`. Written here because a general 4x4 eigen-solver
/// costs about 1.5 us, over the fit's 1 us budget; this costs a fraction of that. `None` when the largest
/// eigenvalue is not well separated (the caller falls back to the general solver).
fn largest_eigenvector(s: &Matrix3) -> Option<UnitQuaternion> {
    let n = horn_matrix(s);
    let p2 = n.norm_squared(); // tr(N²) of a symmetric matrix
    if !(p2 > 0.0 && p2.is_finite()) {
        return None;
    }
    // tr(N³)/3 = 8 det S (Theobald's C1), det N from complementary 2x2 minors of rows 0-1 and 2-3.
    let (c2, c1) = (-p2 / 2.0, -8.0 * s.determinant());
    let (top, bottom) = (minors(&n, 0, 1), minors(&n, 2, 3));
    let c0 = top[0] * bottom[5] - top[1] * bottom[4] + top[2] * bottom[3] + top[3] * bottom[2] - top[4] * bottom[1]
        + top[5] * bottom[0];
    let mut lambda = p2.sqrt();
    for _ in 0..50 {
        let l2 = lambda * lambda;
        let f = l2 * l2 + c2 * l2 + c1 * lambda + c0;
        let df = 4.0 * l2 * lambda + 2.0 * c2 * lambda + c1;
        if df == 0.0 {
            break;
        }
        let step = f / df;
        lambda -= step;
        if step.abs() <= 1e-13 * lambda.abs() {
            break;
        }
    }
    let a = n - crate::math::Matrix4::identity() * lambda;
    // The adjugate's columns from the 2x2 minors of rows 2-3 (its columns 0 and 1) and of rows 0-1 (2 and 3):
    // each is a multiple of the null vector; the largest is the best conditioned.
    let (m01, m23) = (minors(&a, 0, 1), minors(&a, 2, 3));
    let column = |r: usize, m: &[Real; 6]| {
        // Cofactors of row r expanded along the other row pair: m = [c01, c02, c03, c12, c13, c23].
        crate::math::Vector4::new(
            a[(r, 1)] * m[5] - a[(r, 2)] * m[4] + a[(r, 3)] * m[3],
            -(a[(r, 0)] * m[5] - a[(r, 2)] * m[2] + a[(r, 3)] * m[1]),
            a[(r, 0)] * m[4] - a[(r, 1)] * m[2] + a[(r, 3)] * m[0],
            -(a[(r, 0)] * m[3] - a[(r, 1)] * m[1] + a[(r, 2)] * m[0]),
        )
    };
    let candidates = [column(0, &m23), column(1, &m23), column(2, &m01), column(3, &m01)];
    let best = candidates.iter().max_by(|x, y| x.norm_squared().total_cmp(&y.norm_squared()))?;
    let norm = best.norm();
    if !(norm > 1e-12 * p2.powf(1.5) && norm.is_finite()) {
        return None;
    }
    Some(UnitQuaternion::new_normalize(crate::math::Quaternion::new(best[0], best[1], best[2], best[3])))
}

/// The 2x2 minors of rows `r0`, `r1` of a 4x4 matrix over the column pairs 01, 02, 03, 12, 13, 23.
fn minors(m: &crate::math::Matrix4, r0: usize, r1: usize) -> [Real; 6] {
    let d = |c0: usize, c1: usize| m[(r0, c0)] * m[(r1, c1)] - m[(r0, c1)] * m[(r1, c0)];
    [d(0, 1), d(0, 2), d(0, 3), d(1, 2), d(1, 3), d(2, 3)]
}

/// The index of the worst marker, its squared residual and the sum of squared residuals.
fn residuals(body_m: &[Vector3], lab_m: &[Option<Vector3>], mask: u64, pose: &Isometry3) -> (usize, Real, Real) {
    let (mut worst, mut worst_sq, mut sum_sq) = (0, 0.0, 0.0);
    for (i, (b, l)) in body_m.iter().zip(lab_m).enumerate() {
        let (true, Some(l)) = (mask & (1 << i) != 0, l) else { continue };
        let r_sq = (pose.rotation * b + pose.translation.vector - l).norm_squared();
        sum_sq += r_sq;
        if r_sq > worst_sq {
            (worst, worst_sq) = (i, r_sq);
        }
    }
    (worst, worst_sq, sum_sq)
}

fn for_each(body_m: &[Vector3], lab_m: &[Option<Vector3>], mask: u64, mut f: impl FnMut(&Vector3, &Vector3)) {
    for (i, (b, l)) in body_m.iter().zip(lab_m).enumerate() {
        if let (true, Some(l)) = (mask & (1 << i) != 0, l) {
            f(b, l);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;

    fn club_set() -> MarkerSet {
        MarkerSet::new([
            ("A".to_string(), Vector3::new(0.04, 0.0, 0.01)),
            ("B".to_string(), Vector3::new(-0.04, 0.005, 0.01)),
            ("C".to_string(), Vector3::new(0.0, 0.03, -0.012)),
            ("D".to_string(), Vector3::new(0.01, -0.02, -0.03)),
        ])
        .unwrap()
    }

    fn pose() -> Isometry3 {
        Isometry3::new(Vector3::new(0.3, 1.1, -0.4), Vector3::new(0.7, -1.9, 0.4))
    }

    fn seen(set: &MarkerSet, pose: &Isometry3) -> Vec<Option<Vector3>> {
        set.body_m.iter().map(|b| Some(pose.rotation * b + pose.translation.vector)).collect()
    }

    #[test]
    fn recovers_an_exact_pose() {
        let fitter = MarkerFitter::new(club_set());
        let fit = fitter.fit(&seen(&fitter.set, &pose())).unwrap();
        assert!(fit.lab_from_body.rotation.angle_to(&pose().rotation) < 1e-9);
        assert!((fit.lab_from_body.translation.vector - pose().translation.vector).norm() < 1e-12);
        assert!(fit.residual_m < 1e-12);
        assert_eq!((fit.used_mask, fit.rejected), (0b1111, 0));
    }

    #[test]
    fn three_markers_are_enough_and_two_are_not() {
        let fitter = MarkerFitter::new(club_set());
        let mut lab = seen(&fitter.set, &pose());
        lab[1] = None;
        let fit = fitter.fit(&lab).unwrap();
        assert!(fit.lab_from_body.rotation.angle_to(&pose().rotation) < 1e-9);
        lab[2] = None;
        assert_eq!(fitter.fit(&lab).unwrap_err(), FitFailure::TooFew { seen: 2 });
    }

    #[test]
    fn a_swapped_marker_is_rejected_not_averaged() {
        let fitter = MarkerFitter::new(club_set());
        let mut lab = seen(&fitter.set, &pose());
        lab.swap(1, 2);
        // A swap moves both markers: every 3 of the 4 still hold a swapped one (best: 10.9 mm off), so two are
        // rejected and 2 valid are left. Other swaps of this set cannot be seen in one frame by any rule: A, C
        // and D make a nearly isosceles triangle (|AD| = 53.9 mm, |CD| = 54.1 mm), so A and C swapped fit another
        // pose within 0.15 mm; the best 3 of the other swaps are within 0.4-1.8 mm. A set's markers should sit at
        // unequal distances from each other.
        assert!(matches!(fitter.fit(&lab).unwrap_err(), FitFailure::Rejected { seen: 4, rejected: 2, .. }));
        let mut lab = seen(&fitter.set, &pose());
        lab[3] = lab[3].map(|p| p + Vector3::new(0.0, 0.05, 0.0)); // a ghost 5 cm off
        let fit = fitter.fit(&lab).unwrap();
        assert_eq!((fit.used_mask, fit.rejected), (0b0111, 1));
        assert!(fit.lab_from_body.rotation.angle_to(&pose().rotation) < 1e-9);
    }

    /// The reading: occluded exactly when fewer than 3 markers are valid, a rejected marker not valid.
    /// 4 markers with one a ghost: the pose of the other 3, whichever marker is the ghost and whichever way it
    /// moved (2 cm, over 6 times the 3 mm limit; a ghost pulls the 4-marker fit towards itself, so the largest
    /// residual of that fit can be another marker's). 3 markers with one a ghost that changes their triangle
    /// (moved 2 cm along a side): 2 valid, occluded. (Three markers cannot see a ghost that keeps their side
    /// lengths: one moved 2 cm off their plane changes each side by a few millimetres at most.)
    #[test]
    fn a_ghost_among_four_leaves_the_pose_of_three_and_among_three_leaves_two() {
        let fitter = MarkerFitter::new(club_set());
        let mut rng = Rng::new(3);
        for ghost in 0..4 {
            for _ in 0..200 {
                let mut lab = seen(&fitter.set, &pose());
                let dir = Vector3::new(rng.normal(), rng.normal(), rng.normal()).normalize();
                lab[ghost] = lab[ghost].map(|p| p + dir * 0.02);
                let fit = fitter.fit(&lab).unwrap();
                assert_eq!((fit.used_mask, fit.rejected), (0b1111 & !(1 << ghost), 1), "ghost {ghost} along {dir:?}");
                assert!(fit.lab_from_body.rotation.angle_to(&pose().rotation) < 1e-9);
                let (other, gone) = ((ghost + 2) % 4, (ghost + 1) % 4);
                let mut lab = seen(&fitter.set, &pose());
                let side = (lab[ghost].unwrap() - lab[other].unwrap()).normalize();
                lab[ghost] = lab[ghost].map(|p| p + side * 0.02);
                lab[gone] = None;
                let err = fitter.fit(&lab).unwrap_err();
                assert!(matches!(err, FitFailure::Rejected { seen: 3, rejected: 1, .. }), "{err}");
                assert!(err.to_string().contains("2 valid"), "{err}");
            }
        }
    }

    #[test]
    fn the_characteristic_polynomial_finds_the_general_solvers_eigenvector() {
        let mut rng = Rng::new(11);
        for _ in 0..1000 {
            let s = Matrix3::from_fn(|_, _| rng.normal());
            let fast = rotation_of(&s);
            let n = horn_matrix(&s);
            let eigen = crate::math::SymmetricEigen::new(n);
            let best = (0..4).max_by(|a, b| eigen.eigenvalues[*a].total_cmp(&eigen.eigenvalues[*b])).unwrap();
            let q = eigen.eigenvectors.column(best);
            let slow = UnitQuaternion::new_normalize(crate::math::Quaternion::new(q[0], q[1], q[2], q[3]));
            assert!(largest_eigenvector(&s).is_some());
            assert!(fast.angle_to(&slow) < 1e-6, "{}", fast.angle_to(&slow));
        }
    }

    #[test]
    fn noise_gives_a_residual_of_its_size() {
        // 0.1 mm of isotropic noise per axis: each marker is sqrt(3) x 0.1 mm off on average before the fit takes
        // up 6 of the 12 degrees of freedom, so the RMS residual is 0.1 mm x sqrt(3 x (12 - 6) / 12) ≈ 0.12 mm.
        let fitter = MarkerFitter::new(club_set());
        let mut rng = Rng::new(7);
        let mut sum_sq = 0.0;
        let frames = 2000;
        for _ in 0..frames {
            let lab: Vec<_> = seen(&fitter.set, &pose())
                .into_iter()
                .map(|p| p.map(|p| p + Vector3::new(rng.normal(), rng.normal(), rng.normal()) * 1e-4))
                .collect();
            let fit = fitter.fit(&lab).unwrap();
            sum_sq += fit.residual_m * fit.residual_m;
        }
        let rms = (sum_sq / frames as Real).sqrt();
        assert!((rms - 1.2247e-4).abs() < 0.05e-4, "rms residual {rms}");
    }
}
