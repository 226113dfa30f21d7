//! Ground reaction on an iron's head (seed section 4.2): the sole in Bekker soil ([`super::sole`], eq. 4.3-4.9)
//! and the passive earth pressure on the face below the surface ([`super::face_pressure`], eq. 4.10-4.13).
//!
//! The ground is the plane `y = y_ground` (world; for a ball resting on the turf `y_ground = y_ball − r_ball`,
//! ARCHITECTURE.md section 2). Contact has two phases (seed 4.2): compression, while only the sole is below the
//! surface and the soil is pressed down; and the divot, once the leading edge is below the surface and the
//! face pushes soil forward. The sole's forces act in both phases, the face's only in the second.

use crate::equipment::soil::SoilSpec;
use crate::equipment::sole::{SoleArc, SoleSpec};
use crate::equipment::ClubSpec;
use crate::math::{Isometry3, Real, Rotation3, Vector3};

use super::face_pressure::{face_forces, FacePressure};
use super::sole::{sole_forces, SoleContact};
use super::sole_arc::{GaussRule, SoleArcWorld};

/// The contact phase (seed 4.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum GroundPhase {
    /// The sole above the surface: no ground force.
    Clear,
    /// Only the sole below the surface.
    Compression,
    /// The leading edge below the surface: the face cuts a divot.
    Divot,
}

/// Every ground force at one instant (world frame; moments about the head's CG).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GroundForces {
    /// The sole's pressure and shear (eq. 4.3-4.9).
    pub sole: SoleContact,
    /// The face's passive earth pressure (eq. 4.10-4.13; zero until the divot phase).
    pub face: FacePressure,
    /// The contact phase.
    pub phase: GroundPhase,
}

impl GroundForces {
    /// The resultant force (N).
    pub fn force_n(&self) -> Vector3 {
        self.sole.pressure_n + self.sole.shear_n + self.face.force_n
    }

    /// The resultant moment about the CG (N m).
    pub fn torque_nm(&self) -> Vector3 {
        self.sole.torque_nm + self.face.torque_nm
    }
}

/// The ground under an iron: soil, the sole's geometry and the surface's height.
#[derive(Debug, Clone, PartialEq)]
pub struct SoilGround {
    /// The soil's Bekker moduli and exponent, density and friction angle (Table 4.3).
    pub soil: SoilSpec,
    /// The sole's geometry: lie, width, length, bounce, radius (Table 4.1 values for the seed's 7-iron).
    pub sole: SoleSpec,
    /// The sole's cylinder in the club frame.
    pub arc: SoleArc,
    /// Outward face normal and up-the-face direction, club frame.
    pub face_normal: Vector3,
    /// See `face_normal`.
    pub up_face: Vector3,
    /// The playing surface's height `y_ground` (m, world).
    pub ground_y_m: Real,
    /// Shear smoothing speed (m/s).
    pub slip_regularisation_mps: Real,
    /// The sole's Gauss rule heel to toe.
    pub strips: GaussRule,
    /// The sole's Gauss rule along its arc.
    pub along_arc: GaussRule,
    /// The face's Gauss rule along the leading edge.
    pub along_edge: GaussRule,
}

impl SoilGround {
    /// The ground `y = ground_y_m` under `club` with `sole` in `soil`; default quadrature (3 strips heel to toe,
    /// 5 points along the arc; 3 along the leading edge, exact for eq. 4.13's quadratic pressure and its moment).
    pub fn new(soil: SoilSpec, sole: SoleSpec, club: &ClubSpec, ground_y_m: Real) -> Self {
        let arc = sole.arc(&club.face.center_m, club.face.loft_rad);
        SoilGround {
            soil,
            sole,
            arc,
            face_normal: club.face.n0(),
            up_face: club.face.u0(),
            ground_y_m,
            slip_regularisation_mps: 0.05,
            strips: GaussRule::new(3),
            along_arc: GaussRule::new(5),
            along_edge: GaussRule::new(3),
        }
    }

