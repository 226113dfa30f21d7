//! The synthetic rig's own checks: a club no swing fits, frames from one shot into the next, a failing rig.

use super::*;
use crate::equipment::FaceOutline;
use crate::impact::ImpactError;

/// Options for a rig whose club no swing fits: its face outline leaves out the face centre, so the drawn
/// strike and the centred one are both off the face.
fn club_without_a_centre() -> SimOptions {
    let mut club = ClubSpec::driver();
    club.face_outline = FaceOutline { vertices_mm: vec![[10.0, 10.0], [20.0, 10.0], [20.0, 20.0]] };
    SimOptions { club, shots: 1, wait_for_subscriber_s: 0.0, ..SimOptions::default() }
}

/// The off-face shot is an error naming the rig and the shot, with the impact layer's refusal as its source
/// (it was a panic: "a centred swing is always valid").
#[test]
fn a_shot_no_swing_fits_is_an_error_not_a_panic() {
    let mut rig = SimRig::new("bay1", &club_without_a_centre(), 1_000_000_000, 1);
    let e = rig.next_sample().unwrap_err();
    assert!(matches!(&e, DaemonError::SimSwing { rig, shot: 1, .. } if rig == "bay1"), "{e:?}");
    let source = std::error::Error::source(&e).and_then(|s| s.downcast_ref::<ImpactError>());
    assert!(matches!(source, Some(ImpactError::OffFace { h_mm, v_mm }) if *h_mm == 0.0 && *v_mm == 0.0), "{e}");
    assert!(e.to_string().starts_with("rig bay1: shot 1 cannot be swung"), "{e}");
}

/// The rig's frames run through each shot and into the next (the pair of shots moves on at each span); a
/// rig of the same seed gives the same frames.
#[test]
fn the_frames_follow_one_shot_into_the_next_the_same_for_a_seed() {
    let options = SimOptions { shots: 3, interval_s: 0.2, ..SimOptions::default() };
    let frames = || {
        let mut rig = SimRig::new("bay1", &options, 1_000_000_000, 5);
        let mut out = Vec::new();
        while !rig.done() {
            out.push(rig.next_sample().unwrap());
        }
        out
    };
    let (a, b) = (frames(), frames());
    assert_eq!(a.len(), b.len());
    assert!(a.iter().zip(&b).all(|(x, y)| x.0 == y.0 && x.1 == y.1));
    let truths: Vec<u64> = a.iter().filter_map(|(_, t)| t.as_ref().map(|t| t.shot)).collect();
    assert_eq!(truths, [1, 2, 3]);
    // Where one shot's span gives way to the next, the club waits at the top of the shot it glided to: the
    // frames either side differ by the glide's last millimetres and the noise, not by another swing's top.
    let span = |s: &ClubheadSample| (s.t_ns - 1_000_000_000) / 200_000_000;
    let jumps: Vec<f64> = a
        .windows(2)
        .filter(|w| span(&w[0].0) != span(&w[1].0))
        .map(|w| (w[1].0.position_m - w[0].0.position_m).norm())
        .collect();
    assert_eq!(jumps.len(), 3, "{jumps:?}");
    assert!(jumps.iter().all(|&j| j < 0.01), "{jumps:?} m where one shot gives way to the next");
}

/// `run_sim` returns the rig's error (it was a panic in the rig's thread, its shots lost without a word).
#[tokio::test(flavor = "multi_thread")]
async fn run_sim_fails_with_the_rig_that_cannot_swing() {
    let endpoint = format!("tcp/127.0.0.1:{}", crate::daemon::bus::free_loopback_port().unwrap());
    let session = crate::daemon::bus::ZenohArgs::loopback(vec![endpoint], vec![]).open().await.unwrap();
    let r = run_sim(&session, club_without_a_centre(), std::future::pending()).await;
    let _ = session.close().await;
    assert!(matches!(r, Err(DaemonError::SimSwing { shot: 1, .. })), "{r:?}");
}

/// The truth is predicted by the default model, with the club file's parameters when given.
#[test]
fn the_truth_is_the_default_model_with_the_club_files_parameters() {
    assert_eq!(TRUTH.as_str(), crate::impact::registry::DEFAULT_MODEL);
    let loaded = crate::equipment::load_club("iron7").unwrap();
    let tuning = ImpulseTuning::from_sections(&loaded.club, &loaded.sections).unwrap();
    let options = SimOptions { club: loaded.club, tuning: Some(tuning), ..SimOptions::default() };
    let rig = SimRig::new("bay1", &options, 1_000_000_000, 5);
    assert_eq!(rig.truth_model.tuning, Some(tuning));
    assert_eq!(SimRig::new("bay1", &SimOptions::default(), 0, 5).truth_model.tuning, None);
}
