//! `impactd sim`: a synthetic rig publishing clubhead samples at real rate, with a seeded spread of swings, and
//! the truth of each shot on `sim/<rig>/truth` (its launch by the default model, `slip`, with the club file's numbers).
//!
//! Each shot occupies `interval_s`: the club waits at the top of its arc, swings through the ball at the shot's
//! impact instant, and holds its follow-through; frames keep coming at the rig's rate throughout, with a random
//! phase of the frame clock against each impact.

use std::future::Future;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;

use zenoh::Wait;

use crate::daemon::{clock::Clock, DaemonError};
use crate::equipment::ClubSpec;
use crate::impact::impulse::ImpulseTuning;
use crate::impact::{DeliveryMetrics, Equipment, ImpactModel, ImpulseModel, ImpulseVariant};
use crate::kinematics::{so3, Calibration, ClubPose, ClubheadSample};
use crate::math::Vector3;
use crate::offline::swing::{Swing, SwingSpec};
use crate::rng::Rng;
use crate::wire::{self, keys, ClubheadSampleMsg, PredictOutput, TruthMessage};

/// How the synthetic rig behaves.
#[derive(Debug, Clone)]
pub struct SimOptions {
    pub rigs: Vec<String>,
    pub club: ClubSpec,
    /// The impulse models' parameters the truth is predicted with: the club file's (`ImpulseTuning::from_sections`)
    /// as the daemon's rig reads them; `None`, the seed's for the club.
    pub tuning: Option<ImpulseTuning>,
    /// Shots per rig (0: until stopped).
    pub shots: u64,
    pub rate_hz: f64,
    /// Time between shots (s).
    pub interval_s: f64,
    pub seed: u64,
    pub noise_mm: f64,
    pub noise_deg: f64,
    /// Wait this long for a subscriber before publishing (s); 0 publishes at once.
    pub wait_for_subscriber_s: f64,
    /// The tracked body each sample names (`body`), as a rig with several clubs (`[rig.clubs]`) sees them.
    pub body: Option<String>,
    /// How long each rig keeps its publishers after its last put (s; [`PUBLISHER_DRAIN_S`]).
    pub publisher_drain_s: f64,
    /// The clock the samples are stamped and paced by (the system's unless a test drives one).
    pub clock: Clock,
}

impl Default for SimOptions {
    fn default() -> Self {
        SimOptions {
            rigs: vec!["rig1".into()],
            club: ClubSpec::driver(),
            tuning: None,
            shots: 5,
            rate_hz: 720.0,
            interval_s: 1.5,
            seed: 1,
            noise_mm: 0.2,
            noise_deg: 0.1,
            wait_for_subscriber_s: 10.0,
            body: None,
            publisher_drain_s: PUBLISHER_DRAIN_S,
            clock: Clock::system(),
        }
    }
}

/// The most shots per rig a run may ask for (about 17 days at the default interval).
pub const MAX_SHOTS: u64 = 1_000_000;

impl SimOptions {
    /// Refuses what would panic, never end or overflow the clock: a rate, interval or noise that is not a
    /// finite number in its range, no rig, or more shots than [`MAX_SHOTS`].
    pub fn check(&self) -> Result<(), SimOptionError> {
        let bad = |option, reason| Err(SimOptionError { option, reason });
        if self.rigs.is_empty() {
            return bad("--rigs", "must name at least one rig");
        }
        if !(60.0..=10_000.0).contains(&self.rate_hz) {
            return bad("--rate", "must be within 60 and 10000 Hz");
        }
        if !(0.2..=3600.0).contains(&self.interval_s) {
            return bad("--interval", "must be within 0.2 and 3600 s");
        }
        if self.shots > MAX_SHOTS {
            return bad("--shots", "must be at most 1000000");
        }
        if !(0.0..=1e3).contains(&self.noise_mm) || !(0.0..=1e3).contains(&self.noise_deg) {
            return bad("--noise-mm/--noise-deg", "must be within 0 and 1000");
        }
        if !(0.0..=10.0).contains(&self.publisher_drain_s) {
            return bad("publisher_drain_s", "must be within 0 and 10 s");
        }
        if !(0.0..=3600.0).contains(&self.wait_for_subscriber_s) {
            return bad("wait_for_subscriber_s", "must be within 0 and 3600 s");
        }
        Ok(())
    }
}

