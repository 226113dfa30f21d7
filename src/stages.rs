//! The timed stages of `impactd bench` and the criterion benches: fixed workloads, one per model and club, so
//! both report the same thing.

use std::time::Instant;

use std::sync::Arc;

use crate::equipment::{ClubSpec, LoadedClub, ModelSections};
use crate::impact::registry::{self, BuildOptions};
use crate::impact::{Delivery, Equipment, ImpactModel, ImpactState};
use crate::kinematics::arc::ArcFit;
use crate::kinematics::estimate::estimate;
use crate::kinematics::{Calibration, ClubPose, EstimatorSpec, Scene, Track, TrackLimits};
use crate::math::Vector3;
use crate::offline::swing::{sample, Sampling, Swing, SwingSpec};
use crate::rng::Rng;

/// One named workload: `run(i)` does one operation on the `i`-th input (cycled) and returns a value to keep the
/// optimiser honest.
pub struct Stage {
    pub name: String,
    pub run: Box<dyn FnMut(usize) -> f64>,
}

/// A fixed spread of 64 golfers' deliveries for `club` (seeded, the same on every machine; the club's
/// [`GolferProfile`](crate::offline::swing::GolferProfile) with the swing's closure rate).
pub fn delivery_spread(club: &ClubSpec) -> Vec<Delivery> {
    let eq = Equipment::new(club.clone());
    let mut rng = Rng::new(0x1F2E_3D4C);
    (0..64).filter_map(|_| Swing::new(&SwingSpec::golfer(club, &mut rng), &eq).ok().map(|s| s.delivery)).collect()
}

/// Impact states for the spread.
pub fn state_spread(equipment: &Equipment) -> Vec<ImpactState> {
    delivery_spread(&equipment.club).iter().filter_map(|d| d.to_state(equipment).ok()).collect()
}

/// One prediction of `model` per operation on the club's spread of impact states.
/// `None` when the model does not apply to the club (its first prediction fails: the ground model on a driver's
/// curved face), so no stage times an error.
fn model_stage(name: String, model: Arc<dyn ImpactModel>, club: ClubSpec) -> Option<Stage> {
    let eq = Equipment::new(club);
    let states = state_spread(&eq);
    model.predict(states.first()?, &eq).ok()?;
    Some(Stage {
        name,
        run: Box::new(move |i| {
            let s = &states[i % states.len()];
            model.predict(s, &eq).map(|l| l.ball_velocity_mps.x).unwrap_or(0.0)
        }),
    })
}

/// Every registered model on both presets: `<model name>/<club>` (`adjusted/driver`,
/// `continuous/iron7`, ...), one prediction per operation.
pub fn model_stages() -> Vec<Stage> {
    let mut stages = Vec::new();
    for entry in registry::MODELS {
        for club in [ClubSpec::driver(), ClubSpec::iron7()] {
            let loaded = LoadedClub { club, sections: ModelSections::default() };
            if let Ok(model) = registry::build_one(entry.name, &loaded, &BuildOptions::default()) {
                let name = format!("{}/{}", model.name(), loaded.club.name);
                stages.extend(model_stage(name, model, loaded.club));
            }
        }
    }
    stages
}

/// The iron-plus-ground model on firm soil, a fat strike (15 mm up the face: the sole meets the ground 2.9 ms
/// before the ball): `ground/firm/iron7_fat`, one prediction (to the ball's release) per operation.
pub fn ground_stages() -> Vec<Stage> {
    use crate::equipment::soil::SoilSpec;
    use crate::impact::continuous::iron_ground::GroundModel;
    let eq = Equipment::new(ClubSpec::iron7());
    let plane = 60f64.to_radians();
    let fat = Delivery {
        club_speed_mps: 90.0 * crate::units::MPS_PER_MPH,
        attack_angle_rad: (-4.3f64).to_radians(),
        club_path_rad: 0.0,
        face_angle_rad: 0.0,
        dynamic_loft_rad: 25f64.to_radians(),
        impact_h_m: 0.0,
        impact_v_m: 0.015,
        club_angular_velocity_radps: 27.0 * Vector3::new(0.0, plane.cos(), plane.sin()),
    };
    let (Ok(model), Ok(state)) = (GroundModel::new(SoilSpec::firm()).prepare(&eq), fat.to_state(&eq)) else {
        return Vec::new();
    };
    vec![Stage {
        name: "ground/firm/iron7_fat".into(),
        run: Box::new(move |_| model.predict(&state, &eq).map(|l| l.ball_velocity_mps.x).unwrap_or(0.0)),
    }]
}

