//! The extrapolation evaluation: synthetic swings with exact truth through every estimator, and the errors of
//! the delivery and of the launch the adjusted model predicts from the estimate versus from the truth.

use serde::{Deserialize, Serialize};

use crate::equipment::ClubSpec;
use crate::impact::{DeliveryMetrics, Equipment, ImpactModel, ImpactState, LaunchMetrics};
use crate::kinematics::{Calibration, DetectorConfig, EstimatorSpec, ImpactDetector, Track, TrackLimits};
use crate::math::Real;
use crate::offline::swing::{sample, Sampling, Swing, SwingSpec};
use crate::rng::Rng;

/// What to evaluate.
#[derive(Debug, Clone)]
pub struct EvalConfig {
    pub club: ClubSpec,
    /// The model whose launch errors are reported (from `impact::registry`; the adjusted model by default).
    pub launch_model: std::sync::Arc<dyn ImpactModel>,
    pub rate_hz: Real,
    pub shots: usize,
    pub noise_mm: Real,
    pub noise_deg: Real,
    pub jitter_us: Real,
    pub drop_probability: Real,
    pub seed: u64,
    pub estimators: Vec<EstimatorSpec>,
    /// The shape of the synthetic swings' path.
    pub path: crate::offline::swing::SwingPath,
}

/// RMS and largest absolute error.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct ErrorStats {
    pub rms: Real,
    pub max: Real,
}

/// The error of each delivery and launch number (estimate minus truth).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct Errors {
    pub club_speed_pct: ErrorStats,
    pub attack_angle_deg: ErrorStats,
    pub club_path_deg: ErrorStats,
    pub face_angle_deg: ErrorStats,
    pub dynamic_loft_deg: ErrorStats,
    pub impact_h_mm: ErrorStats,
    pub impact_v_mm: ErrorStats,
    pub t_impact_us: ErrorStats,
    pub ball_speed_mph: ErrorStats,
    pub launch_angle_deg: ErrorStats,
    pub launch_direction_deg: ErrorStats,
    pub backspin_rpm: ErrorStats,
    pub sidespin_rpm: ErrorStats,
}

impl Errors {
    /// Keys in order, with their stats.
    pub fn entries(&self) -> [(&'static str, ErrorStats); 13] {
        [
            ("club_speed_pct", self.club_speed_pct),
            ("attack_angle_deg", self.attack_angle_deg),
            ("club_path_deg", self.club_path_deg),
            ("face_angle_deg", self.face_angle_deg),
            ("dynamic_loft_deg", self.dynamic_loft_deg),
            ("impact_h_mm", self.impact_h_mm),
            ("impact_v_mm", self.impact_v_mm),
            ("t_impact_us", self.t_impact_us),
            ("ball_speed_mph", self.ball_speed_mph),
            ("launch_angle_deg", self.launch_angle_deg),
            ("launch_direction_deg", self.launch_direction_deg),
            ("backspin_rpm", self.backspin_rpm),
            ("sidespin_rpm", self.sidespin_rpm),
        ]
    }
}

/// The error of TrackMan's club data from the frames (docs/club-data.md; estimate minus truth), over the shots
/// whose path gave a swing arc.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct ClubDataErrors {
    pub shots: usize,
    pub swing_direction_deg: ErrorStats,
    pub swing_plane_deg: ErrorStats,
    pub low_point_distance_mm: ErrorStats,
    pub low_point_height_mm: ErrorStats,
    pub dynamic_lie_deg: ErrorStats,
    pub closure_rate_degps: ErrorStats,
    pub face_to_path_deg: ErrorStats,
}

