//! The stepping's hooks for contact laws with history, on the two-layer model's parts (a free head, no ground):
//! the separation located within the last step, a finer step where the law flags a start, the slip since a
//! step's start integrated for a law that asks for it.

use super::tests::{assembly, start_state, strike};
use super::{FixedStep, Flow, StepPolicy, StepStart, SteppedState};
use crate::impact::continuous::assembly::Assembly;
use crate::impact::continuous::ball::{BallPart, TwoLayerBall};
use crate::impact::continuous::club::{ClubPart, FreeHead, Head};
use crate::impact::continuous::ground::NoGround;
use crate::impact::continuous::law::volumetric::Volumetric;
use crate::impact::continuous::law::{Contact, ContactForce, ContactLaw};
use crate::impact::continuous::surface::{FaceSurface, Overlap};
use crate::impact::ImpactError;
use crate::math::{Real, Vector3};

/// The two-layer model's step (s).
const H_S: Real = 0.6e-6;

/// One step size (`fine_s` where the law flags a start), the separation located or not; records each step's
/// start, size and overlap depth, and the law's state at the last start.
struct Probe<S> {
    h_s: Real,
    fine_s: Option<Real>,
    separation: bool,
    touched: bool,
    steps: Vec<(Real, Real, Option<Real>)>,
    last_law: Option<S>,
}

impl<S> Probe<S> {
    fn new(fine_s: Option<Real>, separation: bool) -> Self {
        Probe { h_s: H_S, fine_s, separation, touched: false, steps: Vec::new(), last_law: None }
    }
}

impl<L: ContactLaw> StepPolicy<L, TwoLayerBall, FreeHead, NoGround> for Probe<L::State> {
    fn step(&self, _: Real, _: &SteppedState<TwoLayerBall, FreeHead>, _: &Head) -> &Real {
        &self.h_s
    }

    fn refined_step(&self) -> Option<&Real> {
        self.fine_s.as_ref()
    }

    fn end_at_separation(&self) -> bool {
        self.separation
    }

    fn law_state(&mut self, _: &L, state: &L::State) {
        self.last_law = Some(state.clone());
    }

    fn observe(
        &mut self,
        _: &Assembly<L, TwoLayerBall, FreeHead, NoGround>,
        t_s: Real,
        h_s: Real,
        _: &SteppedState<TwoLayerBall, FreeHead>,
        start: &StepStart<Head, ()>,
    ) -> Result<Flow, ImpactError> {
        self.steps.push((t_s, h_s, start.ball.map(|c| c.depth_m)));
        if start.ball.is_some() {
            self.touched = true;
        } else if self.touched || self.steps.len() > 10 {
            return Ok(Flow::Stop);
        }
        Ok(if self.steps.len() > 100_000 { Flow::Stop } else { Flow::Continue })
    }
}

/// The two-layer law, its starts deeper than `flag_m` flagged for finer steps.
struct Flagged {
    inner: Volumetric,
    flag_m: Real,
}

impl ContactLaw for Flagged {
    type State = ();
    fn force(&self, c: &Contact, s: &()) -> ContactForce {
        self.inner.force(c, s)
    }
    fn refine(&self, c: &Contact, _: &()) -> bool {
        c.overlap.depth_m > self.flag_m
    }
    fn stored_energy_j(&self, surface: &FaceSurface, r: Real, o: &Overlap) -> Real {
        self.inner.stored_energy_j(surface, r, o)
    }
}

/// The two-layer law asking for the slip since each step's start, which it records at each commit with the
/// contact's normal and slip velocity there (its forces ignore it).
struct SlipProbe(Volumetric);

impl ContactLaw for SlipProbe {
    type State = Vec<(Vector3, Vector3, Vector3)>;
    const TRACKS_SLIP: bool = true;
    fn force(&self, c: &Contact, _: &Self::State) -> ContactForce {
        self.0.force(c, &())
    }
    fn commit(&self, c: Option<&Contact>, state: &mut Self::State, _: Real) {
        if let Some(c) = c {
            state.push((c.slip_since_step_m, c.normal, c.slip_mps));
        }
    }
    fn stored_energy_j(&self, surface: &FaceSurface, r: Real, o: &Overlap) -> Real {
        self.0.stored_energy_j(surface, r, o)
    }
}

