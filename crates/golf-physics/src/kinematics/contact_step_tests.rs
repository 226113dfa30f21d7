//! Synthetic swings with a speed step at a known instant: the face centre on a 1.4 m arc at 45 m/s, slowing at
//! 20 m/s², its speed stepping down by a fraction over the 0.5 ms contact, with Gaussian noise on each frame's
//! position; the geometric contact the search starts from is off by up to a frame.

use super::*;
use crate::rng::Rng;

const RADIUS_M: Real = 1.4;

/// The frames of one swing at `rate_hz`: 16 before and 16 after the reference, the true step `offset_s` after it.
fn swing(rate_hz: Real, drop: Real, noise_m: Real, offset_s: Real, rng: &mut Rng) -> Vec<(Real, Vector3)> {
    let (v0, decel) = (45.0, 20.0);
    // Path length at time t from the true step's start (the contact).
    let s = |t: Real| {
        let free = v0 * t - 0.5 * decel * t * t;
        let lost = if t <= 0.0 {
            0.0
        } else if t < CONTACT_S {
            drop * v0 * t * t / (2.0 * CONTACT_S)
        } else {
            drop * v0 * (t - 0.5 * CONTACT_S)
        };
        free - lost
    };
    let phase = rng.unit() / rate_hz;
    (-16..16)
        .map(|k| {
            let t = k as Real / rate_hz + phase;
            let angle = s(t - offset_s) / RADIUS_M;
            let p = Vector3::new(RADIUS_M * angle.sin(), RADIUS_M * (1.0 - angle.cos()), 0.0);
            (t, p + Vector3::new(rng.normal(), rng.normal(), rng.normal()) * noise_m)
        })
        .collect()
}

/// Over `n` swings: the largest error of the placed instant against the truth (the step's centre, a quarter of
/// the contact's length after its start) in frame intervals, and how many were refused.
fn errors(rate_hz: Real, drop: Real, noise_m: Real, n: u64) -> (Real, usize, Option<StepUnresolved>) {
    let (mut worst, mut refused, mut why) = (0.0f64, 0, None);
    for seed in 0..n {
        let mut rng = Rng::new(seed);
        let offset_s = (rng.unit() - 0.5) / rate_hz;
        match find(&swing(rate_hz, drop, noise_m, offset_s, &mut rng), noise_m) {
            Ok(step) => {
                let truth = offset_s + 0.5 * CONTACT_S;
                worst = worst.max((step.t_from_contact_s - truth).abs() * rate_hz);
            }
            Err(e) => {
                refused += 1;
                why = Some(e);
            }
        }
    }
    (worst, refused, why)
}

#[test]
fn the_im_model_takes_a_third_of_a_drivers_speed() {
    let f = im_speed_drop_fraction(0.0459, 0.204, 0.83);
    assert!((f - 1.83 * 0.0459 / 0.2499).abs() < 1e-12 && (f - 0.336).abs() < 1e-3, "{f}");
}

/// Every step placed is within one frame interval of the truth, at every rate and step size; how many are placed
/// grows with the step and the rate (printed: the table in docs/estimation.md).
#[test]
fn at_720_and_360_hz_a_step_is_placed_within_one_frame_interval_and_never_guessed() {
    for rate in [720.0, 360.0, 240.0] {
        for drop in [0.01, 0.02, 0.03, 0.3] {
            let (worst, refused, _) = errors(rate, drop, 0.2e-3, 200);
            println!(
                "{rate} Hz, {:.0} % step, 0.2 mm: {} of 200 placed, worst error {worst:.3} frame intervals",
                drop * 100.0,
                200 - refused
            );
            assert!(worst < 1.0, "{rate} Hz {drop}: worst {worst}");
        }
    }
    assert_eq!(errors(720.0, 0.02, 0.2e-3, 200).1, 0, "720 Hz: every 2 % step placed");
    assert!(errors(360.0, 0.03, 0.2e-3, 200).1 <= 10, "360 Hz: 95 % of 3 % steps placed");
}

#[test]
fn the_im_models_step_is_placed_at_every_rate() {
    for rate in [720.0, 360.0, 240.0] {
        let (worst, refused, why) = errors(rate, 0.3, 0.2e-3, 100);
        println!("{rate} Hz, 30 % step: worst error {worst:.3} frame intervals, {refused} refused {why:?}");
        assert!(worst < 1.0 && refused == 0, "{rate} Hz: worst {worst}, refused {refused}: {why:?}");
    }
}

#[test]
fn at_240_hz_a_one_percent_step_is_below_the_noise_and_is_not_guessed() {
    let (worst, refused, why) = errors(240.0, 0.01, 0.3e-3, 100);
    println!("240 Hz, 1 % step, 0.3 mm: worst error {worst:.3} frame intervals, {refused} refused {why:?}");
    assert!(worst < 1.0, "a placed step is within a frame interval: {worst}");
    assert!(refused >= 90, "{refused} of 100 refused");
    assert!(matches!(why, Some(StepUnresolved::BelowNoise { .. })), "{why:?}");
    assert!(why.unwrap().to_string().contains("below the noise"));
}

#[test]
fn without_frames_after_the_contact_there_is_no_step() {
    let mut rng = Rng::new(1);
    let frames: Vec<_> = swing(720.0, 0.02, 0.2e-3, 0.0, &mut rng).into_iter().filter(|f| f.0 < 0.001).collect();
    assert!(matches!(find(&frames, 0.2e-3), Err(StepUnresolved::TooFewFrames { .. })));
}
