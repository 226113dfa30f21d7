//! One part of the ground's force acting alone, for research/ground-parts.md: the model's own force laws, the
//! sole's (eq. 4.3-4.9) and the face's (eq. 4.10-4.13), evaluated point by point (`sole_point_forces`,
//! `face_point_forces`), each point's force kept in the world components `keep` names (ones: the whole force,
//! `(0, 1, 0)` the vertical part, `(1, 0, 1)` the horizontal), summed with its moment about the head's CG. Run
//! in place of the soil by `PreparedGround::simulate_with`; the ground model itself always applies the whole
//! force. Shared by research/tests/ground_parts.rs and examples/ground_parts.rs.

use impactd::impact::continuous::club::Head;
use impactd::impact::continuous::ground::{
    face_point_forces, sole_point_forces, FacePressure, GroundForces, GroundPhase, GroundWrench, SampledGround,
    SoilGround, SoleArcWorld, SoleContact,
};
use impactd::math::Vector3;

/// The soil under the ball with only the world components `keep` of each point's force kept (1 keeps, 0 drops).
pub struct PartOfGround {
    pub ground: SoilGround,
    pub keep: Vector3,
}

impl SampledGround for PartOfGround {
    type Forces = GroundForces;

    /// `SoilGround::forces_at` with each point's force multiplied by `keep` before it is summed.
    fn forces_on(&self, head: &Head) -> GroundForces {
        let g = &self.ground;
        let (v, w) = (&head.velocity_mps, &head.angular_velocity_radps);
        let placed = SoleArcWorld::at(&g.arc, &head.world_from_club, &head.position_m, g.ground_y_m);
        let mut sole = SoleContact::default();
        let max_sinkage_m = sole_point_forces(
            &placed,
            &g.soil,
            v,
            w,
            g.slip_regularisation_mps,
            &g.strips,
            &g.along_arc,
            |r, f_p, f_s| {
                let (f_p, f_s) = (f_p.component_mul(&self.keep), f_s.component_mul(&self.keep));
                sole.pressure_n += f_p;
                sole.shear_n += f_s;
                sole.torque_nm += r.cross(&(f_p + f_s));
            },
        );
        sole.max_sinkage_m = max_sinkage_m;
        if max_sinkage_m <= 0.0 {
            return GroundForces { sole, face: FacePressure::default(), phase: GroundPhase::Clear };
        }
        let r = &head.world_from_club;
        let mut face = FacePressure::default();
        let depth_m = face_point_forces(
            &placed,
            &(r * g.face_normal),
            &(r * g.up_face),
            &g.soil,
            v,
            w,
            g.slip_regularisation_mps,
            &g.along_edge,
            |r, f| {
                let f = f.component_mul(&self.keep);
                face.force_n += f;
                face.torque_nm += r.cross(&f);
            },
        );
        face.leading_edge_depth_m = depth_m;
        let phase = if depth_m > 0.0 { GroundPhase::Divot } else { GroundPhase::Compression };
        GroundForces { sole, face, phase }
    }

    fn wrench_of(forces: &GroundForces) -> GroundWrench {
        GroundWrench { force_n: forces.force_n(), torque_nm: forces.torque_nm() }
    }
}
