//! The flexible club's elastic motion in its lowest modes.
//!
//! With the mass-normalised modes `Φ` of the clamped club ([`FlexibleClub::modes`]) the free DOFs are
//! `q = Φ η` and each modal coordinate obeys `η̈ᵢ + 2ζωᵢ η̇ᵢ + ωᵢ² ηᵢ = Φ_tipᵢᵀ f_tip`, `f_tip` the force and moment
//! the head's contacts put on the tip node (shaft frame). Modes above `max_frequency_hz` are dropped; the
//! response converges as the cut-off and the mesh are raised (crates/golf-physics/tests/shaft.rs).

use crate::math::{DMatrix, SMatrix, SVector};

use super::{FlexibleClub, ShaftError};
use crate::math::{Real, Rotation3, Vector3};

/// The most modes kept.
pub const MAX_MODES: usize = 48;
/// A vector of modal coordinates.
pub type ModalVec = SVector<MAX_MODES>;

/// The reduced club.
#[derive(Debug, Clone, PartialEq)]
pub struct ModalClub {
    /// Modes kept.
    pub n_modes: usize,
    /// Natural frequencies (rad/s) of the kept modes; zero beyond `n_modes`.
    pub omega: ModalVec,
    /// Modal damping ratio ζ.
    pub damping_ratio: Real,
    /// The tip node's six DOFs (translation, rotation; shaft frame) per unit modal coordinate.
    pub tip_modes: SMatrix<6, MAX_MODES>,
    /// The club's linear momentum (shaft frame) per unit modal velocity.
    pub momentum_modes: SMatrix<3, MAX_MODES>,
    /// The clamp's reaction force on the shaft (shaft frame) per unit modal coordinate and acceleration.
    pub grip_stiffness_modes: SMatrix<3, MAX_MODES>,
    /// See `grip_stiffness_modes` (per unit modal acceleration).
    pub grip_mass_modes: SMatrix<3, MAX_MODES>,
    /// The shaft frame in the club frame.
    pub club_from_shaft: Rotation3,
    /// The head's CG from the tip, shaft frame (m).
    pub cg_from_tip_shaft_m: Vector3,
}

/// Modal coordinates and velocities.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModalState {
    /// Modal coordinates `η`.
    pub eta: ModalVec,
    /// Their rates `η̇`.
    pub eta_dot: ModalVec,
}

impl Default for ModalState {
    fn default() -> Self {
        ModalState { eta: ModalVec::zeros(), eta_dot: ModalVec::zeros() }
    }
}

/// The head's small displacement relative to the grip's rigid frame, club frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeadOffset {
    /// CG displacement (m) and its rate (m/s).
    pub cg_m: Vector3,
    /// See `cg_m`.
    pub cg_velocity_mps: Vector3,
    /// Small rotation vector (rad) and its rate (rad/s).
    pub rotation_rad: Vector3,
    /// See `rotation_rad`.
    pub angular_velocity_radps: Vector3,
}

/// Sums the translation rows of every node: a 3 x (6 n) selector.
fn translation_sum(dofs: usize) -> DMatrix {
    DMatrix::from_fn(3, dofs, |i, j| if j % 6 == i { 1.0 } else { 0.0 })
}

impl ModalClub {
    /// Keeps the modes of `club` below `max_frequency_hz` (at most [`MAX_MODES`]); `damping_ratio` in [0, 1)
    /// (underdamped modes).
    pub fn new(club: &FlexibleClub, max_frequency_hz: Real, damping_ratio: Real) -> Result<Self, ShaftError> {
        if !(0.0..1.0).contains(&damping_ratio) {
            return Err(ShaftError::Mesh(format!("modal damping ratio {damping_ratio} is not in [0, 1)")));
        }
        let (omega_all, phi) = club.modes()?;
        let n_modes =
            omega_all.iter().take_while(|w| **w / std::f64::consts::TAU <= max_frequency_hz).count().min(MAX_MODES);
        if n_modes == 0 {
            return Err(ShaftError::Mesh(format!("no mode below {max_frequency_hz} Hz")));
        }
        let phi = phi.columns(0, n_modes).into_owned();
        let tip = club.tip_dof();
        let momentum =
            (translation_sum(club.dofs()) * &club.m + translation_sum(club.k_cf.nrows()) * &club.m_cf) * &phi;
        let sc = translation_sum(club.k_cf.nrows());
        let grip_k = &sc * &club.k_cf * &phi;
        let grip_m = &sc * &club.m_cf * &phi;
        let mut out = ModalClub {
            n_modes,
            omega: ModalVec::zeros(),
            damping_ratio,
            tip_modes: SMatrix::zeros(),
            momentum_modes: SMatrix::zeros(),
            grip_stiffness_modes: SMatrix::zeros(),
            grip_mass_modes: SMatrix::zeros(),
            club_from_shaft: club.club_from_shaft,
            cg_from_tip_shaft_m: club.cg_from_tip_shaft_m,
        };
        for c in 0..n_modes {
            out.omega[c] = omega_all[c];
            for i in 0..6 {
                out.tip_modes[(i, c)] = phi[(tip + i, c)];
            }
            for i in 0..3 {
                out.momentum_modes[(i, c)] = momentum[(i, c)];
                out.grip_stiffness_modes[(i, c)] = grip_k[(i, c)];
                out.grip_mass_modes[(i, c)] = grip_m[(i, c)];
            }
        }
        Ok(out)
    }

