//! Ball flight: carry, apex, landing and offline from launch conditions, then bounce and roll to rest (the
//! seed's section 4.3 uses an aerodynamic model for the same purpose, Figures 4.16-4.17).
//!
//! A point mass with gravity, drag and Magnus lift, and a decaying spin:
//!
//! - `m dv/dt = m g − ½ ρ A C_D |u| u + ½ ρ A C_L |u|² (ŵ × û)`, with `u = v − wind` the air-relative velocity and
//!   `ŵ` the spin axis (the lift is perpendicular to both).
//! - `C_D(Re, S)` and `C_L(Re, S)` from the Reynolds number `Re = ρ |u| d / μ` and the spin ratio `S = r |ω| / |u|`
//!   ([`aero`]: six physical numbers, fitted to the TrackMan tour averages by [`fit`], their curves checked against
//!   wind-tunnel and free-flight measurements in `docs/flight.md`).
//! - `dω/dt = −(ω / τ) (|u| / 50 m/s)`: spin decays in proportion to the airspeed, with time constant `τ` = 22 s at
//!   50 m/s, Smits and Smith's measured decay ([`aero::SPIN_TAU_S`]).
//! - Air density and viscosity from temperature, pressure, humidity and altitude ([`air`]); a uniform wind.
//! - After landing, bounces and the roll on a fairway of configurable firmness ([`turf`], Penner's model).
//!
//! Integration: classical Runge-Kutta at 100 ms with the landing found exactly on the cubic Hermite interpolant of
//! the last step (position and velocity at both ends) crossing the ground plane `y = 0` (within 1 cm of a
//! 0.05 ms reference over drives, irons and wedges); the apex is the peak of the same interpolant over the step
//! where the ball turns down.

pub mod aero;
pub mod air;
pub mod cv;
pub mod envelope;
pub mod fit;
pub mod reference;
pub mod tradeoff;
pub mod turf;

pub use aero::Aero;
pub use air::{Conditions, ConditionsError};
pub use turf::{Turf, TurfError};

use crate::equipment::BallSpec;
use crate::integrate::{rk4_step, Ode};
use crate::math::{Real, Vector3};
use crate::units::m_to_yd;

/// Standard gravity (m/s²).
pub const G: Real = 9.80665;

/// The ball leaving the face.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LaunchState {
    /// Ball velocity (m/s, world).
    pub velocity_mps: Vector3,
    /// Ball angular velocity (rad/s, world).
    pub spin_radps: Vector3,
}

impl LaunchState {
    /// From TrackMan numbers: speed (m/s), launch angle and direction (deg), backspin and sidespin (rpm).
    pub fn from_metrics(
        speed_mps: Real,
        launch_deg: Real,
        direction_deg: Real,
        backspin_rpm: Real,
        sidespin_rpm: Real,
    ) -> Self {
        let m = crate::impact::LaunchMetrics {
            ball_speed_mps: speed_mps,
            ball_speed_mph: crate::units::mps_to_mph(speed_mps),
            launch_angle_deg: launch_deg,
            launch_direction_deg: direction_deg,
            backspin_rpm,
            sidespin_rpm,
            total_spin_rpm: backspin_rpm.hypot(sidespin_rpm),
            spin_axis_deg: sidespin_rpm.atan2(backspin_rpm).to_degrees(),
        };
        LaunchState { velocity_mps: m.velocity_mps(), spin_radps: m.spin_vector_radps() }
    }
}

