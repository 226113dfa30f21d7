//! The solver (eq. 3.2-3.12) against two closed forms of a rigid head struck off its CG, in the plane of the
//! strike:
//!
//! - Effective mass off centre. A strike a distance `r` from the CG along the face turns the head about the axis
//!   perpendicular to `r` and the normal, so the head meets the ball with `m_eff = 1 / (1/m + r^2 / I)` and the
//!   normal impulse is `P = (1 + e) v / (1/m_eff + 1/m_b)` (with the CG in the face plane nothing couples the
//!   normal to the tangent, so the rolling condition asks no tangential impulse) (e.g. A. R. Penner, "The physics of golf", Rep. Prog. Phys. 66, 2003,
//!   section 3; R. Cross, "Physics of Baseball & Softball", 2011, ch. 9 for a bat).
//! - Gear effect with a rolling ball (eq. 3.9-3.10). A head of mass `M`, inertia `I` about the vertical through
//!   its CG, CG a depth `d` behind the face, struck `x` toward the toe by a ball of mass `m`, radius `R`, inertia
//!   `I_b`, closing at `v` along the normal. In the (normal, toe) plane the contact's velocity changes by
//!   `-K P` with `K = [[1/M + 1/m + x^2/I, -x d/I], [-x d/I, 1/M + 1/m + d^2/I + R^2/I_b]]`; restitution `e`
//!   along the normal and rolling (`u_t' = 0`) give `K P = ((1 + e) v, 0)`, so
//!   `P_t = (1 + e) v (x d / I) / det K`, the head turns open about its CG (`-(d P_t - x P_n)/I`, toe back) and
//!   the ball leaves spinning the other way, `omega_b = R P_t / I_b` about the vertical, toward the draw for a
//!   toe strike: the gear effect of a rigid head (A. R. Penner, "The physics of golf: the convex face of a
//!   driver", Am. J. Phys. 69, 2001, its rigid-head impulse model).
//! - The D-plane: a ball rolling off a face that does not move (no gear effect) spins about `u x n`, the normal
//!   of the plane of the club's path `u` and the face normal `n` (T. P. Jorgensen, "The Physics of Golf", 2nd
//!   ed., 1999, ch. 7; TrackMan's D-plane). With spin loft `s` and face to path `f`, the axis tilts
//!   `atan(cos s sin f / sin s)` from the horizontal, about `1 / tan s` degrees per degree of face to path (4.0 at
//!   14 deg): the geometry every rigid-face model starts from, before a head that turns adds its gear effect.

#![allow(clippy::unwrap_used)]

use super::*;

const M: Real = 0.200;
const I_VERT: Real = 5.0e-4;
const DEPTH: Real = 0.035;
const BALL_M: Real = 0.0459;
const BALL_R: Real = 0.02135;
const V: Real = 45.0;
const E: Real = 0.8;

/// World: x the face normal (toward the ball), y up, z toward the toe; the head's inertia diagonal.
fn problem(x_toe_m: Real, depth_m: Real) -> ContactProblem {
    let ball_i = 0.4 * BALL_M * BALL_R * BALL_R;
    ContactProblem {
        club_mass_kg: M,
        club_inertia_inv: Matrix3::from_diagonal(&Vector3::new(1.0 / 3.0e-4, 1.0 / I_VERT, 1.0 / 4.0e-4)),
        ball_mass_kg: BALL_M,
        ball_inertia_inv: Matrix3::from_diagonal_element(1.0 / ball_i),
        r_club_m: Vector3::new(depth_m, 0.0, x_toe_m),
        r_ball_m: Vector3::new(-BALL_R, 0.0, 0.0),
        world_from_impact: Matrix3::identity(),
        club_velocity_mps: Vector3::new(V, 0.0, 0.0),
        club_angular_velocity_radps: Vector3::zeros(),
        ball_velocity_mps: Vector3::zeros(),
        ball_angular_velocity_radps: Vector3::zeros(),
        restitution: Vector3::new(E, 0.0, 0.0),
    }
}

#[test]
fn normal_impulse_off_centre_is_the_effective_mass_closed_form() {
    for x_mm in [0.0, 5.0, 10.0, 20.0, 30.0] {
        let x = x_mm * 1e-3;
        let s = solve(&problem(x, 0.0)).unwrap();
        // The strike x along z turns the head about y (the vertical): m_eff = 1 / (1/M + x^2 / I_y).
        let m_eff = 1.0 / (1.0 / M + x * x / I_VERT);
        let p = (1.0 + E) * V / (1.0 / m_eff + 1.0 / BALL_M);
        assert!((s.impulse_n_s.x - p).abs() < 1e-9 * p, "{x_mm} mm: {} against {p}", s.impulse_n_s.x);
        assert!(s.impulse_n_s.z.abs() < 1e-12 && s.ball_angular_velocity_radps.norm() < 1e-9);
    }
}

