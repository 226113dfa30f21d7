//! The club on a flexible shaft (seed section 4.1, eq. 4.1-4.2): the head rigidly on the tip of a tapered steel
//! shaft whose butt is driven kinematically.
//!
//! - Discretisation: beam finite elements ([`beam`]): bending in both planes (eq. 4.1's `EI`), torsion (eq. 4.2's
//!   `GJ`) and stretch, consistent mass; stations of Table 4.2 are nodes. The head (mass, Table 3.1 inertia) is a
//!   rigid body on the tip node, at the club frame's CG, the tip at the hosel ([`SoleSpec`]).
//! - Boundary: every DOF of the nodes within `clamp_m` of the butt is fixed (0 for the driven grip end; a club
//!   fitter's frequency meter clamps 5 in = 0.127 m of the butt).
//! - Dynamics ([`modal`]): the elastic motion relative to the grip's moving frame, in the lowest modes of the
//!   clamped club (mass-normalised, `ΦᵀMΦ = 1`, `ΦᵀKΦ = ω²`), driven by the forces on the head.
//!
//! Assumptions: small elastic displacements and rotations relative to the grip frame; the frame's own rotation
//! does not act on the elastic motion (no Coriolis, centrifugal stiffening or softening: the swing turns the club
//! by ~0.2 rad during the few milliseconds of ground contact), so the undisturbed swing's shaft bend is part of
//! the delivered head pose and only the contact forces bend the shaft further; no structural damping.

pub mod beam;
pub mod exponential;
pub mod grip;
pub mod modal;

use crate::math::{DMatrix, DVector};

use crate::equipment::shaft::ShaftSpec;
use crate::equipment::sole::SoleSpec;
use crate::equipment::ClubSpec;
use crate::math::{skew, Matrix3, Real, Rotation3, Vector3};

/// Errors of the flexible club.
#[derive(Debug, thiserror::Error)]
pub enum ShaftError {
    /// The shaft's or the sole's specification refused.
    #[error("shaft: {0}")]
    Equipment(#[from] crate::equipment::EquipmentError),
    /// A mesh the shaft's stations cannot take.
    #[error("shaft mesh: {0}")]
    Mesh(String),
    /// The assembled matrices are not positive definite.
    #[error("shaft matrices are not positive definite")]
    NotPositiveDefinite,
}

/// The shaft's discretisation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShaftMesh {
    /// Number of beam elements along the shaft (at least one per segment).
    pub elements: usize,
    /// Length of the butt held fixed (m).
    pub clamp_m: Real,
}

impl Default for ShaftMesh {
    fn default() -> Self {
        ShaftMesh { elements: 12, clamp_m: 0.0 }
    }
}

/// The head as the shaft carries it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeadOnShaft {
    /// The head's mass (kg).
    pub mass_kg: Real,
    /// Inertia about the CG, club frame (kg m²).
    pub inertia_kg_m2: Matrix3,
}

impl HeadOnShaft {
    /// The head of `club` alone (the shaft's share of a free head's mass left out).
    pub fn of(club: &ClubSpec) -> Self {
        // The head alone: this model carries the shaft, so not the share a free head is given for it.
        HeadOnShaft { mass_kg: club.mass_kg, inertia_kg_m2: club.head_inertia_kg_m2() }
    }
}

/// The assembled club: shaft elements, head on the tip, butt clamped; its matrices over the free DOFs.
#[derive(Debug, Clone)]
pub struct FlexibleClub {
    /// Node positions from the butt (m).
    pub nodes_m: Vec<Real>,
    /// Index of the first free node.
    pub first_free: usize,
    /// Stiffness and mass over the free DOFs (6 per free node, butt to tip).
    pub k: DMatrix,
    /// See `k`.
    pub m: DMatrix,
    /// Rows of the clamped DOFs against the free ones: the clamp's reaction is `K_cf q + M_cf q̈`.
    pub k_cf: DMatrix,
    /// See `k_cf`.
    pub m_cf: DMatrix,
    /// The shaft frame in the club frame (x from butt to tip, y the club's forward, z = x × y).
    pub club_from_shaft: Rotation3,
    /// The tip (hosel) and the butt in the club frame (m).
    pub tip_m: Vector3,
    /// See `tip_m`.
    pub butt_m: Vector3,
    /// The head's CG from the tip, shaft frame (m).
    pub cg_from_tip_shaft_m: Vector3,
}

