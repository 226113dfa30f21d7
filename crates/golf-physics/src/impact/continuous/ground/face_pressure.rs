//! The face below the surface (seed section 4.2.2, eq. 4.10-4.13, Figure 4.9): passive earth pressure once the
//! leading edge is below the playing surface (the divot phase).
//!
//! - Eq. 4.10 without cohesion: `σ_p = γ_s z N_Φ`, `γ_s = ρ g` the soil's unit weight, `z` the depth.
//! - Eq. 4.11: `N_Φ = tan²(45° + Φ/2)` = 3 at Φ = 30°.
//! - Eq. 4.12-4.13: over a face of width `w` whose leading edge is `h` deep, `F_P = ∫₀ʰ w σ_p dz =
//!   w (½ γ_s N_Φ h²)`, horizontal, against the face's motion, acting at the centroid of the triangular
//!   distribution, `2/3 h` below the surface.
//!
//! The leading edge can be tilted heel to toe (lie, face rotation), so `h` varies along it: each strip `ds`
//! carries `½ γ_s N_Φ h(s)² ds` at its own `2/3 h(s)`; three Gauss points integrate the quadratic force and its
//! cubic moment exactly. The face's width is the sole's heel-toe length. The soil pushes back only while the face
//! moves into it (its horizontal velocity along the face's horizontal normal is positive), smoothed by
//! `tanh(v / v_reg)`.

use super::sole_arc::{GaussRule, SoleArcWorld};
use crate::equipment::soil::SoilSpec;
use crate::math::{Real, Vector3};

/// The face's passive earth pressure at one instant (world frame, about the CG).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct FacePressure {
    /// Resultant of eq. 4.13's pressure (N, world; horizontal).
    pub force_n: Vector3,
    /// Its moment about the head's CG (N m, world).
    pub torque_nm: Vector3,
    /// The leading edge's deepest point below the surface (m; negative when above).
    pub leading_edge_depth_m: Real,
}

/// The face's forces: `arc` the sole placed in the world (its leading edge is the face's lower edge),
/// `face_normal` and `up_face` the face's outward normal and up-the-face direction (world).
#[allow(clippy::too_many_arguments)]
pub fn face_forces(
    arc: &SoleArcWorld,
    face_normal: &Vector3,
    up_face: &Vector3,
    soil: &SoilSpec,
    v_cg: &Vector3,
    w: &Vector3,
    v_reg_mps: Real,
    rule: &GaussRule,
) -> FacePressure {
    let (mut force_n, mut torque_nm) = (Vector3::zeros(), Vector3::zeros());
    let leading_edge_depth_m = face_point_forces(arc, face_normal, up_face, soil, v_cg, w, v_reg_mps, rule, |r, f| {
        force_n += f;
        torque_nm += r.cross(&f);
    });
    FacePressure { force_n, torque_nm, leading_edge_depth_m }
}

/// [`face_forces`] point by point: `each(r, force)` for every Gauss point of the wetted leading edge that pushes
/// soil, in order, with `r` the point of action (the centroid of its triangular pressure) from the head's CG (m)
/// and its share of eq. 4.13's force (N, world). Returns the leading edge's deepest point below the surface (m;
/// negative when above, and then no point is visited).
#[allow(clippy::too_many_arguments)]
pub fn face_point_forces(
    arc: &SoleArcWorld,
    face_normal: &Vector3,
    up_face: &Vector3,
    soil: &SoilSpec,
    v_cg: &Vector3,
    w: &Vector3,
    v_reg_mps: Real,
    rule: &GaussRule,
    mut each: impl FnMut(&Vector3, Vector3),
) -> Real {
    let half = arc.half_length_m;
    let (h_heel, h_toe) = (arc.leading_edge_depth_m(-half), arc.leading_edge_depth_m(half));
    let depth_m = h_heel.max(h_toe);
    if depth_m <= 0.0 {
        return depth_m;
    }
    let horizontal = Vector3::new(face_normal.x, 0.0, face_normal.z);
    let Some(n_h) = horizontal.try_normalize(1e-9) else {
        return depth_m; // a face lying flat pushes no soil forward
    };
    // Wetted part of the leading edge: h is linear in s.
    let slope = (h_toe - h_heel) / (2.0 * half);
    let mid = 0.5 * (h_heel + h_toe);
    let (lo, hi) = if slope.abs() < 1e-14 {
        (-half, half)
    } else {
        let root = -mid / slope;
        if slope > 0.0 {
            (root.max(-half), half)
        } else {
            (-half, root.min(half))
        }
    };
    if hi <= lo {
        return depth_m;
    }
    let k = 0.5 * soil.unit_weight_n_per_m3() * soil.flow_value();
    let rise = up_face.y.max(1e-6);
    for i in 0..rule.n {
        let s = lo + rule.x[i] * (hi - lo);
        let h = mid + slope * s;
        if h <= 0.0 {
            continue;
        }
        let edge = arc.point(arc.theta_le_rad, s);
        // The centroid of the triangular pressure: 2/3 h below the surface, h/3 above the edge, on the face.
        let p = edge + (h / 3.0 / rise) * up_face;
        let r = p - arc.cg_m;
        let speed = (v_cg + w.cross(&r)).dot(&n_h);
        if speed <= 0.0 {
            continue;
        }
        let f = -(k * h * h * rule.w[i] * (hi - lo) * (speed / v_reg_mps).tanh()) * n_h;
        each(&r, f);
    }
    depth_m
}