impl ClubDataErrors {
    /// Keys in order, with their stats.
    pub fn entries(&self) -> [(&'static str, ErrorStats); 7] {
        [
            ("swing_direction_deg", self.swing_direction_deg),
            ("swing_plane_deg", self.swing_plane_deg),
            ("low_point_distance_mm", self.low_point_distance_mm),
            ("low_point_height_mm", self.low_point_height_mm),
            ("dynamic_lie_deg", self.dynamic_lie_deg),
            ("closure_rate_degps", self.closure_rate_degps),
            ("face_to_path_deg", self.face_to_path_deg),
        ]
    }
}

/// One estimator's result.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EstimatorReport {
    pub name: String,
    /// Shots with an estimate.
    pub shots: usize,
    /// Shots the estimator refused or missed, by reason.
    pub refused: std::collections::BTreeMap<String, usize>,
    pub errors: Errors,
    #[serde(default)]
    pub club_data: ClubDataErrors,
    /// The reported uncertainty's coverage of the truth, per field (`offline::coverage`).
    #[serde(default)]
    pub coverage: Vec<crate::offline::coverage::FieldCoverage>,
    /// Estimates that reported no uncertainty.
    #[serde(default)]
    pub without_uncertainty: usize,
}

/// The whole evaluation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EvalReport {
    pub club: String,
    pub rate_hz: Real,
    pub shots: usize,
    pub noise_mm: Real,
    pub noise_deg: Real,
    pub seed: u64,
    pub path: crate::offline::swing::SwingPath,
    pub estimators: Vec<EstimatorReport>,
}

#[derive(Clone)]
struct Acc<const N: usize> {
    n: usize,
    sums: [Real; N],
    maxes: [Real; N],
}

impl<const N: usize> Default for Acc<N> {
    fn default() -> Self {
        Acc { n: 0, sums: [0.0; N], maxes: [0.0; N] }
    }
}

impl<const N: usize> Acc<N> {
    fn add(&mut self, e: &[Real; N]) {
        self.n += 1;
        for ((sum, max), e) in self.sums.iter_mut().zip(self.maxes.iter_mut()).zip(e) {
            *sum += e * e;
            *max = max.max(e.abs());
        }
    }
    fn stats(&self, i: usize) -> ErrorStats {
        ErrorStats {
            rms: if self.n > 0 { (self.sums[i] / self.n as Real).sqrt() } else { Real::NAN },
            max: self.maxes[i],
        }
    }
}

impl Acc<7> {
    fn club_data(&self) -> ClubDataErrors {
        let s = |i| self.stats(i);
        ClubDataErrors {
            shots: self.n,
            swing_direction_deg: s(0),
            swing_plane_deg: s(1),
            low_point_distance_mm: s(2),
            low_point_height_mm: s(3),
            dynamic_lie_deg: s(4),
            closure_rate_degps: s(5),
            face_to_path_deg: s(6),
        }
    }
}

impl Acc<13> {
    fn errors(&self) -> Errors {
        let s = |i| self.stats(i);
        Errors {
            club_speed_pct: s(0),
            attack_angle_deg: s(1),
            club_path_deg: s(2),
            face_angle_deg: s(3),
            dynamic_loft_deg: s(4),
            impact_h_mm: s(5),
            impact_v_mm: s(6),
            t_impact_us: s(7),
            ball_speed_mph: s(8),
            launch_angle_deg: s(9),
            launch_direction_deg: s(10),
            backspin_rpm: s(11),
            sidespin_rpm: s(12),
        }
    }
}

fn launch(model: &dyn ImpactModel, state: &ImpactState, eq: &Equipment) -> Option<LaunchMetrics> {
    let l = model.predict(state, eq).ok()?;
    Some(LaunchMetrics::from_ball(&l.ball_velocity_mps, &l.ball_spin_radps))
}