impl FlexibleClub {
    /// Assembles the club: `shaft` on `head`, mounted as `sole` says.
    pub fn new(shaft: &ShaftSpec, head: &HeadOnShaft, sole: &SoleSpec, mesh: ShaftMesh) -> Result<Self, ShaftError> {
        shaft.validate()?;
        sole.validate()?;
        let length = shaft.length_m();
        if mesh.elements < shaft.stations.len() - 1 {
            return Err(ShaftError::Mesh(format!("needs at least {} elements", shaft.stations.len() - 1)));
        }
        if !(mesh.clamp_m >= 0.0 && mesh.clamp_m < 0.5 * length) {
            return Err(ShaftError::Mesh(format!("clamp {} m must lie in [0, half the shaft)", mesh.clamp_m)));
        }
        let nodes_m = mesh_nodes(shaft, mesh);
        let first_free = nodes_m.iter().position(|&x| x > mesh.clamp_m + 1e-12).unwrap_or(1);
        let n_nodes = nodes_m.len();
        let mut k_all = DMatrix::zeros(6 * n_nodes, 6 * n_nodes);
        let mut m_all = DMatrix::zeros(6 * n_nodes, 6 * n_nodes);
        for e in 0..n_nodes - 1 {
            let (ke, me) = beam::element(shaft, nodes_m[e], nodes_m[e + 1]);
            let o = 6 * e;
            for i in 0..12 {
                for j in 0..12 {
                    k_all[(o + i, o + j)] += ke[(i, j)];
                    m_all[(o + i, o + j)] += me[(i, j)];
                }
            }
        }
        // The shaft frame: x from butt to tip, y the club's forward axis (perpendicular to the shaft), z = x × y.
        let x_s = -sole.shaft_axis_up();
        let y_s = (Vector3::x() - Vector3::x().dot(&x_s) * x_s).normalize();
        let club_from_shaft = Rotation3::from_basis_unchecked(&[x_s, y_s, x_s.cross(&y_s)]);
        let tip_m = sole.shaft_tip_m();
        let butt_m = tip_m + length * sole.shaft_axis_up();
        let r = club_from_shaft.inverse_transform_vector(&(-tip_m));
        let inertia = club_from_shaft.matrix().transpose() * head.inertia_kg_m2 * club_from_shaft.matrix();
        let (m_h, rx) = (head.mass_kg, skew(&r));
        let o = 6 * (n_nodes - 1);
        let blocks =
            [(0, 0, Matrix3::identity() * m_h), (0, 3, -m_h * rx), (3, 0, m_h * rx), (3, 3, inertia - m_h * rx * rx)];
        for (bi, bj, b) in blocks {
            for i in 0..3 {
                for j in 0..3 {
                    m_all[(o + bi + i, o + bj + j)] += b[(i, j)];
                }
            }
        }
        let c = 6 * first_free;
        let nf = 6 * n_nodes - c;
        Ok(FlexibleClub {
            k: k_all.view((c, c), (nf, nf)).into_owned(),
            m: m_all.view((c, c), (nf, nf)).into_owned(),
            k_cf: k_all.view((0, c), (c, nf)).into_owned(),
            m_cf: m_all.view((0, c), (c, nf)).into_owned(),
            nodes_m,
            first_free,
            club_from_shaft,
            tip_m,
            butt_m,
            cg_from_tip_shaft_m: r,
        })
    }

    /// Number of free DOFs.
    pub fn dofs(&self) -> usize {
        self.k.nrows()
    }

