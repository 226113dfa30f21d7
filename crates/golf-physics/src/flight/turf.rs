//! Bounce and roll on a fairway: Penner's model of the run of a golf ball (A. R. Penner, "The run of a golf
//! ball", Can. J. Phys. 80 (2002) 931-940; also in "The physics of golf: the optimum loft of a driver",
//! Am. J. Phys. 69 (2001) 563), with the turf's firmness as one configurable number.
//!
//! - Bounce: the ball, rigid, meets the turf as if it met a rigid plane tilted back toward it by the effective
//!   contact angle `θ_c = 15.4° · (v_i / 18.6 m/s) · (θ_i / 44.4°)` (the crater the ball presses into soft
//!   turf), `v_i` the landing speed and `θ_i` the angle of descent. Relative to that plane the normal speed is
//!   restored by `e = 0.510 − 0.0375 v_n + 0.000903 v_n²` (`v_n` ≤ 20 m/s; 0.120 above) and the tangential
//!   impulse is Coulomb friction `μ = 0.4` times the normal impulse, unless less brings the contact point to rest
//!   (the ball then leaves rolling: `v_t' = (5 v_t − 2 r ω) / 7` with backspin `ω`, the rigid sphere's result).
//! - Hops between bounces are parabolas (the air's forces at a few m/s are negligible); once the ball leaves the
//!   turf at less than [`SETTLE_MPS`] upward, it stays on the ground: it slides with friction `μ g` until it
//!   rolls, then rolls to rest against the turf's rolling resistance `μ_r g` (`μ_r` = [`ROLL_RESISTANCE`] on
//!   Penner's fairway). Backspin that outlasts the forward speed rolls the ball back.
//!
//! Firmness `f` in [0, 1] moves the three turf properties from soft to firm, with Penner's fairway at 0.5: the
//! contact angle scales by `1.5 − f` (half Penner's on firm turf, half again as much on soft), the restitution
//! by `0.85 + 0.3 f`, and the rolling resistance by `2^(0.5 − f)` (√2 times Penner's at 0, 1/√2 at 1). Only the
//! middle is measured; the ends are this model's reading of soft and firm turf.
//!
//! The bounce is taken in the vertical plane of the ball's travel, with the backspin about the horizontal axis
//! across it; sidespin does not act on the ground.

use crate::math::Real;

/// Penner's effective contact angle (deg) at the reference landing speed and angle.
pub const CONTACT_ANGLE_DEG: Real = 15.4;
/// Penner's reference landing speed (m/s) and angle of descent (deg) for the contact angle.
pub const CONTACT_REF_MPS: Real = 18.6;
/// Penner's reference angle of descent (deg) for the contact angle.
pub const CONTACT_REF_DEG: Real = 44.4;
/// Coulomb friction between ball and turf.
pub const FRICTION: Real = 0.4;
/// Rolling resistance of Penner's fairway (deceleration / g of a rolling ball).
pub const ROLL_RESISTANCE: Real = 0.131;
/// The ball stays on the ground once it leaves the turf slower than this upward (m/s).
pub const SETTLE_MPS: Real = 0.3;
/// At most this many bounces.
const MAX_BOUNCES: usize = 20;

/// The turf the ball lands on.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Turf {
    /// 0 soft (wet turf), 0.5 Penner's fairway, 1 firm (dry links turf).
    pub firmness: Real,
}

impl Default for Turf {
    fn default() -> Self {
        Turf { firmness: 0.5 }
    }
}

/// Why a ground is not usable.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TurfError {
    /// `firmness` outside 0-1 (or not finite).
    #[error("`firmness` must be within 0 and 1, got {0}")]
    Firmness(Real),
}

/// One stretch of the run: a hop (a parabola) or a slide or roll (constant deceleration along the ground).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    /// Start, from landing (s).
    pub t0_s: Real,
    /// How long it lasts (s).
    pub duration_s: Real,
    /// Distance along the line of travel from the landing point at the start (m), speed and acceleration along it.
    pub d0_m: Real,
    /// Speed along the line of travel at the start (m/s).
    pub v_mps: Real,
    /// Acceleration along the line of travel (m/s², negative: slowing).
    pub a_mps2: Real,
    /// Upward speed at the start of a hop (0 on the ground).
    pub up_mps: Real,
}

