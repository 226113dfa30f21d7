//! The continuous two-layer ball model (seed section 3.2.1, Table 3.5; McNally et al.): the collision resolved
//! in time on a free clubhead.
//!
//! - Ball: a core and a cover of uniform density (cover thickness `t`), sharing translation; their relative
//!   rotation `θ` is resisted by a 3D rotary spring-damper, torque `k_ball θ + c_ball (ω_cover − ω_core)`.
//! - Normal force, eq. 3.14: `F_N = kV + d ẋ kV` along the contact normal, `V` the volume of intersection
//!   (sphere-plane for irons, sphere-sphere with the face sphere for drivers, see [`contact`]), `ẋ` the normal
//!   approach velocity, applied at the centroid of the intersection. Never negative (no adhesion).
//! - Friction, eq. 3.15 (and 2.8, Brown and McPhee): `F_f = μ F_N tanh(4 v_t / v_tr)` on the cover at the
//!   contact, against the relative tangential velocity `v_t`.
//! - Clubhead: a free 6-DOF rigid body (Newton-Euler in its body frame, unit-quaternion attitude); no shaft and no
//!   gravity during the half millisecond of contact.
//!
//! Integration: classical fourth-order Runge-Kutta at a fixed step (default 0.6 us), from first contact until the
//! bodies separate. Forces are equal and opposite at every stage, so linear momentum is conserved to rounding.
//! After separation the ball's spin is its total angular momentum over its total inertia (core and cover keep
//! ringing against each other, exchanging nothing with the outside).
//!
//! Assumptions (seed 3.2.1): the contact never reaches the face's edges; a face whose bulge and roll differ is
//! taken as a sphere of their geometric-mean radius.

pub mod contact;
pub mod ground;
pub mod iron_ground;
pub mod shaft;

use contact::{overlap_energy, FaceSurface};

use super::{Equipment, ImpactError, ImpactModel, ImpactState, Launch};
use crate::equipment::{BallSpec, ClubSpec};
use crate::face::FaceShape;
use crate::math::{Matrix3, Real, UnitQuaternion, Vector3};

/// The parameters of Table 3.5 (units as in `tests/data/seed-tables.toml`).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TwoLayerParams {
    /// Volumetric stiffness `k` (N/m³).
    pub k_v_n_per_m3: Real,
    /// Hunt-Crossley damping `d` (s/m).
    pub d_s_per_m: Real,
    /// Dynamic friction coefficient.
    pub mu: Real,
    /// Rotary spring between core and cover (N m/rad).
    pub k_ball_nm_per_rad: Real,
    /// Rotary damper between core and cover (N m s/rad).
    pub c_ball_nms_per_rad: Real,
    /// Cover thickness (m).
    pub cover_thickness_m: Real,
    /// Friction transition velocity (m/s).
    pub v_tr_mps: Real,
}

impl TwoLayerParams {
    /// Table 3.5, driver.
    pub const DRIVER: TwoLayerParams = TwoLayerParams {
        k_v_n_per_m3: 6.25e9,
        d_s_per_m: 6.42e-3,
        mu: 0.372,
        k_ball_nm_per_rad: 13.5,
        c_ball_nms_per_rad: 2.53e-3,
        cover_thickness_m: 1.26e-3,
        v_tr_mps: 0.936,
    };
    /// Table 3.5, 7-iron.
    pub const IRON7: TwoLayerParams = TwoLayerParams {
        k_v_n_per_m3: 6.83e9,
        d_s_per_m: 9.26e-3,
        mu: 0.489,
        k_ball_nm_per_rad: 34.1,
        c_ball_nms_per_rad: 13.2e-3,
        cover_thickness_m: 2.55e-3,
        v_tr_mps: 0.812,
    };

    /// The preset for a club: the driver's for a curved face, the 7-iron's for a flat one.
    pub fn for_club(club: &ClubSpec) -> Self {
        club.continuous
    }