/// Pre-impact frames of 32 noisy synthetic swings at 720 Hz (0.2 mm, 0.1 deg), with their revealing times.
pub fn pre_impact_spread(club: &ClubSpec) -> Vec<(Vec<ClubPose>, u64)> {
    let eq = Equipment::new(club.clone());
    let mut rng = Rng::new(0x5EED);
    let sampling =
        Sampling { position_noise_m: 0.2e-3, orientation_noise_rad: 0.1f64.to_radians(), ..Default::default() };
    let calibration = Calibration::default();
    let mut out = Vec::new();
    while out.len() < 32 {
        let spec = SwingSpec::golfer(club, &mut rng);
        let Ok(swing) = Swing::new(&spec, &eq) else {
            continue;
        };
        let sampled = sample(&swing, &sampling, &calibration, 1_000_000_000, 1, &mut rng);
        let mut track = Track::new(calibration, TrackLimits::default());
        for s in &sampled.samples {
            let _ = track.push(s);
            if s.t_ns > sampled.t_impact_ns {
                let poses: Vec<ClubPose> = track.poses().iter().filter(|p| p.t_ns < s.t_ns).copied().collect();
                out.push((poses, s.t_ns));
                break;
            }
        }
    }
    out
}

/// The extrapolation stages: `extrapolate/<estimator>/<club>`, one impact-state estimate (fit, contact solve,
/// state) per operation.
pub fn extrapolation_stages() -> Vec<Stage> {
    let mut out = Vec::new();
    for spec in [EstimatorSpec::linear2(), EstimatorSpec::poly(), EstimatorSpec::arc()] {
        for club in [ClubSpec::driver(), ClubSpec::iron7()] {
            let name = format!("extrapolate/{}/{}", spec.name, club.name);
            let shots = pre_impact_spread(&club);
            let spec = spec.clone();
            out.push(Stage {
                name,
                run: Box::new(move |i| {
                    let (poses, reveal) = &shots[i % shots.len()];
                    let scene = Scene {
                        face: &club.face,
                        ball_position_m: Vector3::zeros(),
                        ball_radius_m: crate::equipment::BallSpec::SEED.radius_m,
                        max_extrapolation_s: 0.01,
                    };
                    estimate(&spec, poses, *reveal, &scene).map(|e| e.state.cg_velocity_mps.x).unwrap_or(0.0)
                }),
            });
        }
    }
    out
}

