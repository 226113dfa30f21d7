//! A body's pose from its markers: the least-squares rigid fit of the marker set onto the markers seen in one
//! frame, with a marker that jumps (a label swap, a ghost) rejected by its residual rather than averaged in.
//!
//! The fit is Horn's closed form (B. K. P. Horn, "Closed-form solution of absolute orientation using unit
//! quaternions", J. Opt. Soc. Am. A 4(4), 1987): with the body-frame positions `b_i` and the seen positions `l_i`
//! about their centroids, `S = Σ b_i l_iᵀ`; the rotation is the unit quaternion of the largest eigenvalue of the
//! symmetric 4x4 matrix N(S) (Horn's eq. 41), and the translation `l̄ - R b̄`. It minimises `Σ |R b_i + t - l_i|²`
//! over rotations (never a reflection), and needs at least 3 markers not on one line.
//!
//! Rejection: when the worst marker's residual is over `reject_m` and more than 3 markers are left, that marker is
//! dropped and the fit repeated. A fit whose worst residual is still over `reject_m` (3 markers that disagree)
//! gives no pose: the frame is occluded. Any input (a C3D file, a live marker stream) calls
//! [`MarkerFitter::fit`] once per frame; it does not allocate.

use crate::math::{Isometry3, Matrix3, Real, Translation3, UnitQuaternion, Vector3};

use super::marker_set::MarkerSet;

/// How far a marker may sit from its fitted place before it is taken for a swap or a ghost (m). Tracking noise
/// is a fraction of a millimetre; a swapped marker on a clubhead is centimetres off.
pub const DEFAULT_REJECT_M: Real = 0.003;

/// A pose fitted from markers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyFit {
    pub lab_from_body: Isometry3,
    /// Root-mean-square distance of the markers used from their fitted places (m).
    pub residual_m: Real,
    /// The markers used (bit i: the set's marker i).
    pub used_mask: u64,
    /// Visible markers rejected by their residual.
    pub rejected: u32,
}

/// Why a frame gave no pose.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum FitFailure {
    #[error("{visible} of the set's markers visible, a pose needs 3")]
    TooFew { visible: u32 },
    #[error("the markers disagree: a residual of {worst_mm:.2} mm is over the {reject_mm:.2} mm limit")]
    Inconsistent { worst_mm: Real, reject_mm: Real },
}

/// Fits one marker set, frame after frame.
#[derive(Debug, Clone)]
pub struct MarkerFitter {
    pub set: MarkerSet,
    pub reject_m: Real,
}

impl MarkerFitter {
    pub fn new(set: MarkerSet) -> Self {
        MarkerFitter { set, reject_m: DEFAULT_REJECT_M }
    }

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
        let visible = mask.count_ones();
        if visible < 3 {
            return Err(FitFailure::TooFew { visible });
        }
        let mut rejected = 0;
        loop {
            let lab_from_body = horn(&self.set.body_m, lab_m, mask);
            let (worst, worst_sq, sum_sq) = residuals(&self.set.body_m, lab_m, mask, &lab_from_body);
            if worst_sq <= self.reject_m * self.reject_m {
                let residual_m = (sum_sq / Real::from(mask.count_ones())).sqrt();
                return Ok(BodyFit { lab_from_body, residual_m, used_mask: mask, rejected });
            }
            if mask.count_ones() <= 3 {
                return Err(FitFailure::Inconsistent {
                    worst_mm: worst_sq.sqrt() * 1e3,
                    reject_mm: self.reject_m * 1e3,
                });
            }
            mask &= !(1 << worst);
            rejected += 1;
        }
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
    let (sxx, sxy, sxz) = (s[(0, 0)], s[(0, 1)], s[(0, 2)]);
    let (syx, syy, syz) = (s[(1, 0)], s[(1, 1)], s[(1, 2)]);
    let (szx, szy, szz) = (s[(2, 0)], s[(2, 1)], s[(2, 2)]);
    #[rustfmt::skip]
    let n = nalgebra::Matrix4::new(
        sxx + syy + szz, syz - szy,        szx - sxz,        sxy - syx,
        syz - szy,       sxx - syy - szz,  sxy + syx,        szx + sxz,
        szx - sxz,       sxy + syx,        -sxx + syy - szz, syz + szy,
        sxy - syx,       szx + sxz,        syz + szy,        -sxx - syy + szz,
    );
    let eigen = nalgebra::SymmetricEigen::new(n);
    let mut best = 0;
    for i in 1..4 {
        if eigen.eigenvalues[i] > eigen.eigenvalues[best] {
            best = i;
        }
    }
    let q = eigen.eigenvectors.column(best);
    UnitQuaternion::new_normalize(nalgebra::Quaternion::new(q[0], q[1], q[2], q[3]))
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
        assert_eq!(fitter.fit(&lab).unwrap_err(), FitFailure::TooFew { visible: 2 });
    }

    #[test]
    fn a_swapped_marker_is_rejected_not_averaged() {
        let fitter = MarkerFitter::new(club_set());
        let mut lab = seen(&fitter.set, &pose());
        lab.swap(0, 2);
        // A swap moves both markers; rejecting one leaves three that still disagree.
        assert!(matches!(fitter.fit(&lab).unwrap_err(), FitFailure::Inconsistent { .. }));
        let mut lab = seen(&fitter.set, &pose());
        lab[3] = lab[3].map(|p| p + Vector3::new(0.0, 0.05, 0.0)); // a ghost 5 cm off
        let fit = fitter.fit(&lab).unwrap();
        assert_eq!((fit.used_mask, fit.rejected), (0b0111, 1));
        assert!(fit.lab_from_body.rotation.angle_to(&pose().rotation) < 1e-9);
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
