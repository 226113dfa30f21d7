//! Synthetic swings with exact ground truth, for tests, the demo and the extrapolation evaluation.
//!
//! A swing passes through exactly a target delivery at a known impact instant `t_i` (τ = t − t_i):
//!
//! - The face centre runs on an arc in a tilted swing plane: `f(τ) = c + ρ(τ) (−n_c cos φ + v̂ sin φ)` with
//!   `c = f_i + ρ₀ n_c`, `φ(τ) = (s τ + a τ²/2 + j τ³/6) / ρ₀` and `ρ(τ) = ρ₀ (1 + κ τ²)`, so `f(0) = f_i` and
//!   `f'(0) = s v̂` exactly (club speed, attack angle and path), with a centripetal acceleration `s²/ρ₀` of
//!   100-200 g for ρ₀ of 1-2 m.
//! - Or, with [`SwingSpec::double_pendulum`], the face centre is the end of a double pendulum in the same plane:
//!   `f(τ) = c + l₁ u(θ₁) + l₂ u(θ₂)`, `u(θ) = −n_c cos θ + v̂ sin θ`, an arm `l₁` about a fixed shoulder at the
//!   arc's centre and a club `l₂` about the wrist (`l₁ + l₂ = ρ₀`), aligned at impact, the club turning 2.5-4
//!   times as fast as the arm (`l₁ θ₁' + l₂ θ₂' = s`, so `f(0)` and `f'(0)` are the same) and each with its own
//!   angular acceleration. Over the last 60 ms the wrist uncocks through 60-90 deg, so the distance from the
//!   shoulder changes by 10-30 % along a cosine, not a parabola: a path no estimator's model reproduces exactly.
//! - The head turns as `R(τ) = Exp(τ ω + τ² α/2 + τ³ ζ/6) R_i`: `R(0) = R_i` (face angle and dynamic loft) and
//!   the angular velocity at impact is exactly `ω` = the arc's rate `s/ρ₀` about the swing-plane normal plus the
//!   face closure rate (1500-3000 deg/s) about the shaft.
//! - The CG is `p(τ) = f(τ) − R(τ) r_fc`; the truth state is [`Delivery::to_state`] of the delivery with that
//!   `ω`, so the CG velocity is `v_face − ω × r_fc` as everywhere else.
//! - After impact the head continues on the arc at the speed and with the angular velocity that the adjusted
//!   impulse-momentum model leaves it (slowed by the impulse).
//!
//! Sampling adds a random phase against the impact instant, Gaussian position and orientation noise, timestamp
//! jitter, dropped and occluded frames; everything is drawn from a seeded [`Rng`].

pub mod golfer;
mod truth;

use crate::equipment::ClubSpec;
use crate::impact::{Delivery, Equipment, ImpactError, ImpactModel, ImpactState, ImpulseModel, ImpulseVariant};
use crate::kinematics::so3;
use crate::kinematics::{Calibration, ClubPose, ClubheadSample};
use crate::math::{Isometry3, Real, Translation3Ext, UnitQuaternion, Vector3};
use crate::rng::Rng;
pub use golfer::GolferProfile;

/// Spread (standard deviation per world axis) of the head's angular acceleration at impact in
/// [`SwingSpec::random`] (rad/s²; about 23,000 deg/s²).
pub const ANGULAR_ACCEL_SIGMA_RADPS2: Real = 400.0;

/// Spread of the rate of the angular acceleration at impact (rad/s³): the club's rotation peaks within about
/// 50 ms of impact.
pub const ANGULAR_JERK_SIGMA_RADPS3: Real = 1.5e4;

