//! The best-fit plane through marker centres, with how well its markers condition it.

use crate::math::{Matrix3, Real, SymmetricEigen, Vector3};

use super::CalibrationError;

/// A plane fitted through points by least squares (the eigenvector of their scatter matrix with the smallest
/// eigenvalue), and what says how well the points determine it.
#[derive(Debug, Clone, PartialEq)]
pub struct PlaneFit {
    /// The points' mean, a point of the plane (in the points' frame, m).
    pub centroid: Vector3,
    /// Unit normal; its sign is the caller's to choose.
    pub normal: Vector3,
    /// How far the points spread across their best-fit line within the plane: the RMS distance of the points
    /// from that line, `sqrt(lambda_2 / n)` with `lambda_2` the middle eigenvalue of their scatter matrix (m). The
    /// plane's tilt about that line is uncertain by about `sigma / (sqrt(n) * line_spread_m)` for `sigma` of
    /// noise or unevenness across the plane: points near one line leave it open.
    pub line_spread_m: Real,
    /// Each point's signed distance from the plane along `normal` (m).
    pub off_plane_m: Vec<Real>,
}

/// The plane through `points` (at least 3, spread at least 1 mm off one line).
pub fn fit_plane(points: &[Vector3], what: &'static str) -> Result<PlaneFit, CalibrationError> {
    if points.len() < 3 {
        return Err(CalibrationError::TooFew { what, need: 3, got: points.len() });
    }
    let n = points.len() as Real;
    let centroid = points.iter().sum::<Vector3>() / n;
    let mut scatter = Matrix3::zeros();
    for p in points {
        scatter += (p - centroid) * (p - centroid).transpose();
    }
    let eigen = SymmetricEigen::new(scatter);
    let mut order = [0, 1, 2];
    order.sort_by(|a, b| eigen.eigenvalues[*a].total_cmp(&eigen.eigenvalues[*b]));
    let line_spread_m = (eigen.eigenvalues[order[1]].max(0.0) / n).sqrt();
    if line_spread_m < 1e-3 {
        return Err(CalibrationError::Geometry(format!("the {what} markers lie on one line: they give no plane")));
    }
    let normal: Vector3 = eigen.eigenvectors.column(order[0]).into_owned().normalize();
    let off_plane_m = points.iter().map(|p| (p - centroid).dot(&normal)).collect();
    Ok(PlaneFit { centroid, normal, line_spread_m, off_plane_m })
}

impl PlaneFit {
    /// The normal on the side of `hint` (its component along `hint` positive).
    pub fn normal_toward(&self, hint: &Vector3) -> Vector3 {
        if self.normal.dot(hint) < 0.0 {
            -self.normal
        } else {
            self.normal
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spread_across_the_line_is_the_rms_distance_from_it() {
        // Four points, two on each side of the x axis 30 mm off it: RMS 30 mm.
        let p = [
            Vector3::new(0.0, 0.03, 0.0),
            Vector3::new(0.0, -0.03, 0.0),
            Vector3::new(3.0, 0.03, 0.0),
            Vector3::new(3.0, -0.03, 0.0),
        ];
        let fit = fit_plane(&p, "floor").unwrap();
        assert!((fit.line_spread_m - 0.03).abs() < 1e-9, "{}", fit.line_spread_m);
        assert!((fit.normal.z.abs() - 1.0).abs() < 1e-9);
        assert!(fit.normal_toward(&-Vector3::z()).z < 0.0);
    }
}
