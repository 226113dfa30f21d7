//! The multi-rate stepping on the two-layer model's parts (a free head, no ground): the two-layer model's policy
//! without its bound is the plain policy, and with it each step is as long as the friction allows; events end a
//! step where they fall; a held ground is evaluated once per hold.

use super::{FixedStep, Flow, StepLadder, StepPolicy, StepStart, SteppedState, StiffnessBound, StiffnessStep};
use crate::equipment::ClubSpec;
use crate::impact::continuous::assembly::{Assembly, Integration, State};
use crate::impact::continuous::ball::{BallPart, TwoLayerBall};
use crate::impact::continuous::club::{ClubPart, FreeHead, Head};
use crate::impact::continuous::ground::{GroundWrench, NoGround, SampledGround};
use crate::impact::continuous::law::volumetric::Volumetric;
use crate::impact::continuous::law::{Contact, ContactForce, ContactLaw};
use crate::impact::continuous::two_layer::slip_compliance_per_kg;
use crate::impact::continuous::{ContinuousModel, Start, TwoLayerContact, TwoLayerParams, TwoLayerReading};
use crate::impact::{Delivery, Equipment, ImpactError, ImpactState};
use crate::math::{Real, Vector3};

/// A 7-iron struck 6 mm toward the toe and 4 mm up the face, turning: the contact's moment acts on the head.
pub(super) fn strike() -> (Equipment, ImpactState) {
    let eq = Equipment::new(ClubSpec::iron7());
    let delivery = Delivery {
        club_speed_mps: 40.0,
        attack_angle_rad: (-4.0f64).to_radians(),
        club_path_rad: 0.02,
        face_angle_rad: -0.01,
        dynamic_loft_rad: 28f64.to_radians(),
        impact_h_m: 6e-3,
        impact_v_m: 4e-3,
        club_angular_velocity_radps: Vector3::new(1.0, 10.0, 20.0),
    };
    let state = delivery.to_state(&eq).unwrap();
    (eq, state)
}

/// The two-layer model's assembly, as `ContinuousModel::simulate` builds it, on ground `G`.
pub(super) fn assembly<G>(eq: &Equipment, ground: G) -> Assembly<Volumetric, TwoLayerBall, FreeHead, G> {
    let p = TwoLayerParams::preset(&eq.club, TwoLayerReading::default());
    let TwoLayerContact { law, ball, surface } = p.contact(&eq.club, &eq.ball).unwrap();
    Assembly { law, ball, club: FreeHead::new(&eq.club), ground, surface }
}

/// One step size, an optional event and hold; stops after `max_steps` (or once the ball has left); records each
/// step's start.
struct Fixed {
    h_s: Real,
    event_s: Option<Real>,
    hold_s: Option<Real>,
    max_steps: usize,
    touched: bool,
    starts_s: Vec<Real>,
}

impl Fixed {
    fn new(h_s: Real, max_steps: usize) -> Self {
        Fixed { h_s, event_s: None, hold_s: None, max_steps, touched: false, starts_s: Vec::new() }
    }
}

impl<G: SampledGround> StepPolicy<Volumetric, TwoLayerBall, FreeHead, G> for Fixed {
    fn step(&self, _: Real, _: &SteppedState<TwoLayerBall, FreeHead>, _: &Head) -> &Real {
        &self.h_s
    }

    fn events(&self, _: Real, _: Real) -> impl IntoIterator<Item = Real> {
        self.event_s
    }

    fn ground_hold_s(&self, _: Real) -> Option<Real> {
        self.hold_s
    }

    fn observe(
        &mut self,
        _: &Assembly<Volumetric, TwoLayerBall, FreeHead, G>,
        t_s: Real,
        _: Real,
        _: &SteppedState<TwoLayerBall, FreeHead>,
        start: &StepStart<Head, G::Forces>,
    ) -> Result<Flow, ImpactError> {
        let steps = self.starts_s.len();
        self.starts_s.push(t_s);
        let left = if start.ball.is_some() {
            self.touched = true;
            false
        } else {
            self.touched || steps > 10
        };
        Ok(if left || steps + 1 >= self.max_steps { Flow::Stop } else { Flow::Continue })
    }
}

pub(super) fn start_state(
    asm: &Assembly<Volumetric, TwoLayerBall, FreeHead, impl Sized>,
    eq: &Equipment,
    state: &ImpactState,
) -> SteppedState<TwoLayerBall, FreeHead> {
    let start = Start::new(state, eq).unwrap();
    State { club: ClubPart::initial(&asm.club, state), ball: asm.ball.at_rest(start.ball_centre_m) }
}

