//! The integration of [`super::HertzModel`]: RK4 on the shared parts (any [`ClubPart`] and [`BallPart`]: the
//! seed's models use a free head and a rigid ball) and the contact's tangential slip, the tangential law's history
//! committed after each step, the separation located by secant.

use super::{HertzModel, HertzResult, HertzTracePoint};
use crate::impact::continuous::ball::{rk4_mean, BallPart};
use crate::impact::continuous::club::{ClubPart, Head};
use crate::impact::continuous::law::hertz::{
    elastic_energy, equivalent_radius, normal_force, ContactArm, ContactKinematics, Hertz, TangentialLaw,
};
use crate::impact::continuous::surface::FaceSurface;
use crate::impact::{Equipment, ImpactError, ImpactState, Launch};
use crate::math::{Real, Vector3};

/// A step the tangential law flags ([`TangentialLaw::refine`]) is split into this many.
const REFINE: usize = 8;

#[derive(Debug, Clone, Copy)]
struct State<CS, BS> {
    club: CS,
    ball: BS,
    /// Tangential slip of the ball's contact point relative to the face's, integrated (m).
    slip_m: Vector3,
}

/// Time derivatives, in the same layout.
#[derive(Debug, Clone, Copy)]
struct Rates<CR, BR> {
    club: CR,
    ball: BR,
    slip_rate_mps: Vector3,
}

struct Setup<C, B> {
    k: Real,
    hertz: Hertz,
    surface: FaceSurface,
    r_ball_m: Real,
    contact_arm: ContactArm,
    ball: B,
    club: C,
}

type PartState<C, B> = State<<C as ClubPart>::State, <B as BallPart>::State>;
type PartRates<C, B> = Rates<<C as ClubPart>::Rate, <B as BallPart>::Rate>;

/// The contact at a state: kinematics for the law, the contact point's lever arms, the normal force.
struct Contact {
    kin: ContactKinematics,
    r_b: Vector3,
    r_c: Vector3,
}

impl<C: ClubPart, B: BallPart> Setup<C, B> {
    fn contact(&self, s: &PartState<C, B>, s_step: &Vector3) -> Option<Contact> {
        self.contact_at(s, &self.club.head(&s.club), s_step)
    }

    fn contact_at(&self, s: &PartState<C, B>, head: &Head, s_step: &Vector3) -> Option<Contact> {
        let rot = &head.world_from_club;
        let (p_b_m, v_b_mps) = B::centre(&s.ball);
        let ball = rot.inverse_transform_vector(&(p_b_m - head.position_m));
        let (x, normal) = match self.surface {
            FaceSurface::Plane { point, normal } => (self.r_ball_m - normal.dot(&(ball - point)), normal),
            FaceSurface::Sphere { centre, radius_m } => {
                let d = ball - centre;
                let dn = d.norm();
                (self.r_ball_m + radius_m - dn, d / dn)
            }
        };
        if x < -1e-12 {
            return None;
        }
        let x = x.max(0.0);
        let n = rot * normal;
        let point = p_b_m - self.contact_arm.arm_m(self.r_ball_m, x) * n;
        let (r_b, r_c) = (point - p_b_m, point - head.position_m);
        let w_c = head.angular_velocity_radps;
        let v_rel = (v_b_mps + B::surface_spin(&s.ball).cross(&r_b)) - (head.velocity_mps + w_c.cross(&r_c));
        let xdot = -v_rel.dot(&n);
        if x == 0.0 && xdot <= 0.0 {
            return None; // touching, not pressing
        }
        let ds = s.slip_m - s_step;
        let kin = ContactKinematics {
            normal: n,
            x_m: x,
            xdot_mps: xdot,
            normal_force_n: normal_force(self.k, self.hertz.d_s_per_m, x, xdot),
            slip_velocity_mps: v_rel - v_rel.dot(&n) * n,
            slip_since_step_m: ds - ds.dot(&n) * n,
        };
        Some(Contact { kin, r_b, r_c })
    }