/// The highest value of the cubic Hermite interpolant through `(0, y0, v0)` and `(h, y1, v1)`.
fn hermite_peak(y0: Real, v0: Real, y1: Real, v1: Real, h: Real) -> Real {
    // y(u) = a u³ + b u² + c u + d on u in [0, 1]; y'(u) = 3a u² + 2b u + c.
    let (c, d) = (h * v0, y0);
    let a = 2.0 * y0 + h * v0 - 2.0 * y1 + h * v1;
    let b = -3.0 * y0 - 2.0 * h * v0 + 3.0 * y1 - h * v1;
    let y = |u: Real| ((a * u + b) * u + c) * u + d;
    let mut best = y0.max(y1);
    let disc = 4.0 * b * b - 12.0 * a * c;
    let roots = if a.abs() < 1e-15 {
        if b.abs() > 1e-15 {
            [-c / (2.0 * b), f64::NAN]
        } else {
            [f64::NAN; 2]
        }
    } else if disc >= 0.0 {
        let q = disc.sqrt();
        [(-2.0 * b + q) / (6.0 * a), (-2.0 * b - q) / (6.0 * a)]
    } else {
        [f64::NAN; 2]
    };
    for u in roots {
        if (0.0..=1.0).contains(&u) {
            best = best.max(y(u));
        }
    }
    best
}

/// Where and how the ball lands.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
pub struct Trajectory {
    /// Horizontal distance from the launch point to where the ball lands (m).
    pub carry_m: Real,
    /// `carry_m` in yards.
    pub carry_yd: Real,
    /// Distance right (+) or left (−) of the target line at landing.
    pub offline_m: Real,
    /// `offline_m` in yards.
    pub offline_yd: Real,
    /// Highest point above the ground (m).
    pub apex_m: Real,
    /// `apex_m` in yards.
    pub apex_yd: Real,
    /// Time from launch to landing (s).
    pub hang_time_s: Real,
    /// Angle of descent below the horizontal at landing (deg).
    pub land_angle_deg: Real,
    /// Ball speed at landing (m/s).
    pub land_speed_mps: Real,
    /// Where the ball comes to rest after bouncing and rolling, from the launch point.
    pub total_m: Real,
    /// `total_m` in yards.
    pub total_yd: Real,
    /// How far the ball ran from its landing point to rest along its line of travel (negative: spun back).
    pub roll_m: Real,
    /// `roll_m` in yards.
    pub roll_yd: Real,
    /// Sampled positions `[t_s, x_m, y_m, z_m]` in the air and on the ground, when asked for.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub points: Vec<[Real; 4]>,
}

/// The flight model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Flight {
    /// Drag and lift coefficients ([`aero`]).
    pub aero: Aero,
    /// The air and the wind ([`air`]).
    pub conditions: Conditions,
    /// The ball's mass and radius.
    pub ball: BallSpec,
    /// The turf the ball lands, bounces and rolls on.
    pub turf: Turf,
    /// Integration step (s).
    pub step_s: Real,
}

impl Default for Flight {
    fn default() -> Self {
        Flight {
            aero: Aero::FITTED,
            conditions: Conditions::default(),
            ball: BallSpec::SEED,
            turf: Turf::default(),
            step_s: 0.1,
        }
    }
}

/// The ball in the air as an ODE for the shared integrator.
struct Air<'a> {
    flight: &'a Flight,
    env: &'a Env,
}

impl Ode for Air<'_> {
    type State = S;
    type Rate = (Vector3, Vector3, Vector3);

    #[inline]
    fn rate(&self, s: &S) -> Self::Rate {
        let (a, dw) = self.flight.accel(self.env, s);
        (s.v, a, dw)
    }

    #[inline]
    fn advance(s: &S, k: &Self::Rate, c: Real) -> S {
        S { p: s.p + k.0 * c, v: s.v + k.1 * c, w: s.w + k.2 * c }
    }

    #[inline]
    fn advance_rk4(s: &S, k: [&Self::Rate; 4], h: Real) -> S {
        let [k1, k2, k3, k4] = k;
        S {
            p: s.p + (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0) * (h / 6.0),
            v: s.v + (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1) * (h / 6.0),
            w: s.w + (k1.2 + 2.0 * k2.2 + 2.0 * k3.2 + k4.2) * (h / 6.0),
        }
    }
}

#[derive(Clone, Copy)]
struct S {
    p: Vector3,
    v: Vector3,
    w: Vector3,
}

struct Env {
    k: Real, // ½ ρ A / m
    r: Real,
    /// Reynolds number per m/s of airspeed: ρ d / μ.
    re_per_mps: Real,
    wind: Vector3,
}