impl Segment {
    /// Distance along the line of travel and height, `tau_s` into the segment.
    pub fn at(&self, tau_s: Real, g: Real) -> (Real, Real) {
        let d = self.d0_m + self.v_mps * tau_s + 0.5 * self.a_mps2 * tau_s * tau_s;
        let y = if self.up_mps > 0.0 { self.up_mps * tau_s - 0.5 * g * tau_s * tau_s } else { 0.0 };
        (d, y.max(0.0))
    }
}

/// The run after landing.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Run {
    /// Where the ball comes to rest, along the line of travel from the landing point (m; negative: spun back).
    pub roll_m: Real,
    /// Time from landing to rest (s).
    pub duration_s: Real,
    /// Hops before the ball settles.
    pub bounces: usize,
    /// The hops, then the slide and roll, in time order.
    pub segments: Vec<Segment>,
}

impl Turf {
    /// Checks that `firmness` is within 0-1.
    pub fn validate(&self) -> Result<(), TurfError> {
        if self.firmness.is_finite() && (0.0..=1.0).contains(&self.firmness) {
            Ok(())
        } else {
            Err(TurfError::Firmness(self.firmness))
        }
    }

    /// Penner's normal restitution at normal speed `v_n_mps`, scaled for the firmness.
    pub fn restitution(&self, v_n_mps: Real) -> Real {
        let e = if v_n_mps <= 20.0 { 0.510 - 0.0375 * v_n_mps + 0.000903 * v_n_mps * v_n_mps } else { 0.120 };
        (e * (0.85 + 0.3 * self.firmness)).min(0.9)
    }

    /// The effective contact angle (rad) for landing speed `v_mps` at `descent_rad` below the horizontal.
    pub fn contact_angle_rad(&self, v_mps: Real, descent_rad: Real) -> Real {
        let deg = CONTACT_ANGLE_DEG * (v_mps / CONTACT_REF_MPS) * (descent_rad.to_degrees() / CONTACT_REF_DEG);
        (deg * (1.5 - self.firmness)).to_radians()
    }

    /// Deceleration of a rolling ball (m/s²).
    pub fn roll_decel_mps2(&self, g: Real) -> Real {
        ROLL_RESISTANCE * (2.0 as Real).powf(0.5 - self.firmness) * g
    }

    /// One bounce: the velocity along the travel line and upward, and the backspin (rad/s), in; out the same.
    pub fn bounce(&self, along_mps: Real, down_mps: Real, backspin_radps: Real, radius_m: Real) -> (Real, Real, Real) {
        let v_i = along_mps.hypot(down_mps);
        let descent = down_mps.atan2(along_mps.abs().max(1e-12));
        let tilt = self.contact_angle_rad(v_i, descent) * along_mps.signum();
        let (sin_c, cos_c) = tilt.sin_cos();
        // The incoming velocity in the tilted plane's tangent (forward) and normal (into the turf) directions.
        let v_t = along_mps * cos_c - down_mps * sin_c;
        let v_n = along_mps * sin_c + down_mps * cos_c;
        let e = self.restitution(v_n);
        // Topspin about the forward direction; the contact point slips forward at v_t − r Ω.
        let topspin = -backspin_radps;
        let slip = v_t - radius_m * topspin;
        let to_roll = 2.0 / 7.0 * slip;
        let max_impulse = FRICTION * (1.0 + e) * v_n;
        let j = if to_roll.abs() <= max_impulse { to_roll } else { max_impulse * slip.signum() };
        let v_t_out = v_t - j;
        let topspin_out = topspin + 2.5 * j / radius_m;
        let v_n_out = e * v_n;
        let along_out = v_t_out * cos_c + v_n_out * sin_c;
        let up_out = -v_t_out * sin_c + v_n_out * cos_c;
        (along_out, up_out, -topspin_out)
    }

