//! Picking up another club, through a real NatNet input: a NatNet server on 127.0.0.1 (unicast) streams two
//! rigid bodies, `club` and `wand`; the rig maps them to the driver and the 7-iron (`[rig.clubs]`). A driver swing
//! on `club` (the wand out of view), then a 7-iron swing on `wand` (the club out of view) give one launch with
//! each club, each naming its club file, with no command in between.

#![allow(clippy::unwrap_used)]

use crate::common;
use crate::natnet_server;

use std::time::Duration;

use common::{client, collect, start_daemon, wait_until};
use impactd::daemon::sim::{SimOptions, SimRig};
use impactd::daemon::RunOptions;
use impactd::equipment::{load_club, presets, sha256_hex};
use impactd::kinematics::ClubheadSample;
use impactd::mocap::natnet::{Frame, RigidBody, Version};
use impactd::wire::{LaunchPrediction, StatusMessage};
use natnet_server::{NatNetServer, CLOCK_HZ};

/// One swing of `club` at 720 Hz, capture times from `start_ns`.
fn swing(club: &str, start_ns: u64, seed: u64) -> Vec<ClubheadSample> {
    let options =
        SimOptions { club: load_club(club).unwrap().club, shots: 1, interval_s: 0.4, seed, ..Default::default() };
    let mut rig = SimRig::new("rig1", &options, start_ns, seed);
    let mut out = Vec::new();
    while !rig.done() {
        out.push(rig.next_sample().unwrap().0);
    }
    out
}

/// A frame with both bodies: `s` on the tracked one (id 3 `club`, or id 7 `wand`), the other not tracked.
fn frame(s: &ClubheadSample, frame_number: i32, on_wand: bool) -> Frame {
    let pose = RigidBody {
        id: if on_wand { 7 } else { 3 },
        position_m: [s.position_m.x as f32, s.position_m.y as f32, s.position_m.z as f32],
        orientation_xyzw: s.orientation_xyzw.map(|v| v as f32),
        mean_error_m: 0.0002,
        tracking_valid: !s.occluded,
    };
    let away = RigidBody { id: if on_wand { 3 } else { 7 }, position_m: [0.0; 3], tracking_valid: false, ..pose };
    let t_s = s.t_ns as f64 * 1e-9;
    Frame {
        frame_number,
        rigid_bodies: vec![away, pose],
        labeled_markers: Vec::new(),
        timestamp_s: t_s,
        mid_exposure_ticks: (t_s * CLOCK_HZ as f64) as u64,
        data_received_ticks: (t_s * CLOCK_HZ as f64) as u64 + 20_000,
        transmit_ticks: (t_s * CLOCK_HZ as f64) as u64 + 35_000,
        models_changed: false,
    }
}

#[tokio::test(flavor = "multi_thread")]
async fn another_tracked_body_switches_the_club() {
    let server = NatNetServer::start(Version::V4_1, &[(7, "wand"), (3, "club")]);
    let config = format!(
        "status_period_s = 0.2\n[[rig]]\nname = \"rig1\"\nclub = \"driver\"\n[rig.input]\nnatnet = \"127.0.0.1\"\n\
         body = \"club\"\nunicast = true\ncommand_port = {}\ndata_port = 0\n[rig.clubs]\nclub = \"driver\"\n\
         wand = \"iron7\"\n",
        server.port
    );
    let daemon = start_daemon(&config, RunOptions::default()).await;
    let session = client(&daemon.endpoint).await;
    let (launches, _l) = collect::<LaunchPrediction>(&session, "golf/rig1/launch");
    let (statuses, _s) = collect::<StatusMessage>(&session, "golf/rig1/status");
    assert!(
        wait_until(Duration::from_secs(10), || server.model_requests.load(std::sync::atomic::Ordering::Relaxed) > 0)
            .await
    );
    assert_eq!(server.clients(), 1, "the daemon is the server's one client");
    tokio::time::sleep(Duration::from_millis(200)).await;
    let driver = swing("driver", 1_000_000_000, 5);
    let iron = swing("iron7", driver.last().unwrap().t_ns + 1_000_000_000, 6);
    let frames = driver.iter().map(|s| (s, false)).chain(iron.iter().map(|s| (s, true)));
    for (i, (s, on_wand)) in frames.enumerate() {
        server.send_frame(&frame(s, i as i32 + 1, on_wand));
        if i % 4 == 3 {
            std::thread::sleep(Duration::from_millis(2));
        }
    }
    assert!(wait_until(Duration::from_secs(10), || launches.lock().unwrap().len() >= 2).await, "two launches");
    tokio::time::sleep(Duration::from_millis(500)).await;
    let launches = launches.lock().unwrap().clone();
    let status = statuses.lock().unwrap().last().cloned().unwrap();
    daemon.stop().await;

    let sha = |name: &str| sha256_hex(presets::find(name).unwrap().bytes());
    let used: Vec<(String, String)> =
        launches.iter().map(|l| l.club_file.as_ref().map(|c| (c.file.clone(), c.sha256.clone())).unwrap()).collect();
    assert_eq!(used, [("driver".into(), sha("driver")), ("iron7".into(), sha("iron7"))], "{status:?}");
    assert_eq!(launches.iter().map(|l| l.club.as_str()).collect::<Vec<_>>(), ["driver", "iron7"]);
    // The body out of view is occluded, never rejected; nothing was refused.
    assert!(status.rejected.is_empty(), "{:?}", status.rejected);
    assert_eq!((status.shots, status.predictions), (2, 2), "{status:?}");
}