    /// The rates at an intermediate stage.
    fn rates(&self, s: &PartState<C, B>, s_step: &Vector3, law: &dyn TangentialLaw) -> PartRates<C, B> {
        let head = self.club.head(&s.club);
        match self.contact_at(s, &head, s_step) {
            Some(c) => {
                let f_t = law.force(&c.kin);
                self.rates_with(s, &head, Some((&c, &f_t)))
            }
            None => self.rates_with(s, &head, None),
        }
    }

    /// The rates at `s` with the contact and tangential force found there (`None`: apart): the parts' rates
    /// under the contact force on the ball and its opposite on the head at the same point.
    fn rates_with(&self, s: &PartState<C, B>, head: &Head, cf: Option<(&Contact, &Vector3)>) -> PartRates<C, B> {
        let (mut f, mut r_b, mut torque_club, mut slip_rate_mps) =
            (Vector3::zeros(), Vector3::zeros(), Vector3::zeros(), Vector3::zeros());
        if let Some((c, f_t)) = cf {
            f = c.kin.normal_force_n * c.kin.normal + *f_t;
            r_b = c.r_b;
            torque_club = c.r_c.cross(&(-f));
            slip_rate_mps = c.kin.slip_velocity_mps;
        }
        Rates {
            club: self.club.rate(&s.club, head, -f, torque_club),
            ball: self.ball.rate(&s.ball, f, r_b),
            slip_rate_mps,
        }
    }

    fn momentum(&self, s: &PartState<C, B>) -> (Vector3, Vector3) {
        let (lc, ac) = self.club.momentum(&s.club);
        let (lb, ab) = self.ball.momentum(&s.ball);
        (lc + lb, ac + ab)
    }

    fn energy(&self, s: &PartState<C, B>, law: &dyn TangentialLaw) -> Real {
        let ke = self.club.energy_j(&s.club) + self.ball.energy_j(&s.ball);
        let x = self.contact(s, &s.slip_m).map(|c| c.kin.x_m).unwrap_or(0.0);
        ke + elastic_energy(self.k, x) + law.stored_energy_j()
    }
}

fn advance<C: ClubPart, B: BallPart>(s: &PartState<C, B>, r: &PartRates<C, B>, h: Real) -> PartState<C, B> {
    State {
        club: C::advance(&s.club, &r.club, h),
        ball: B::advance(&s.ball, &r.ball, h),
        slip_m: s.slip_m + r.slip_rate_mps * h,
    }
}

/// `s + h (k1 + 2 k2 + 2 k3 + k4) / 6`, the head's attitude normalised.
fn advance_rk4<C: ClubPart, B: BallPart>(s: &PartState<C, B>, k: [&PartRates<C, B>; 4], h: Real) -> PartState<C, B> {
    let [k1, k2, k3, k4] = k;
    State {
        club: C::advance_rk4(&s.club, [&k1.club, &k2.club, &k3.club, &k4.club], h),
        ball: B::advance_rk4(&s.ball, [&k1.ball, &k2.ball, &k3.ball, &k4.ball], h),
        slip_m: s.slip_m + rk4_mean(k1.slip_rate_mps, k2.slip_rate_mps, k3.slip_rate_mps, k4.slip_rate_mps) * h,
    }
}