/// What a synthetic swing looks like around impact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SwingSpec {
    /// The delivery at impact. Its angular velocity is replaced by the arc rate plus the face closure.
    pub delivery: Delivery,
    /// Face closure rate about the shaft at impact (deg/s, closing +).
    pub face_closure_degps: Real,
    /// Radius of the face centre's arc at impact (m).
    pub arc_radius_m: Real,
    /// Inclination of the swing plane from the ground (deg).
    pub plane_angle_deg: Real,
    /// Tangential acceleration and jerk of the face centre at impact (m/s², m/s³).
    pub tangential_accel_mps2: Real,
    /// Tangential jerk of the face centre at impact (m/s³).
    pub tangential_jerk_mps3: Real,
    /// Relative change of the arc radius: ρ = ρ₀ (1 + κ τ²) (1/s²).
    pub radius_curvature_per_s2: Real,
    /// Angular acceleration and its rate at impact (rad/s², rad/s³, world).
    pub angular_accel_radps2: Vector3,
    /// Rate of the angular acceleration at impact (rad/s³, world).
    pub angular_jerk_radps3: Vector3,
    /// When set, the face centre's path before impact is a double pendulum instead of the arc.
    pub double_pendulum: Option<DoublePendulum>,
    /// The head turned about its face-centre normal at impact, toe up + (deg): the dynamic lie falls below the
    /// static lie by about this much while face angle and dynamic loft stay. 0 in the drawn swings.
    pub face_roll_deg: Real,
}

/// The arm and club of a double-pendulum path (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DoublePendulum {
    /// The arm's share of the arc radius (the club has the rest).
    pub arm_share: Real,
    /// The club's angular rate over the arm's at impact.
    pub rate_ratio: Real,
    /// Angular accelerations at impact (rad/s²).
    pub arm_accel_radps2: Real,
    /// The club's angular acceleration at impact (rad/s²).
    pub club_accel_radps2: Real,
}

/// The shape of the face centre's path before impact.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SwingPath {
    /// A circle in the swing plane with a slowly changing radius (the estimators' `arc` model is exact for it).
    #[default]
    Arc,
    /// A double pendulum (arm and club) in the swing plane.
    DoublePendulum,
}

impl SwingPath {
    /// The name on the command line and in JSON.
    pub fn name(self) -> &'static str {
        match self {
            SwingPath::Arc => "arc",
            SwingPath::DoublePendulum => "double-pendulum",
        }
    }
}

impl SwingSpec {
    /// A plausible swing for `club` with a random delivery, drawn from `rng`.
    pub fn random(club: &ClubSpec, rng: &mut Rng) -> SwingSpec {
        let driver = club.face.shape.is_curved();
        let (speed_mph, attack, loft) = if driver {
            ((85.0, 120.0), (-4.0, 5.0), (club.loft_deg() - 1.0, club.loft_deg() + 5.0))
        } else {
            ((65.0, 95.0), (-7.0, -1.0), (club.loft_deg() - 10.0, club.loft_deg() - 2.0))
        };
        let (hw, hh) = (club.face_half_width_m * 0.45, club.face_half_height_m * 0.45);
        let delivery = Delivery {
            club_speed_mps: crate::units::mph_to_mps(rng.uniform(speed_mph.0, speed_mph.1)),
            attack_angle_rad: rng.uniform(attack.0, attack.1).to_radians(),
            club_path_rad: rng.uniform(-5.0, 5.0).to_radians(),
            face_angle_rad: rng.uniform(-4.0, 4.0).to_radians(),
            dynamic_loft_rad: rng.uniform(loft.0, loft.1).to_radians(),
            impact_h_m: rng.uniform(-hw, hw),
            impact_v_m: rng.uniform(-hh, hh),
            club_angular_velocity_radps: Vector3::zeros(),
        };
        Self::around(delivery, None, rng)
    }

    /// A golfer's swing for `club`: the delivery drawn from the club's [`GolferProfile`] (launch-monitor
    /// statistics, docs/synthetic-golfers.md), the swing around it as in [`SwingSpec::random`].
    pub fn golfer(club: &ClubSpec, rng: &mut Rng) -> SwingSpec {
        let (delivery, plane_deg) = GolferProfile::for_club(club).draw(club, rng);
        Self::around(delivery, Some(plane_deg), rng)
    }

