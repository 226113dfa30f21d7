//! Off-centre strikes in the continuous two-layer model (seed section 3.2.1): why its driver shows almost no gear
//! effect with Table 3.5's ball, and why its 7-iron's best strike is below the face centre.
//!
//! The contact law is wrapped to record every force it gives (all four Runge-Kutta stages), so the impulses can
//! be summed with the integrator's own weights and compared with what the bodies carry away.

#![allow(clippy::unwrap_used)]

use impactd::equipment::ClubSpec;
use impactd::impact::continuous::ball::{BallPart, RigidBall, TwoLayerBall};
use impactd::impact::continuous::club::{ClubLoad, ClubPart, FreeHead, FreeHeadState, Head, SteppedClub};
use impactd::impact::continuous::ground::NoGround;
use impactd::impact::continuous::law::volumetric::Volumetric;
use impactd::impact::continuous::law::{Contact, ContactForce, ContactLaw};
use impactd::impact::continuous::stepping::StiffnessStep;
use impactd::impact::continuous::surface::{FaceSurface, Overlap};
use impactd::impact::continuous::{Assembly, Integration, Start, TwoLayerParams};
use impactd::impact::LaunchMetrics;
use impactd::impact::{Delivery, Equipment, ImpactModel, ImpactState, ImpulseModel, ImpulseVariant, Launch};
use impactd::math::{Real, Vector3};
use std::cell::{Cell, RefCell};

const STEP_S: Real = 0.6e-6;

/// Eq. 3.14-3.15, recording each contact and force it computes.
struct Recorded {
    law: Volumetric,
    log: RefCell<Vec<(Contact, ContactForce)>>,
}

impl ContactLaw for Recorded {
    type State = ();
    fn force(&self, c: &Contact, s: &()) -> ContactForce {
        let f = self.law.force(c, s);
        self.log.borrow_mut().push((*c, f));
        f
    }
    fn stored_energy_j(&self, surface: &FaceSurface, r: Real, o: &Overlap) -> Real {
        self.law.stored_energy_j(surface, r, o)
    }
}

/// The free head, remembering the last state it was asked about (the state at separation).
struct LastHead {
    head: FreeHead,
    last: Cell<Option<FreeHeadState>>,
}

impl ClubPart for LastHead {
    type State = FreeHeadState;
    type Rate = <FreeHead as ClubPart>::Rate;
    fn initial(&self, state: &ImpactState) -> FreeHeadState {
        self.head.initial(state)
    }
    fn head(&self, s: &FreeHeadState) -> Head {
        self.last.set(Some(*s));
        self.head.head(s)
    }
    fn rate(&self, s: &FreeHeadState, head: &Head, force_n: Vector3, torque_nm: Vector3) -> Self::Rate {
        ClubPart::rate(&self.head, s, head, force_n, torque_nm)
    }
    fn advance(s: &FreeHeadState, r: &Self::Rate, h: Real) -> FreeHeadState {
        FreeHead::advance(s, r, h)
    }
    fn advance_rk4(s: &FreeHeadState, k: [&Self::Rate; 4], h: Real) -> FreeHeadState {
        FreeHead::advance_rk4(s, k, h)
    }
    fn momentum(&self, s: &FreeHeadState) -> (Vector3, Vector3) {
        self.head.momentum(s)
    }
    fn energy_j(&self, s: &FreeHeadState) -> Real {
        self.head.energy_j(s)
    }
}

