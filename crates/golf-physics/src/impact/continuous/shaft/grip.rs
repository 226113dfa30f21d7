//! The grip's kinematic drive: the swing's undisturbed motion carried through the club's static geometry
//! (seed section 4.1: "the position and orientation of the grip end is kinematically driven").
//!
//! The delivery gives the rigid club's state at ball contact (t = 0): the CG's velocity `v₀` and the club's
//! angular velocity `ω` (world). Between motion-capture frames the seed assumes a constant acceleration; with
//! the one state a delivery carries, the undisturbed motion is the constant twist through it (the club keeps
//! turning at `ω` and its CG's velocity turns with it):
//!
//! - `R(t) = exp([ω] t) R₀`, `v(t) = exp([ω] t) v₀` (its acceleration `ω × v` is constant in size);
//! - `p(t) = p₀ + (t I + (1 − cos ωt)/ω² [ω] + (ωt − sin ωt)/ω³ [ω]²) v₀`.
//!
//! The grip is then the butt's point of the rigid club (the lie and length of [`SoleSpec`](crate::equipment::sole::SoleSpec) and the shaft), and
//! the head rides on the shaft relative to this frame ([`super::modal`]).

use crate::math::{skew, Isometry3, Matrix3, Real, Translation3, UnitQuaternion, Vector3};

/// The rigid club's undisturbed motion: a constant twist through the delivered state at t = 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConstantTwist {
    /// The club's pose at ball contact (CG origin).
    pub world_from_club: Isometry3,
    /// CG velocity at t = 0 (m/s, world).
    pub cg_velocity_mps: Vector3,
    /// Angular velocity (rad/s, world).
    pub angular_velocity_radps: Vector3,
}

impl ConstantTwist {
    /// `exp([ω] t)` and `∫₀ᵗ exp([ω] s) ds`.
    fn rotation_and_integral(&self, t_s: Real) -> (Matrix3, Matrix3) {
        let w = self.angular_velocity_radps;
        let rate_radps = w.norm();
        let k = skew(&w);
        if rate_radps * t_s.abs() < 1e-6 {
            let r = Matrix3::identity() + k * t_s + 0.5 * k * k * t_s * t_s;
            let i = Matrix3::identity() * t_s + 0.5 * k * t_s * t_s + k * k * t_s.powi(3) / 6.0;
            return (r, i);
        }
        let th = rate_radps * t_s;
        let (sin, cos) = crate::math::sin_cos_small(th);
        let r = Matrix3::identity() + k * (sin / rate_radps) + k * k * ((1.0 - cos) / (rate_radps * rate_radps));
        let i = Matrix3::identity() * t_s
            + k * ((1.0 - cos) / (rate_radps * rate_radps))
            + k * k * ((th - sin) / rate_radps.powi(3));
        (r, i)
    }

    /// The twist with its time-independent parts computed once, for evaluations at many instants.
    pub fn prepared(&self) -> PreparedTwist {
        let w = self.angular_velocity_radps;
        let k = skew(&w);
        PreparedTwist {
            k,
            k2: k * k,
            rate_radps: w.norm(),
            rotation0: *self.world_from_club.rotation.to_rotation_matrix().matrix(),
            position0_m: self.world_from_club.translation.vector,
            velocity0_mps: self.cg_velocity_mps,
        }
    }

    /// The rigid club's attitude (world from club), CG position and CG velocity at `t_s`, in one evaluation.
    pub fn at(&self, t_s: Real) -> (crate::math::Rotation3, Vector3, Vector3) {
        let (r, i) = self.rotation_and_integral(t_s);
        let rot = crate::math::Rotation3::from_matrix_unchecked(
            r * self.world_from_club.rotation.to_rotation_matrix().matrix(),
        );
        (rot, self.world_from_club.translation.vector + i * self.cg_velocity_mps, r * self.cg_velocity_mps)
    }

    /// The rigid club's pose at `t_s` from ball contact.
    pub fn world_from_club(&self, t_s: Real) -> Isometry3 {
        let (_, i) = self.rotation_and_integral(t_s);
        let rot = UnitQuaternion::from_scaled_axis(self.angular_velocity_radps * t_s) * self.world_from_club.rotation;
        let p = self.world_from_club.translation.vector + i * self.cg_velocity_mps;
        Isometry3::from_parts(Translation3::from(p), rot)
    }

    /// The CG's velocity at `t_s` (m/s, world).
    pub fn cg_velocity_mps(&self, t_s: Real) -> Vector3 {
        self.rotation_and_integral(t_s).0 * self.cg_velocity_mps
    }

    /// The velocity of the club-frame point `p_club` at `t_s` (m/s, world).
    pub fn point_velocity_mps(&self, t_s: Real, p_club: &Vector3) -> Vector3 {
        let pose = self.world_from_club(t_s);
        self.cg_velocity_mps(t_s) + self.angular_velocity_radps.cross(&(pose.rotation * p_club))
    }

