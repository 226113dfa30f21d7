//! eq. 3.16's Hertz normal force with Hunt-Crossley damping and a tangential law ([`Tangential`]: Maw's rings,
//! Arakawa's eq. 3.23) as one [`ContactLaw`], the Hertzian models' law on the shared assembly.
//!
//! - Geometry: the approach `x` is the overlap of the ball with the face surface along the normal; the contact
//!   point sits on the normal through the ball's centre, [`ContactArm`] from it (`R`, or `R − x/2`). A ball that
//!   touches (`x` down to −1 pm, taken as 0) while the face still approaches is in contact with no force: the
//!   run starts at the first touch. No volume: eq. 3.16 reads the depth.
//! - History: the tangential law's state, and the tangential force it committed at the end of the last step,
//!   which is the next step's first stage (the same instant; recomputing it differs only by rounding, and costs
//!   a law evaluation per step).
//! - The tangential law reads the slip since the step's start ([`ContactLaw::TRACKS_SLIP`]).

use super::hertz::{elastic_energy, normal_force, ContactArm, ContactKinematics, Tangential};
use super::{BallAt, Contact, ContactForce, ContactLaw};
use crate::impact::continuous::club::Head;
use crate::impact::continuous::surface::{FaceSurface, Overlap};
use crate::math::{Real, Vector3};

/// eq. 3.16 with stiffness `k` and damping `d` along the normal, `tangential` in the tangent plane.
#[derive(Debug, Clone, PartialEq)]
pub struct HertzContact<T> {
    /// eq. 3.17's stiffness (N/m^1.5).
    pub k: Real,
    /// Hunt-Crossley damping `d` (s/m).
    pub d_s_per_m: Real,
    /// The friction's lever arm from the ball's centre (`R` or `R − x/2`).
    pub contact_arm: ContactArm,
    /// The tangential law.
    pub tangential: T,
}

/// The tangential law's history and the force it committed last (`None`: apart, or not yet committed).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct HertzState<S> {
    /// The tangential law's history.
    pub tangential: S,
    committed_friction_n: Option<Vector3>,
}

impl<T: Tangential> HertzContact<T> {
    /// The contact as the tangential law reads it.
    #[inline(always)]
    fn kinematics(&self, c: &Contact) -> ContactKinematics {
        ContactKinematics {
            normal: c.normal,
            x_m: c.overlap.depth_m,
            xdot_mps: c.approach_mps,
            normal_force_n: normal_force(self.k, self.d_s_per_m, c.overlap.depth_m, c.approach_mps),
            slip_velocity_mps: c.slip_mps,
            slip_since_step_m: c.slip_since_step_m,
        }
    }

    /// How many rings are stuck in `state` (Maw), if the law has rings.
    pub fn stuck_rings(&self, state: &HertzState<T::State>) -> Option<usize> {
        self.tangential.stuck_rings(&state.tangential)
    }
}

impl<T: Tangential> ContactLaw for HertzContact<T> {
    type State = HertzState<T::State>;
    const TRACKS_SLIP: bool = true;

    fn initial_state(&self) -> Self::State {
        HertzState { tangential: self.tangential.initial_state(), committed_friction_n: None }
    }

    #[inline(always)]
    fn contact(&self, surface: &FaceSurface, head: &Head, ball: &BallAt) -> Option<Contact> {
        let rot = &head.world_from_club;
        let r = ball.radius_m;
        let ball_club = rot.inverse_transform_vector(&(ball.centre_m - head.position_m));
        let (x, normal) = match *surface {
            FaceSurface::Plane { point, normal } => (r - normal.dot(&(ball_club - point)), normal),
            FaceSurface::Sphere { centre, radius_m } => {
                let d = ball_club - centre;
                let dn = d.norm();
                (r + radius_m - dn, d / dn)
            }
        };
        if x < -1e-12 {
            return None;
        }
        let x = x.max(0.0);
        let n = rot * normal;
        let arm_m = self.contact_arm.arm_m(r, x);
        let point = ball.centre_m - arm_m * n;
        let (r_b, r_c) = (point - ball.centre_m, point - head.position_m);
        let v_rel = (ball.velocity_mps + ball.surface_spin_radps.cross(&r_b))
            - (head.velocity_mps + head.angular_velocity_radps.cross(&r_c));
        let xdot = -v_rel.dot(&n);
        if x == 0.0 && xdot <= 0.0 {
            return None; // touching, not pressing
        }
        Some(Contact {
            overlap: Overlap { volume_m3: 0.0, centroid_m: ball_club - arm_m * normal, normal, depth_m: x },
            normal: n,
            r_club_m: r_c,
            r_ball_m: r_b,
            approach_mps: xdot,
            slip_mps: v_rel - v_rel.dot(&n) * n,
            slip_since_step_m: Vector3::zeros(),
        })
    }