#[test]
fn rolling_side_spin_is_the_rigid_head_gear_effect() {
    let ball_i = 0.4 * BALL_M * BALL_R * BALL_R;
    for x_mm in [-20.0, -10.0, 5.0, 15.0, 25.0] {
        let x = x_mm * 1e-3;
        let s = solve(&problem(x, DEPTH)).unwrap();
        let a = 1.0 / M + 1.0 / BALL_M + x * x / I_VERT;
        let b = -x * DEPTH / I_VERT;
        let c = 1.0 / M + 1.0 / BALL_M + DEPTH * DEPTH / I_VERT + BALL_R * BALL_R / ball_i;
        let det = a * c - b * b;
        let (p_n, p_t) = ((1.0 + E) * V * c / det, -(1.0 + E) * V * b / det);
        assert!((s.impulse_n_s.x - p_n).abs() < 1e-9 * p_n && (s.impulse_n_s.z - p_t).abs() < 1e-9 * p_n);
        // The ball's spin about the vertical: r_b x P = (-R, 0, 0) x (P_n, 0, P_t) = (0, R P_t, 0).
        let omega = BALL_R * p_t / ball_i;
        assert!((s.ball_angular_velocity_radps.y - omega).abs() < 1e-9 * omega.abs(), "{x_mm} mm");
        // The head turns the other way about the vertical (gear effect: the ball's spin opposite the head's).
        assert!(s.club_angular_velocity_radps.y * s.ball_angular_velocity_radps.y < 0.0, "{x_mm} mm");
        // And it is the gear effect alone: zero CG depth, zero side spin.
        assert!(solve(&problem(x, 0.0)).unwrap().ball_angular_velocity_radps.y.abs() < 1e-9);
    }
}

#[test]
fn a_ball_rolling_off_a_fixed_face_spins_about_the_d_plane_normal() {
    let ball_i = 0.4 * BALL_M * BALL_R * BALL_R;
    for (spin_loft_deg, face_to_path_deg) in [(14.0_f64, 1.0_f64), (14.0, -3.0), (25.0, 2.0), (40.0, 5.0)] {
        let (s, f) = (spin_loft_deg.to_radians(), face_to_path_deg.to_radians());
        // The path along x, the face normal turned up by the spin loft and right (+z) by the face to path.
        let n = Vector3::new(s.cos() * f.cos(), s.sin(), s.cos() * f.sin());
        let up = (Vector3::y() - n * n.y).normalize();
        let world_from_impact = Matrix3::from_columns(&[n, up, n.cross(&up)]);
        let problem = ContactProblem {
            club_mass_kg: 1.0e12,
            club_inertia_inv: Matrix3::zeros(),
            ball_mass_kg: BALL_M,
            ball_inertia_inv: Matrix3::from_diagonal_element(1.0 / ball_i),
            r_club_m: Vector3::zeros(),
            r_ball_m: -BALL_R * n,
            world_from_impact,
            club_velocity_mps: Vector3::new(V, 0.0, 0.0),
            club_angular_velocity_radps: Vector3::zeros(),
            ball_velocity_mps: Vector3::zeros(),
            ball_angular_velocity_radps: Vector3::zeros(),
            restitution: Vector3::new(E, 0.0, 0.0),
        };
        let w = solve(&problem).unwrap().ball_angular_velocity_radps;
        // The ball spins about u x n = (0, -n_z, n_y) (the D-plane's normal); its tilt out of the horizontal:
        let d_plane = Vector3::x().cross(&n);
        assert!(w.normalize().cross(&d_plane.normalize()).norm() < 1e-9, "{spin_loft_deg}, {face_to_path_deg}: {w}");
        let tilt_deg = (w.y / w.z.abs()).atan().to_degrees();
        let closed_deg = (s.cos() * f.sin() / s.sin()).atan().to_degrees();
        assert!((tilt_deg.abs() - closed_deg.abs()).abs() < 1e-9, "{tilt_deg} against {closed_deg}");
    }
    // At the kept drives' 14 deg of spin loft: 4.0 deg of axis per deg of face to path, before any gear effect.
    let per_deg = (14.0_f64.to_radians().cos() * 1.0_f64.to_radians().sin() / 14.0_f64.to_radians().sin()).atan();
    assert!((per_deg.to_degrees() - 4.0).abs() < 0.05, "{}", per_deg.to_degrees());
}