/// A synthetic rig's option the sim refuses ([`SimOptions::check`]): which (its flag's name), and why.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{option} {reason}")]
pub struct SimOptionError {
    pub option: &'static str,
    pub reason: &'static str,
}

/// What the rig sent.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct SimSummary {
    pub samples: u64,
    pub shots: u64,
}

/// How long a rig keeps its publishers after its last put. zenoh 1.10 sends an undeclaration on its control lane,
/// which can overtake data still queued on the data lane: a receiver tearing its subscriber down then logs
/// `Received Data for unknown key_expr` per late sample (loopback, 3,000 puts: 1 line in 10 rounds to 139 in 30;
/// held 200-250 ms first: none; `tests/sim_drain.rs`, which also runs this rig into a receiver that closes at once).
pub const PUBLISHER_DRAIN_S: f64 = 0.25;

/// The swing follows its arc from this long before impact (s); earlier the club waits at the top. It spans the
/// longest estimator window (the arc's 60 ms, counted from the newest frame before contact) with room to spare.
const BEFORE_S: f64 = 0.07;
const AFTER_S: f64 = 0.03;

/// The truth's model: the default (`registry::DEFAULT_MODEL`, a test holds them together).
const TRUTH: ImpulseVariant = ImpulseVariant::Slip;

/// A publisher of `kind` on `key` whose puts wait in a busy queue instead of being dropped unseen (zenoh's
/// default): the rig is scored against its truth, so every sample and truth must arrive.
async fn blocking_publisher(
    session: &zenoh::Session,
    key: String,
    kind: wire::MessageType,
) -> Result<zenoh::pubsub::Publisher<'static>, DaemonError> {
    session
        .declare_publisher(key)
        .encoding(kind.encoding())
        .congestion_control(zenoh::qos::CongestionControl::Block)
        .await
        .map_err(DaemonError::zenoh)
}

/// One synthetic rig: samples at any frame, deterministic for a seed.
pub struct SimRig {
    pub name: String,
    club: ClubSpec,
    equipment: Equipment,
    /// What predicts each shot's truth: the default model (`registry::DEFAULT_MODEL`).
    truth_model: ImpulseModel,
    rng: Rng,
    period_ns: f64,
    interval_ns: u64,
    start_ns: u64,
    /// The next frame's number and index from the start.
    pub frame: u64,
    shots: u64,
    noise_m: f64,
    noise_rad: f64,
    /// The shot being swung and the next one (none before the first frame).
    swings: Option<ShotPair>,
    truth_sent: u64,
}

/// A shot of the synthetic rig: its index from the start, its swing and its impact time.
struct Shot {
    k: u64,
    swing: Swing,
    t_impact_ns: u64,
}

/// The shot being swung and the next: after its follow-through the club glides to the next one's top.
struct ShotPair {
    current: Shot,
    next: Shot,
}

impl SimRig {
    pub fn new(name: &str, options: &SimOptions, start_ns: u64, seed: u64) -> Self {
        SimRig {
            name: name.to_string(),
            club: options.club.clone(),
            equipment: Equipment::new(options.club.clone()),
            truth_model: options.tuning.map_or(ImpulseModel::new(TRUTH), |t| ImpulseModel::new(TRUTH).with_tuning(t)),
            rng: Rng::new(seed),
            period_ns: 1e9 / options.rate_hz,
            interval_ns: (options.interval_s * 1e9) as u64,
            start_ns,
            frame: 0,
            shots: options.shots,
            noise_m: options.noise_mm * 1e-3,
            noise_rad: options.noise_deg.to_radians(),
            swings: None,
            truth_sent: 0,
        }
    }