/// The integration of the two-layer model at a fixed 0.6 us step.
fn fixed_integration(trace_every: usize) -> Integration {
    Integration { step_s: ContinuousModel::STEP_S, max_contact_s: 3e-3, trace_every, model: "continuous" }
}

/// Without its bound the two-layer model's policy ([`StiffnessStep`]) steps as the plain one ([`FixedStep`]) and
/// stops where it does: the same end state bit for bit, the same steps and contact time. A strike, not a miss:
/// over 30 m/s after 0.3-0.7 ms.
#[test]
fn without_a_bound_the_two_layer_policy_is_the_plain_policy() {
    let (eq, state) = strike();
    let asm = assembly(&eq, NoGround);
    let start = Start::new(&state, &eq).unwrap();
    let r = StiffnessStep::new(&asm.club, fixed_integration(1), None, start.slip0)
        .run(&asm, &state, start.ball_centre_m)
        .unwrap();
    let mut plain = FixedStep::new(ContinuousModel::STEP_S, 100_000, "continuous");
    let (s, t_s) = asm.run_stepped(start_state(&asm, &eq, &state), 0.0, &mut plain).unwrap();
    let (_, v_mps) = TwoLayerBall::centre(&s.ball);
    assert_eq!(r.launch.ball_velocity_mps, v_mps);
    assert_eq!(r.launch.ball_spin_radps, asm.ball.spin(&s.ball));
    assert_eq!((r.contact_time_s, r.steps), (t_s, plain.steps()));
    assert!(plain.touched() && r.trace.len() == r.steps + 1);
    assert!(v_mps.norm() > 30.0 && (3e-4..7e-4).contains(&t_s), "{} m/s after {t_s} s", v_mps.norm());
}

/// The two-layer model's policy with its bound, recording each step's size, whether the ball touched at its
/// start and the slip mode's rate `λ` there (1/s).
struct Recorded {
    policy: StiffnessStep<Real>,
    long_s: Real,
    k: Real,
    steps: Vec<(Real, bool, Real)>,
}

impl StepPolicy<Volumetric, TwoLayerBall, FreeHead, NoGround> for Recorded {
    fn step(&self, t_s: Real, s: &SteppedState<TwoLayerBall, FreeHead>, head: &Head) -> &Real {
        StepPolicy::<Volumetric, TwoLayerBall, FreeHead, NoGround>::step(&self.policy, t_s, s, head)
    }

    fn contact_step_s(&self, asm: &System, contact: &Contact, force: &ContactForce) -> Option<Real> {
        self.policy.contact_step_s(asm, contact, force)
    }

    fn observe(
        &mut self,
        asm: &System,
        t_s: Real,
        h_s: Real,
        s: &SteppedState<TwoLayerBall, FreeHead>,
        start: &StepStart<Head, ()>,
    ) -> Result<Flow, ImpactError> {
        let lambda = asm.contact(&start.motion, &s.ball).map_or(0.0, |c| {
            let f = asm.law.force(&c, &());
            self.k * asm.law.slip_stiffness(&c, f.normal_n, self.long_s * self.k)
        });
        self.steps.push((h_s, start.ball.is_some(), lambda));
        self.policy.observe(asm, t_s, h_s, s, start)
    }
}

type System = Assembly<Volumetric, TwoLayerBall, FreeHead, NoGround>;

/// With the bound each step is as long as the friction allows: from 0.6 us up to six times it, the longest out of
/// contact, and in contact `h λ <= 2.4` (classical Runge-Kutta's stability on the slip mode, eq. 3.15) unless
/// at the shortest step. The stiff middle of the contact takes the shortest step, its ends the longest, in about
/// half the fixed step's steps (crates/golf-physics/tests/continuous.rs bounds the launch against a 0.05 us step).
#[test]
fn each_step_is_as_long_as_the_friction_allows() {
    let (eq, state) = strike();
    let asm = assembly(&eq, NoGround);
    let start = Start::new(&state, &eq).unwrap();
    let step_s = ContinuousModel::STEP_S;
    let k = slip_compliance_per_kg(&asm.ball, &eq.club);
    let bound = StiffnessBound { growth: 6.0, h_lambda: 2.4, slip_compliance_per_kg: k };
    let mut policy = Recorded {
        policy: StiffnessStep::new(&asm.club, fixed_integration(0), Some(bound), start.slip0),
        long_s: 6.0 * step_s,
        k,
        steps: Vec::new(),
    };
    asm.run_stepped(start_state(&asm, &eq, &state), 0.0, &mut policy).unwrap();
    let steps = &policy.steps;
    for &(h_s, touching, lambda) in steps {
        assert!(h_s >= step_s && h_s <= 6.0 * step_s * (1.0 + 1e-15), "{h_s}");
        if !touching {
            assert_eq!(h_s, 6.0 * step_s);
        } else if h_s > step_s {
            assert!(h_s * lambda <= 2.4 * (1.0 + 1e-12), "h {h_s} s, h lambda {}", h_s * lambda);
        }
    }
    let in_contact: Vec<Real> = steps.iter().filter(|s| s.1).map(|s| s.0).collect();
    assert!(in_contact.contains(&step_s) && in_contact.contains(&(6.0 * step_s)), "{in_contact:?}");
    let mut plain = FixedStep::new(step_s, 100_000, "continuous");
    asm.run_stepped(start_state(&asm, &eq, &state), 0.0, &mut plain).unwrap();
    assert!(3 * steps.len() <= 2 * plain.steps(), "{} steps against {}", steps.len(), plain.steps());
}