    #[inline]
    fn force(&self, c: &Contact, state: &Self::State) -> ContactForce {
        let kin = self.kinematics(c);
        ContactForce { normal_n: kin.normal_force_n, friction_n: self.tangential.force(&kin, &state.tangential) }
    }

    #[inline]
    fn start_force(&self, c: &Contact, state: &Self::State) -> ContactForce {
        match state.committed_friction_n {
            Some(friction_n) => ContactForce {
                normal_n: normal_force(self.k, self.d_s_per_m, c.overlap.depth_m, c.approach_mps),
                friction_n,
            },
            None => self.force(c, state),
        }
    }

    fn commit(&self, contact: Option<&Contact>, state: &mut Self::State, _h: Real) {
        state.committed_friction_n = match contact {
            Some(c) => Some(self.tangential.commit(&self.kinematics(c), &mut state.tangential)),
            None => {
                self.tangential.commit(&ContactKinematics::at_rest(Vector3::zeros()), &mut state.tangential);
                None
            }
        };
    }

    fn refine(&self, c: &Contact, state: &Self::State) -> bool {
        self.tangential.refine(&self.kinematics(c), &state.tangential)
    }

    /// eq. 3.16's elastic part, `(2/5) k x^{5/2}`.
    fn stored_energy_j(&self, _: &FaceSurface, _: Real, overlap: &Overlap) -> Real {
        elastic_energy(self.k, overlap.depth_m)
    }