    /// Natural frequencies (rad/s, ascending) and mass-normalised mode shapes (columns) of the clamped club.
    pub fn modes(&self) -> Result<(DVector, DMatrix), ShaftError> {
        let chol = self.m.clone().cholesky().ok_or(ShaftError::NotPositiveDefinite)?;
        let l = chol.l();
        // A = L⁻¹ K L⁻ᵀ, symmetric.
        let x = l.solve_lower_triangular(&self.k).ok_or(ShaftError::NotPositiveDefinite)?;
        let a = l.solve_lower_triangular(&x.transpose()).ok_or(ShaftError::NotPositiveDefinite)?;
        let a = 0.5 * (&a + a.transpose());
        let eig = a.symmetric_eigen();
        let mut order: Vec<usize> = (0..eig.eigenvalues.len()).collect();
        order.sort_by(|&i, &j| eig.eigenvalues[i].total_cmp(&eig.eigenvalues[j]));
        let n = order.len();
        let mut omega = DVector::zeros(n);
        let mut y = DMatrix::zeros(n, n);
        for (c, &i) in order.iter().enumerate() {
            if eig.eigenvalues[i] <= 0.0 {
                return Err(ShaftError::NotPositiveDefinite);
            }
            omega[c] = eig.eigenvalues[i].sqrt();
            y.set_column(c, &eig.eigenvectors.column(i));
        }
        let phi = l.transpose().solve_upper_triangular(&y).ok_or(ShaftError::NotPositiveDefinite)?;
        Ok((omega, phi))
    }

    /// The lowest natural frequency (Hz): the club's first bending mode.
    pub fn first_frequency_hz(&self) -> Result<Real, ShaftError> {
        let (omega, _) = self.modes()?;
        Ok(omega[0] / std::f64::consts::TAU)
    }

    /// The static displacement of the free DOFs under generalized forces `f` (N and N m, shaft frame).
    pub fn static_displacement(&self, f: &DVector) -> Result<DVector, ShaftError> {
        let chol = self.k.clone().cholesky().ok_or(ShaftError::NotPositiveDefinite)?;
        Ok(chol.solve(f))
    }

    /// Index of the tip node's first DOF among the free DOFs.
    pub fn tip_dof(&self) -> usize {
        self.dofs() - 6
    }
}

/// Nodes from the butt: every station of the profile, the clamp's end, and `elements` elements spread over the
/// segments in proportion to their length.
fn mesh_nodes(shaft: &ShaftSpec, mesh: ShaftMesh) -> Vec<Real> {
    let length = shaft.length_m();
    let mut nodes = vec![0.0];
    let mut breaks: Vec<Real> = shaft.stations.iter().skip(1).map(|s| s.from_butt_m).collect();
    if mesh.clamp_m > 0.0 {
        breaks.push(mesh.clamp_m);
        breaks.sort_by(|a, b| a.total_cmp(b));
    }
    let mut start = 0.0;
    for b in breaks {
        let n = ((mesh.elements as Real * (b - start) / length).round() as usize).max(1);
        for i in 1..=n {
            nodes.push(start + (b - start) * i as Real / n as Real);
        }
        start = b;
    }
    nodes
}

/// The three-point bending test of eq. 4.1 on the model: supports `span_m` apart centred `centre_m` from the
/// butt, a load at mid-span; returns `EI = F L³ / (48 δ)` from the model's mid-span deflection (N m²).
pub fn three_point_ei(shaft: &ShaftSpec, centre_m: Real, span_m: Real, elements: usize) -> Option<Real> {
    let n = elements.max(2) & !1; // even, so a node sits at mid-span
    let (xa, h) = (centre_m - 0.5 * span_m, span_m / n as Real);
    let dofs = 2 * (n + 1);
    let mut k = DMatrix::zeros(dofs, dofs);
    for e in 0..n {
        let ke = beam::bending_stiffness(shaft, xa + e as Real * h, xa + (e + 1) as Real * h);
        for i in 0..4 {
            for j in 0..4 {
                k[(2 * e + i, 2 * e + j)] += ke[(i, j)];
            }
        }
    }
    // Simply supported: no deflection at either support (DOFs 0 and 2n); rotations free.
    let keep: Vec<usize> = (0..dofs).filter(|&d| d != 0 && d != 2 * n).collect();
    let kr = DMatrix::from_fn(keep.len(), keep.len(), |i, j| k[(keep[i], keep[j])]);
    let force_n = 1.0;
    let mut f = DVector::zeros(keep.len());
    let mid = keep.iter().position(|&d| d == n)?; // the mid-span deflection DOF (node n/2, DOF 2 (n/2))
    f[mid] = force_n;
    let u = kr.cholesky()?.solve(&f);
    Some(force_n * span_m.powi(3) / (48.0 * u[mid]))
}
