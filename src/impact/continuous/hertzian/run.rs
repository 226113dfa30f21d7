//! The integration of [`super::HertzModel`]: RK4 on both free bodies, the tangential law's history committed
//! after each step, the separation located by secant.

use super::{HertzModel, HertzResult, HertzTracePoint};
use crate::impact::continuous::law::hertz::{
    elastic_energy, equivalent_radius, normal_force, ContactArm, ContactKinematics, Hertz, TangentialLaw,
};
use crate::impact::continuous::surface::FaceSurface;
use crate::impact::{Equipment, ImpactError, ImpactState, Launch};
use crate::math::{Real, UnitQuaternion, Vector3};

type Rotation3 = crate::math::Rotation3;

/// A step the tangential law flags ([`TangentialLaw::refine`]) is split into this many.
const REFINE: usize = 8;

#[derive(Debug, Clone, Copy)]
struct State {
    p_c_m: Vector3,
    v_c_mps: Vector3,
    q_c: UnitQuaternion,
    w_c_body_radps: Vector3,
    p_b_m: Vector3,
    v_b_mps: Vector3,
    w_b_radps: Vector3,
    /// Tangential slip of the ball's contact point relative to the face's, integrated (m).
    slip_m: Vector3,
}

/// Time derivatives, in the same layout.
#[derive(Debug, Clone, Copy)]
struct Rates {
    v_c_mps: Vector3,
    a_c_mps2: Vector3,
    q_dot: crate::math::Quaternion,
    alpha_c_body_radps2: Vector3,
    v_b_mps: Vector3,
    a_b_mps2: Vector3,
    alpha_b_radps2: Vector3,
    slip_rate_mps: Vector3,
}

struct Setup {
    k: Real,
    hertz: Hertz,
    surface: FaceSurface,
    r_ball_m: Real,
    contact_arm: ContactArm,
    m_b_kg: Real,
    i_b_kgm2: Real,
    m_c_kg: Real,
    i_c_kgm2: crate::math::Matrix3,
    i_c_inv_per_kgm2: crate::math::Matrix3,
}

/// The contact at a state: kinematics for the law, the contact point's lever arms, the normal force.
struct Contact {
    kin: ContactKinematics,
    r_b: Vector3,
    r_c: Vector3,
}

impl Setup {
    fn contact(&self, s: &State, s_step: &Vector3) -> Option<Contact> {
        self.contact_rot(s, &s.q_c.to_rotation_matrix(), s_step)
    }