    /// Shot `k`: a golfer's swing for the club, struck at the face centre when the drawn strike cannot be swung
    /// (off this club's face); an error when even that cannot.
    fn make_shot(&mut self, k: u64) -> Result<Shot, DaemonError> {
        let spec = SwingSpec::golfer(&self.club, &mut self.rng);
        let swing = match Swing::new(&spec, &self.equipment) {
            Ok(swing) => swing,
            Err(_) => {
                let mut s = spec;
                s.delivery = crate::impact::Delivery { impact_h_m: 0.0, impact_v_m: 0.0, ..spec.delivery };
                Swing::new(&s, &self.equipment).map_err(|source| DaemonError::SimSwing {
                    rig: self.name.clone(),
                    shot: k + 1,
                    source,
                })?
            }
        };
        // Impact in the middle of the shot's span, at a random phase against the frame clock.
        let t_impact_ns =
            self.start_ns + k * self.interval_ns + self.interval_ns / 2 + (self.rng.unit() * self.period_ns) as u64;
        Ok(Shot { k, swing, t_impact_ns })
    }

    /// Capture time of the next frame (ns).
    pub fn next_t_ns(&self) -> u64 {
        self.start_ns + (self.frame as f64 * self.period_ns).round() as u64
    }

    /// Whether every shot has been swung and followed through.
    pub fn done(&self) -> bool {
        self.shots > 0 && self.next_t_ns() > self.start_ns + self.shots * self.interval_ns
    }

    /// The next frame, and the truth of a shot whose impact it has just passed; an error when a shot cannot be
    /// swung with this club ([`DaemonError::SimSwing`]).
    pub fn next_sample(&mut self) -> Result<(ClubheadSample, Option<TruthMessage>), DaemonError> {
        let t_ns = self.next_t_ns();
        let k = (t_ns - self.start_ns) / self.interval_ns;
        let swings = match self.swings.take() {
            Some(pair) if pair.current.k == k => pair,
            Some(ShotPair { next, .. }) if next.k == k => ShotPair { current: next, next: self.make_shot(k + 1)? },
            _ => {
                let current = self.make_shot(k)?;
                ShotPair { current, next: self.make_shot(k + 1)? }
            }
        };
        let next = self.sample_at(t_ns, &swings);
        self.swings = Some(swings);
        Ok(next)
    }

    /// The frame at `t_ns` of the shots in `swings`, and the truth of the current one once its impact is passed.
    fn sample_at(&mut self, t_ns: u64, swings: &ShotPair) -> (ClubheadSample, Option<TruthMessage>) {
        let (k, swing, t_impact) = (swings.current.k, &swings.current.swing, swings.current.t_impact_ns);
        let tau = (t_ns as i64 - t_impact as i64) as f64 * 1e-9;
        let mut pose = if tau > AFTER_S {
            // Glide back from the follow-through to the next swing's top, where the club waits until its span begins.
            let next_swing = &swings.next.swing;
            let from = swing.pose(AFTER_S);
            let to = next_swing.pose(-BEFORE_S);
            let t0 = t_impact as f64 * 1e-9 + AFTER_S;
            let t1 = (self.start_ns + (k + 1) * self.interval_ns) as f64 * 1e-9;
            let x = ((t_ns as f64 * 1e-9 - t0) / (t1 - t0)).clamp(0.0, 1.0);
            let x = x * x * (3.0 - 2.0 * x);
            crate::math::Isometry3::from_parts(
                (from.translation.vector.lerp(&to.translation.vector, x)).into(),
                from.rotation.slerp(&to.rotation, x),
            )
        } else {
            swing.pose(tau.max(-BEFORE_S))
        };
        let n = |rng: &mut Rng| Vector3::new(rng.normal(), rng.normal(), rng.normal());
        pose.translation.vector += n(&mut self.rng) * self.noise_m;
        pose.rotation = so3::exp(&(n(&mut self.rng) * self.noise_rad)) * pose.rotation;
        let sample = ClubPose { frame: self.frame + 1, t_ns, world_from_club: pose }.to_sample(&Calibration::default());
        self.frame += 1;
        let truth = if t_ns > t_impact && self.truth_sent <= k && (self.shots == 0 || k < self.shots) {
            self.truth_sent = k + 1;
            let mut delivery = DeliveryMetrics::from_state(&swing.truth, &self.club);
            delivery.swing_arc = swing.swing_arc_truth(&Vector3::zeros(), self.equipment.ball.radius_m);
            self.truth_model.predict(&swing.truth, &self.equipment).ok().map(|l| TruthMessage {
                rig: self.name.clone(),
                shot: k + 1,
                t_impact_ns: t_impact,
                club: self.club.name.clone(),
                delivery,
                launch: PredictOutput::new(&l, &delivery, Default::default(), &self.equipment),
            })
        } else {
            None
        };
        (sample, truth)
    }
}