    /// Modal accelerations under a force `force_club_n` at the head's CG and a torque `torque_club_nm` about it
    /// (both club frame).
    #[inline]
    pub fn acceleration(&self, s: &ModalState, force_club_n: &Vector3, torque_club_nm: &Vector3) -> ModalVec {
        let mut a = self.load(force_club_n, torque_club_nm);
        for i in 0..self.n_modes {
            let w = self.omega[i];
            a[i] = a[i] - w * w * s.eta[i] - 2.0 * self.damping_ratio * w * s.eta_dot[i];
        }
        a
    }

    /// The modal loads `g = Φ_tipᵀ f_tip` of a force `force_club_n` at the head's CG and a torque
    /// `torque_club_nm` about it (both club frame): the accelerations of a club at rest.
    #[inline]
    pub fn load(&self, force_club_n: &Vector3, torque_club_nm: &Vector3) -> ModalVec {
        let f = self.club_from_shaft.inverse_transform_vector(force_club_n);
        let m = self.club_from_shaft.inverse_transform_vector(torque_club_nm) + self.cg_from_tip_shaft_m.cross(&f);
        let load = [f.x, f.y, f.z, m.x, m.y, m.z];
        let mut g = ModalVec::zeros();
        for i in 0..self.n_modes {
            let col = self.tip_modes.column(i);
            let mut gi = 0.0;
            for k in 0..6 {
                gi += col[k] * load[k];
            }
            g[i] = gi;
        }
        g
    }

    /// The head's offset from the rigid club, club frame.
    #[inline]
    pub fn head_offset(&self, s: &ModalState) -> HeadOffset {
        // Column by column (each mode's six tip DOFs as a fixed-size array, so the six sums vectorise).
        let (mut q, mut qd) = ([0.0; 6], [0.0; 6]);
        let n = self.n_modes;
        let cols = self.tip_modes.as_slice().chunks_exact(6);
        for ((col, e), ed) in cols.zip(&s.eta.as_slice()[..n]).zip(&s.eta_dot.as_slice()[..n]) {
            if let Ok(col) = <&[Real; 6]>::try_from(col) {
                for k in 0..6 {
                    q[k] += col[k] * e;
                    qd[k] += col[k] * ed;
                }
            }
        }
        let r = &self.cg_from_tip_shaft_m;
        let (u, phi) = (Vector3::new(q[0], q[1], q[2]), Vector3::new(q[3], q[4], q[5]));
        let (ud, phid) = (Vector3::new(qd[0], qd[1], qd[2]), Vector3::new(qd[3], qd[4], qd[5]));
        let c = &self.club_from_shaft;
        HeadOffset {
            cg_m: c * (u + phi.cross(r)),
            cg_velocity_mps: c * (ud + phid.cross(r)),
            rotation_rad: c * phi,
            angular_velocity_radps: c * phid,
        }
    }

    /// The club's linear momentum from its elastic motion, club frame (N s).
    pub fn momentum(&self, s: &ModalState) -> Vector3 {
        self.club_from_shaft * (self.momentum_modes * s.eta_dot)
    }

    /// The clamp's reaction force on the shaft, club frame (N), given the modal accelerations.
    pub fn grip_force(&self, s: &ModalState, eta_ddot: &ModalVec) -> Vector3 {
        let mut g = Vector3::zeros();
        for i in 0..self.n_modes {
            g += self.grip_stiffness_modes.column(i) * s.eta[i] + self.grip_mass_modes.column(i) * eta_ddot[i];
        }
        self.club_from_shaft * g
    }

    /// Elastic strain plus kinetic energy of the elastic motion (J).
    pub fn energy_j(&self, s: &ModalState) -> Real {
        (0..self.n_modes)
            .map(|i| 0.5 * (s.eta_dot[i] * s.eta_dot[i] + self.omega[i] * self.omega[i] * s.eta[i] * s.eta[i]))
            .sum()
    }
}
