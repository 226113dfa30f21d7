//! A ball on a fixed rigid plate (seed section 3.2.2, Figures 3.3-3.4; Maw, Barber and Fawcett 1976 and 1981):
//! the 2D experiment the Maw model was built for, used to check it against the published elastic theory and
//! to draw Figure 3.4.
//!
//! The plate's normal is `+x`; the ball arrives at speed `V` and incidence `α` from the normal with no spin,
//! its contact point slipping along `+y`. Forces as in [`super::hertzian`]: eq. 3.16 along the normal, a
//! tangential law in the plane, at the contact point `R − x/2` from the ball's centre.
//!
//! Maw, Barber and Fawcett's non-dimensional variables (elastic bodies, `d = 0`):
//! - `χ = (1 − ν)(1 + 1/K²)/(2 − ν)`, `K² = I/(m R²)`;
//! - incidence `ψ₁ = (G*/E*) v_t1 / (μ v_n1)` and rebound `ψ₂ = (G*/E*) v_t2 / (μ v_n2)`, `v_t` the contact
//!   point's tangential velocity (positive along the incident slip), `v_n` the normal speed, `G*/E* = 2(1 − ν)/(2 − ν)`;
//! - gross slip throughout the impact for `ψ₁ ≥ 4χ − 1`, where `ψ₂ = ψ₁ − 4χ` (Coulomb's line); rigid-body
//!   ("simple") theory rolls from `ψ₁ < 4χ` with `ψ₂ = 0`, while with tangential compliance `ψ₂ < 0` at small
//!   `ψ₁`: the contact point's tangential velocity reverses.

use super::law::hertz::{normal_force, Begin, ContactKinematics, Hertz, Tangential};
use super::law::maw::{MawParams, MawRings, MawState};
use crate::equipment::BallSpec;
use crate::math::{Real, Vector3};

/// One sample of a plate impact.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct PlateSample {
    /// Time from first contact (µs).
    pub t_us: Real,
    /// The normal force (N).
    pub normal_force_n: Real,
    /// Tangential force on the ball against the incident slip (N); negative once it has reversed.
    pub tangential_force_n: Real,
    /// The ball's spin in the sense the friction first gives it (rad/s).
    pub spin_radps: Real,
    /// How many of Maw's rings are stuck.
    pub stuck_rings: usize,
}

/// The result of a plate impact.
#[derive(Debug, Clone, PartialEq)]
pub struct PlateImpact {
    /// The contact's course.
    pub samples: Vec<PlateSample>,
    /// Rebound normal speed and the contact point's tangential velocity after (m/s, + along the incident slip).
    pub rebound_normal_mps: Real,
    /// See `rebound_normal_mps`.
    pub rebound_contact_tangential_mps: Real,
    /// The ball's spin after, in the sense the friction first gives it (rad/s).
    pub spin_radps: Real,
    /// From first contact until the ball leaves (s).
    pub contact_time_s: Real,
}

/// The non-dimensional parameter `χ` of Maw, Barber and Fawcett.
pub fn chi(nu: Real, ball: &BallSpec) -> Real {
    let k2 = ball.inertia_kg_m2 / (ball.mass_kg * ball.radius_m * ball.radius_m);
    (1.0 - nu) * (1.0 + 1.0 / k2) / (2.0 - nu)
}

/// The plate problem's state: the overlap, its rate (approach), the centre's tangential velocity, the spin (+
/// gives a -y contact velocity) and the contact's slip since the start.
#[derive(Debug, Clone, Copy)]
struct PlateState {
    x_m: Real,
    xdot_mps: Real,
    vt_mps: Real,
    spin_radps: Real,
    slip_m: Real,
}

/// The time derivative of a [`PlateState`], field by field.
#[derive(Debug, Clone, Copy)]
struct PlateRate {
    xdot_mps: Real,
    xddot_mps2: Real,
    vt_dot_mps2: Real,
    spin_dot_radps2: Real,
    slip_rate_mps: Real,
}

impl PlateState {
    /// `self + h r`.
    fn advanced(&self, r: &PlateRate, h: Real) -> PlateState {
        PlateState {
            x_m: self.x_m + r.xdot_mps * h,
            xdot_mps: self.xdot_mps + r.xddot_mps2 * h,
            vt_mps: self.vt_mps + r.vt_dot_mps2 * h,
            spin_radps: self.spin_radps + r.spin_dot_radps2 * h,
            slip_m: self.slip_m + r.slip_rate_mps * h,
        }
    }

    /// `self + h (k1 + 2 k2 + 2 k3 + k4) / 6`.
    fn advanced_rk4(&self, [k1, k2, k3, k4]: [&PlateRate; 4], h: Real) -> PlateState {
        let mean = |f: fn(&PlateRate) -> Real| h * (f(k1) + 2.0 * f(k2) + 2.0 * f(k3) + f(k4)) / 6.0;
        PlateState {
            x_m: self.x_m + mean(|k| k.xdot_mps),
            xdot_mps: self.xdot_mps + mean(|k| k.xddot_mps2),
            vt_mps: self.vt_mps + mean(|k| k.vt_dot_mps2),
            spin_radps: self.spin_radps + mean(|k| k.spin_dot_radps2),
            slip_m: self.slip_m + mean(|k| k.slip_rate_mps),
        }
    }
}