    /// Checks every parameter, naming a bad one.
    pub fn validate(&self, ball: &BallSpec) -> Result<(), String> {
        let positive = [
            ("k_v_n_per_m3", self.k_v_n_per_m3),
            ("mu", self.mu),
            ("k_ball_nm_per_rad", self.k_ball_nm_per_rad),
            ("cover_thickness_m", self.cover_thickness_m),
            ("v_tr_mps", self.v_tr_mps),
        ];
        for (name, v) in positive {
            if !(v.is_finite() && v > 0.0) {
                return Err(format!("`{name}` must be positive, got {v}"));
            }
        }
        for (name, v) in [("d_s_per_m", self.d_s_per_m), ("c_ball_nms_per_rad", self.c_ball_nms_per_rad)] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(format!("`{name}` must not be negative, got {v}"));
            }
        }
        if self.cover_thickness_m >= ball.radius_m {
            return Err("`cover_thickness_m` must be less than the ball's radius".into());
        }
        Ok(())
    }
}

/// The two-layer ball's split of mass and inertia (uniform density).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TwoLayerBall {
    pub mass_kg: Real,
    pub radius_m: Real,
    pub core_inertia_kg_m2: Real,
    pub cover_inertia_kg_m2: Real,
}

impl TwoLayerBall {
    /// Core of radius `R − t` and cover shell, of one density, with the ball's total inertia split in proportion
    /// to `r⁵` (a uniform sphere's inertia is `(8/15) π ρ r⁵`); the total is the ball's given inertia.
    pub fn new(ball: &BallSpec, cover_thickness_m: Real) -> Self {
        let r_core = ball.radius_m - cover_thickness_m;
        let core_fraction = (r_core / ball.radius_m).powi(5);
        TwoLayerBall {
            mass_kg: ball.mass_kg,
            radius_m: ball.radius_m,
            core_inertia_kg_m2: ball.inertia_kg_m2 * core_fraction,
            cover_inertia_kg_m2: ball.inertia_kg_m2 * (1.0 - core_fraction),
        }
    }
}

/// The integrated state: club position, velocity, attitude and body rate; ball position, velocity, core and
/// cover spins and their relative rotation.
#[derive(Debug, Clone, Copy, PartialEq)]
struct State {
    p_c: Vector3,
    v_c: Vector3,
    q_c: UnitQuaternion,
    w_c_body: Vector3,
    p_b: Vector3,
    v_b: Vector3,
    w_core: Vector3,
    w_cover: Vector3,
    theta: Vector3,
}

#[derive(Debug, Clone, Copy)]
struct Rates {
    v_c: Vector3,
    a_c: Vector3,
    q_dot: nalgebra::Quaternion<Real>,
    alpha_c_body: Vector3,
    v_b: Vector3,
    a_b: Vector3,
    alpha_core: Vector3,
    alpha_cover: Vector3,
    theta_dot: Vector3,
}

/// The forces at one instant, for traces.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ContactForces {
    pub normal_n: Real,
    /// Friction on the ball (N, world).
    pub friction_n: Vector3,
    pub in_contact: bool,
    pub depth_m: Real,
}

/// One sample of a trace.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct TracePoint {
    pub t_us: Real,
    pub normal_force_n: Real,
    /// Friction on the ball along the initial slip direction's opposite (N): positive while it drives the ball's
    /// cover against the slip, negative once it has reversed.
    pub tangential_force_n: Real,
    /// The ball's total spin (rpm) and the cover's (rpm).
    pub ball_spin_rpm: Real,
    pub cover_spin_rpm: Real,
    pub compression_mm: Real,
}

/// What a continuous run gives besides the launch.
#[derive(Debug, Clone, PartialEq)]
pub struct ContinuousResult {
    pub launch: Launch,
    pub contact_time_s: Real,
    pub peak_normal_force_n: Real,
    pub steps: usize,
    pub trace: Vec<TracePoint>,
    /// Total mechanical energy (kinetic + spring + contact) before and after (J).
    pub energy_before_j: Real,
    pub energy_after_j: Real,
    /// Largest increase of the total mechanical energy over any step (J).
    pub max_energy_increase_j: Real,
    /// Linear momentum (N s) and angular momentum about the world origin (N m s) of both bodies, before and
    /// after.
    pub momentum_before: (Vector3, Vector3),
    pub momentum_after: (Vector3, Vector3),
}

