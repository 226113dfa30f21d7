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
    pub contact_arm: ContactArm,
    pub tangential: T,
}

/// The tangential law's history and the force it committed last (`None`: apart, or not yet committed).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct HertzState<S> {
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