/// The same head on the assembly's stepping (classical Runge-Kutta's own stages).
impl SteppedClub for LastHead {
    type State = FreeHeadState;
    type Rate = <FreeHead as SteppedClub>::Rate;
    type Motion = Head;
    type Step = Real;
    type Half = ();
    fn step(&self, h_s: Real) -> Real {
        h_s
    }
    fn step_s(step: &Real) -> Real {
        *step
    }
    fn motion(&self, s: &FreeHeadState, t_s: Real) -> Head {
        self.head.motion(s, t_s)
    }
    fn head(m: &Head) -> Head {
        *m
    }
    fn rate(&self, s: &FreeHeadState, m: &Head, load: &ClubLoad) -> Self::Rate {
        SteppedClub::rate(&self.head, s, m, load)
    }
    fn free_half(&self, step: &Real, s: &FreeHeadState) {
        self.head.free_half(step, s)
    }
    fn half(&self, step: &Real, s: &FreeHeadState, free: &(), k: &Self::Rate) -> FreeHeadState {
        self.head.half(step, s, free, k)
    }
    fn fourth(
        &self,
        step: &Real,
        s: &FreeHeadState,
        s2: &FreeHeadState,
        k1: &Self::Rate,
        k3: &Self::Rate,
    ) -> FreeHeadState {
        self.head.fourth(step, s, s2, k1, k3)
    }
    fn finish(&self, step: &Real, s: &FreeHeadState, k: [&Self::Rate; 4]) -> FreeHeadState {
        self.head.finish(step, s, k)
    }
}

/// One run: the launch, every recorded (contact, force) and the head's first and last states.
struct Run {
    launch: Launch,
    contact_time_s: Real,
    log: Vec<(Contact, ContactForce)>,
    head0: FreeHeadState,
    head1: FreeHeadState,
}

impl Run {
    /// `sum_k w_k h f(contact_k, force_k)` over the steps with the Runge-Kutta weights (1, 2, 2, 1) / 6: the
    /// integral the integrator applies.
    fn integral(&self, f: impl Fn(&Contact, &ContactForce) -> Vector3) -> Vector3 {
        let w = [1.0, 2.0, 2.0, 1.0];
        self.log.iter().enumerate().map(|(i, (c, cf))| w[i % 4] / 6.0 * STEP_S * f(c, cf)).sum()
    }

    /// Sidespin (rpm, + fade) of the launch.
    fn sidespin_rpm(&self) -> Real {
        sidespin_rpm(&self.launch)
    }
}

fn sidespin_rpm(l: &Launch) -> Real {
    LaunchMetrics::from_ball(&l.ball_velocity_mps, &l.ball_spin_radps).sidespin_rpm
}

fn ball_speed_mps(l: &Launch) -> Real {
    l.ball_velocity_mps.norm()
}

fn state(eq: &Equipment, speed_mph: Real, loft_deg: Real, attack_deg: Real, h_mm: Real, v_mm: Real) -> ImpactState {
    Delivery {
        club_speed_mps: speed_mph * 0.44704,
        attack_angle_rad: attack_deg.to_radians(),
        club_path_rad: 0.0,
        face_angle_rad: 0.0,
        dynamic_loft_rad: loft_deg.to_radians(),
        impact_h_m: h_mm * 1e-3,
        impact_v_m: v_mm * 1e-3,
        club_angular_velocity_radps: Vector3::zeros(),
    }
    .to_state(eq)
    .unwrap()
}

/// The continuous model's assembly (as [`impactd::impact::ContinuousModel`] builds it) with any ball.
fn run<B: BallPart>(eq: &Equipment, st: &ImpactState, p: &TwoLayerParams, ball: B) -> Run {
    let club = &eq.club;
    let start = Start::new(st, eq).unwrap();
    let asm = Assembly {
        law: Recorded {
            law: Volumetric { k_v_n_per_m3: p.k_v_n_per_m3, d_s_per_m: p.d_s_per_m, mu: p.mu, v_tr_mps: p.v_tr_mps },
            log: RefCell::new(Vec::new()),
        },
        ball,
        club: LastHead { head: FreeHead::new(club), last: Cell::new(None) },
        ground: NoGround,
        surface: FaceSurface::of_club(club),
    };
    let integration = Integration { step_s: STEP_S, max_contact_s: 3e-3, trace_every: 0, model: "continuous" };
    let r = StiffnessStep::new(&asm.club, integration, None, start.slip0).run(&asm, st, start.ball_centre_m).unwrap();
    Run {
        launch: r.launch,
        contact_time_s: r.contact_time_s,
        log: asm.law.log.take(),
        head0: asm.club.head.initial(st),
        head1: asm.club.last.get().unwrap(),
    }
}