impl Flight {
    fn env(&self) -> Env {
        let rho = self.conditions.density_kg_m3();
        let r = self.ball.radius_m;
        let area = std::f64::consts::PI * r * r;
        Env {
            k: 0.5 * rho * area / self.ball.mass_kg,
            r,
            re_per_mps: aero::reynolds(1.0, 2.0 * r, rho, self.conditions.viscosity_pa_s()),
            wind: self.conditions.wind_mps(),
        }
    }

    #[inline]
    fn accel(&self, env: &Env, s: &S) -> (Vector3, Vector3) {
        let u = s.v - env.wind;
        let speed = u.norm();
        let mut a = Vector3::new(0.0, -G, 0.0);
        if speed > 1e-9 {
            let w = s.w.norm();
            let spin_ratio = env.r * w / speed;
            let (drag, lift) = self.aero.coefficients(env.re_per_mps * speed, spin_ratio);
            a -= env.k * drag * speed * u;
            if w > 1e-9 {
                let lift_dir = s.w.cross(&u) / (w * speed);
                a += env.k * lift * speed * speed * lift_dir;
            }
        }
        (a, -s.w * (speed / (50.0 * self.aero.spin_tau_s)))
    }

    fn step(&self, env: &Env, s: &S, h: Real) -> S {
        let system = Air { flight: self, env };
        let k1 = system.rate(s);
        rk4_step(&system, s, &k1, h)
    }