/// A ball at `speed_mps` and incidence `incidence_deg` (from the normal) on a fixed plate, Maw's rings as the
/// tangential law; a sample every `every` steps of `step_s`. `small_strain` puts the contact point at the
/// ball's undeformed radius, as Maw, Barber and Fawcett's theory does.
pub fn impact(
    small_strain: bool,
    params: &MawParams,
    ball: &BallSpec,
    speed_mps: Real,
    incidence_deg: Real,
    step_s: Real,
    every: usize,
) -> PlateImpact {
    let hertz = Hertz { e_pa: params.e_pa, nu: params.nu, d_s_per_m: params.d_s_per_m };
    let r = ball.radius_m;
    let k = hertz.stiffness(r);
    let (m, i) = (ball.mass_kg, ball.inertia_kg_m2);
    let a = incidence_deg.to_radians();
    let begin = Begin { slip_dir: Vector3::y(), xdot0_mps: speed_mps * a.cos(), k, r_eq_m: r, reduced_mass_kg: m };
    let law = MawRings::new(params, &begin);
    let mut rings = law.initial_state();
    let mut st = PlateState {
        x_m: 0.0,
        xdot_mps: speed_mps * a.cos(),
        vt_mps: speed_mps * a.sin(),
        spin_radps: 0.0,
        slip_m: 0.0,
    };
    let kin = |st: &PlateState, s0: Real| {
        let arm = if small_strain { r } else { r - 0.5 * st.x_m };
        let slip = st.vt_mps - st.spin_radps * arm;
        let f_n = normal_force(k, hertz.d_s_per_m, st.x_m, st.xdot_mps);
        (
            ContactKinematics {
                normal: Vector3::x(),
                x_m: st.x_m,
                xdot_mps: st.xdot_mps,
                normal_force_n: f_n,
                slip_velocity_mps: Vector3::new(0.0, slip, 0.0),
                slip_since_step_m: Vector3::new(0.0, st.slip_m - s0, 0.0),
            },
            arm,
        )
    };
    let rates = |st: &PlateState, s0: Real, rings: &MawState| -> (PlateRate, Real, Real) {
        let (c, arm) = kin(st, s0);
        let f_t = if st.x_m > 0.0 { law.force(&c, rings).y } else { 0.0 };
        let f_n = c.normal_force_n;
        // Friction -y at the contact point (r = -arm x) gives the spin torque -arm * f_t about +z.
        let rate = PlateRate {
            xdot_mps: st.xdot_mps,
            xddot_mps2: -f_n / m,
            vt_dot_mps2: f_t / m,
            spin_dot_radps2: -arm * f_t / i,
            slip_rate_mps: c.slip_velocity_mps.y,
        };
        (rate, f_n, f_t)
    };
    let mut samples = Vec::new();
    let mut steps = 0usize;
    let h = step_s;
    loop {
        let s0 = st.slip_m;
        let (k1, f_n, f_t) = rates(&st, s0, &rings);
        if every > 0 && steps % every == 0 {
            samples.push(PlateSample {
                t_us: steps as Real * h * 1e6,
                normal_force_n: f_n,
                tangential_force_n: -f_t,
                spin_radps: st.spin_radps,
                stuck_rings: law.stuck_rings(&rings).unwrap_or(0),
            });
        }
        if (steps > 0 && st.x_m <= 0.0) || steps > 1_000_000 {
            break;
        }
        let (k2, ..) = rates(&st.advanced(&k1, 0.5 * h), s0, &rings);
        let (k3, ..) = rates(&st.advanced(&k2, 0.5 * h), s0, &rings);
        let (k4, ..) = rates(&st.advanced(&k3, h), s0, &rings);
        st = st.advanced_rk4([&k1, &k2, &k3, &k4], h);
        law.commit(&kin(&st, s0).0, &mut rings);
        steps += 1;
    }
    PlateImpact {
        samples,
        rebound_normal_mps: -st.xdot_mps,
        rebound_contact_tangential_mps: st.vt_mps - st.spin_radps * r,
        spin_radps: st.spin_radps,
        contact_time_s: steps as Real * h,
    }
}

/// Elastic Maw (`d = 0`) on the plate at non-dimensional incidence `psi1`: the rebound `ψ₂`.
pub fn rebound_psi(params: &MawParams, ball: &BallSpec, psi1: Real) -> Real {
    let p = MawParams { d_s_per_m: 0.0, ..*params };
    let ratio = p.hertz().tangential_ratio();
    let tan_a = psi1 * p.mu / ratio;
    let speed = 10.0;
    let incidence_deg = tan_a.atan().to_degrees();
    // A step of 1/2000 of the Hertz contact time keeps the curve converged to 1e-3.
    let k = p.hertz().stiffness(ball.radius_m);
    let v_n = speed * tan_a.atan().cos();
    let x_max = (5.0 * ball.mass_kg * v_n * v_n / (4.0 * k)).powf(0.4);
    let step = 2.94 * x_max / v_n / 2000.0;
    let r = impact(true, &p, ball, speed, incidence_deg, step, 0);
    ratio * r.rebound_contact_tangential_mps / (p.mu * r.rebound_normal_mps)
}