fn two_layer(eq: &Equipment, p: &TwoLayerParams) -> TwoLayerBall {
    TwoLayerBall::new(&eq.ball, p.cover_thickness_m, p.k_ball_nm_per_rad, p.c_ball_nms_per_rad)
}

/// The one-cycle ball of `clubs/driver-one-cycle.toml` and `clubs/iron7-one-cycle.toml`: Table 3.5 with the
/// core-cover spring 1000 N m/rad, 0.05 N m s/rad, and the iron's Hunt-Crossley damping 4.5 ms/m.
fn one_cycle(table: TwoLayerParams) -> TwoLayerParams {
    let d_s_per_m = if table == TwoLayerParams::IRON7 { 4.5e-3 } else { table.d_s_per_m };
    TwoLayerParams { k_ball_nm_per_rad: 1000.0, c_ball_nms_per_rad: 0.05, d_s_per_m, ..table }
}

/// The driver of the observation: 100 mph, 10.5 deg dynamic loft, level, square, on the face's centre line.
fn driver_state(eq: &Equipment, h_mm: Real) -> ImpactState {
    state(eq, 100.0, 10.5, 0.0, h_mm, 0.0)
}

/// Momentum bookkeeping on off-centre strikes (seed eq. 3.2-3.5 integrated over the contact): the head's angular
/// momentum about its CG changes by `∫ r_club × F_club dt` and the ball's about its centre by
/// `∫ r_ball × F_ball dt`, summed from the recorded forces with the integrator's weights (closed form: Euler's
/// law for each body; the only error is the Runge-Kutta truncation, far below 1e-6 at 0.6 us).
#[test]
fn angular_impulses_match_r_cross_f() {
    let driver = Equipment::new(ClubSpec::driver());
    let iron = Equipment::new(ClubSpec::iron7());
    let cases = [
        (&driver, TwoLayerParams::DRIVER, driver_state(&driver, 20.0)),
        (&driver, TwoLayerParams::DRIVER, driver_state(&driver, -20.0)),
        (&iron, TwoLayerParams::IRON7, state(&iron, 85.0, 32.0, -4.5, 17.0, -3.0)),
    ];
    for (eq, p, st) in cases {
        let r = run(eq, &st, &p, two_layer(eq, &p));
        let i = eq.club.inertia_kg_m2;
        let l_head = |s: &FreeHeadState| s.world_from_body.to_rotation_matrix() * (i * s.body_rate_radps);
        let head_change = l_head(&r.head1) - l_head(&r.head0);
        let head_impulse = r.integral(|c, f| c.r_club_m.cross(&-(f.normal_n * c.normal + f.friction_n)));
        assert!(
            (head_change - head_impulse).norm() <= 1e-6 * head_impulse.norm(),
            "{}: head dL {head_change:?} vs int r x F {head_impulse:?}",
            eq.club.name
        );
        let ball_change = eq.ball.inertia_kg_m2 * r.launch.ball_spin_radps;
        let ball_impulse = r.integral(|c, f| c.r_ball_m.cross(&(f.normal_n * c.normal + f.friction_n)));
        assert!(
            (ball_change - ball_impulse).norm() <= 1e-6 * ball_impulse.norm(),
            "{}: ball dL {ball_change:?} vs int r x F {ball_impulse:?}",
            eq.club.name
        );
        // And the head's yaw rate agrees with the standard impulse model's (eq. 3.3, the same r_c x P about a
        // fixed point) within 10 %: the lever arm, inertia and frames are the same in both models.
        let standard = ImpulseModel::new(ImpulseVariant::Standard).predict(&st, eq).unwrap();
        let (yaw, yaw_std) = (r.launch.club_angular_velocity_radps.y, standard.club_angular_velocity_radps.y);
        if eq.club.name == "driver" {
            assert!((yaw - yaw_std).abs() < 0.1 * yaw_std.abs(), "driver yaw {yaw} vs standard {yaw_std}");
        }
    }
}

/// Sidespin change (rpm) from the centre strike to `h_mm` toward the toe: negative is draw.
fn gear_rpm(f: &impl Fn(Real) -> Real, h_mm: Real) -> Real {
    f(h_mm) - f(0.0)
}