    /// The sole placed at `world_from_club`.
    pub fn placed(&self, world_from_club: &Isometry3) -> SoleArcWorld {
        SoleArcWorld::new(&self.arc, world_from_club, self.ground_y_m)
    }

    /// Every ground force on the head at pose `world_from_club`, CG velocity `v_cg` and angular velocity `w`.
    pub fn forces(&self, world_from_club: &Isometry3, v_cg: &Vector3, w: &Vector3) -> GroundForces {
        let rotation = world_from_club.rotation.to_rotation_matrix();
        self.forces_at(&rotation, &world_from_club.translation.vector, v_cg, w)
    }

    /// [`Self::forces`] with the pose as a rotation matrix and the CG's position.
    pub fn forces_at(&self, world_from_club: &Rotation3, cg_m: &Vector3, v_cg: &Vector3, w: &Vector3) -> GroundForces {
        let placed = SoleArcWorld::at(&self.arc, world_from_club, cg_m, self.ground_y_m);
        let sole =
            sole_forces(&placed, &self.soil, v_cg, w, self.slip_regularisation_mps, &self.strips, &self.along_arc);
        if sole.max_sinkage_m <= 0.0 {
            return GroundForces { sole, face: FacePressure::default(), phase: GroundPhase::Clear };
        }
        let r = world_from_club;
        let face = face_forces(
            &placed,
            &(r * self.face_normal),
            &(r * self.up_face),
            &self.soil,
            v_cg,
            w,
            self.slip_regularisation_mps,
            &self.along_edge,
        );
        let phase = if face.leading_edge_depth_m > 0.0 { GroundPhase::Divot } else { GroundPhase::Compression };
        GroundForces { sole, face, phase }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An n-point Gauss-Legendre rule integrates polynomials of degree 2n − 1 exactly: ∫₀¹ x^k dx = 1/(k + 1).
    #[test]
    fn gauss_rules_are_exact_to_degree_2n_minus_1() {
        for n in [1, 2, 3, 6, 8, 16] {
            let g = GaussRule::new(n);
            assert!((g.w[..n].iter().sum::<Real>() - 1.0).abs() < 1e-14);
            for k in 0..2 * n {
                let got: Real = (0..n).map(|i| g.w[i] * g.x[i].powi(k as i32)).sum();
                assert!((got - 1.0 / (k as Real + 1.0)).abs() < 1e-13, "n {n} k {k}: {got}");
            }
        }
    }

    /// A delofted, open, toe-down sole in firm soil moving along a descending path: the default quadrature
    /// (3 x 5) is within 0.5 % of 16 x 16 in force and moment.
    #[test]
    fn quadrature_converges_on_a_tilted_sole() {
        let club = ClubSpec::iron7();
        let mut ground = SoilGround::new(SoilSpec::firm(), SoleSpec::IRON7, &club, 0.0);
        let rot = crate::math::UnitQuaternion::from_euler_angles(0.03, -0.05, -0.08);
        let probe = Isometry3::from_parts(crate::math::Translation3::identity(), rot);
        let lowest = -ground.placed(&probe).max_sinkage_m();
        let pose = Isometry3::from_parts(crate::math::Translation3::new(0.0, -lowest - 0.006, 0.0), rot);
        let (v, w) = (Vector3::new(34.0, -2.5, 1.0), Vector3::new(2.0, -5.0, -30.0));
        let coarse = ground.forces(&pose, &v, &w);
        ground.strips = GaussRule::new(16);
        ground.along_arc = GaussRule::new(16);
        let fine = ground.forces(&pose, &v, &w);
        let df = (coarse.force_n() - fine.force_n()).norm() / fine.force_n().norm();
        let dt = (coarse.torque_nm() - fine.torque_nm()).norm() / fine.torque_nm().norm();
        assert!(df < 5e-3 && dt < 5e-3, "force {df}, torque {dt}");
        assert!((fine.sole.max_sinkage_m - 0.006).abs() < 1e-12);
    }
}