/// The continuous two-layer model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContinuousModel {
    /// Parameters; `None` uses the club's own (its preset or its club file's `[continuous]`).
    pub params: Option<TwoLayerParams>,
    /// Integration step (s).
    pub step_s: Real,
    /// Give up after this long in contact (s).
    pub max_contact_s: Real,
}

impl Default for ContinuousModel {
    fn default() -> Self {
        ContinuousModel { params: None, step_s: 0.6e-6, max_contact_s: 3e-3 }
    }
}

struct Setup {
    params: TwoLayerParams,
    ball: TwoLayerBall,
    club_mass: Real,
    club_inertia: Matrix3,
    club_inertia_inv: Matrix3,
    surface: FaceSurface,
}

impl Setup {
    fn forces(&self, s: &State, rot: &nalgebra::Rotation3<Real>) -> (ContactForces, Vector3, Vector3) {
        let club = BodyMotion {
            position_m: s.p_c,
            rotation: *rot,
            velocity_mps: s.v_c,
            angular_velocity_radps: rot * s.w_c_body,
        };
        let ball = BodyMotion {
            position_m: s.p_b,
            rotation: nalgebra::Rotation3::identity(),
            velocity_mps: s.v_b,
            angular_velocity_radps: s.w_cover,
        };
        two_layer_contact(&self.params, self.ball.radius_m, &self.surface, &club, &ball).unwrap_or((
            ContactForces::default(),
            Vector3::zeros(),
            Vector3::zeros(),
        ))
    }

    fn rates(&self, s: &State) -> (Rates, ContactForces) {
        let rot = s.q_c.to_rotation_matrix();
        let (cf, f_ball, r_b) = self.forces(s, &rot);
        let r_c = s.p_b + r_b - s.p_c;
        let torque_club_body = rot.inverse_transform_vector(&r_c.cross(&(-f_ball)));
        let w = s.w_c_body;
        let alpha_c_body = self.club_inertia_inv * (torque_club_body - w.cross(&(self.club_inertia * w)));
        let w_rel = s.w_cover - s.w_core;
        let spring = self.params.k_ball_nm_per_rad * s.theta + self.params.c_ball_nms_per_rad * w_rel;
        let q_dot = s.q_c.quaternion() * nalgebra::Quaternion::from_imag(w) * 0.5;
        (
            Rates {
                v_c: s.v_c,
                a_c: -f_ball / self.club_mass,
                q_dot,
                alpha_c_body,
                v_b: s.v_b,
                a_b: f_ball / self.ball.mass_kg,
                alpha_core: spring / self.ball.core_inertia_kg_m2,
                alpha_cover: (r_b.cross(&f_ball) - spring) / self.ball.cover_inertia_kg_m2,
                theta_dot: w_rel,
            },
            cf,
        )
    }

    fn momentum(&self, s: &State) -> (Vector3, Vector3) {
        let rot = s.q_c.to_rotation_matrix();
        let linear = self.club_mass * s.v_c + self.ball.mass_kg * s.v_b;
        let angular = self.club_mass * s.p_c.cross(&s.v_c)
            + rot * (self.club_inertia * s.w_c_body)
            + self.ball.mass_kg * s.p_b.cross(&s.v_b)
            + self.ball.core_inertia_kg_m2 * s.w_core
            + self.ball.cover_inertia_kg_m2 * s.w_cover;
        (linear, angular)
    }

