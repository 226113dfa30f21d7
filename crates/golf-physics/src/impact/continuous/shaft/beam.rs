//! Beam elements for the tapered shaft: Euler-Bernoulli bending in two planes (cubic Hermite), axial stretch and
//! Saint-Venant torsion (linear), with the section properties integrated along each element.
//!
//! Node DOFs, shaft frame (x along the axis from butt to tip): `[uₓ, u_y, u_z, φₓ, φ_y, φ_z]`. Bending in the
//! x-y plane uses `(u_y, φ_z = du_y/dx)`, in the x-z plane `(u_z, φ_y = −du_z/dx)`.
//!
//! - Stiffness: `K = ∫ EA N′ᵀN′ + GJ N′ᵀN′ + EI (H″ᵀH″)` per field; eq. 4.1's `EI` and eq. 4.2's `GJ` vary along
//!   the element as the tube's radius and wall do.
//! - Mass: consistent, `M = ∫ ρA (NᵀN + HᵀH) + ρJ NᵀN` (bending rotary inertia neglected).
//!
//! Five-point Gauss-Legendre quadrature is exact for these integrands when an element lies within one segment of
//! the profile (the section properties are polynomials of degree 4 there).

use crate::math::{SMatrix, SVector};

use crate::equipment::shaft::ShaftSpec;
use crate::math::Real;

/// A 12 x 12 element matrix.
pub type Mat12 = SMatrix<12, 12>;

/// Gauss-Legendre points and weights on [0, 1].
const GAUSS5: [(Real, Real); 5] = [
    (0.5 - 0.5 * 0.906_179_845_938_664, 0.5 * 0.236_926_885_056_189_1),
    (0.5 - 0.5 * 0.538_469_310_105_683_1, 0.5 * 0.478_628_670_499_366_5),
    (0.5, 0.5 * 0.568_888_888_888_888_9),
    (0.5 + 0.5 * 0.538_469_310_105_683_1, 0.5 * 0.478_628_670_499_366_5),
    (0.5 + 0.5 * 0.906_179_845_938_664, 0.5 * 0.236_926_885_056_189_1),
];

/// Hermite shape functions on an element of length `l` at `xi` in [0, 1], for `(v₁, θ₁, v₂, θ₂)`.
fn hermite(xi: Real, l: Real) -> [Real; 4] {
    let (x2, x3) = (xi * xi, xi * xi * xi);
    [1.0 - 3.0 * x2 + 2.0 * x3, l * (xi - 2.0 * x2 + x3), 3.0 * x2 - 2.0 * x3, l * (x3 - x2)]
}

/// Their second derivatives with respect to x.
fn hermite_dd(xi: Real, l: Real) -> [Real; 4] {
    [(12.0 * xi - 6.0) / (l * l), (6.0 * xi - 4.0) / l, (6.0 - 12.0 * xi) / (l * l), (6.0 * xi - 2.0) / l]
}

/// DOFs of the x-y bending field and their signs, then of the x-z field.
const BEND_Y: ([usize; 4], [Real; 4]) = ([1, 5, 7, 11], [1.0, 1.0, 1.0, 1.0]);
const BEND_Z: ([usize; 4], [Real; 4]) = ([2, 4, 8, 10], [1.0, -1.0, 1.0, -1.0]);

fn add_outer(m: &mut Mat12, dofs: &[usize], signs: &[Real], f: &[Real], c: Real) {
    for (a, (&i, &si)) in dofs.iter().zip(signs).enumerate() {
        for (b, (&j, &sj)) in dofs.iter().zip(signs).enumerate() {
            m[(i, j)] += c * si * sj * f[a] * f[b];
        }
    }
}