    /// The swing around `delivery`: arc, plane (drawn unless given), closure rate and accelerations.
    fn around(delivery: Delivery, plane_deg: Option<Real>, rng: &mut Rng) -> SwingSpec {
        let rand_vec = |rng: &mut Rng, scale: Real| Vector3::new(rng.normal(), rng.normal(), rng.normal()) * scale;
        // A centripetal load of 100-200 g at impact, on an arc of 1-2 m.
        let g_load = rng.uniform(100.0, 200.0);
        let arc_radius_m = (delivery.club_speed_mps.powi(2) / (g_load * 9.81)).clamp(1.0, 2.0);
        let face_closure_degps = rng.uniform(1500.0, 3000.0);
        let drawn_plane_deg = rng.uniform(45.0, 65.0);
        SwingSpec {
            delivery,
            face_closure_degps,
            arc_radius_m,
            plane_angle_deg: plane_deg.unwrap_or(drawn_plane_deg),
            tangential_accel_mps2: rng.uniform(-100.0, 200.0),
            tangential_jerk_mps3: rng.uniform(-1.0e4, 1.0e4),
            radius_curvature_per_s2: rng.uniform(-20.0, 20.0),
            angular_accel_radps2: rand_vec(rng, ANGULAR_ACCEL_SIGMA_RADPS2),
            angular_jerk_radps3: rand_vec(rng, ANGULAR_JERK_SIGMA_RADPS3),
            double_pendulum: None,
            face_roll_deg: 0.0,
        }
    }

    /// A plausible swing whose path has the given shape (the double pendulum's parameters drawn after the rest).
    pub fn random_on(path: SwingPath, club: &ClubSpec, rng: &mut Rng) -> SwingSpec {
        let mut spec = Self::random(club, rng);
        if path == SwingPath::DoublePendulum {
            spec.double_pendulum = Some(DoublePendulum {
                arm_share: rng.uniform(0.35, 0.45),
                rate_ratio: rng.uniform(2.5, 4.0),
                arm_accel_radps2: rng.uniform(-150.0, 0.0),
                club_accel_radps2: rng.uniform(-200.0, 200.0),
            });
        }
        spec
    }
}

/// A swing: its exact pose at any time and its truth at impact.
#[derive(Debug, Clone)]
pub struct Swing {
    /// What was swung.
    pub spec: SwingSpec,
    /// The delivery at impact, with the angular velocity the swing really has.
    pub delivery: Delivery,
    /// The exact impact state (the ball at the world origin).
    pub truth: ImpactState,
    r_fc: Vector3,
    f_i: Vector3,
    centre: Vector3,
    n_c: Vector3,
    v_hat: Vector3,
    r_i: UnitQuaternion,
    speed_after_mps: Real,
    omega_after: Vector3,
}

impl Swing {
    /// Builds the swing for `spec` on `equipment`.
    pub fn new(spec: &SwingSpec, equipment: &Equipment) -> Result<Swing, ImpactError> {
        let club = &equipment.club;
        let d = spec.delivery;
        let v_hat = d.direction();
        let s = d.club_speed_mps;
        let beta = spec.plane_angle_deg.to_radians();
        // Toward the arc's centre: up and toward the golfer (-z for a right-hander), normal to the velocity.
        let toward = Vector3::new(0.0, beta.sin(), -beta.cos());
        let n_c = (toward - toward.dot(&v_hat) * v_hat).normalize();
        let omega_arc = (s / spec.arc_radius_m) * v_hat.cross(&n_c);
        // The orientation at impact does not depend on the angular velocity.
        let mut delivery = d;
        delivery.club_angular_velocity_radps = Vector3::zeros();
        let r_i = truth::rolled(delivery.to_state(equipment)?.world_from_club.rotation, club, spec.face_roll_deg);
        let shaft_world = r_i * club.shaft_axis_up();
        delivery.club_angular_velocity_radps = omega_arc + spec.face_closure_degps.to_radians() * shaft_world;
        let truth = truth::state(&delivery, equipment, r_i)?;
        let r_fc = club.face.center_m;
        let f_i = truth.world_from_club.translation.vector + r_i * r_fc;
        let after = ImpulseModel::new(ImpulseVariant::Adjusted).predict(&truth, equipment)?;
        let v_face_after = after.club_velocity_mps + after.club_angular_velocity_radps.cross(&(r_i * r_fc));
        Ok(Swing {
            spec: *spec,
            delivery,
            truth,
            r_fc,
            f_i,
            centre: f_i + spec.arc_radius_m * n_c,
            n_c,
            v_hat,
            r_i,
            speed_after_mps: v_face_after.norm(),
            omega_after: after.club_angular_velocity_radps,
        })
    }