    fn energy(&self, s: &State) -> Real {
        let ke_club =
            0.5 * self.club_mass * s.v_c.norm_squared() + 0.5 * s.w_c_body.dot(&(self.club_inertia * s.w_c_body));
        let ke_ball = 0.5 * self.ball.mass_kg * s.v_b.norm_squared()
            + 0.5 * self.ball.core_inertia_kg_m2 * s.w_core.norm_squared()
            + 0.5 * self.ball.cover_inertia_kg_m2 * s.w_cover.norm_squared();
        let spring = 0.5 * self.params.k_ball_nm_per_rad * s.theta.norm_squared();
        let rot = s.q_c.to_rotation_matrix();
        let ball_club = rot.inverse_transform_vector(&(s.p_b - s.p_c));
        let contact = self
            .surface
            .overlap(&ball_club, self.ball.radius_m)
            .map(|o| self.params.k_v_n_per_m3 * overlap_energy(&self.surface, self.ball.radius_m, o.depth_m))
            .unwrap_or(0.0);
        ke_club + ke_ball + spring + contact
    }
}

/// A rigid body's pose and velocity at one instant (world frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyMotion {
    pub position_m: Vector3,
    pub rotation: nalgebra::Rotation3<Real>,
    pub velocity_mps: Vector3,
    pub angular_velocity_radps: Vector3,
}

/// The face's contact with the two-layer ball's cover (eq. 3.14-3.15): `club` the head (CG and attitude),
/// `ball` the ball's centre and its cover's spin. Returns the forces, the force on the ball (world) and the
/// ball centre -> contact lever; `None` when apart.
pub fn two_layer_contact(
    params: &TwoLayerParams,
    ball_radius_m: Real,
    surface: &FaceSurface,
    club: &BodyMotion,
    ball: &BodyMotion,
) -> Option<(ContactForces, Vector3, Vector3)> {
    let rot = &club.rotation;
    let ball_club = rot.inverse_transform_vector(&(ball.position_m - club.position_m));
    let o = surface.overlap(&ball_club, ball_radius_m)?;
    let n = rot * o.normal;
    let r_c = rot * o.centroid_m; // club CG -> contact (world)
    let point = club.position_m + r_c;
    let r_b = point - ball.position_m; // ball centre -> contact
    let v_club = club.velocity_mps + club.angular_velocity_radps.cross(&r_c);
    let v_ball = ball.velocity_mps + ball.angular_velocity_radps.cross(&r_b);
    let approach = (v_club - v_ball).dot(&n);
    let normal = (params.k_v_n_per_m3 * o.volume_m3 * (1.0 + params.d_s_per_m * approach)).max(0.0);
    let v_rel = v_ball - v_club;
    let v_t = v_rel - v_rel.dot(&n) * n;
    let speed_t = v_t.norm();
    let friction = if speed_t > 1e-12 {
        -(params.mu * normal * (4.0 * speed_t / params.v_tr_mps).tanh() / speed_t) * v_t
    } else {
        Vector3::zeros()
    };
    Some((
        ContactForces { normal_n: normal, friction_n: friction, in_contact: true, depth_m: o.depth_m },
        normal * n + friction,
        r_b,
    ))
}

fn advance(s: &State, r: &Rates, h: Real) -> State {
    State {
        p_c: s.p_c + r.v_c * h,
        v_c: s.v_c + r.a_c * h,
        q_c: UnitQuaternion::new_unchecked(s.q_c.quaternion() + r.q_dot * h),
        w_c_body: s.w_c_body + r.alpha_c_body * h,
        p_b: s.p_b + r.v_b * h,
        v_b: s.v_b + r.a_b * h,
        w_core: s.w_core + r.alpha_core * h,
        w_cover: s.w_cover + r.alpha_cover * h,
        theta: s.theta + r.theta_dot * h,
    }
}