/// Too few steps for the contact is an error naming the model, not a launch.
#[test]
fn a_contact_longer_than_the_steps_allowed_is_an_error() {
    let (eq, state) = strike();
    let asm = assembly(&eq, NoGround);
    let mut policy = FixedStep::new(0.6e-6, 50, "continuous");
    let err = asm.run_stepped(start_state(&asm, &eq, &state), 0.0, &mut policy).unwrap_err();
    assert!(matches!(err, ImpactError::NotConverged { model: "continuous", .. }), "{err}");
}

/// An event inside a step ends the step there, and the steps after it keep their size: a 1 us step with an
/// event at 3.3 us starts steps at 0, 1, 2, 3, 3.3, 4.3, ... us.
#[test]
fn an_event_ends_the_step_it_falls_in() {
    let (eq, state) = strike();
    let asm = assembly(&eq, NoGround);
    let mut policy = Fixed::new(1e-6, 7);
    policy.event_s = Some(3.3e-6);
    asm.run_stepped(start_state(&asm, &eq, &state), 0.0, &mut policy).unwrap();
    let want = [0.0, 1e-6, 2e-6, 3e-6, 3.3e-6, 4.3e-6, 5.3e-6];
    assert_eq!(policy.starts_s.len(), want.len());
    for (got, want) in policy.starts_s.iter().zip(want) {
        assert!((got - want).abs() < 1e-18, "{:?}", policy.starts_s);
    }
}

/// A ground that counts its evaluations (and pushes nothing).
#[derive(Default)]
struct Counting(std::cell::Cell<usize>);

impl SampledGround for Counting {
    type Forces = ();
    fn forces_on(&self, _: &Head) {
        self.0.set(self.0.get() + 1);
    }
    fn wrench_of(_: &()) -> GroundWrench {
        GroundWrench::default()
    }
}

/// Held over five steps, the ground is evaluated once every five steps (4 times in 20) where it is otherwise
/// evaluated at each of Runge-Kutta's four stages (80 times in 20); with nothing from the ground the strike is
/// the same either way.
#[test]
fn a_held_ground_is_evaluated_once_per_hold() {
    let (eq, state) = strike();
    let h_s = 1e-6;
    let run = |hold_s: Option<Real>| {
        let asm = assembly(&eq, Counting::default());
        let mut policy = Fixed::new(h_s, 20);
        policy.hold_s = hold_s;
        let (s, _) = asm.run_stepped(start_state(&asm, &eq, &state), 0.0, &mut policy).unwrap();
        (asm.ground.0.get(), s)
    };
    let (every_stage, s1) = run(None);
    let (held, s2) = run(Some(5.0 * h_s));
    assert_eq!((every_stage, held), (80, 4));
    assert_eq!(s1, s2);
}

/// The ladder: 2 us up to 120 us by powers of two (2, 4, ..., 64 us, then 120 us); the largest step not above a
/// request, the short one at least.
#[test]
fn the_ladder_takes_the_largest_step_that_fits() {
    let ladder = StepLadder::new(|h_s| h_s, 2e-6, 120e-6);
    assert_eq!(*ladder.short(), 2e-6);
    assert_eq!(*ladder.long(), 120e-6);
    assert_eq!(*ladder.at_most(1e-6), 2e-6);
    assert_eq!(*ladder.at_most(5e-6), 4e-6);
    assert_eq!(*ladder.at_most(100e-6), 64e-6);
    assert_eq!(*ladder.at_most(1.0), 120e-6);
}