    /// The CG's acceleration `ω × v(t)` (m/s², world).
    pub fn cg_acceleration_mps2(&self, t_s: Real) -> Vector3 {
        self.angular_velocity_radps.cross(&self.cg_velocity_mps(t_s))
    }
}

/// [`ConstantTwist::at`] with `[ω]`, `[ω]²`, `|ω|` and the initial pose computed once.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PreparedTwist {
    k: Matrix3,
    k2: Matrix3,
    rate_radps: Real,
    rotation0: Matrix3,
    position0_m: Vector3,
    velocity0_mps: Vector3,
}

impl PreparedTwist {
    /// The rigid club's attitude (world from club), CG position and CG velocity at `t_s`.
    pub fn at(&self, t_s: Real) -> (crate::math::Rotation3, Vector3, Vector3) {
        let (k, k2, rate_radps) = (&self.k, &self.k2, self.rate_radps);
        let (r, i) = if rate_radps * t_s.abs() < 1e-6 {
            let r = Matrix3::identity() + k * t_s + k2 * (0.5 * t_s * t_s);
            let i = Matrix3::identity() * t_s + k * (0.5 * t_s * t_s) + k2 * (t_s.powi(3) / 6.0);
            (r, i)
        } else {
            let th = rate_radps * t_s;
            let (sin, cos) = crate::math::sin_cos_small(th);
            let r = Matrix3::identity() + k * (sin / rate_radps) + k2 * ((1.0 - cos) / (rate_radps * rate_radps));
            let i = Matrix3::identity() * t_s
                + k * ((1.0 - cos) / (rate_radps * rate_radps))
                + k2 * ((th - sin) / rate_radps.powi(3));
            (r, i)
        };
        let rot = crate::math::Rotation3::from_matrix_unchecked(r * self.rotation0);
        (rot, self.position0_m + i * self.velocity0_mps, r * self.velocity0_mps)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn twist() -> ConstantTwist {
        ConstantTwist {
            world_from_club: Isometry3::from_parts(
                Translation3::new(-0.01, 0.02, 0.0),
                UnitQuaternion::from_euler_angles(0.0, -0.05, -0.1),
            ),
            cg_velocity_mps: Vector3::new(38.0, -2.7, 1.0),
            angular_velocity_radps: Vector3::new(3.0, -6.0, -35.0),
        }
    }

    /// At t = 0 the motion is the delivery; its derivative is the CG velocity, and the attitude turns at ω.
    #[test]
    fn reproduces_the_delivery_and_differentiates() {
        let m = twist();
        assert!((m.world_from_club(0.0).translation.vector - m.world_from_club.translation.vector).norm() < 1e-15);
        for t in [-4e-3, 0.0, 2e-3] {
            let h = 1e-6;
            let d =
                (m.world_from_club(t + h).translation.vector - m.world_from_club(t - h).translation.vector) / (2.0 * h);
            assert!((d - m.cg_velocity_mps(t)).norm() < 1e-6, "{t}");
            let dr = m.world_from_club(t + h).rotation * m.world_from_club(t - h).rotation.inverse();
            let w = dr.scaled_axis() / (2.0 * h);
            assert!((w - m.angular_velocity_radps).norm() < 1e-6, "{t}");
            let dv = (m.cg_velocity_mps(t + h) - m.cg_velocity_mps(t - h)) / (2.0 * h);
            assert!((dv - m.cg_acceleration_mps2(t)).norm() < 1e-4);
            let (rot, p, v) = m.at(t);
            let (rot2, p2, v2) = m.prepared().at(t);
            assert!((rot.matrix() - rot2.matrix()).norm() < 1e-15 && (p - p2).norm() < 1e-15);
            assert!((v - v2).norm() < 1e-12);
            assert!((rot.matrix() - m.world_from_club(t).rotation.to_rotation_matrix().matrix()).norm() < 1e-12);
            assert!((p - m.world_from_club(t).translation.vector).norm() < 1e-15);
            assert!((v - m.cg_velocity_mps(t)).norm() < 1e-12);
            // Speed is constant under a constant twist.
            assert!((m.cg_velocity_mps(t).norm() - m.cg_velocity_mps.norm()).abs() < 1e-12);
        }
    }

    /// Without rotation the club translates in a straight line.
    #[test]
    fn no_rotation_is_a_straight_line() {
        let mut m = twist();
        m.angular_velocity_radps = Vector3::zeros();
        let p = m.world_from_club(-0.003).translation.vector;
        assert!((p - (m.world_from_club.translation.vector - 0.003 * m.cg_velocity_mps)).norm() < 1e-15);
    }
}
