//! Whether the reported uncertainty is honest: on synthetic swings with exact truth, the fraction of shots whose
//! truth falls within one and two reported sigmas of the estimate, per field (a Gaussian error with the sigma
//! it reports: 68.3 % and 95.4 %), with the RMS sigma beside the RMS error and the RMS of their ratio.

use serde::{Deserialize, Serialize};

use crate::math::Real;

/// The fields whose coverage is measured: the delivery's, the launch's, and the impact instant.
pub const FIELDS: [&str; 14] = [
    "club_speed_mph",
    "attack_angle_deg",
    "club_path_deg",
    "face_angle_deg",
    "dynamic_loft_deg",
    "face_to_path_deg",
    "impact_h_mm",
    "impact_v_mm",
    "ball_speed_mph",
    "launch_angle_deg",
    "launch_direction_deg",
    "total_spin_rpm",
    "spin_axis_deg",
    "t_impact_us",
];

/// One field's coverage over the shots that reported an uncertainty.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FieldCoverage {
    pub field: String,
    pub shots: usize,
    /// Fraction of shots whose truth is within one (two) reported sigmas.
    pub within_1_sigma: Real,
    pub within_2_sigma: Real,
    pub rms_sigma: Real,
    pub rms_error: Real,
    /// RMS of error / sigma (1 for an honest Gaussian sigma).
    pub rms_z: Real,
}

/// Counts of one estimator's shots.
#[derive(Debug, Clone, Default)]
pub struct CoverageAcc {
    n: usize,
    /// Estimated shots that reported no uncertainty.
    pub without: usize,
    within_1: [usize; FIELDS.len()],
    within_2: [usize; FIELDS.len()],
    sigma2: [Real; FIELDS.len()],
    error2: [Real; FIELDS.len()],
    z2: [Real; FIELDS.len()],
}

impl CoverageAcc {
    /// One shot's errors (estimate minus truth) and reported sigmas, in [`FIELDS`]' order.
    pub fn add(&mut self, errors: &[Real; FIELDS.len()], sigmas: &[Real; FIELDS.len()]) {
        self.n += 1;
        for i in 0..FIELDS.len() {
            let (e, s) = (errors[i].abs(), sigmas[i]);
            self.within_1[i] += usize::from(e <= s);
            self.within_2[i] += usize::from(e <= 2.0 * s);
            self.sigma2[i] += s * s;
            self.error2[i] += e * e;
            self.z2[i] += if s > 0.0 { (e / s).powi(2) } else { Real::INFINITY };
        }
    }

    /// Shots counted.
    pub fn shots(&self) -> usize {
        self.n
    }

    /// Every field's coverage.
    pub fn report(&self) -> Vec<FieldCoverage> {
        let n = self.n.max(1) as Real;
        FIELDS
            .iter()
            .enumerate()
            .map(|(i, f)| FieldCoverage {
                field: f.to_string(),
                shots: self.n,
                within_1_sigma: self.within_1[i] as Real / n,
                within_2_sigma: self.within_2[i] as Real / n,
                rms_sigma: (self.sigma2[i] / n).sqrt(),
                rms_error: (self.error2[i] / n).sqrt(),
                rms_z: (self.z2[i] / n).sqrt(),
            })
            .collect()
    }
}
