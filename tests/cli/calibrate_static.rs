//! A static trial that is not static is refused with the motion measured (which marker, how far, in which
//! frame), unless `--static-mm` widens the limit: averaged, a club that moved gives a mean pose and a fit that
//! looks perfect.

use crate::static_trials::*;

use impactd::equipment::ClubSpec;

#[test]
fn a_moving_static_trial_is_refused_with_its_motion() {
    let dir = tempfile::tempdir().unwrap();
    let club = ClubSpec::driver();
    let (set, capture, cfg) =
        (dir.path().join("set.toml"), dir.path().join("club.c3d"), dir.path().join("impactd.toml"));
    std::fs::write(&set, marker_set(false, &club)).unwrap();
    let truth = world_from_lab(true);
    config(&cfg, &truth);
    // The whole club drifts 8 mm toward the target over the 50 frames: its ends are 4 mm from the mean.
    let markers = club_markers(&club, &world_from_club_at_address());
    let head = ["CROWN", "TOE", "HOSEL", "BACK", "SHAFT1", "SHAFT2"];
    write_trial(&capture, &truth, &markers, 11, (&head, 0.008));
    let (s, c, g) = (set.to_str().unwrap(), capture.to_str().unwrap(), cfg.to_str().unwrap());
    let base = ["calibrate", "club", c, "--markers", s, "-c", g, "--frames", "50", "--shaft", "SHAFT1,SHAFT2"];
    let err = impactd_refused(&base);
    assert!(err.contains("the trial is not static: marker `"), "{err}");
    let moved: f64 = err.split("` moved ").nth(1).unwrap().split(" mm").next().unwrap().parse().unwrap();
    assert!((moved - 4.0).abs() < 0.6, "{err}");
    assert!(err.contains("more than the 2.0 mm a static trial allows") && err.contains("--static-mm"), "{err}");
    // Widened, the same trial is taken, and the report says how far its markers moved.
    let err = impactd_ok(&[&base[..], &["--static-mm", "6"]].concat());
    assert!(err.contains("the most any marker used moved from its mean: 4.") && err.contains("limit 6.0 mm"), "{err}");
    // The same in a lab trial: one floor marker kicked 5 mm.
    let mut lab = floor_markers();
    lab.extend(markers);
    write_trial(&capture, &truth, &lab, 12, (&["F2"], 0.005));
    let err = impactd_refused(&[
        "calibrate",
        "lab",
        c,
        "--frames",
        "50",
        "--target-line",
        "REAR,FRONT",
        "--floor",
        "REAR,FRONT,F1,F2,F3",
    ]);
    assert!(err.contains("marker `F2` moved 2."), "{err}");
}
