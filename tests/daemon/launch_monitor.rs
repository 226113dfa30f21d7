//! The Open Connect listener for real: a launch monitor connector on loopback TCP talks to a running daemon as
//! it would to a simulator, with glued, fragmented, malformed, oversized and repeated messages. Each shot is
//! answered 200 and published once as a `MeasuredLaunch` on zenoh and recorded; each bad message is answered
//! 501 with its reason, and the connection (and the next shot) carries on.

#![allow(clippy::unwrap_used)]
#![cfg(feature = "daemon")]

use crate::common;

use std::time::Duration;

use common::{collect, recorded, start_daemon, wait_until};
use impactd::daemon::bridges::open_connect::codec::Reply;
use impactd::daemon::bridges::open_connect::splitter::{Frame, Splitter};
use impactd::daemon::RunOptions;
use impactd::wire::{MeasuredLaunch, StatusMessage};
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;

/// A shot as a launch monitor connector sends it (the field layout of GSPro's Open Connect v1 page).
fn shot(number: u64, speed_mph: f64, vla_deg: f64) -> String {
    format!(
        r#"{{"DeviceID":"LM 1","Units":"Yards","ShotNumber":{number},"APIversion":"1","BallData":{{"Speed":{speed_mph},"SpinAxis":-3.5,"TotalSpin":2650.0,"HLA":1.25,"VLA":{vla_deg}}},"ClubData":{{"Speed":104.0,"AngleOfAttack":2.0,"FaceToTarget":0.5,"Path":1.5}},"ShotDataOptions":{{"ContainsBallData":true,"ContainsClubData":true}}}}"#
    )
}

const HEARTBEAT: &str = r#"{"DeviceID":"LM 1","Units":"Yards","ShotNumber":0,"APIversion":"1","ShotDataOptions":{"ContainsBallData":false,"ContainsClubData":false,"LaunchMonitorIsReady":true,"IsHeartBeat":true}}"#;

/// Reads replies until `n` have come (or a second passes without one).
async fn replies(stream: &mut TcpStream, splitter: &mut Splitter, n: usize) -> Vec<Reply> {
    let mut out = Vec::new();
    let mut buf = vec![0u8; 4096];
    while out.len() < n {
        let read = tokio::time::timeout(Duration::from_secs(2), stream.read(&mut buf)).await;
        let Ok(Ok(k)) = read else { break };
        if k == 0 {
            break;
        }
        splitter.push(&buf[..k], &mut |f| {
            if let Frame::Object(o) = f {
                out.push(serde_json::from_slice::<Reply>(&o).unwrap());
            }
        });
    }
    out
}