fn standard_sidespin(eq: &Equipment) -> impl Fn(Real) -> Real + '_ {
    move |h| sidespin_rpm(&ImpulseModel::new(ImpulseVariant::Standard).predict(&driver_state(eq, h), eq).unwrap())
}

/// Period (s) of the ball's core-cover mode: `2π / sqrt(k (1/I_core + 1/I_cover))`.
fn core_cover_period_s(b: &TwoLayerBall) -> Real {
    let k = b.k_ball_nm_per_rad * (1.0 / b.core_inertia_kg_m2 + 1.0 / b.cover_inertia_kg_m2);
    std::f64::consts::TAU / k.sqrt()
}

/// When the cover first rolls (slip under `v_tr / 4`, s), and the ball's spin about the vertical (rad/s, + draw)
/// from the friction before and after.
fn yaw_spin_by_phase(r: &Run, eq: &Equipment, v_tr_mps: Real) -> (Real, Real, Real) {
    let w = [1.0, 2.0, 2.0, 1.0];
    let rolling_at = r.log.iter().step_by(4).position(|(c, _)| c.slip_mps.norm() < v_tr_mps / 4.0).unwrap();
    let (mut sliding, mut rolling) = (0.0, 0.0);
    for (i, (c, f)) in r.log.iter().enumerate() {
        let spin = w[i % 4] / 6.0 * STEP_S * c.r_ball_m.cross(&f.friction_n).y / eq.ball.inertia_kg_m2;
        if i / 4 < rolling_at {
            sliding += spin
        } else {
            rolling += spin
        }
    }
    (rolling_at as Real * STEP_S, sliding, rolling)
}

/// With Table 3.5's ball the driver's continuous model has almost no gear effect, and it is not for want of
/// friction: the cover reaches rolling (slip under `v_tr / 4`, where eq. 3.15's tanh is 0.76 of `μ F_N`) within
/// the first quarter of the contact, and `μ = 2` instead of 0.372 leaves it as small. The cause is the ball: the
/// core-cover mode's period (2.2 ms) is five times the contact (0.44 ms), so only the cover (26 % of the inertia)
/// turns with the face; the friction that keeps it rolling as the head yaws gives the ball little draw spin (37
/// rad/s at 20 mm toe against a rigid ball's 112), and the fade that the bulge's oblique face gave while the
/// cover slid (-33 rad/s; rigid -83) cancels 90 % of it. Measured (this test): -16 rpm at 20 mm toe, +16 at 20 mm
/// heel; the standard impulse model (rolling, eq. 3.9-3.10) gives -207 and +207.
#[test]
fn table_3_5_ball_rolls_early_yet_shows_almost_no_gear_effect() {
    let eq = Equipment::new(ClubSpec::driver());
    let p = TwoLayerParams::DRIVER;
    let ball = two_layer(&eq, &p);
    let toe = run(&eq, &driver_state(&eq, 20.0), &p, ball);
    assert!(core_cover_period_s(&ball) > 4.0 * toe.contact_time_s, "period {}", core_cover_period_s(&ball));
    let (rolling_s, sliding, rolling) = yaw_spin_by_phase(&toe, &eq, p.v_tr_mps);
    eprintln!("rolling after {:.1} us of {:.1}", rolling_s * 1e6, toe.contact_time_s * 1e6);
    assert!(rolling_s < 0.25 * toe.contact_time_s, "rolling after {rolling_s} s of {}", toe.contact_time_s);
    let rigid = run(&eq, &driver_state(&eq, 20.0), &p, RigidBall::new(&eq.ball));
    let (_, sliding_rigid, rolling_rigid) = yaw_spin_by_phase(&rigid, &eq, p.v_tr_mps);
    eprintln!("yaw spin from friction (rad/s, + draw): sliding {sliding:.1}, rolling {rolling:.1}");
    eprintln!("rigid ball: sliding {sliding_rigid:.1}, rolling {rolling_rigid:.1}");
    // The rolling phase's draw is a third of a rigid ball's, and the sliding phase's fade cancels 90 % of it.
    assert!(sliding < 0.0 && sliding_rigid < 0.0, "the bulge's sliding friction fades");
    assert!(rolling < 0.5 * rolling_rigid, "rolling-phase draw {rolling} vs rigid {rolling_rigid} rad/s");
    assert!((sliding + rolling).abs() < 0.2 * rolling, "net {} of {rolling} rad/s", sliding + rolling);
    let eq = &eq;
    let side = |p: TwoLayerParams| move |h: Real| run(eq, &driver_state(eq, h), &p, two_layer(eq, &p)).sidespin_rpm();
    let (table, slippery) = (side(p), side(TwoLayerParams { mu: 2.0, ..p }));
    for h in [20.0, -20.0] {
        let g = gear_rpm(&table, h);
        assert!(g.abs() < 60.0, "Table 3.5 gear effect at {h} mm: {g} rpm");
        let g2 = gear_rpm(&slippery, h);
        assert!(g2.abs() < 60.0, "mu = 2 gear effect at {h} mm: {g2} rpm");
        eprintln!("h {h}: table 3.5 {g:.0} rpm, mu=2 {g2:.0} rpm, standard {:.0}", gear_rpm(&standard_sidespin(eq), h));
    }
}