    fn history_energy_j(&self, state: &Self::State) -> Real {
        self.tangential.stored_energy_j(&state.tangential)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::impact::continuous::law::arakawa::{ArakawaLaw, ArakawaParams};
    use crate::impact::continuous::law::hertz::Begin;
    use crate::math::Rotation3;

    const R_M: Real = 0.0213;

    /// A flat face through the club frame's origin facing +x, the head at rest at the world's origin.
    fn face() -> (FaceSurface, Head) {
        let head = Head {
            position_m: Vector3::zeros(),
            world_from_club: Rotation3::identity(),
            velocity_mps: Vector3::zeros(),
            angular_velocity_radps: Vector3::zeros(),
        };
        (FaceSurface::Plane { point: Vector3::zeros(), normal: Vector3::x() }, head)
    }

    fn law() -> HertzContact<ArakawaLaw> {
        let p = ArakawaParams::IRON7;
        let k = p.hertz().stiffness(R_M);
        let begin = Begin { slip_dir: Vector3::y(), xdot0_mps: 40.0, k, r_eq_m: R_M, reduced_mass_kg: 0.04 };
        HertzContact {
            k,
            d_s_per_m: p.d_s_per_m,
            contact_arm: ContactArm::Radius,
            tangential: ArakawaLaw::new(&p, &begin),
        }
    }

    /// The ball `depth_m` into the face, moving at `v` (m/s) with spin `w` (rad/s).
    fn ball(depth_m: Real, v: Vector3, w: Vector3) -> BallAt {
        BallAt {
            centre_m: Vector3::new(R_M - depth_m, 0.0, 0.0),
            velocity_mps: v,
            surface_spin_radps: w,
            radius_m: R_M,
        }
    }

    /// The force acts on the normal through the ball's centre at the radius (Maw, Barber and Fawcett's arm); the
    /// approach and slip are the contact point's: a ball 1 mm in, moving at −2 m/s along the normal and 3 m/s
    /// along +y, spinning 100 rad/s about −z: `ẋ` = 2 m/s, slip `3 + 100 × 0.0213` = 5.13 m/s along +y.
    #[test]
    fn the_contact_is_on_the_radius_through_the_centre() {
        let (surface, head) = face();
        let c =
            law().contact(&surface, &head, &ball(1e-3, Vector3::new(-2.0, 3.0, 0.0), -100.0 * Vector3::z())).unwrap();
        assert!((c.overlap.depth_m - 1e-3).abs() < 1e-15 && c.normal == Vector3::x());
        assert!((c.r_ball_m + R_M * Vector3::x()).norm() < 1e-15, "{:?}", c.r_ball_m);
        assert!((c.approach_mps - 2.0).abs() < 1e-12);
        assert!((c.slip_mps - Vector3::new(0.0, 3.0 + 100.0 * R_M, 0.0)).norm() < 1e-12, "{:?}", c.slip_mps);
    }

    /// Touching (within 1 pm) while approaching is a contact with no force: the run starts at the first touch;
    /// touching while leaving, or 10 pm apart, is none.
    #[test]
    fn a_touch_counts_only_while_approaching() {
        let (surface, head) = face();
        let law = law();
        let c = law.contact(&surface, &head, &ball(-1e-13, Vector3::new(-1.0, 0.0, 0.0), Vector3::zeros())).unwrap();
        assert_eq!(c.overlap.depth_m, 0.0);
        assert_eq!(law.force(&c, &law.initial_state()).normal_n, 0.0);
        assert!(law.contact(&surface, &head, &ball(-1e-13, Vector3::new(1.0, 0.0, 0.0), Vector3::zeros())).is_none());
        assert!(law.contact(&surface, &head, &ball(-1e-11, Vector3::new(-1.0, 0.0, 0.0), Vector3::zeros())).is_none());
    }

    /// After a commit the next step's first stage takes the committed tangential force; recomputing it at the
    /// same instant (no slip since) gives the same force to rounding (1e-12 relative here), and the normal force
    /// is eq. 3.16's either way.
    #[test]
    fn the_first_stage_takes_the_committed_force() {
        let (surface, head) = face();
        let law = law();
        let mut state = law.initial_state();
        let mut c = law.contact(&surface, &head, &ball(2e-3, Vector3::new(-10.0, 3.0, 0.0), Vector3::zeros())).unwrap();
        assert_eq!(law.start_force(&c, &state), law.force(&c, &state));
        c.slip_since_step_m = 1e-5 * Vector3::y();
        law.commit(Some(&c), &mut state, 1e-6);
        let committed = law.tangential.force(&law.kinematics(&c), &HertzState::<_>::default().tangential);
        let start = law.start_force(&Contact { slip_since_step_m: Vector3::zeros(), ..c }, &state);
        let again = law.force(&Contact { slip_since_step_m: Vector3::zeros(), ..c }, &state);
        assert!(start.friction_n.norm() > 1.0, "{:?}", start.friction_n);
        assert!((start.friction_n - again.friction_n).norm() <= 1e-12 * start.friction_n.norm());
        assert_eq!(start.normal_n, normal_force(law.k, law.d_s_per_m, c.overlap.depth_m, c.approach_mps));
        let nominal = normal_force(law.k, law.d_s_per_m, 2e-3, 10.0);
        assert!((start.normal_n - nominal).abs() < 1e-12 * nominal, "{} vs {nominal}", start.normal_n);
        assert_eq!(start.normal_n, again.normal_n);
        // What the commit found is what the first stage takes (from a fresh state the force on the same slip).
        assert!((start.friction_n - committed).norm() <= 1e-12 * committed.norm(), "{start:?} vs {committed:?}");
        // Out of contact the history is released: the next contact starts from its own force.
        law.commit(None, &mut state, 1e-6);
        assert_eq!(law.start_force(&c, &state), law.force(&c, &state));
        assert_eq!(law.history_energy_j(&state), 0.0);
    }
}