/// Adds one shot's errors against its reported uncertainty (the adjusted model's Jacobian, as live).
#[allow(clippy::too_many_arguments)]
fn add_coverage(
    acc: &mut crate::offline::coverage::CoverageAcc,
    config: &EvalConfig,
    eq: &Equipment,
    est: &crate::kinematics::ImpactEstimate,
    scene: &crate::kinematics::Scene,
    (m, truth): (&DeliveryMetrics, &DeliveryMetrics),
    (l, t): (&LaunchMetrics, &LaunchMetrics),
    t_err_us: Real,
) {
    use crate::impact::uncertainty::LaunchJacobian;
    use crate::kinematics::uncertainty::{estimate_uncertainty, CalibrationSigma};
    let Some(u) = estimate_uncertainty(est, scene, &config.club, &CalibrationSigma::default()) else {
        acc.without += 1;
        return;
    };
    let Ok(jac) =
        LaunchJacobian::of(config.launch_model.as_ref(), eq, &m.to_delivery(), m.dynamic_lie_deg.to_radians())
    else {
        acc.without += 1;
        return;
    };
    let (d, lu) = (u.delivery.sigmas(), jac.uncertainty(&u.delivery));
    let wrap = |a: Real| (a + 180.0).rem_euclid(360.0) - 180.0;
    acc.add(
        &[
            m.club_speed_mph - truth.club_speed_mph,
            m.attack_angle_deg - truth.attack_angle_deg,
            m.club_path_deg - truth.club_path_deg,
            m.face_angle_deg - truth.face_angle_deg,
            m.dynamic_loft_deg - truth.dynamic_loft_deg,
            m.face_to_path_deg - truth.face_to_path_deg,
            m.impact_h_mm - truth.impact_h_mm,
            m.impact_v_mm - truth.impact_v_mm,
            l.ball_speed_mph - t.ball_speed_mph,
            l.launch_angle_deg - t.launch_angle_deg,
            l.launch_direction_deg - t.launch_direction_deg,
            l.total_spin_rpm - t.total_spin_rpm,
            wrap(l.spin_axis_deg - t.spin_axis_deg),
            t_err_us,
        ],
        &[
            d.club_speed_mph,
            d.attack_angle_deg,
            d.club_path_deg,
            d.face_angle_deg,
            d.dynamic_loft_deg,
            d.face_to_path_deg,
            d.impact_h_mm,
            d.impact_v_mm,
            lu.ball_speed_mph,
            lu.launch_angle_deg,
            lu.launch_direction_deg,
            lu.total_spin_rpm,
            lu.spin_axis_deg,
            u.t_impact_sigma_s * 1e6,
        ],
    );
}