/// The same assembly with a rigid ball (the law, head, face and lever arms unchanged) gives the gear effect of
/// the standard impulse model, whose rolling condition (eq. 3.9-3.10) is the limit a rolling rigid ball reaches:
/// same sign, within 25 % at 20 mm toe and heel (measured -238 and +239 rpm against -207 and +207). So the head's
/// yaw, the contact point and the frames are right; what removes the gear effect is Table 3.5's ball.
#[test]
fn a_rigid_ball_on_the_same_head_gives_the_rolling_gear_effect() {
    let eq = Equipment::new(ClubSpec::driver());
    let p = TwoLayerParams::DRIVER;
    let rigid = |h: Real| run(&eq, &driver_state(&eq, h), &p, RigidBall::new(&eq.ball)).sidespin_rpm();
    let standard = standard_sidespin(&eq);
    for h in [20.0, -20.0] {
        let (g, g_std) = (gear_rpm(&rigid, h), gear_rpm(&standard, h));
        eprintln!("h {h}: rigid {g:.0} rpm, standard {g_std:.0}");
        assert!(g * g_std > 0.0 && (g - g_std).abs() < 0.25 * g_std.abs(), "h {h}: rigid {g} vs standard {g_std}");
    }
    // Toe draws, heel fades (seed section 5.2).
    assert!(gear_rpm(&rigid, 20.0) < -100.0 && gear_rpm(&rigid, -20.0) > 100.0);
}

/// The one-cycle ball (`clubs/driver-one-cycle.toml`: core-cover period 0.25 ms, shorter than the contact) turns
/// as a whole with the face and gives a gear effect at least the standard impulse model's (measured -381 and +382
/// rpm at 20 mm toe and heel against -207 and +207; the adjusted model -214 and +217).
#[test]
fn one_cycle_ball_gives_a_gear_effect() {
    let eq = Equipment::new(ClubSpec::driver());
    let p = one_cycle(TwoLayerParams::DRIVER);
    let ball = two_layer(&eq, &p);
    let centre = run(&eq, &driver_state(&eq, 0.0), &p, ball);
    assert!(core_cover_period_s(&ball) < centre.contact_time_s, "period {}", core_cover_period_s(&ball));
    let one = |h: Real| run(&eq, &driver_state(&eq, h), &p, two_layer(&eq, &p)).sidespin_rpm();
    let standard = standard_sidespin(&eq);
    for h in [20.0, -20.0] {
        let (g, g_std) = (gear_rpm(&one, h), gear_rpm(&standard, h));
        eprintln!("h {h}: one-cycle {g:.0} rpm, standard {g_std:.0}");
        assert!(g / g_std >= 1.0 && g / g_std < 2.5, "h {h}: one-cycle {g} vs standard {g_std}");
    }
}

