//! The sole in the soil (seed section 4.2.1, eq. 4.3-4.9, Figure 4.8): Bekker's pressure and the soil's shear
//! strength integrated over the wetted part of the sole's cylinder.
//!
//! A sole point at angle θ (from straight down, positive toward the leading edge) and heel-toe offset s is
//! `P = c + R (sin θ x̂ − cos θ ŷ) + s ẑ` in the sole's frame ([`SoleArc`](crate::equipment::sole::SoleArc); the club frame turned toe down by
//! `toe_down_deg` about the face normal). Its sinkage below the undisturbed
//! playing surface is `z = y_ground − P_y`. Over the wetted arc `θ_T.E ≤ θ ≤ θ_L.E` where `z > 0`:
//!
//! - pressure, eq. 4.3: `σ(z) = (k_c / b + k_φ) zⁿ`, `b` the smaller of the wetted patch's length (along the arc)
//!   and width (heel to toe);
//! - the pressure acts along the cylinder's inward normal `(−sin θ, cos θ)`: eq. 4.4 `F_σx = −w ∫ σ R sin θ dθ`
//!   and eq. 4.5 `F_σz = w ∫ σ R cos θ dθ` in the seed's 2D picture;
//! - shear at the soil's strength, eq. 4.7 `τ = σ/√3` (Mohr-Coulomb, eq. 4.6, no cohesion, Φ = 30°), against the
//!   sole's slip: for a sole pushed forward this is eq. 4.8 `F_τx = −w ∫ τ R cos θ dθ` and eq. 4.9
//!   `F_τz = −w ∫ τ R sin θ dθ`. In 3D the slip also has a heel-toe part; the shear opposes the whole slip in
//!   the sole's tangent plane, smoothed as `tanh(|v_slip| / v_reg)` so a resting sole feels none.
//!
//! The seed applies the resultant at the centroid of the distributed force; here each quadrature point's force
//! acts where it is, which gives the same resultant and moment. Both contact phases use these forces.
//!
//! Quadrature: the sinkage is linear in s and `A + Rρ cos(θ − θ₀)` in θ, so the wetted interval of every strip
//! is found in closed form and integrated by Gauss-Legendre over exactly that interval.
//!
//! Assumptions (the seed's): the soil has no memory (sinkage is measured from the undisturbed surface, the
//! pressure follows the sinkage up and down), no grass, no cohesion.

use super::sole_arc::{GaussRule, SoleArcWorld};
use crate::equipment::soil::SoilSpec;
use crate::math::{Real, Vector3};

/// What the sole feels at one instant (world frame, about the CG).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SoleContact {
    /// Resultant of the pressure (eq. 4.4-4.5) and of the shear (eq. 4.8-4.9), N.
    pub pressure_n: Vector3,
    /// See `pressure_n`.
    pub shear_n: Vector3,
    /// Moment of both about the head's CG (N m).
    pub torque_nm: Vector3,
    /// Deepest sinkage of the sole (m; ≤ 0 when clear of the ground).
    pub max_sinkage_m: Real,
}

/// The sole's forces. `arc` is the sole placed in the world, `v_cg` and `w` the head's velocity and angular
/// velocity, `v_reg` the shear's smoothing speed; `strips` the Gauss rule heel to toe, `along` along the arc.
#[allow(clippy::too_many_arguments)]
pub fn sole_forces(
    arc: &SoleArcWorld,
    soil: &SoilSpec,
    v_cg: &Vector3,
    w: &Vector3,
    v_reg_mps: Real,
    strips: &GaussRule,
    along: &GaussRule,
) -> SoleContact {
    let (mut pressure_n, mut shear_n, mut torque_nm) = (Vector3::zeros(), Vector3::zeros(), Vector3::zeros());
    let max_sinkage_m = sole_point_forces(arc, soil, v_cg, w, v_reg_mps, strips, along, |r, f_p, f_s| {
        pressure_n += f_p;
        shear_n += f_s;
        torque_nm += r.cross(&(f_p + f_s));
    });
    SoleContact { pressure_n, shear_n, torque_nm, max_sinkage_m }
}