fn combine(k1: &Rates, k2: &Rates, k3: &Rates, k4: &Rates) -> Rates {
    let c = |a: Vector3, b: Vector3, c: Vector3, d: Vector3| (a + 2.0 * b + 2.0 * c + d) / 6.0;
    Rates {
        v_c: c(k1.v_c, k2.v_c, k3.v_c, k4.v_c),
        a_c: c(k1.a_c, k2.a_c, k3.a_c, k4.a_c),
        q_dot: (k1.q_dot + k2.q_dot * 2.0 + k3.q_dot * 2.0 + k4.q_dot) / 6.0,
        alpha_c_body: c(k1.alpha_c_body, k2.alpha_c_body, k3.alpha_c_body, k4.alpha_c_body),
        v_b: c(k1.v_b, k2.v_b, k3.v_b, k4.v_b),
        a_b: c(k1.a_b, k2.a_b, k3.a_b, k4.a_b),
        alpha_core: c(k1.alpha_core, k2.alpha_core, k3.alpha_core, k4.alpha_core),
        alpha_cover: c(k1.alpha_cover, k2.alpha_cover, k3.alpha_cover, k4.alpha_cover),
        theta_dot: c(k1.theta_dot, k2.theta_dot, k3.theta_dot, k4.theta_dot),
    }
}

impl ContinuousModel {
    /// The face surface for the normal force: the plane for a flat face, the face sphere for a curved one.
    pub fn surface(club: &ClubSpec) -> FaceSurface {
        let face = &club.face;
        match face.shape {
            FaceShape::Plane => FaceSurface::Plane { point: face.center_m, normal: face.n0() },
            FaceShape::Torus { bulge_radius_m, roll_radius_m } => {
                let radius_m = if bulge_radius_m.is_finite() && roll_radius_m.is_finite() {
                    (bulge_radius_m * roll_radius_m).sqrt()
                } else {
                    bulge_radius_m.min(roll_radius_m)
                };
                FaceSurface::Sphere { centre: face.center_m - radius_m * face.n0(), radius_m }
            }
        }
    }