/// Publishes synthetic rigs on `session` at real rate until every shot is done or `shutdown` completes.
pub async fn run_sim(
    session: &zenoh::Session,
    options: SimOptions,
    shutdown: impl Future<Output = ()>,
) -> Result<SimSummary, DaemonError> {
    options.check()?;
    let stop = Arc::new(AtomicBool::new(false));
    let start_ns = options.clock.wall_ns() + 200_000_000;
    let mut threads = Vec::new();
    for (i, name) in options.rigs.iter().enumerate() {
        if !keys::valid_rig_name(name) {
            return Err(DaemonError::BadRigName(name.clone()));
        }
        let samples = blocking_publisher(session, keys::clubhead(name), wire::MessageType::ClubheadSample).await?;
        let truth_pub = blocking_publisher(session, keys::truth(name), wire::MessageType::TruthMessage).await?;
        if options.wait_for_subscriber_s > 0.0 {
            let deadline = std::time::Instant::now() + Duration::from_secs_f64(options.wait_for_subscriber_s);
            while !samples.matching_status().await.map(|m| m.matching()).unwrap_or(false) {
                if std::time::Instant::now() > deadline {
                    tracing::warn!(
                        "rig {name}: no subscriber after {} s; publishing anyway",
                        options.wait_for_subscriber_s
                    );
                    break;
                }
                tokio::time::sleep(Duration::from_millis(20)).await;
            }
        }
        let mut rig =
            SimRig::new(name, &options, start_ns + i as u64 * 37_000_000, options.seed.wrapping_add(i as u64 * 7919));
        let (stop, body, clock) = (stop.clone(), options.body.clone(), options.clock.clone());
        let drain = Duration::from_secs_f64(options.publisher_drain_s);
        threads.push(tokio::task::spawn_blocking(move || {
            let mut summary = SimSummary::default();
            let mut failed = None;
            while !stop.load(Ordering::Relaxed) && !rig.done() {
                let due = rig.next_t_ns();
                let now = clock.wall_ns();
                if due > now {
                    std::thread::sleep(Duration::from_nanos(due - now));
                }
                let (sample, truth) = match rig.next_sample() {
                    Ok(next) => next,
                    Err(e) => {
                        // The run has failed: the other rigs stop too.
                        stop.store(true, Ordering::Relaxed);
                        failed = Some(e);
                        break;
                    }
                };
                let mut msg = ClubheadSampleMsg::from_sample(&rig.name, &sample);
                msg.body = body.clone();
                if let Err(e) = samples.put(serde_json::to_vec(&msg).unwrap_or_default()).wait() {
                    tracing::warn!("rig {}: publishing a sample: {e}", rig.name);
                }
                summary.samples += 1;
                if let Some(t) = truth {
                    summary.shots += 1;
                    let _ = truth_put(&truth_pub, &t);
                }
            }
            if summary.samples > 0 {
                std::thread::sleep(drain);
            }
            drop((samples, truth_pub));
            failed.map_or(Ok(summary), Err)
        }));
    }
    let joined = async {
        let mut total = SimSummary::default();
        let mut failed = None;
        for t in threads {
            match t.await {
                Ok(Ok(s)) => {
                    total.samples += s.samples;
                    total.shots += s.shots;
                }
                Ok(Err(e)) => {
                    failed.get_or_insert(e);
                }
                Err(e) => {
                    failed.get_or_insert(DaemonError::Task(e));
                }
            }
        }
        failed.map_or(Ok(total), Err)
    };
    tokio::pin!(joined);
    tokio::select! {
        total = &mut joined => total,
        _ = shutdown => {
            stop.store(true, Ordering::Relaxed);
            joined.await
        }
    }
}

fn truth_put(publisher: &zenoh::pubsub::Publisher<'static>, t: &TruthMessage) -> Result<(), DaemonError> {
    publisher.put(serde_json::to_vec(t).unwrap_or_default()).wait().map_err(DaemonError::zenoh)
}

#[cfg(test)]
mod tests;