/// The step in which the ball leaves ends where the overlap closes (the signed overlap there below 1e-12 m, a
/// micrometre's millionth; the contact's depth is millimetres), inside the step the plain run stops after, and
/// the run ends there: as many steps as the plain run, the last one shorter.
#[test]
fn the_step_the_ball_leaves_in_ends_where_the_overlap_closes() {
    let (eq, state) = strike();
    let asm = assembly(&eq, NoGround);
    let mut plain = FixedStep::new(H_S, 100_000, "continuous");
    let (_, t_stop_s) = asm.run_stepped(start_state(&asm, &eq, &state), 0.0, &mut plain).unwrap();
    let mut probe = Probe::new(None, true);
    let (s, t_s) = asm.run_stepped(start_state(&asm, &eq, &state), 0.0, &mut probe).unwrap();
    assert!(t_stop_s - H_S < t_s && t_s < t_stop_s, "{t_s} vs {t_stop_s}");
    let head = ClubPart::head(&asm.club, &s.club);
    let ball_club = head.world_from_club.inverse_transform_vector(&(TwoLayerBall::centre(&s.ball).0 - head.position_m));
    let depth_m = asm.surface.signed_depth_m(&ball_club, asm.ball.radius_m());
    assert!(depth_m.abs() < 1e-12, "{depth_m}");
    assert_eq!(probe.steps.len(), plain.steps());
    let &(t_last_s, h_last_s, depth_last) = probe.steps.last().unwrap();
    assert!(h_last_s < H_S && (t_last_s + h_last_s - t_s).abs() < 1e-18 && depth_last.is_some());
}

/// A start the law flags (deeper than 1 mm) takes the policy's finer step, every other start the policy's own.
#[test]
fn a_start_the_law_flags_takes_the_finer_step() {
    let (eq, state) = strike();
    let plain = assembly(&eq, NoGround);
    let asm = Assembly {
        law: Flagged { inner: plain.law, flag_m: 1e-3 },
        ball: plain.ball,
        club: plain.club,
        ground: NoGround,
        surface: plain.surface,
    };
    let fine_s = H_S / 8.0;
    let mut probe = Probe::new(Some(fine_s), false);
    let s0 = start_state(&plain, &eq, &state);
    asm.run_stepped(s0, 0.0, &mut probe).unwrap();
    let mut fine = 0;
    for &(t_s, h_s, depth) in &probe.steps {
        let flagged = depth.is_some_and(|d| d > 1e-3);
        fine += usize::from(flagged);
        assert_eq!(h_s, if flagged { fine_s } else { H_S }, "at {t_s} s, depth {depth:?}");
    }
    assert!(fine > 10 && fine < probe.steps.len() - 10, "{fine} fine steps of {}", probe.steps.len());
}

/// A law that asks for the slip leaves the parts' steps as they are (the same end state, bit for bit), and each
/// commit sees the slip since the step's start in the tangent plane (1e-12 of its size along the normal), the
/// step times the slip velocity's mean over the step to 2 % once it slips (beyond 1 µm a step) where the
/// velocity changes slowly (by less than 2 % over the step); a mean from the ends, the trapezoid rule against
/// the stages' Simpson.
#[test]
fn a_law_that_tracks_the_slip_sees_the_slip_since_the_steps_start() {
    let (eq, state) = strike();
    let plain = assembly(&eq, NoGround);
    let asm = Assembly {
        law: SlipProbe(plain.law),
        ball: plain.ball,
        club: plain.club,
        ground: NoGround,
        surface: plain.surface,
    };
    let (a, t_a) =
        plain.run_stepped(start_state(&plain, &eq, &state), 0.0, &mut FixedStep::new(H_S, 100_000, "x")).unwrap();
    let mut probe = Probe::new(None, false);
    let (b, t_b) = asm.run_stepped(start_state(&plain, &eq, &state), 0.0, &mut probe).unwrap();
    assert_eq!((a, t_a), (b, t_b));
    let record = probe.last_law.unwrap();
    assert!(record.len() > 500, "{}", record.len());
    let mut compared = 0;
    for pair in record.windows(2) {
        let [(_, _, v0), (since, n, v1)] = pair else { unreachable!() };
        assert!(since.dot(n).abs() <= 1e-12 * since.norm() + 1e-30, "{since:?} along {n:?}");
        let mean = 0.5 * (v0 + v1) * H_S;
        if mean.norm() > 1e-6 && (v1 - v0).norm() < 0.02 * v0.norm() {
            compared += 1;
            assert!((since - mean).norm() < 0.02 * mean.norm(), "{since:?} vs {mean:?}");
        }
    }
    assert!(compared > 10, "{compared}");
}