#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn every_shot_is_published_once_and_bad_messages_are_answered_and_survived() {
    let port = impactd::daemon::bus::free_loopback_port().unwrap();
    let config = format!(
        "status_period_s = 0.3\n[[rig]]\nname = \"bay1\"\n[rig.launch_monitor]\nopen_connect_listen = \"127.0.0.1:{port}\"\n"
    );
    let dir = tempfile::tempdir().unwrap();
    let recording = dir.path().join("lm.mcap");
    let daemon = start_daemon(&config, RunOptions { record: Some(recording.clone()), ..Default::default() }).await;
    let observer = common::client(&daemon.endpoint).await;
    let (measured, _s1) = collect::<MeasuredLaunch>(&observer, "lm/bay1/launch");
    let (statuses, _s2) = collect::<StatusMessage>(&observer, "golf/bay1/status");
    tokio::time::sleep(Duration::from_millis(300)).await;

    let mut lm = TcpStream::connect(("127.0.0.1", port)).await.unwrap();
    let mut splitter = Splitter::new(64 * 1024);
    let expect = |got: &[Reply], codes: &[u16]| {
        assert_eq!(got.iter().map(|r| r.code).collect::<Vec<_>>(), codes, "{got:?}");
    };
    // Two shots glued in one write.
    lm.write_all(format!("{}{}", shot(1, 150.5, 11.0), shot(2, 148.0, 12.5)).as_bytes()).await.unwrap();
    expect(&replies(&mut lm, &mut splitter, 2).await, &[200, 200]);
    // A shot split across three writes, with pauses between.
    let third = shot(3, 120.25, 18.0);
    for part in [&third[..7], &third[7..200], &third[200..]] {
        lm.write_all(part.as_bytes()).await.unwrap();
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
    expect(&replies(&mut lm, &mut splitter, 1).await, &[200]);
    // Malformed JSON, bytes outside any object, an object over 64 KiB, a heartbeat (not answered), the same
    // shot again (answered, not published twice), impossible numbers, then a good shot, all in one write.
    let oversized = format!(r#"{{"DeviceID":"LM 1","Pad":"{}"}}"#, "x".repeat(70_000));
    let burst = [
        r#"{"DeviceID": nope}"#.to_string(),
        "hello\r\n".to_string(),
        oversized,
        HEARTBEAT.to_string(),
        third.clone(),
        shot(5, 140.0, 143.0),
        shot(4, 99.5, 21.0),
    ]
    .concat();
    lm.write_all(burst.as_bytes()).await.unwrap();
    let got = replies(&mut lm, &mut splitter, 6).await;
    expect(&got, &[501, 501, 501, 200, 501, 200]);
    assert!(got[0].message.contains("not an Open Connect v1 message"), "{}", got[0].message);
    assert!(got[1].message.contains("outside any JSON object"), "{}", got[1].message);
    assert!(got[2].message.contains("over the 65536-byte limit"), "{}", got[2].message);
    assert!(got[3].message.contains("already received"), "{}", got[3].message);
    assert!(got[4].message.contains("VLA"), "{}", got[4].message);

    assert!(wait_until(Duration::from_secs(30), || measured.lock().unwrap().len() >= 4).await);
    tokio::time::sleep(Duration::from_millis(400)).await;
    let summary = daemon.stop().await;
    observer.close().await.unwrap();

    let measured = measured.lock().unwrap().clone();
    let numbers: Vec<_> = measured.iter().map(|m| m.shot_number.unwrap()).collect();
    assert_eq!(numbers, [1, 2, 3, 4], "each shot published once, in order");
    let m = &measured[2];
    assert_eq!((m.rig.as_str(), m.device.as_str()), ("bay1", "open_connect:LM 1"));
    assert_eq!((m.ball_speed_mph, m.launch_angle_deg, m.launch_direction_deg), (120.25, 18.0, 1.25));
    assert_eq!((m.total_spin_rpm, m.spin_axis_deg), (Some(2650.0), Some(-3.5)));
    // back = total cos(axis), side = total sin(axis) (ARCHITECTURE.md section 2: axis + = tilted right).
    let (back, side) = m.spin_components_rpm().unwrap();
    assert!((back - 2650.0 * 3.5f64.to_radians().cos()).abs() < 1e-9 && side < 0.0);
    assert_eq!(m.club.as_ref().unwrap().club_speed_mph, Some(104.0));

    let lm_status = &summary.launch_monitors["bay1"];
    assert_eq!((lm_status.shots, lm_status.duplicates, lm_status.heartbeats), (4, 1, 1), "{lm_status:?}");
    for reason in ["malformed", "not_json", "oversized", "invalid"] {
        assert_eq!(lm_status.rejected.get(reason), Some(&1), "{reason}: {lm_status:?}");
    }
    assert!(statuses.lock().unwrap().iter().any(|s| s.launch_monitor.as_ref().is_some_and(|l| l.shots == 4)));
    let rec = recorded(&recording);
    assert_eq!(rec["/lm/bay1/launch"].len(), 4, "each shot recorded once");
    let traffic = &rec["/lm/bay1/open_connect"];
    let sent = traffic.iter().filter(|t| t["direction"] == "sent").count();
    assert_eq!(sent, 9, "every reply recorded");
}
