//! Tests of the pose fits (`fit.rs`).

use super::*;

/// A quadratic position and a constant-acceleration rotation about a fixed axis are reproduced exactly by a
/// degree-2 fit, including extrapolation.
#[test]
fn exact_for_polynomial_motion() {
    let axis = Vector3::new(0.2, 0.9, -0.3).normalize();
    let r0 = UnitQuaternion::from_euler_angles(0.1, 0.2, -0.3);
    let truth = |t: Real| {
        (
            Vector3::new(1.0 + 40.0 * t + 300.0 * t * t, 0.5 - 2.0 * t, 0.1 * t * t),
            r0 * so3::exp(&(axis * (30.0 * t + 500.0 * t * t))),
        )
    };
    let poses: Vec<TimedPose> = (0..10)
        .map(|k| {
            let t = -0.02 + k as Real / 720.0;
            let (p, q) = truth(t);
            TimedPose { t_s: t, position_m: p, orientation: q }
        })
        .collect();
    let fit = PoseFit::fit(&poses, 2, 2).unwrap();
    let t = 0.0;
    let s = fit.at(t);
    let (p, q) = truth(t);
    assert!((s.position_m - p).norm() < 1e-9);
    assert!((s.velocity_mps - Vector3::new(40.0, -2.0, 0.0)).norm() < 1e-7);
    assert!(q.angle_to(&s.orientation) < 1e-9);
    let w = r0 * axis * (30.0 + 1000.0 * t);
    assert!((s.angular_velocity_radps - w).norm() < 1e-6, "{} vs {w}", s.angular_velocity_radps);
}

/// The fits' weights of each frame at a time reproduce the fitted value and rate: `Σ a_k p_k` is the fitted
/// position and `Σ ȧ_k p_k` its velocity, extrapolated too; the rotation fit's weights of a constant give
/// the constant (`Σ b_k = 1`, `Σ ḃ_k = 0`). `kinematics::uncertainty` carries the frames' shared errors
/// through them.
#[test]
fn shared_weights_reproduce_the_fit() {
    let poses: Vec<TimedPose> = (0..24)
        .map(|k| {
            let t = -0.03 + k as Real / 720.0;
            let p = Vector3::new(1.0 + 40.0 * t + 300.0 * t * t + 2e4 * t * t * t, 0.5 - 2.0 * t, (90.0 * t).sin());
            TimedPose { t_s: t, position_m: p, orientation: so3::exp(&Vector3::new(0.0, 30.0 * t, 0.0)) }
        })
        .collect();
    let series = PoseSeries::new(&poses, 16).unwrap();
    let fit = series.fit(20, 3, 16, 2).unwrap();
    let times: Vec<Real> = poses.iter().map(|p| p.t_s).collect();
    let t = 0.004;
    let w = fit.shared_weights(&times, t);
    assert_eq!(w.len(), 16);
    let (mut p, mut v) = (Vector3::zeros(), Vector3::zeros());
    let newest = poses.len() - 20;
    // The position fit's weights over all its 20 frames: the shared 16 are its newest.
    let taus: Vec<Real> = times[newest..].iter().map(|x| (x - fit.t_ref_s) / fit.scale_s).collect();
    for ((a, da), pose) in fit.position_factor.weights((t - fit.t_ref_s) / fit.scale_s, &taus).zip(&poses[newest..]) {
        p += a * pose.position_m;
        v += da / fit.scale_s * pose.position_m;
    }
    let at = fit.at(t);
    assert!((p - at.position_m).norm() < 1e-9, "{p} vs {}", at.position_m);
    assert!((v - at.velocity_mps).norm() < 1e-6, "{v} vs {}", at.velocity_mps);
    for (k, &(t_k, a, da, _, _)) in w.iter().enumerate() {
        let all = fit.position_factor.weights((t - fit.t_ref_s) / fit.scale_s, &taus).nth(4 + k).unwrap();
        assert_eq!(t_k, times[8 + k]);
        assert!((a - all.0).abs() < 1e-12 && (da - all.1 / fit.scale_s).abs() < 1e-9);
    }
    let (sb, sdb) = w.iter().fold((0.0, 0.0), |(s, d), x| (s + x.3, d + x.4));
    assert!((sb - 1.0).abs() < 1e-9 && sdb.abs() < 1e-6, "{sb} {sdb}");
}