/// How sure a shot is, once per impact: `uncertainty/<club>`, the delivery's covariance from the `arc` estimate's
/// fits (`kinematics::uncertainty`) and the launch's through the adjusted model's Jacobian
/// (`impact::uncertainty`), on the extrapolation stages' shots: what a launch's uncertainty adds to the live path.
pub fn uncertainty_stages() -> Vec<Stage> {
    use crate::impact::uncertainty::LaunchJacobian;
    use crate::impact::{DeliveryMetrics, ImpulseModel, ImpulseVariant};
    use crate::kinematics::uncertainty::{estimate_uncertainty, CalibrationSigma};
    let mut out = Vec::new();
    for club in [ClubSpec::driver(), ClubSpec::iron7()] {
        let (ball, radius) = (Vector3::zeros(), crate::equipment::BallSpec::SEED.radius_m);
        let scene = Scene { face: &club.face, ball_position_m: ball, ball_radius_m: radius, max_extrapolation_s: 0.01 };
        let estimates: Vec<_> = pre_impact_spread(&club)
            .into_iter()
            .filter_map(|(poses, reveal)| estimate(&EstimatorSpec::arc(), &poses, reveal, &scene).ok())
            .collect();
        let (equipment, model) = (Equipment::new(club.clone()), ImpulseModel::new(ImpulseVariant::Adjusted));
        let name = format!("uncertainty/{}", club.name);
        out.push(Stage {
            name,
            run: Box::new(move |i| {
                let e = &estimates[i % estimates.len()];
                let scene =
                    Scene { face: &club.face, ball_position_m: ball, ball_radius_m: radius, max_extrapolation_s: 0.01 };
                let Some(u) = estimate_uncertainty(e, &scene, &club, &CalibrationSigma::default()) else { return 0.0 };
                let d = DeliveryMetrics::from_state(&e.state, &club);
                LaunchJacobian::of(&model, &equipment, &d.to_delivery(), d.dynamic_lie_deg.to_radians())
                    .map_or(0.0, |j| j.uncertainty(&u.delivery).ball_speed_mph)
            }),
        });
    }
    out
}

/// TrackMan's club data of the path, once per impact: `club_data/<club>`, one swing arc (the plane and low point
/// of the `arc` estimate's arc, or of a fit of its own where the estimate has none) per operation on the
/// extrapolation stages' shots.
pub fn club_data_stages() -> Vec<Stage> {
    let mut out = Vec::new();
    for club in [ClubSpec::driver(), ClubSpec::iron7()] {
        let (ball, radius) = (Vector3::zeros(), crate::equipment::BallSpec::SEED.radius_m);
        let scene = Scene { face: &club.face, ball_position_m: ball, ball_radius_m: radius, max_extrapolation_s: 0.01 };
        let shots: Vec<(Vec<ClubPose>, u64, f64, Option<ArcFit>)> = pre_impact_spread(&club)
            .into_iter()
            .filter_map(|(poses, reveal)| {
                let e = estimate(&EstimatorSpec::arc(), &poses, reveal, &scene).ok()?;
                Some((poses, reveal, e.t_from_reveal_s, e.arc))
            })
            .collect();
        let centre = club.face.center_m;
        out.push(Stage {
            name: format!("club_data/{}", club.name),
            run: Box::new(move |i| {
                let (poses, reveal, t, arc) = &shots[i % shots.len()];
                crate::kinematics::club_data::swing_arc(poses, *reveal, *t, arc.as_ref(), &centre, &ball, radius)
                    .map_or(0.0, |a| a.swing_plane_deg)
            }),
        });
    }
    out
}

/// Twenty golfers' swings for `club`, sampled as a rig would (0.2 mm, 0.1 deg noise), one after another.
fn swing_samples(club: &ClubSpec) -> Vec<crate::kinematics::ClubheadSample> {
    let eq = Equipment::new(club.clone());
    let mut rng = Rng::new(0xFEED);
    let sampling =
        Sampling { position_noise_m: 0.2e-3, orientation_noise_rad: 0.1f64.to_radians(), ..Default::default() };
    let mut samples = Vec::new();
    let mut frame = 1;
    for k in 0..20u64 {
        let spec = SwingSpec::golfer(club, &mut rng);
        let Ok(swing) = Swing::new(&spec, &eq) else {
            continue;
        };
        let s = sample(&swing, &sampling, &Calibration::default(), 1_000_000_000 * (k + 1), frame, &mut rng);
        frame = s.next_frame;
        samples.extend(s.samples);
    }
    samples
}