/// The 7-iron: the ball rolls up the face during the contact, so the contact's centroid (where eq. 3.14's force
/// acts) climbs the face and the head pitches about its toe axis far more than about the fixed contact point of
/// the impulse models. The strike that gives the most ball speed therefore lies lower than the standard impulse
/// model's (the seed finds the same, section 4.4: "the maximum carry distance occurs slightly below the center of
/// the clubface"), by about the normal-impulse-weighted climb; the 7-iron's small loss at 17 mm toe measured
/// from the face centre (research/offcentre-iron.md) is mostly this shifted reference.
///
/// Measured here (85 mph, 32 deg loft, -4.5 deg attack, the delivery of research/offcentre-iron.md): the centroid
/// climbs 6.5 mm over 0.47 ms; the head's pitch rate after impact is 276 rad/s against the standard model's 123;
/// the fastest strike is 8 mm below centre (standard: 3 mm, the CG's projection on the face at -2.35 mm); 17 mm
/// toe at that height loses 4.3 % of ball speed (2.0 % from the centre; the published 8-iron pair 5.7 %).
#[test]
fn iron_ball_rolls_up_the_face_and_the_best_strike_is_lower() {
    for p in [TwoLayerParams::IRON7, one_cycle(TwoLayerParams::IRON7)] {
        iron_rolls_up(&p);
    }
}

fn iron_rolls_up(p: &TwoLayerParams) {
    let p = *p;
    let eq = Equipment::new(ClubSpec::iron7());
    let at = |h: Real, v: Real| state(&eq, 85.0, 32.0, -4.5, h, v);
    let r = run(&eq, &at(0.0, 0.0), &p, two_layer(&eq, &p));
    let u0 = eq.club.face.u0();
    let climb = |c: &Contact| (c.overlap.centroid_m - r.log[0].0.overlap.centroid_m).dot(&u0);
    let climb_m = climb(&r.log.last().unwrap().0);
    // Upper bound: the ball's centre cannot move up the face faster than at first contact, when the ball is at
    // rest and the face slides under it at the whole tangential speed (the slip then).
    let bound_m = r.log[0].0.slip_mps.norm() * r.contact_time_s;
    assert!(climb_m > 0.5 * bound_m && climb_m < bound_m, "climb {climb_m} m, bound {bound_m} m");
    let n_impulse: Real = r.log.iter().map(|(_, f)| f.normal_n).sum();
    let mean_climb_m = r.log.iter().map(|(c, f)| f.normal_n * climb(c)).sum::<Real>() / n_impulse;
    let standard = ImpulseModel::new(ImpulseVariant::Standard).predict(&at(0.0, 0.0), &eq).unwrap();
    let (pitch, pitch_std) = (r.launch.club_angular_velocity_radps.z, standard.club_angular_velocity_radps.z);
    assert!(pitch > 1.5 * pitch_std, "pitch {pitch} vs standard {pitch_std} rad/s");

    let continuous_speed = |h: Real, v: Real| ball_speed_mps(&run(&eq, &at(h, v), &p, two_layer(&eq, &p)).launch);
    let standard_speed =
        |v: Real| ball_speed_mps(&ImpulseModel::new(ImpulseVariant::Standard).predict(&at(0.0, v), &eq).unwrap());
    let best = |speed: &dyn Fn(Real) -> Real| {
        (-14..=4).map(|v| v as Real).max_by(|a, b| speed(*a).total_cmp(&speed(*b))).unwrap()
    };
    let (best_c, best_s) = (best(&|v| continuous_speed(0.0, v)), best(&standard_speed));
    eprintln!(
        "climb {:.2} mm (impulse-weighted {:.2}); best v {best_c} vs {best_s} mm",
        climb_m * 1e3,
        mean_climb_m * 1e3
    );
    assert!(best_s - best_c >= 3.0, "best strike: continuous {best_c} mm, standard {best_s} mm");
    assert!(((best_s - best_c) - mean_climb_m * 1e3).abs() <= 2.0, "shift {} vs climb {mean_climb_m}", best_s - best_c);
    let loss_pct = 100.0 * (1.0 - continuous_speed(17.0, best_c) / continuous_speed(0.0, best_c));
    eprintln!("pitch {pitch:.0} vs {pitch_std:.0}; toe loss {loss_pct:.2} %");
    assert!((3.0..6.0).contains(&loss_pct), "17 mm toe at the best height loses {loss_pct} %");
}