    /// The club frame's exact pose at `tau_s` from impact.
    pub fn pose(&self, tau_s: Real) -> Isometry3 {
        let sp = &self.spec;
        let rho0 = sp.arc_radius_m;
        let (phi, rotation) = if tau_s <= 0.0 {
            let t2 = tau_s * tau_s;
            let arc = self.delivery.club_speed_mps * tau_s
                + 0.5 * sp.tangential_accel_mps2 * t2
                + sp.tangential_jerk_mps3 * t2 * tau_s / 6.0;
            let theta = tau_s * self.truth.angular_velocity_radps
                + 0.5 * t2 * sp.angular_accel_radps2
                + t2 * tau_s / 6.0 * sp.angular_jerk_radps3;
            (arc / rho0, theta)
        } else {
            let arc = self.speed_after_mps * tau_s + 0.5 * sp.tangential_accel_mps2 * tau_s * tau_s;
            (arc / rho0, tau_s * self.omega_after)
        };
        let f = if tau_s <= 0.0 {
            self.approach_face_centre(tau_s)
        } else {
            let rho = rho0 * (1.0 + sp.radius_curvature_per_s2 * tau_s * tau_s);
            self.centre + rho * self.in_plane(phi)
        };
        let r = so3::exp(&rotation) * self.r_i;
        let p = f - r * self.r_fc;
        Isometry3::from_parts(p.into_translation(), r)
    }

    /// The face centre at impact (m, world).
    pub fn face_centre_at_impact(&self) -> Vector3 {
        self.f_i
    }
}

/// How a synthetic rig samples a swing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sampling {
    /// Frame rate (Hz).
    pub rate_hz: Real,
    /// Gaussian position noise per axis (m).
    pub position_noise_m: Real,
    /// Gaussian orientation noise per axis of the rotation vector (rad).
    pub orientation_noise_rad: Real,
    /// Gaussian timestamp jitter (s).
    pub jitter_s: Real,
    /// Probability that a frame never arrives.
    pub drop_probability: Real,
    /// Probability that a frame arrives flagged occluded.
    pub occlusion_probability: Real,
    /// Sampled time before and after impact (s).
    pub before_s: Real,
    /// Sampled time after impact (s).
    pub after_s: Real,
}

impl Default for Sampling {
    fn default() -> Self {
        Sampling {
            rate_hz: 720.0,
            position_noise_m: 0.0,
            orientation_noise_rad: 0.0,
            jitter_s: 0.0,
            drop_probability: 0.0,
            occlusion_probability: 0.0,
            before_s: 0.06,
            after_s: 0.03,
        }
    }
}

/// The samples of one swing, with the truth of when the impact happened.
#[derive(Debug, Clone)]
pub struct SampledSwing {
    /// The frames as the rig sends them (dropped ones missing).
    pub samples: Vec<ClubheadSample>,
    /// The exact impact instant on the rig's clock (ns).
    pub t_impact_ns: u64,
    /// The next free frame number.
    pub next_frame: u64,
}