    /// Flies a ball launched from the ground at the origin; `sample_every_s` > 0 records the path.
    pub fn fly(&self, launch: &LaunchState, sample_every_s: Real) -> Trajectory {
        let env = self.env();
        let h = self.step_s;
        let mut s = S { p: Vector3::zeros(), v: launch.velocity_mps, w: launch.spin_radps };
        let mut t = 0.0;
        let mut apex: Real = 0.0;
        let mut points = Vec::new();
        let mut next_sample = 0.0;
        if sample_every_s > 0.0 {
            points.push([0.0, 0.0, 0.0, 0.0]);
            next_sample = sample_every_s;
        }
        // Position on the cubic Hermite interpolant of one step (position and velocity at both ends), `u` in [0, 1].
        let hermite = |x0: Real, v0: Real, x1: Real, v1: Real, u: Real| {
            let (u2, u3) = (u * u, u * u * u);
            (2.0 * u3 - 3.0 * u2 + 1.0) * x0
                + (u3 - 2.0 * u2 + u) * h * v0
                + (-2.0 * u3 + 3.0 * u2) * x1
                + (u3 - u2) * h * v1
        };
        let point_at = |a: &S, b: &S, u: Real| {
            [
                hermite(a.p.x, a.v.x, b.p.x, b.v.x, u),
                hermite(a.p.y, a.v.y, b.p.y, b.v.y, u),
                hermite(a.p.z, a.v.z, b.p.z, b.v.z, u),
            ]
        };
        let landed = loop {
            let n = self.step(&env, &s, h);
            if n.p.y < 0.0 && (t > 0.0 || n.v.y < 0.0) {
                break Some((s, n));
            }
            if s.v.y > 0.0 && n.v.y <= 0.0 {
                apex = apex.max(hermite_peak(s.p.y, s.v.y, n.p.y, n.v.y, h));
            }
            // The sampled path at the requested spacing, on the step's interpolant.
            while sample_every_s > 0.0 && next_sample <= t + h {
                let [x, y, z] = point_at(&s, &n, (next_sample - t) / h);
                points.push([next_sample, x, y, z]);
                next_sample += sample_every_s;
            }
            t += h;
            s = n;
            apex = apex.max(s.p.y);
            if t > 60.0 {
                break None;
            }
        };
        let Some((a, b)) = landed else {
            return Trajectory {
                carry_m: f64::NAN,
                carry_yd: f64::NAN,
                offline_m: f64::NAN,
                offline_yd: f64::NAN,
                apex_m: apex,
                apex_yd: m_to_yd(apex),
                hang_time_s: t,
                land_angle_deg: f64::NAN,
                land_speed_mps: f64::NAN,
                total_m: f64::NAN,
                total_yd: f64::NAN,
                roll_m: f64::NAN,
                roll_yd: f64::NAN,
                points,
            };
        };
        // The landing on the last step's interpolant: y = 0 by Newton from the linear guess.
        let dhermite = |x0: Real, v0: Real, x1: Real, v1: Real, u: Real| {
            let u2 = u * u;
            ((6.0 * u2 - 6.0 * u) * x0
                + (3.0 * u2 - 4.0 * u + 1.0) * h * v0
                + (-6.0 * u2 + 6.0 * u) * x1
                + (3.0 * u2 - 2.0 * u) * h * v1)
                / h
        };
        let mut u = a.p.y / (a.p.y - b.p.y);
        for _ in 0..8 {
            let y = hermite(a.p.y, a.v.y, b.p.y, b.v.y, u);
            let dy = dhermite(a.p.y, a.v.y, b.p.y, b.v.y, u) * h;
            if dy.abs() < 1e-15 {
                break;
            }
            u = (u - y / dy).clamp(0.0, 1.0);
        }
        let x = hermite(a.p.x, a.v.x, b.p.x, b.v.x, u);
        let z = hermite(a.p.z, a.v.z, b.p.z, b.v.z, u);
        let v_land = Vector3::new(
            dhermite(a.p.x, a.v.x, b.p.x, b.v.x, u),
            dhermite(a.p.y, a.v.y, b.p.y, b.v.y, u),
            dhermite(a.p.z, a.v.z, b.p.z, b.v.z, u),
        );
        let t_land = t + u * h;
        if sample_every_s > 0.0 {
            while next_sample < t_land {
                let [x, y, z] = point_at(&a, &b, (next_sample - t) / h);
                points.push([next_sample, x, y, z]);
                next_sample += sample_every_s;
            }
            points.push([t_land, x, 0.0, z]);
        }
        // The run: along the landing's horizontal direction, with the backspin about the horizontal axis across it.
        let horizontal = v_land.x.hypot(v_land.z);
        let heading = if horizontal > 1e-9 {
            Vector3::new(v_land.x / horizontal, 0.0, v_land.z / horizontal)
        } else {
            Vector3::x()
        };
        let w_land = a.w + (b.w - a.w) * u;
        let backspin = w_land.dot(&heading.cross(&Vector3::y()));
        let run = self.turf.run(horizontal, -v_land.y, backspin, self.ball.radius_m, G, t_land);
        if sample_every_s > 0.0 {
            for seg in &run.segments {
                while next_sample < seg.t0_s + seg.duration_s {
                    let (d, y) = seg.at(next_sample - seg.t0_s, G);
                    points.push([next_sample, x + d * heading.x, y, z + d * heading.z]);
                    next_sample += sample_every_s;
                }
            }
            points.push([t_land + run.duration_s, x + run.roll_m * heading.x, 0.0, z + run.roll_m * heading.z]);
        }
        let total = (x + run.roll_m * heading.x).hypot(z + run.roll_m * heading.z);
        Trajectory {
            carry_m: x.hypot(z),
            carry_yd: m_to_yd(x.hypot(z)),
            offline_m: z,
            offline_yd: m_to_yd(z),
            apex_m: apex,
            apex_yd: m_to_yd(apex),
            hang_time_s: t_land,
            land_angle_deg: (-v_land.y).atan2(horizontal).to_degrees(),
            land_speed_mps: v_land.norm(),
            total_m: total,
            total_yd: m_to_yd(total),
            roll_m: run.roll_m,
            roll_yd: m_to_yd(run.roll_m),
            points,
        }
    }

    /// Flies from TrackMan numbers.
    pub fn fly_metrics(
        &self,
        speed_mps: Real,
        launch_deg: Real,
        direction_deg: Real,
        backspin_rpm: Real,
        sidespin_rpm: Real,
    ) -> Trajectory {
        self.fly(&LaunchState::from_metrics(speed_mps, launch_deg, direction_deg, backspin_rpm, sidespin_rpm), 0.0)
    }
}