    fn contact_rot(&self, s: &State, rot: &Rotation3, s_step: &Vector3) -> Option<Contact> {
        let ball = rot.inverse_transform_vector(&(s.p_b_m - s.p_c_m));
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
        let point = s.p_b_m - self.contact_arm.arm_m(self.r_ball_m, x) * n;
        let (r_b, r_c) = (point - s.p_b_m, point - s.p_c_m);
        let w_c = rot * s.w_c_body_radps;
        let v_rel = (s.v_b_mps + s.w_b_radps.cross(&r_b)) - (s.v_c_mps + w_c.cross(&r_c));
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
    fn rates(&self, s: &State, s_step: &Vector3, law: &dyn TangentialLaw) -> Rates {
        let rot = s.q_c.to_rotation_matrix();
        match self.contact_rot(s, &rot, s_step) {
            Some(c) => {
                let f_t = law.force(&c.kin);
                self.rates_with(s, &rot, Some((&c, &f_t)))
            }
            None => self.rates_with(s, &rot, None),
        }
    }

    /// The rates at `s` with the contact and tangential force found there (`None`: apart).
    fn rates_with(&self, s: &State, rot: &Rotation3, cf: Option<(&Contact, &Vector3)>) -> Rates {
        let w = s.w_c_body_radps;
        let q_dot = s.q_c.quaternion() * crate::math::Quaternion::from_imag(w) * 0.5;
        // The head's torque in its body frame: gyroscopic, plus the contact's.
        let mut torque_body = -w.cross(&(self.i_c_kgm2 * w));
        let mut r = Rates {
            v_c_mps: s.v_c_mps,
            a_c_mps2: Vector3::zeros(),
            q_dot,
            alpha_c_body_radps2: Vector3::zeros(),
            v_b_mps: s.v_b_mps,
            a_b_mps2: Vector3::zeros(),
            alpha_b_radps2: Vector3::zeros(),
            slip_rate_mps: Vector3::zeros(),
        };
        if let Some((c, f_t)) = cf {
            let f = c.kin.normal_force_n * c.kin.normal + *f_t;
            r.a_b_mps2 = f / self.m_b_kg;
            r.alpha_b_radps2 = c.r_b.cross(&f) / self.i_b_kgm2;
            r.a_c_mps2 = -f / self.m_c_kg;
            torque_body += rot.inverse_transform_vector(&c.r_c.cross(&(-f)));
            r.slip_rate_mps = c.kin.slip_velocity_mps;
        }
        r.alpha_c_body_radps2 = self.i_c_inv_per_kgm2 * torque_body;
        r
    }

    fn momentum(&self, s: &State) -> (Vector3, Vector3) {
        let rot = s.q_c.to_rotation_matrix();
        let linear = self.m_c_kg * s.v_c_mps + self.m_b_kg * s.v_b_mps;
        let angular = self.m_c_kg * s.p_c_m.cross(&s.v_c_mps)
            + rot * (self.i_c_kgm2 * s.w_c_body_radps)
            + self.m_b_kg * s.p_b_m.cross(&s.v_b_mps)
            + self.i_b_kgm2 * s.w_b_radps;
        (linear, angular)
    }

    fn energy(&self, s: &State, law: &dyn TangentialLaw) -> Real {
        let ke = 0.5 * self.m_c_kg * s.v_c_mps.norm_squared()
            + 0.5 * s.w_c_body_radps.dot(&(self.i_c_kgm2 * s.w_c_body_radps))
            + 0.5 * self.m_b_kg * s.v_b_mps.norm_squared()
            + 0.5 * self.i_b_kgm2 * s.w_b_radps.norm_squared();
        let x = self.contact(s, &s.slip_m).map(|c| c.kin.x_m).unwrap_or(0.0);
        ke + elastic_energy(self.k, x) + law.stored_energy_j()
    }
}

fn advance(s: &State, r: &Rates, h: Real) -> State {
    State {
        p_c_m: s.p_c_m + r.v_c_mps * h,
        v_c_mps: s.v_c_mps + r.a_c_mps2 * h,
        q_c: UnitQuaternion::new_unchecked(s.q_c.quaternion() + r.q_dot * h),
        w_c_body_radps: s.w_c_body_radps + r.alpha_c_body_radps2 * h,
        p_b_m: s.p_b_m + r.v_b_mps * h,
        v_b_mps: s.v_b_mps + r.a_b_mps2 * h,
        w_b_radps: s.w_b_radps + r.alpha_b_radps2 * h,
        slip_m: s.slip_m + r.slip_rate_mps * h,
    }
}

fn combine(k: [&Rates; 4]) -> Rates {
    let c = |f: fn(&Rates) -> Vector3| (f(k[0]) + 2.0 * f(k[1]) + 2.0 * f(k[2]) + f(k[3])) / 6.0;
    Rates {
        v_c_mps: c(|r| r.v_c_mps),
        a_c_mps2: c(|r| r.a_c_mps2),
        q_dot: (k[0].q_dot + k[1].q_dot * 2.0 + k[2].q_dot * 2.0 + k[3].q_dot) / 6.0,
        alpha_c_body_radps2: c(|r| r.alpha_c_body_radps2),
        v_b_mps: c(|r| r.v_b_mps),
        a_b_mps2: c(|r| r.a_b_mps2),
        alpha_b_radps2: c(|r| r.alpha_b_radps2),
        slip_rate_mps: c(|r| r.slip_rate_mps),
    }
}

pub(super) fn run(
    model: &HertzModel,
    state: &ImpactState,
    eq: &Equipment,
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
        m_b_kg: eq.ball.mass_kg,
        i_b_kgm2: eq.ball.inertia_kg_m2,
        m_c_kg: club.mass_kg,
        i_c_kgm2: club.inertia_kg_m2,
        i_c_inv_per_kgm2: club.inertia_inv_kg_m2,
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
        p_c_m: iso.translation.vector,
        v_c_mps: state.cg_velocity_mps,
        q_c: rot,
        w_c_body_radps: rot.inverse_transform_vector(&state.angular_velocity_radps),
        p_b_m: iso.translation.vector + rot * ball_club,
        v_b_mps: Vector3::zeros(),
        w_b_radps: Vector3::zeros(),
        slip_m: Vector3::zeros(),
    };
    let n0 = (s.p_b_m - s.p_c_m - rot * contact.point_m).normalize();
    let v_face0 = state.cg_velocity_mps + state.angular_velocity_radps.cross(&(rot * contact.point_m));
    let xdot0 = v_face0.dot(&n0);
    if xdot0 <= 0.0 {
        return Err(ImpactError::NotApproaching);
    }
    // The ball slips against the face's tangential motion; Figure 3.5's tangential axis.
    let face_t = v_face0 - xdot0 * n0;
    let face_dir = if face_t.norm() > 1e-9 { face_t.normalize() } else { rot * club.face.u0() };
    let reduced_mass = setup.m_b_kg * setup.m_c_kg / (setup.m_b_kg + setup.m_c_kg);
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
        let rot = s.q_c.to_rotation_matrix();
        let c1 = match committed.take() {
            Some(cf) => cf,
            None => setup.contact_rot(&s, &rot, &s0).map(|c| {
                let f_t = law.force(&c.kin);
                (c, f_t)
            }),
        };
        let k1 = setup.rates_with(&s, &rot, c1.as_ref().map(|(c, f)| (c, f)));
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
                ball_spin_rpm: crate::units::radps_to_rpm(s.w_b_radps.dot(&spin_axis)),
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
            let k2 = setup.rates(&advance(&s, &k1, 0.5 * h), &s0, law);
            let k3 = setup.rates(&advance(&s, &k2, 0.5 * h), &s0, law);
            let k4 = setup.rates(&advance(&s, &k3, h), &s0, law);
            let mut next = advance(&s, &combine([&k1, &k2, &k3, &k4]), h);
            next.q_c = UnitQuaternion::new_normalize(next.q_c.into_inner());
            next
        };
        let mut next = step(h);
        // Separation inside the step: shorten it to end where the overlap closes (secant on the overlap), so
        // the forces that jump there (Arakawa's ẋ term) stop at the right instant.
        let c_next = setup.contact(&next, &s0);
        if let (Some((c0, _)), None) = (&c1, &c_next) {
            let gap = |st: &State| signed_overlap(&setup, st);
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
    let rot = s.q_c.to_rotation_matrix();
    let size = ft_max.max(-ft_min);
    Ok(HertzResult {
        launch: Launch {
            ball_velocity_mps: s.v_b_mps,
            ball_spin_radps: s.w_b_radps,
            club_velocity_mps: s.v_c_mps,
            club_angular_velocity_radps: rot * s.w_c_body_radps,
            impulse_ns: setup.m_b_kg * s.v_b_mps,
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
fn signed_overlap(setup: &Setup, st: &State) -> Real {
    let rot = st.q_c.to_rotation_matrix();
    let ball = rot.inverse_transform_vector(&(st.p_b_m - st.p_c_m));
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