/// Runs the evaluation; `progress(done)` is called after each shot.
pub fn run(config: &EvalConfig, mut progress: impl FnMut(usize)) -> EvalReport {
    let eq = Equipment::new(config.club.clone());
    let mut rng = Rng::new(config.seed);
    let sampling = Sampling {
        rate_hz: config.rate_hz,
        position_noise_m: config.noise_mm * 1e-3,
        orientation_noise_rad: config.noise_deg.to_radians(),
        jitter_s: config.jitter_us * 1e-6,
        drop_probability: config.drop_probability,
        ..Sampling::default()
    };
    let mut accs = vec![Acc::<13>::default(); config.estimators.len()];
    let mut club_accs = vec![Acc::<7>::default(); config.estimators.len()];
    let mut coverage = vec![crate::offline::coverage::CoverageAcc::default(); config.estimators.len()];
    let mut refused = vec![std::collections::BTreeMap::<String, usize>::new(); config.estimators.len()];
    let calibration = Calibration::default();
    for shot in 0..config.shots {
        let spec = SwingSpec::random_on(config.path, &config.club, &mut rng);
        let Ok(swing) = Swing::new(&spec, &eq) else {
            progress(shot + 1);
            continue;
        };
        let t_impact_ns = 1_000_000_000 + shot as u64 * 10_000_000_000;
        let sampled = sample(&swing, &sampling, &calibration, t_impact_ns, 1, &mut rng);
        let mut track = Track::new(calibration, TrackLimits::default());
        let mut detector = ImpactDetector::new(DetectorConfig::default());
        let mut detections = None;
        for s in &sampled.samples {
            if let Ok(crate::kinematics::track::Accepted::Pose { .. }) = track.push(s) {
                if let Some(d) = detector.on_pose(&track, &config.club, &config.estimators) {
                    detections = Some(d);
                    break;
                }
            }
        }
        let truth = DeliveryMetrics::from_state(&swing.truth, &config.club);
        let ball = DetectorConfig::default();
        let truth_arc = swing.swing_arc_truth(&ball.ball_position_m, ball.ball_radius_m);
        let truth_launch = launch(config.launch_model.as_ref(), &swing.truth, &eq);
        for (i, _) in config.estimators.iter().enumerate() {
            let reason = match detections.as_ref().map(|d| &d[i].result) {
                None => Some("not_detected".to_string()),
                Some(Err(e)) => Some(e.key().to_string()),
                Some(Ok(est)) => {
                    let m = DeliveryMetrics::from_state(&est.state, &config.club);
                    let reveal_t_ns = detections.as_ref().map_or(0, |d| d[i].reveal_t_ns);
                    let arc = crate::kinematics::club_data::swing_arc(
                        detector.pre_impact(),
                        reveal_t_ns,
                        est.t_from_reveal_s,
                        est.arc.as_ref(),
                        &config.club.face.center_m,
                        &ball.ball_position_m,
                        ball.ball_radius_m,
                    );
                    if let (Some(a), Some(t)) = (arc, truth_arc) {
                        club_accs[i].add(&[
                            a.swing_direction_deg - t.swing_direction_deg,
                            a.swing_plane_deg - t.swing_plane_deg,
                            a.low_point_distance_mm - t.low_point_distance_mm,
                            a.low_point_height_mm - t.low_point_height_mm,
                            m.dynamic_lie_deg - truth.dynamic_lie_deg,
                            m.closure_rate_degps - truth.closure_rate_degps,
                            m.face_to_path_deg - truth.face_to_path_deg,
                        ]);
                    }
                    match (launch(config.launch_model.as_ref(), &est.state, &eq), truth_launch) {
                        (Some(l), Some(t)) => {
                            let scene = crate::kinematics::Scene {
                                face: &config.club.face,
                                ball_position_m: ball.ball_position_m,
                                ball_radius_m: ball.ball_radius_m,
                                max_extrapolation_s: ball.max_extrapolation_s,
                            };
                            let t_err_us = (est.t_impact_ns as Real - t_impact_ns as Real) * 1e-3;
                            add_coverage(&mut coverage[i], config, &eq, est, &scene, (&m, &truth), (&l, &t), t_err_us);
                            accs[i].add(&[
                                100.0 * (m.club_speed_mps - truth.club_speed_mps) / truth.club_speed_mps,
                                m.attack_angle_deg - truth.attack_angle_deg,
                                m.club_path_deg - truth.club_path_deg,
                                m.face_angle_deg - truth.face_angle_deg,
                                m.dynamic_loft_deg - truth.dynamic_loft_deg,
                                m.impact_h_mm - truth.impact_h_mm,
                                m.impact_v_mm - truth.impact_v_mm,
                                (est.t_impact_ns as Real - t_impact_ns as Real) * 1e-3,
                                l.ball_speed_mph - t.ball_speed_mph,
                                l.launch_angle_deg - t.launch_angle_deg,
                                l.launch_direction_deg - t.launch_direction_deg,
                                l.backspin_rpm - t.backspin_rpm,
                                l.sidespin_rpm - t.sidespin_rpm,
                            ]);
                            None
                        }
                        _ => Some("model_refused".to_string()),
                    }
                }
            };
            if let Some(r) = reason {
                *refused[i].entry(r).or_default() += 1;
            }
        }
        progress(shot + 1);
    }
    EvalReport {
        club: config.club.name.clone(),
        rate_hz: config.rate_hz,
        shots: config.shots,
        noise_mm: config.noise_mm,
        noise_deg: config.noise_deg,
        seed: config.seed,
        path: config.path,
        estimators: config
            .estimators
            .iter()
            .zip(accs.iter().zip(refused).zip(&club_accs))
            .map(|(spec, ((acc, refused), club_acc))| EstimatorReport {
                name: spec.name.clone(),
                shots: acc.n,
                refused,
                errors: acc.errors(),
                club_data: club_acc.club_data(),
                coverage: Vec::new(),
                without_uncertainty: 0,
            })
            .zip(&coverage)
            .map(|(report, c)| EstimatorReport {
                coverage: if c.shots() > 0 { c.report() } else { Vec::new() },
                without_uncertainty: c.without,
                ..report
            })
            .collect(),
    }
}