    /// Runs the collision, optionally recording a trace every `trace_every` steps (0: no trace).
    pub fn simulate(
        &self,
        state: &ImpactState,
        equipment: &Equipment,
        trace_every: usize,
    ) -> Result<ContinuousResult, ImpactError> {
        let club = &equipment.club;
        let params = self.params.unwrap_or(club.continuous);
        params.validate(&equipment.ball).map_err(|reason| ImpactError::NotConverged { model: "continuous", reason })?;
        if !club.on_face(state.impact_h_m, state.impact_v_m) {
            return Err(ImpactError::OffFace { h_mm: state.impact_h_m * 1e3, v_mm: state.impact_v_m * 1e3 });
        }
        let surface = Self::surface(club);
        let setup = Setup {
            params,
            ball: TwoLayerBall::new(&equipment.ball, params.cover_thickness_m),
            club_mass: club.mass_kg,
            club_inertia: club.inertia_kg_m2,
            club_inertia_inv: club.inertia_inv_kg_m2,
            surface,
        };
        // The ball rests touching the face surface at the impact location.
        let contact = club.face.contact(state.impact_h_m, state.impact_v_m)?;
        let ball_club = match surface {
            FaceSurface::Plane { .. } => contact.point_m + equipment.ball.radius_m * contact.normal,
            FaceSurface::Sphere { centre, radius_m } => {
                let dir = (contact.point_m - centre).normalize();
                centre + (radius_m + equipment.ball.radius_m) * dir
            }
        };
        let iso = state.world_from_club;
        let rot = iso.rotation;
        let mut s = State {
            p_c: iso.translation.vector,
            v_c: state.cg_velocity_mps,
            q_c: rot,
            w_c_body: rot.inverse_transform_vector(&state.angular_velocity_radps),
            p_b: iso.translation.vector + rot * ball_club,
            v_b: Vector3::zeros(),
            w_core: Vector3::zeros(),
            w_cover: Vector3::zeros(),
            theta: Vector3::zeros(),
        };
        let n0 = rot * contact.normal;
        let v_contact0 = state.cg_velocity_mps + state.angular_velocity_radps.cross(&(rot * contact.point_m));
        if v_contact0.dot(&n0) <= 0.0 {
            return Err(ImpactError::NotApproaching);
        }
        // The direction the friction first pushes the ball's cover: along the club's tangential motion.
        let slip0 = {
            let t = v_contact0 - v_contact0.dot(&n0) * n0;
            if t.norm() > 1e-9 {
                t.normalize()
            } else {
                rot * club.face.u0()
            }
        };
        let energy_before = setup.energy(&s);
        let momentum_before = setup.momentum(&s);
        let h = self.step_s;
        let max_steps = (self.max_contact_s / h).ceil() as usize;
        let mut trace = Vec::new();
        let mut peak = 0.0f64;
        let mut touched = false;
        let mut steps = 0;
        let mut max_increase = 0.0f64;
        let mut energy = energy_before;
        let mut contact_time = 0.0;
        let record = |t: Real, s: &State, cf: &ContactForces, trace: &mut Vec<TracePoint>| {
            let total = (setup.ball.core_inertia_kg_m2 * s.w_core + setup.ball.cover_inertia_kg_m2 * s.w_cover)
                / (setup.ball.core_inertia_kg_m2 + setup.ball.cover_inertia_kg_m2);
            trace.push(TracePoint {
                t_us: t * 1e6,
                normal_force_n: cf.normal_n,
                tangential_force_n: cf.friction_n.dot(&slip0),
                ball_spin_rpm: crate::units::radps_to_rpm(total.norm()),
                cover_spin_rpm: crate::units::radps_to_rpm(s.w_cover.norm()),
                compression_mm: cf.depth_m * 1e3,
            });
        };
        loop {
            let (k1, cf) = setup.rates(&s);
            if trace_every > 0 && steps % trace_every == 0 {
                record(steps as Real * h, &s, &cf, &mut trace);
            }
            peak = peak.max(cf.normal_n);
            if cf.in_contact {
                touched = true;
            } else if touched || steps > 10 {
                // Separated (or, after a few steps, never in contact: the face moves off).
                if touched {
                    contact_time = steps as Real * h;
                }
                break;
            }
            if steps >= max_steps {
                return Err(ImpactError::NotConverged {
                    model: "continuous",
                    reason: format!("still in contact after {:.2} ms", self.max_contact_s * 1e3),
                });
            }
            let (k2, _) = setup.rates(&advance(&s, &k1, 0.5 * h));
            let (k3, _) = setup.rates(&advance(&s, &k2, 0.5 * h));
            let (k4, _) = setup.rates(&advance(&s, &k3, h));
            s = advance(&s, &combine(&k1, &k2, &k3, &k4), h);
            s.q_c = UnitQuaternion::new_normalize(s.q_c.into_inner());
            steps += 1;
            if trace_every > 0 || cfg!(debug_assertions) {
                let e = setup.energy(&s);
                max_increase = max_increase.max(e - energy);
                energy = e;
            }
        }
        if !touched {
            return Err(ImpactError::NotConverged {
                model: "continuous",
                reason: "the face never pressed the ball".into(),
            });
        }
        let ball = &setup.ball;
        let spin = (ball.core_inertia_kg_m2 * s.w_core + ball.cover_inertia_kg_m2 * s.w_cover)
            / (ball.core_inertia_kg_m2 + ball.cover_inertia_kg_m2);
        let rot = s.q_c.to_rotation_matrix();
        Ok(ContinuousResult {
            launch: Launch {
                ball_velocity_mps: s.v_b,
                ball_spin_radps: spin,
                club_velocity_mps: s.v_c,
                club_angular_velocity_radps: rot * s.w_c_body,
                impulse_ns: ball.mass_kg * s.v_b,
            },
            contact_time_s: contact_time,
            peak_normal_force_n: peak,
            steps,
            trace,
            energy_before_j: energy_before,
            energy_after_j: setup.energy(&s),
            max_energy_increase_j: max_increase,
            momentum_before,
            momentum_after: setup.momentum(&s),
        })
    }
}

impl ImpactModel for ContinuousModel {
    fn name(&self) -> &'static str {
        "continuous/two_layer"
    }

    fn predict(&self, state: &ImpactState, equipment: &Equipment) -> Result<Launch, ImpactError> {
        self.simulate(state, equipment, 0).map(|r| r.launch)
    }
}
