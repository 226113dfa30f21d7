//! A polynomial fit's normal matrix, factored: its solve and the covariance of the fitted value and slope.

use crate::math::{Real, Vector3};

/// The highest polynomial degree supported.
pub const MAX_DEGREE: usize = 5;

/// The Cholesky factor `L` of a polynomial fit's normal matrix (`AᵀA = L Lᵀ`, `A` the powers of the normalised
/// times), kept with the fit so that its coefficients' covariance `σ² (AᵀA)⁻¹` (white noise of variance `σ²` per
/// axis) gives the covariance of the fitted value and slope anywhere, extrapolated too
/// (`kinematics::uncertainty`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NormalFactor {
    pub(super) l: [[Real; MAX_DEGREE + 1]; MAX_DEGREE + 1],
    /// Coefficients (degree + 1).
    pub(super) coefficients: usize,
    /// Frames fitted.
    pub(super) frames: usize,
}

impl NormalFactor {
    pub(super) const EMPTY: NormalFactor =
        NormalFactor { l: [[0.0; MAX_DEGREE + 1]; MAX_DEGREE + 1], coefficients: 0, frames: 0 };

    /// The residual's degrees of freedom per axis (frames minus coefficients).
    pub fn dof(&self) -> usize {
        self.frames.saturating_sub(self.coefficients)
    }

    /// Frames fitted.
    pub fn frames(&self) -> usize {
        self.frames
    }

    /// Per unit noise variance: the variance of the fitted value at `tau`, its covariance with the slope (per unit
    /// of `tau`) and the slope's variance, `[φᵀMφ, φᵀMφ', φ'ᵀMφ']` with `M = (AᵀA)⁻¹`, `φ = (1, τ, τ², ...)`.
    pub fn value_slope(&self, tau: Real) -> [Real; 3] {
        let m = self.coefficients;
        let (phi, dphi) = self.basis(tau);
        // Forward substitution: L a = φ, L b = φ', so φᵀMφ = a·a.
        let (mut a, mut b) = ([0.0; MAX_DEGREE + 1], [0.0; MAX_DEGREE + 1]);
        for i in 0..m {
            let (mut sa, mut sb) = (phi[i], dphi[i]);
            for k in 0..i {
                sa -= self.l[i][k] * a[k];
                sb -= self.l[i][k] * b[k];
            }
            a[i] = sa / self.l[i][i];
            b[i] = sb / self.l[i][i];
        }
        let dot = |x: &[Real], y: &[Real]| x.iter().zip(y).take(m).map(|(p, q)| p * q).sum::<Real>();
        [dot(&a, &a), dot(&a, &b), dot(&b, &b)]
    }

    /// The fit's weights at `tau`: how much each frame's value (at `taus`, the times this factor was made from)
    /// moves the fitted value and slope (per unit of `tau`) there, `φ(τ_k)ᵀ M φ(τ)` and `φ(τ_k)ᵀ M φ'(τ)`, as
    /// `(value, slope)` per frame.
    pub fn weights<'a>(&'a self, tau: Real, taus: &'a [Real]) -> impl Iterator<Item = (Real, Real)> + 'a {
        let m = self.coefficients;
        let (phi, dphi) = self.basis(tau);
        let (c, dc) = (self.solve_normal(phi), self.solve_normal(dphi));
        taus.iter().map(move |&t| {
            let (mut w, mut dw, mut tk) = (0.0, 0.0, 1.0);
            for k in 0..m {
                w += tk * c[k];
                dw += tk * dc[k];
                tk *= t;
            }
            (w, dw)
        })
    }

    /// The powers `φ = (1, τ, τ², ...)` and their derivative `φ'` at `tau`, over the fit's coefficients.
    fn basis(&self, tau: Real) -> ([Real; MAX_DEGREE + 1], [Real; MAX_DEGREE + 1]) {
        let m = self.coefficients;
        let (mut phi, mut dphi) = ([0.0; MAX_DEGREE + 1], [0.0; MAX_DEGREE + 1]);
        let mut tk = 1.0;
        for k in 0..m {
            phi[k] = tk;
            if k + 1 < m {
                dphi[k + 1] = (k + 1) as Real * tk;
            }
            tk *= tau;
        }
        (phi, dphi)
    }

    /// `M b = (L Lᵀ)⁻¹ b`, for scalars or vectors alike (forward, then back substitution).
    // Triangular solves read clearest indexed, as written in the algebra.
    #[allow(clippy::needless_range_loop)]
    fn solve_normal<T>(&self, b: [T; MAX_DEGREE + 1]) -> [T; MAX_DEGREE + 1]
    where
        T: Copy + std::ops::Sub<Output = T> + std::ops::Mul<Real, Output = T> + std::ops::Div<Real, Output = T>,
    {
        let m = self.coefficients;
        let mut z = b;
        for i in 0..m {
            let mut s = b[i];
            for k in 0..i {
                s = s - z[k] * self.l[i][k];
            }
            z[i] = s / self.l[i][i];
        }
        let mut c = z;
        for i in (0..m).rev() {
            let mut s = z[i];
            for k in i + 1..m {
                s = s - c[k] * self.l[k][i];
            }
            c[i] = s / self.l[i][i];
        }
        c
    }

    /// The least-squares coefficients of `values` at `tau` (the times this factor was made from) by the factor:
    /// `Lᵀ c = L⁻¹ Aᵀ y`.
    pub(super) fn solve(&self, tau: &[Real], values: &[Vector3]) -> [Vector3; MAX_DEGREE + 1] {
        let m = self.coefficients;
        let mut aty = [Vector3::zeros(); MAX_DEGREE + 1];
        for (&t, y) in tau.iter().zip(values) {
            let mut tk = 1.0;
            for a in aty.iter_mut().take(m) {
                *a += tk * y;
                tk *= t;
            }
        }
        self.solve_normal(aty)
    }
}