/// [`sole_forces`] point by point: `each(r, pressure, shear)` for every wetted quadrature point, in order, with
/// `r` the point from the head's CG (m) and its share of the pressure (eq. 4.4-4.5) and of the shear (eq.
/// 4.8-4.9, N, world). Returns the deepest sinkage (m; ≤ 0 when clear, and then no point is visited). What one
/// part of the force does alone is read from these (research/ground-parts.md).
#[allow(clippy::too_many_arguments)]
pub fn sole_point_forces(
    arc: &SoleArcWorld,
    soil: &SoilSpec,
    v_cg: &Vector3,
    w: &Vector3,
    v_reg_mps: Real,
    strips: &GaussRule,
    along: &GaussRule,
    mut each: impl FnMut(&Vector3, Vector3, Vector3),
) -> Real {
    let max_sinkage_m = arc.max_sinkage_m();
    if max_sinkage_m <= 0.0 {
        return max_sinkage_m;
    }
    let Some((s_lo, s_hi)) = arc.wetted_heel_toe() else {
        return max_sinkage_m;
    };
    // First pass: each strip's wetted arc, for the patch's smaller dimension b.
    let (gs, gw) = (&strips.x, &strips.w);
    let mut intervals = [(0.0, 0.0, 0.0, 0.0); super::sole_arc::MAX_GAUSS];
    let n = strips.n;
    let mut arc_len_sum = 0.0;
    let mut weight_sum = 0.0;
    for i in 0..n {
        let s = s_lo + gs[i] * (s_hi - s_lo);
        if let Some((a, b)) = arc.wetted_arc(s) {
            intervals[i] = (s, a, b, gw[i]);
            arc_len_sum += gw[i] * arc.radius_m * (b - a);
            weight_sum += gw[i];
        } else {
            intervals[i] = (s, 0.0, 0.0, 0.0);
        }
    }
    if weight_sum <= 0.0 {
        return max_sinkage_m;
    }
    let b_m = (arc_len_sum / weight_sum).min(s_hi - s_lo);
    if b_m <= 1e-9 {
        return max_sinkage_m;
    }
    let tan_phi = soil.shear_ratio();
    let gtw = &along.w;
    let ds = s_hi - s_lo;
    for &(s, a, b, ws) in intervals.iter().take(n) {
        if ws == 0.0 || b <= a {
            continue;
        }
        let angles = node_sin_cos(a, b, along);
        for j in 0..along.n {
            let (sin, cos) = angles[j];
            let p = arc.point_sc(sin, cos, s);
            let z = arc.ground_y_m - p.y;
            if z <= 0.0 {
                continue;
            }
            let area = ws * ds * gtw[j] * (b - a) * arc.radius_m;
            let sigma = soil.pressure_pa(z, b_m);
            let normal = cos * arc.ey - sin * arc.ex; // inward: from the soil into the sole
            let r = p - arc.cg_m;
            let v = v_cg + w.cross(&r);
            let slip = v - v.dot(&normal) * normal;
            let slip_speed = slip.norm();
            let f_p = sigma * area * normal;
            let f_s = if slip_speed > 1e-12 {
                let x = slip_speed / v_reg_mps;
                let smooth = if x > 20.0 { 1.0 } else { x.tanh() }; // tanh(20) = 1 - 8e-18
                -(tan_phi * sigma * area * smooth / slip_speed) * slip
            } else {
                Vector3::zeros()
            };
            each(&r, f_p, f_s);
        }
    }
    max_sinkage_m
}

/// `(sin θⱼ, cos θⱼ)` at the rule's nodes `θⱼ = a + xⱼ (b − a)`. The Gauss-Legendre nodes pair up about the
/// middle `m`, `θ = m ± δ`, so each pair costs one `sin_cos` of `δ` and the sum formulas (one of `m` in all).
fn node_sin_cos(a: Real, b: Real, rule: &GaussRule) -> [(Real, Real); super::sole_arc::MAX_GAUSS] {
    let mut out = [(0.0, 0.0); super::sole_arc::MAX_GAUSS];
    let n = rule.n;
    let (m, half) = (0.5 * (a + b), 0.5 * (b - a));
    let (sm, cm) = crate::math::sin_cos_small(m);
    for j in 0..n.div_ceil(2) {
        let k = n - 1 - j;
        if j == k {
            out[j] = (sm, cm);
            continue;
        }
        // x_j and x_k = 1 - x_j: θ = m ∓ δ, δ = (1 − 2 x_j) (b − a) / 2 (the mean of both nodes' offsets).
        let delta = 0.5 * ((1.0 - 2.0 * rule.x[j]) + (2.0 * rule.x[k] - 1.0)) * half;
        let (sd, cd) = crate::math::sin_cos_small(delta);
        out[j] = (sm * cd - cm * sd, cm * cd + sm * sd);
        out[k] = (sm * cd + cm * sd, cm * cd - sm * sd);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The paired nodes' sines and cosines are the direct ones to rounding, for odd and even rules.
    #[test]
    fn node_angles_are_the_direct_ones() {
        for n in [1, 2, 3, 5, 8, 16] {
            let rule = GaussRule::new(n);
            let (a, b) = (-0.41, 0.63);
            let got = node_sin_cos(a, b, &rule);
            for (j, (x, g)) in rule.x.iter().zip(&got).take(n).enumerate() {
                let (s, c) = (a + x * (b - a)).sin_cos();
                assert!((g.0 - s).abs() < 1e-15 && (g.1 - c).abs() < 1e-15, "n {n} node {j}");
            }
        }
    }
}