/// Stiffness and consistent mass of the element from `xa` to `xb` (m from the butt), shaft frame.
pub fn element(shaft: &ShaftSpec, xa: Real, xb: Real) -> (Mat12, Mat12) {
    let l = xb - xa;
    let mut k = Mat12::zeros();
    let mut m = Mat12::zeros();
    for &(xi, w) in &GAUSS5 {
        let x = xa + xi * l;
        let c = w * l;
        let lin = [1.0 - xi, xi];
        let lin_d = [-1.0 / l, 1.0 / l];
        let ones = [1.0, 1.0];
        // Axial and torsion.
        add_outer(&mut k, &[0, 6], &ones, &lin_d, c * shaft.ea_n(x));
        add_outer(&mut k, &[3, 9], &ones, &lin_d, c * shaft.gj_n_m2(x));
        let rho_a = shaft.mass_per_length_kg_per_m(x);
        add_outer(&mut m, &[0, 6], &ones, &lin, c * rho_a);
        add_outer(&mut m, &[3, 9], &ones, &lin, c * shaft.polar_inertia_per_length_kg_m(x));
        // Bending in both planes.
        let (h, hdd) = (hermite(xi, l), hermite_dd(xi, l));
        let ei = shaft.ei_n_m2(x);
        for (dofs, signs) in [BEND_Y, BEND_Z] {
            add_outer(&mut k, &dofs, &signs, &hdd, c * ei);
            add_outer(&mut m, &dofs, &signs, &h, c * rho_a);
        }
    }
    (k, m)
}

/// The 4 x 4 bending stiffness of one plane, for the three-point test of eq. 4.1.
pub fn bending_stiffness(shaft: &ShaftSpec, xa: Real, xb: Real) -> SMatrix<4, 4> {
    let l = xb - xa;
    let mut k = SMatrix::<4, 4>::zeros();
    for &(xi, w) in &GAUSS5 {
        let d = SVector::<4>::from(hermite_dd(xi, l));
        k += (w * l * shaft.ei_n_m2(xa + xi * l)) * d * d.transpose();
    }
    k
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A uniform element reproduces the textbook matrices: `12EI/l³` for the end shear, `4EI/l` for the end
    /// moment, `EA/l` axially, and a consistent mass of `13/35 ρAl` on the end deflection.
    #[test]
    fn uniform_element_textbook_entries() {
        let mut s = ShaftSpec::iron7();
        for st in &mut s.stations {
            st.outer_radius_m = 6e-3;
            st.wall_m = 0.5e-3;
        }
        let (xa, xb) = (0.1, 0.25);
        let l = xb - xa;
        let (k, m) = element(&s, xa, xb);
        let ei = s.ei_n_m2(0.2);
        let rel = |a: Real, b: Real| (a - b).abs() / b.abs();
        assert!(rel(k[(1, 1)], 12.0 * ei / l.powi(3)) < 1e-12);
        assert!(rel(k[(5, 5)], 4.0 * ei / l) < 1e-12);
        assert!(rel(k[(4, 4)], 4.0 * ei / l) < 1e-12);
        assert!(rel(k[(2, 4)], -6.0 * ei / (l * l)) < 1e-12, "x-z coupling sign");
        assert!(rel(k[(1, 5)], 6.0 * ei / (l * l)) < 1e-12);
        assert!(rel(k[(0, 0)], s.ea_n(0.2) / l) < 1e-12);
        assert!(rel(k[(3, 3)], s.gj_n_m2(0.2) / l) < 1e-12);
        let rho_a = s.mass_per_length_kg_per_m(0.2);
        assert!(rel(m[(1, 1)], 13.0 / 35.0 * rho_a * l) < 1e-12);
        assert!(rel(m[(0, 0)], rho_a * l / 3.0) < 1e-12);
        // Rigid translation carries no elastic force, and the mass of a rigid translation is the element's mass.
        let mut t = SVector::<12>::zeros();
        t[1] = 1.0;
        t[7] = 1.0;
        assert!((k * t).norm() < 1e-9 * k.norm());
        assert!(rel((t.transpose() * m * t)[0], rho_a * l) < 1e-12);
    }
}