/// Runs the collision of `ball` (at rest against the face) and `club` (moving as `state` says).
pub(super) fn run<C: ClubPart, B: BallPart>(
    model: &HertzModel,
    state: &ImpactState,
    eq: &Equipment,
    (club_part, ball_part): (C, B),
    (hertz, contact_arm): (Hertz, ContactArm),
    law: &mut dyn TangentialLaw,
    trace_every: usize,
) -> Result<HertzResult, ImpactError> {
    let club = &eq.club;
    if !club.on_face(state.impact_h_m, state.impact_v_m) {
        return Err(ImpactError::OffFace { h_mm: state.impact_h_m * 1e3, v_mm: state.impact_v_m * 1e3 });
    }
    if !(model.step_s.is_finite() && model.step_s > 0.0) {
        return Err(ImpactError::InvalidParameter {
            field: "step_s".into(),
            reason: format!("{} s must be positive", model.step_s),
        });
    }
    let surface = FaceSurface::of_club(club);
    let r_eq = equivalent_radius(eq.ball.radius_m, &club.face.shape);
    let setup = Setup {
        k: hertz.stiffness(r_eq),
        hertz,
        surface,
        r_ball_m: eq.ball.radius_m,
        contact_arm,
        ball: ball_part,
        club: club_part,
    };
    let contact = club.face.contact(state.impact_h_m, state.impact_v_m)?;
    let ball_club = match surface {
        FaceSurface::Plane { .. } => contact.point_m + eq.ball.radius_m * contact.normal,
        FaceSurface::Sphere { centre, radius_m } => {
            centre + (radius_m + eq.ball.radius_m) * (contact.point_m - centre).normalize()
        }
    };
    let iso = state.world_from_club;
    let rot = iso.rotation;
    let mut s = State {
        club: setup.club.initial(state),
        ball: setup.ball.at_rest(iso.translation.vector + rot * ball_club),
        slip_m: Vector3::zeros(),
    };
    let n0 = (B::centre(&s.ball).0 - iso.translation.vector - rot * contact.point_m).normalize();
    let v_face0 = state.cg_velocity_mps + state.angular_velocity_radps.cross(&(rot * contact.point_m));
    let xdot0 = v_face0.dot(&n0);
    if xdot0 <= 0.0 {
        return Err(ImpactError::NotApproaching);
    }
    // The ball slips against the face's tangential motion; Figure 3.5's tangential axis.
    let face_t = v_face0 - xdot0 * n0;
    let face_dir = if face_t.norm() > 1e-9 { face_t.normalize() } else { rot * club.face.u0() };
    let m_b_kg = setup.ball.mass_kg();
    let reduced_mass = m_b_kg * club.mass_kg / (m_b_kg + club.mass_kg);
    law.begin(-face_dir, xdot0, setup.k, r_eq, reduced_mass);
    let spin_axis = face_dir.cross(&n0);

    let energy_before = setup.energy(&s, law);
    let momentum_before = setup.momentum(&s);
    // Time since first contact (s); steps near a switch the law flags are split in `REFINE`.
    let mut t_s = 0.0;
    let (mut trace, mut peak, mut ft_max, mut ft_min) = (Vec::new(), 0.0f64, 0.0f64, 0.0f64);
    let (mut touched, mut steps, mut contact_time) = (false, 0usize, 0.0);
    let (mut energy, mut max_increase) = (energy_before, 0.0f64);
    // The contact and tangential force found when the last step was committed: the next step's first stage.
    let mut committed: Option<Option<(Contact, Vector3)>> = None;
    loop {
        let s0 = s.slip_m;
        let head = setup.club.head(&s.club);
        let c1 = match committed.take() {
            Some(cf) => cf,
            None => setup.contact_at(&s, &head, &s0).map(|c| {
                let f_t = law.force(&c.kin);
                (c, f_t)
            }),
        };
        let k1 = setup.rates_with(&s, &head, c1.as_ref().map(|(c, f)| (c, f)));
        if let Some((c, f_t)) = &c1 {
            touched = true;
            peak = peak.max(c.kin.normal_force_n);
            let along = f_t.dot(&face_dir);
            ft_max = ft_max.max(along);
            ft_min = ft_min.min(along);
        }
        if trace_every > 0 && steps % trace_every == 0 {
            let (fn_, ft, x) =
                c1.as_ref().map_or((0.0, 0.0, 0.0), |(c, f_t)| (c.kin.normal_force_n, f_t.dot(&face_dir), c.kin.x_m));
            trace.push(HertzTracePoint {
                t_us: t_s * 1e6,
                normal_force_n: fn_,
                tangential_force_n: ft,
                ball_spin_rpm: crate::units::radps_to_rpm(setup.ball.spin(&s.ball).dot(&spin_axis)),
                compression_mm: x * 1e3,
                stuck_rings: law.stuck_rings(),
            });
        }
        if c1.is_none() && (touched || steps > 10) {
            if touched {
                contact_time = t_s;
            }
            break;
        }
        if t_s >= model.max_contact_s {
            return Err(HertzModel::not_converged(format!(
                "still in contact after {:.2} ms",
                model.max_contact_s * 1e3
            )));
        }
        let h = match &c1 {
            Some((c, _)) if law.refine(&c.kin) => model.step_s / REFINE as Real,
            _ => model.step_s,
        };
        let step = |h: Real| {
            let k2 = setup.rates(&advance::<C, B>(&s, &k1, 0.5 * h), &s0, law);
            let k3 = setup.rates(&advance::<C, B>(&s, &k2, 0.5 * h), &s0, law);
            let k4 = setup.rates(&advance::<C, B>(&s, &k3, h), &s0, law);
            advance_rk4::<C, B>(&s, [&k1, &k2, &k3, &k4], h)
        };
        let mut next = step(h);
        // Separation inside the step: shorten it to end where the overlap closes (secant on the overlap), so
        // the forces that jump there (Arakawa's ẋ term) stop at the right instant.
        let c_next = setup.contact(&next, &s0);
        if let (Some((c0, _)), None) = (&c1, &c_next) {
            let gap = |st: &PartState<C, B>| signed_overlap(&setup, st);
            let (mut lo, mut x_lo, mut hi, mut x_hi) = (0.0, c0.kin.x_m, h, gap(&next));
            let mut t = lo + (hi - lo) * x_lo / (x_lo - x_hi);
            for _ in 0..4 {
                let x = gap(&step(t));
                if x.abs() < 1e-15 {
                    break;
                }
                if x > 0.0 {
                    (lo, x_lo) = (t, x);
                } else {
                    (hi, x_hi) = (t, x);
                }
                t = lo + (hi - lo) * x_lo / (x_lo - x_hi);
            }
            next = step(t);
            contact_time = t_s + t;
            s = next;
            law.commit(&contact_at_rest(n0));
            steps += 1;
            break;
        }
        s = next;
        committed = Some(match c_next {
            Some(c) => {
                let f_t = law.commit(&c.kin);
                Some((c, f_t))
            }
            None => {
                law.commit(&contact_at_rest(n0));
                None
            }
        });
        steps += 1;
        t_s += h;
        if trace_every > 0 || cfg!(debug_assertions) {
            let e = setup.energy(&s, law);
            max_increase = max_increase.max(e - energy);
            energy = e;
        }
    }
    if !touched {
        return Err(HertzModel::not_converged("the face never pressed the ball".into()));
    }
    let head = setup.club.head(&s.club);
    let size = ft_max.max(-ft_min);
    Ok(HertzResult {
        launch: Launch {
            ball_velocity_mps: B::centre(&s.ball).1,
            ball_spin_radps: setup.ball.spin(&s.ball),
            club_velocity_mps: head.velocity_mps,
            club_angular_velocity_radps: head.angular_velocity_radps,
            impulse_ns: m_b_kg * B::centre(&s.ball).1,
        },
        contact_time_s: contact_time,
        peak_normal_force_n: peak,
        tangential_reversal: ft_max > 0.01 * size && ft_min < -0.01 * size,
        steps,
        trace,
        energy_before_j: energy_before,
        energy_after_j: setup.energy(&s, law),
        max_energy_increase_j: max_increase,
        momentum_before,
        momentum_after: setup.momentum(&s),
    })
}

/// The overlap along the normal, negative when apart (m).
fn signed_overlap<C: ClubPart, B: BallPart>(setup: &Setup<C, B>, st: &PartState<C, B>) -> Real {
    let head = setup.club.head(&st.club);
    let ball = head.world_from_club.inverse_transform_vector(&(B::centre(&st.ball).0 - head.position_m));
    match setup.surface {
        FaceSurface::Plane { point, normal } => setup.r_ball_m - normal.dot(&(ball - point)),
        FaceSurface::Sphere { centre, radius_m } => setup.r_ball_m + radius_m - (ball - centre).norm(),
    }
}

fn contact_at_rest(normal: Vector3) -> ContactKinematics {
    ContactKinematics {
        normal,
        x_m: 0.0,
        xdot_mps: 0.0,
        normal_force_n: 0.0,
        slip_velocity_mps: Vector3::zeros(),
        slip_since_step_m: Vector3::zeros(),
    }
}