/// The pipeline over recorded-like samples: `pipeline/sample/<club>`, one sample (track, detection, and at
/// each impact the estimate and the prediction) per operation. Its inverse is the replay rate. And
/// `pipeline/shot/<club>`: the frame that reveals an impact (the estimate, its uncertainty, the club data, the
/// model, the launch's uncertainty and the flight with the recording's line), the compute on a live shot's
/// latency path; each operation also copies the pipeline's state from just before that frame.
pub fn pipeline_stages() -> Vec<Stage> {
    let mut out = Vec::new();
    for club in [ClubSpec::driver(), ClubSpec::iron7()] {
        let samples = swing_samples(&club);
        let mut setup = crate::pipeline::RigSetup::new("bench", club.clone());
        let mut pipeline = crate::pipeline::Pipeline::new(setup.clone());
        let mut events = Vec::with_capacity(8);
        let mut next = 0usize;
        // The shots: the pipeline just before each revealing frame, with that frame.
        setup.flight_line_step_s = 0.05;
        let mut before = crate::pipeline::Pipeline::new(setup.clone());
        let mut shots = Vec::new();
        for s in &samples {
            let state = before.clone();
            events.clear();
            before.on_sample(s, &mut events);
            if events.iter().any(|e| matches!(e, crate::pipeline::Event::Launch(_))) {
                shots.push((state, *s));
            }
        }
        let sample_setup = crate::pipeline::RigSetup::new("bench", club.clone());
        out.push(Stage {
            name: format!("pipeline/sample/{}", club.name),
            run: Box::new(move |_| {
                if next == samples.len() {
                    next = 0;
                    pipeline = crate::pipeline::Pipeline::new(sample_setup.clone());
                }
                events.clear();
                pipeline.on_sample(&samples[next], &mut events);
                next += 1;
                events.len() as f64
            }),
        });
        if shots.is_empty() {
            continue;
        }
        let mut shot_events = Vec::with_capacity(8);
        out.push(Stage {
            name: format!("pipeline/shot/{}", club.name),
            run: Box::new(move |i| {
                let (state, sample) = &shots[i % shots.len()];
                let mut p = state.clone();
                shot_events.clear();
                p.on_sample(sample, &mut shot_events);
                shot_events.len() as f64
            }),
        });
    }
    out
}

/// One ball flight with its bounce and roll per operation: `flight/trajectory`, over the TrackMan table's launches.
pub fn flight_stages() -> Vec<Stage> {
    let rows = crate::flight::fit::parse_table(crate::flight::fit::TRACKMAN_CSV).unwrap_or_default();
    let launches: Vec<crate::flight::LaunchState> = rows
        .iter()
        .map(|r| {
            crate::flight::LaunchState::from_metrics(
                crate::units::mph_to_mps(r.ball_speed_mph),
                r.launch_angle_deg,
                1.0,
                r.spin_rpm,
                300.0,
            )
        })
        .collect();
    let flight = crate::flight::Flight::default();
    vec![Stage {
        name: "flight/trajectory".into(),
        run: Box::new(move |i| flight.fly(&launches[i % launches.len()], 0.0).carry_m),
    }]
}

/// Every stage `impactd bench` times.
pub fn all_stages() -> Vec<Stage> {
    let mut stages = model_stages();
    stages.extend(ground_stages());
    stages.extend(extrapolation_stages());
    stages.extend(club_data_stages());
    stages.extend(uncertainty_stages());
    stages.extend(flight_stages());
    stages.extend(pipeline_stages());
    stages
}

/// Median nanoseconds per operation over `batches` batches lasting about `batch_ms` each.
pub fn time_stage(stage: &mut Stage, batches: usize, batch_ms: u64) -> f64 {
    // Calibrate the batch size.
    let mut n = 1usize;
    let mut sink = 0.0;
    loop {
        let t = Instant::now();
        for i in 0..n {
            sink += (stage.run)(i);
        }
        if t.elapsed().as_millis() as u64 >= batch_ms / 4 || n > 1 << 30 {
            break;
        }
        n *= 2;
    }
    let n = n * 4;
    let mut per_op: Vec<f64> = (0..batches)
        .map(|_| {
            let t = Instant::now();
            for i in 0..n {
                sink += (stage.run)(i);
            }
            t.elapsed().as_nanos() as f64 / n as f64
        })
        .collect();
    std::hint::black_box(sink);
    per_op.sort_by(f64::total_cmp);
    per_op[per_op.len() / 2]
}