/// Samples `swing` as a rig would: frame numbers from `first_frame`, impact at `t_impact_ns`, a random phase
/// of the frame clock against the impact, and the noise of `sampling`.
pub fn sample(
    swing: &Swing,
    sampling: &Sampling,
    calibration: &Calibration,
    t_impact_ns: u64,
    first_frame: u64,
    rng: &mut Rng,
) -> SampledSwing {
    let period = 1.0 / sampling.rate_hz;
    let phase = rng.unit();
    let k0 = -(sampling.before_s / period).ceil() as i64;
    let k1 = (sampling.after_s / period).ceil() as i64;
    let mut samples = Vec::with_capacity((k1 - k0 + 1) as usize);
    let mut frame = first_frame;
    let mut last_t_ns = 0u64;
    for k in k0..=k1 {
        let tau = (k as Real + phase) * period;
        let t_true_ns = t_impact_ns as i64 + (tau * 1e9).round() as i64;
        let tau = (t_true_ns - t_impact_ns as i64) as Real * 1e-9; // the pose at the exact (ns) capture time
        let this_frame = frame;
        frame += 1;
        if rng.chance(sampling.drop_probability) {
            continue;
        }
        let jitter = (rng.normal() * sampling.jitter_s * 1e9).round() as i64;
        let t_ns = ((t_true_ns + jitter).max(0) as u64).max(last_t_ns + 1);
        last_t_ns = t_ns;
        if rng.chance(sampling.occlusion_probability) {
            samples.push(ClubheadSample {
                frame: this_frame,
                t_ns,
                position_m: Vector3::zeros(),
                orientation_xyzw: [0.0, 0.0, 0.0, 1.0],
                occluded: true,
            });
            continue;
        }
        let mut pose = swing.pose(tau);
        let dp = Vector3::new(rng.normal(), rng.normal(), rng.normal()) * sampling.position_noise_m;
        let dr = Vector3::new(rng.normal(), rng.normal(), rng.normal()) * sampling.orientation_noise_rad;
        pose.translation.vector += dp;
        pose.rotation = so3::exp(&dr) * pose.rotation;
        samples.push(ClubPose { frame: this_frame, t_ns, world_from_club: pose }.to_sample(calibration));
    }
    SampledSwing { samples, t_impact_ns, next_frame: frame }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::impact::DeliveryMetrics;

    /// The pose function is consistent with the truth: at τ = 0 it is the truth pose, and its finite-difference
    /// velocity and angular velocity are the truth's.
    #[test]
    fn swing_passes_exactly_through_the_delivery() {
        let mut rng = Rng::new(3);
        for club in [ClubSpec::driver(), ClubSpec::iron7()] {
            let eq = Equipment::new(club.clone());
            for _ in 0..20 {
                let spec = SwingSpec::random(&club, &mut rng);
                let swing = Swing::new(&spec, &eq).unwrap();
                let p0 = swing.pose(0.0);
                assert!((p0.translation.vector - swing.truth.world_from_club.translation.vector).norm() < 1e-12);
                let h = 1e-7;
                let (a, b) = (swing.pose(-h), swing.pose(-2.0 * h));
                // Backward difference, second order.
                let v = (3.0 * p0.translation.vector - 4.0 * a.translation.vector + b.translation.vector) / (2.0 * h);
                assert!((v - swing.truth.cg_velocity_mps).norm() < 1e-4, "{v} vs {}", swing.truth.cg_velocity_mps);
                let w = so3::log(&(p0.rotation * a.rotation.inverse())) / h;
                assert!((w - swing.truth.angular_velocity_radps).norm() < 1e-2);
                let m = DeliveryMetrics::from_state(&swing.truth, &club);
                assert!((m.club_speed_mps - spec.delivery.club_speed_mps).abs() < 1e-9);
                // Centripetal acceleration of the face centre: 100-200 g (less for slow irons on the 1 m arc).
                let g_load = spec.delivery.club_speed_mps.powi(2) / spec.arc_radius_m / 9.81;
                assert!((60.0..=200.0 + 1e-9).contains(&g_load), "{g_load}");
                assert!((1.0..=2.0).contains(&spec.arc_radius_m));
                // The ball touches the face at impact and not before.
                let scene = crate::kinematics::Scene {
                    face: &club.face,
                    ball_position_m: Vector3::zeros(),
                    ball_radius_m: eq.ball.radius_m,
                    max_extrapolation_s: 0.01,
                };
                let g0 = scene.gap(&p0);
                assert!(g0.distance_m.abs() < 1e-12, "{g0:?}");
                assert!((g0.h_m - spec.delivery.impact_h_m).abs() < 1e-12);
                assert!((g0.v_m - spec.delivery.impact_v_m).abs() < 1e-12);
                assert!(scene.gap(&swing.pose(-1e-4)).distance_m > 0.0);
                assert!(scene.gap(&swing.pose(1e-4)).distance_m < 0.0);
            }
        }
    }
}
