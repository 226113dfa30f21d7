//! Synthetic datasets for tests and docs: deliveries drawn from a club's typical ranges, launched by a model
//! with chosen parameters, plus launch-monitor noise, written as the JSONL of [`super::dataset`].
//!
//! Deliveries (uniform within the ranges of [`DeliveryRanges`]; the driver's and the 7-iron's are typical elite
//! spreads around the seed's means of Table 3.2, 158.9 mph ball speed for the driver and 117.0 mph for the
//! 7-iron). Launch-monitor noise: independent zero-mean normal errors per field with the standard deviations of
//! [`LmNoise`]; the default is the (0.5 mph, 0.2 deg launch, 0.3 deg direction, 150 rpm per spin
//! component), about what photometric monitors quote. A shot the model cannot launch is drawn again.

use serde::{Deserialize, Serialize};

use super::dataset::{fields_of, launch_fields, DatasetLine};
use super::IdentifyError;
use crate::equipment::{BallSpec, ClubSpec, LoadedClub};
use crate::impact::registry::{self, BuildOptions};
use crate::impact::{Equipment, LaunchMetrics};
use crate::math::Real;
use crate::rng::Rng;
use crate::wire::DeliveryInput;

/// Standard deviations of the launch monitor's errors per field.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LmNoise {
    pub ball_speed_mph: Real,
    pub launch_angle_deg: Real,
    pub launch_direction_deg: Real,
    pub backspin_rpm: Real,
    pub sidespin_rpm: Real,
}

impl Default for LmNoise {
    fn default() -> Self {
        LmNoise {
            ball_speed_mph: 0.5,
            launch_angle_deg: 0.2,
            launch_direction_deg: 0.3,
            backspin_rpm: 150.0,
            sidespin_rpm: 150.0,
        }
    }
}

impl LmNoise {
    pub fn as_array(&self) -> [Real; 5] {
        [self.ball_speed_mph, self.launch_angle_deg, self.launch_direction_deg, self.backspin_rpm, self.sidespin_rpm]
    }
}

/// Uniform ranges `(lo, hi)` of the delivery fields.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DeliveryRanges {
    pub club_speed_mph: (Real, Real),
    pub attack_angle_deg: (Real, Real),
    pub club_path_deg: (Real, Real),
    /// Face angle relative to the path.
    pub face_to_path_deg: (Real, Real),
    pub dynamic_loft_deg: (Real, Real),
    pub impact_h_mm: (Real, Real),
    pub impact_v_mm: (Real, Real),
}

impl DeliveryRanges {
    /// Drives: 95-120 mph, attack -4..+5 deg, dynamic loft 9-16 deg, impacts within 15 mm toe-heel and 10 mm
    /// up and down.
    pub const DRIVER: DeliveryRanges = DeliveryRanges {
        club_speed_mph: (95.0, 120.0),
        attack_angle_deg: (-4.0, 5.0),
        club_path_deg: (-5.0, 5.0),
        face_to_path_deg: (-4.0, 4.0),
        dynamic_loft_deg: (9.0, 16.0),
        impact_h_mm: (-15.0, 15.0),
        impact_v_mm: (-8.0, 10.0),
    };
    /// 7-irons: 75-95 mph, attack -7..-1 deg, dynamic loft 20-30 deg, impacts within 12 mm and 8 mm.
    pub const IRON7: DeliveryRanges = DeliveryRanges {
        club_speed_mph: (75.0, 95.0),
        attack_angle_deg: (-7.0, -1.0),
        club_path_deg: (-5.0, 5.0),
        face_to_path_deg: (-4.0, 4.0),
        dynamic_loft_deg: (20.0, 30.0),
        impact_h_mm: (-12.0, 12.0),
        impact_v_mm: (-8.0, 8.0),
    };

    /// The driver's ranges for a curved face, the 7-iron's for a flat one.
    pub fn for_club(club: &ClubSpec) -> Self {
        match club.face.shape {
            crate::face::FaceShape::Plane => Self::IRON7,
            crate::face::FaceShape::Torus { .. } => Self::DRIVER,
        }
    }