    /// The run from a landing with `along_mps` forward, `down_mps` downward and backspin `backspin_radps`,
    /// starting at time `t0_s`.
    pub fn run(
        &self,
        along_mps: Real,
        down_mps: Real,
        backspin_radps: Real,
        radius_m: Real,
        g: Real,
        t0_s: Real,
    ) -> Run {
        let mut segments = Vec::new();
        let (mut along, mut down, mut back) = (along_mps, down_mps, backspin_radps);
        let (mut d, mut t) = (0.0, t0_s);
        let mut bounces = 0;
        loop {
            let (a, up, w) = self.bounce(along, down, back, radius_m);
            bounces += 1;
            (along, back) = (a, w);
            if up < SETTLE_MPS || bounces >= MAX_BOUNCES {
                break;
            }
            let hop = 2.0 * up / g;
            segments.push(Segment { t0_s: t, duration_s: hop, d0_m: d, v_mps: along, a_mps2: 0.0, up_mps: up });
            d += along * hop;
            t += hop;
            down = up;
        }
        // Slide until the contact point stops slipping, then roll to rest.
        let topspin = -back;
        let slip = along - radius_m * topspin;
        if slip.abs() > 1e-9 {
            let a = -FRICTION * g * slip.signum();
            let dur = 2.0 * slip.abs() / (7.0 * FRICTION * g);
            segments.push(Segment { t0_s: t, duration_s: dur, d0_m: d, v_mps: along, a_mps2: a, up_mps: 0.0 });
            d += along * dur + 0.5 * a * dur * dur;
            t += dur;
            along += a * dur;
        }
        if along.abs() > 1e-9 {
            let decel = self.roll_decel_mps2(g);
            let dur = along.abs() / decel;
            let a = -decel * along.signum();
            segments.push(Segment { t0_s: t, duration_s: dur, d0_m: d, v_mps: along, a_mps2: a, up_mps: 0.0 });
            d += along * dur + 0.5 * a * dur * dur;
            t += dur;
        }
        Run { roll_m: d, duration_s: t - t0_s, bounces, segments }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Penner's restitution: 0.51 at rest, 0.151 at 15 m/s (0.510 − 0.5625 + 0.2032), 0.12 past 20 m/s.
    #[test]
    fn penner_restitution() {
        let g = Turf::default();
        assert!((g.restitution(0.0) - 0.510).abs() < 1e-12);
        assert!((g.restitution(15.0) - 0.150675).abs() < 1e-9);
        assert!((g.restitution(25.0) - 0.120).abs() < 1e-12);
    }

    /// Closed form: when friction suffices, the ball leaves the (tilted) contact plane rolling, with the rigid
    /// sphere's `v_t' = (5 v_t − 2 r ω) / 7` along the plane and topspin `v_t' / r`.
    #[test]
    fn rolling_exit_is_the_rigid_sphere_result() {
        let g = Turf::default();
        let (r, along, down, w): (Real, Real, Real, Real) = (0.0213, 10.0, 8.0, 300.0);
        let tilt = g.contact_angle_rad(along.hypot(down), down.atan2(along));
        let (sin_c, cos_c) = tilt.sin_cos();
        let v_t = along * cos_c - down * sin_c;
        let (along_out, up_out, back_out) = g.bounce(along, down, w, r);
        let v_t_out = along_out * cos_c - up_out * sin_c;
        let expected = (5.0 * v_t - 2.0 * r * w) / 7.0;
        assert!((v_t_out - expected).abs() < 1e-9, "{v_t_out} vs {expected}");
        assert!((back_out + v_t_out / r).abs() < 1e-6, "rolls: topspin = v / r");
    }

    /// Energy never increases at a bounce.
    #[test]
    fn a_bounce_loses_energy() {
        let r = 0.0213;
        let inertia = 0.4 * r * r;
        for firmness in [0.0, 0.3, 0.5, 0.8, 1.0] {
            let g = Turf { firmness };
            for (a, d, w) in [(20.0, 15.0, 300.0), (10.0, 12.0, 800.0), (25.0, 8.0, 100.0), (5.0, 10.0, 900.0)] {
                let (a2, u2, w2) = g.bounce(a, d, w, r);
                let before = a * a + d * d + inertia * w * w;
                let after = a2 * a2 + u2 * u2 + inertia * w2 * w2;
                assert!(after <= before + 1e-9, "{firmness}: {before} -> {after}");
            }
        }
    }
}