    fn draw(&self, rng: &mut Rng) -> DeliveryInput {
        let mut u = |r: (Real, Real)| rng.uniform(r.0, r.1);
        let club_path_deg = u(self.club_path_deg);
        DeliveryInput {
            club_speed_mph: u(self.club_speed_mph),
            attack_angle_deg: u(self.attack_angle_deg),
            club_path_deg,
            face_angle_deg: club_path_deg + u(self.face_to_path_deg),
            dynamic_loft_deg: Some(u(self.dynamic_loft_deg)),
            impact_h_mm: u(self.impact_h_mm),
            impact_v_mm: u(self.impact_v_mm),
            club_angular_velocity_radps: None,
            handedness: None,
            dynamic_lie_deg: None,
        }
    }
}

/// What to generate.
#[derive(Debug, Clone)]
pub struct SynthSpec {
    /// The club with the true parameters in its sections.
    pub club: LoadedClub,
    /// The registry's name of the model that launches the balls.
    pub model: String,
    pub shots: usize,
    pub noise: LmNoise,
    pub ranges: DeliveryRanges,
    pub seed: u64,
}

/// Deliveries through the model, each measured with noise. Deterministic for a seed.
pub fn generate(spec: &SynthSpec) -> Result<Vec<DatasetLine>, IdentifyError> {
    let equipment = Equipment::new(spec.club.club.clone());
    let model =
        registry::build_one(&spec.model, &spec.club, &BuildOptions { ball: BallSpec::SEED, ..Default::default() })?;
    let mut rng = Rng::new(spec.seed);
    let sigma = spec.noise.as_array();
    let mut out = Vec::with_capacity(spec.shots);
    let mut attempts = 0;
    while out.len() < spec.shots {
        attempts += 1;
        if attempts > 10 * spec.shots + 100 {
            return Err(IdentifyError::NoShots("generate: the model failed on nearly every delivery"));
        }
        let delivery = spec.ranges.draw(&mut rng);
        let state = delivery.to_delivery(equipment.club.face.loft_rad.to_degrees()).to_state(&equipment)?;
        let Ok(launch) = model.predict(&state, &equipment) else { continue };
        let truth = fields_of(&LaunchMetrics::from_ball(&launch.ball_velocity_mps, &launch.ball_spin_radps));
        let mut measured = truth;
        for (m, s) in measured.iter_mut().zip(sigma) {
            *m += s * rng.normal();
        }
        out.push(DatasetLine { delivery, measured: launch_fields(&measured) });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::equipment::ModelSections;
    use crate::offline::identify::dataset::{fields_of_launch, resolve};

    #[test]
    fn noise_has_the_documented_spread_and_the_generator_repeats() {
        // Zero noise reproduces the model; the noise gives residual SDs near 0.5 mph ... 150 rpm.
        let mut spec = SynthSpec {
            club: LoadedClub { club: ClubSpec::driver(), sections: ModelSections::default() },
            model: "adjusted".into(),
            shots: 2000,
            noise: LmNoise::default(),
            ranges: DeliveryRanges::DRIVER,
            seed: 4,
        };
        let noisy = generate(&spec).unwrap();
        assert_eq!(generate(&spec).unwrap(), noisy);
        spec.noise = LmNoise {
            ball_speed_mph: 0.0,
            launch_angle_deg: 0.0,
            launch_direction_deg: 0.0,
            backspin_rpm: 0.0,
            sidespin_rpm: 0.0,
        };
        let clean = generate(&spec).unwrap();
        let sigma = LmNoise::default().as_array();
        for (i, sigma_i) in sigma.iter().enumerate() {
            let var = noisy
                .iter()
                .zip(&clean)
                .map(|(a, b)| (fields_of_launch(&a.measured)[i] - fields_of_launch(&b.measured)[i]).powi(2))
                .sum::<Real>()
                / noisy.len() as Real;
            // The sample SD of 2000 normals is within 5 % of sigma (its standard error is sigma / sqrt(4000)).
            assert!((var.sqrt() / sigma_i - 1.0).abs() < 0.05, "field {i}: {}", var.sqrt());
        }
        let shots = resolve(&clean, &Equipment::new(ClubSpec::driver())).unwrap();
        assert_eq!(shots.len(), 2000);
    }
}
