//! Clubs change during a session: a daemon on loopback with a synthetic rig switches its club by a put on
//! `golf/<rig>/club` (a preset name) and by another tracked body coming into view (`[rig.clubs]`, a club file);
//! a bad put is refused and changes nothing. The recording, read back by Python's `mcap` (an independent reader),
//! says which club file each launch used (SHA-256 computed by Python's `hashlib` from the files' bytes), and the
//! launches after each switch are those `impactd predict --club NEW` gives for the recorded delivery, not the old
//! club's; the rig's status on `golf/<rig>/status` names its club now (name and the file's SHA-256) after each
//! switch; `impactd replay` switches where the session did and reproduces every launch byte for byte.

#![allow(clippy::unwrap_used)]

use crate::common;

use std::time::Duration;

use common::{client, python, start_daemon};
use impactd::daemon::sim::{run_sim, SimOptions};
use impactd::daemon::RunOptions;
use impactd::equipment::load_club;
use impactd::wire::keys;
use zenoh::Wait;

const SHOTS: u64 = 2;

/// The independent reader: the recorded club changes and each launch's club file, checked against the files'
/// SHA-256; prints each launch's shot, club name and delivery as JSON lines.
const CHECK: &str = r#"
import hashlib, json, sys
from mcap.reader import make_reader

recording, driver, sw, eight = sys.argv[1:5]
sha = {name: hashlib.sha256(open(path, "rb").read()).hexdigest() for name, path in
       (("driver", driver), ("sw", sw), ("eight", eight))}
changes, launches, bodies = [], [], set()
with open(recording, "rb") as f:
    for schema, channel, message in make_reader(f).iter_messages():
        if channel.topic == "/golf/bay1/club":
            assert schema.name == "impactd.ClubChange", schema.name
            changes.append(json.loads(message.data))
        elif channel.topic == "/golf/bay1/launch":
            launches.append(json.loads(message.data))
        elif channel.topic == "/mocap/bay1/clubhead":
            bodies.add(json.loads(message.data).get("body"))
assert bodies == {None, "eight"}, bodies
# At start (the configuration), by the put (a preset), by the body (a club file): the bad put left no trace.
assert [(c["source"], c["club"]["file"], c.get("body")) for c in changes] == [
    ("config", "driver", None), ("put", "sw", None), ("body", eight, "eight")], changes
assert [c["club"]["sha256"] for c in changes] == [sha["driver"], sha["sw"], sha["eight"]], changes
assert all(c["models"] == ["adjusted"] for c in changes), changes
assert [l["shot"] for l in launches] == list(range(1, 7)), [l["shot"] for l in launches]
for l in launches:
    want = ["driver", "sw", "eight"][(l["shot"] - 1) // 2]
    assert l["club_file"]["sha256"] == sha[want], (l["shot"], l["club_file"], want)
    print(json.dumps({"shot": l["shot"], "club": l["club"], "delivery": l["delivery"], "launch": l["launch"]}))
"#;

async fn swing(session: &zenoh::Session, club: &str, body: Option<&str>, seed: u64) {
    let options = SimOptions {
        rigs: vec!["bay1".into()],
        club: load_club(club).unwrap().club,
        shots: SHOTS,
        interval_s: 0.6,
        seed,
        body: body.map(str::to_string),
        ..SimOptions::default()
    };
    run_sim(session, options, std::future::pending()).await.unwrap();
    tokio::time::sleep(Duration::from_millis(300)).await;
}

/// `impactd predict --club CLUB` on a recorded delivery: (ball speed mph, launch angle deg, backspin rpm).
fn predict(club: &str, delivery: &serde_json::Value) -> (f64, f64, f64) {
    let d = delivery;
    let line = serde_json::json!({
        "club_speed_mph": d["club_speed_mph"], "attack_angle_deg": d["attack_angle_deg"],
        "club_path_deg": d["club_path_deg"], "face_angle_deg": d["face_angle_deg"],
        "dynamic_loft_deg": d["dynamic_loft_deg"], "impact_h_mm": d["impact_h_mm"],
        "impact_v_mm": d["impact_v_mm"], "club_angular_velocity_radps": d["club_angular_velocity_radps"],
    });
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_impactd"))
        .args(["predict", "--club", club, "--model", "adjusted"])
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    use std::io::Write;
    child.stdin.take().unwrap().write_all(format!("{line}\n").as_bytes()).unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stdout));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    (
        v["ball_speed_mph"].as_f64().unwrap(),
        v["launch_angle_deg"].as_f64().unwrap(),
        v["backspin_rpm"].as_f64().unwrap(),
    )
}

fn launch_of(l: &serde_json::Value) -> (f64, f64, f64) {
    let f = |k: &str| l[k].as_f64().unwrap();
    (f("ball_speed_mph"), f("launch_angle_deg"), f("backspin_rpm"))
}

#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn a_put_and_a_body_switch_the_club_and_the_recording_says_which() {
    let dir = tempfile::tempdir().unwrap();
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let eight = dir.path().join("my-8-iron.toml");
    let text = std::fs::read_to_string(root.join("clubs/presets/iron8.toml")).unwrap();
    std::fs::write(&eight, text.replace("name = \"iron8\"", "name = \"my 8-iron\"")).unwrap();
    let eight = eight.to_str().unwrap().to_string();
    let config = format!(
        "status_period_s = 0.2\n[[rig]]\nname = \"bay1\"\nclub = \"driver\"\nmodel = \"adjusted\"\n\
         [rig.clubs]\neight = \"{eight}\"\n"
    );
    let recording = dir.path().join("switch.mcap");
    let options = RunOptions { record: Some(recording.clone()), ..Default::default() };
    let daemon = start_daemon(&config, options).await;
    let session = client(&daemon.endpoint).await;
    let club_key = session.declare_publisher(keys::club("bay1")).await.unwrap();
    let (statuses, _status_sub) = common::collect::<impactd::wire::StatusMessage>(&session, "golf/bay1/status");
    // The rig's status names its club now: name and the SHA-256 of its file (as `sha256sum` prints it).
    let sha = |path: &std::path::Path| -> String {
        let bytes = std::fs::read(path).unwrap();
        let digest = <sha2::Sha256 as sha2::Digest>::digest(&bytes);
        digest.iter().map(|b| format!("{b:02x}")).collect()
    };
    let status_says = |name: &str, sha256: String| {
        let statuses = statuses.clone();
        let name = name.to_string();
        async move {
            let says = || {
                let s = statuses.lock().unwrap();
                s.last().and_then(|s| s.club.clone()).is_some_and(|c| c.name == name && c.sha256 == sha256)
            };
            common::wait_until(Duration::from_secs(30), says).await
        }
    };
    assert!(status_says("driver", sha(&root.join("clubs/presets/driver.toml"))).await, "the status names the driver");
    assert!(
        common::wait_until(Duration::from_secs(10), || club_key.matching_status().wait().is_ok_and(|m| m.matching()))
            .await
    );

    swing(&session, "driver", None, 11).await;
    // A club that does not exist, and a payload that is not text: refused, the driver stays.
    club_key.put("putter").await.unwrap();
    club_key.put(vec![0xffu8, 0xfe]).await.unwrap();
    club_key.put("sw").await.unwrap();
    tokio::time::sleep(Duration::from_millis(300)).await;
    swing(&session, "sw", None, 12).await;
    assert!(status_says("sw", sha(&root.join("clubs/presets/sw.toml"))).await, "the status names the put's club");
    swing(&session, &eight, Some("eight"), 13).await;
    let eight_sha = sha(std::path::Path::new(&eight));
    assert!(status_says("my 8-iron", eight_sha).await, "the status names the body's club");
    // Every swing's shots reach the daemon before it stops, however long their samples take on the way.
    let all_predicted = || statuses.lock().unwrap().last().is_some_and(|s| s.predictions >= 3 * SHOTS);
    assert!(common::wait_until(Duration::from_secs(60), all_predicted).await);
    let summary = daemon.stop().await;
    session.close().await.unwrap();
    let counts = &summary.rigs["bay1"];
    assert_eq!((counts.shots, counts.predictions), (3 * SHOTS, 3 * SHOTS), "{counts:?}");

    let out = python()
        .args(["-c", CHECK, recording.to_str().unwrap()])
        .arg(root.join("clubs/presets/driver.toml"))
        .arg(root.join("clubs/presets/sw.toml"))
        .arg(&eight)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    // A replay switches the clubs where the session did (the put's preset loaded again and its hash checked;
    // the body's samples name it) and so reproduces every recorded launch byte for byte.
    let replay = std::process::Command::new(env!("CARGO_BIN_EXE_impactd"))
        .args(["replay", recording.to_str().unwrap()])
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&replay.stderr).to_string() + &String::from_utf8_lossy(&replay.stdout);
    assert!(said.contains("6 of 6 recorded predictions reproduced byte for byte"), "{said}");
    let launches: Vec<serde_json::Value> =
        String::from_utf8(out.stdout).unwrap().lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    assert_eq!(launches.len() as u64, 3 * SHOTS);

    // Each launch is what its club predicts for the recorded delivery; the club before the switch predicts
    // another launch. The delivery re-entered as TrackMan's numbers leaves out the dynamic lie and closure
    // rate the pipeline's state has: within 0.1 % of ball speed, 0.1° of launch and 0.5 % of backspin; the old
    // club's launch is off by more than three times that in at least one of them.
    for l in &launches {
        let shot = l["shot"].as_u64().unwrap();
        let (club, before) = match shot {
            1 | 2 => ("driver", None),
            3 | 4 => ("sw", Some("driver")),
            _ => (eight.as_str(), Some("sw")),
        };
        let (speed, angle, spin) = launch_of(&l["launch"]);
        let (p_speed, p_angle, p_spin) = predict(club, &l["delivery"]);
        eprintln!(
            "shot {shot} {club}: {speed:.2} {angle:.2} {spin:.0} / predict {p_speed:.2} {p_angle:.2} {p_spin:.0}"
        );
        assert!((speed / p_speed - 1.0).abs() < 1e-3, "shot {shot}: {speed} vs {p_speed} mph");
        assert!((angle - p_angle).abs() < 0.1, "shot {shot}: {angle} vs {p_angle} deg");
        assert!((spin / p_spin - 1.0).abs() < 5e-3, "shot {shot}: {spin} vs {p_spin} rpm");
        if let Some(old) = before {
            let (o_speed, o_angle, o_spin) = predict(old, &l["delivery"]);
            eprintln!("  old club {old}: {o_speed:.2} {o_angle:.2} {o_spin:.0}");
            let moved = (speed / o_speed - 1.0).abs() > 3e-3
                || (angle - o_angle).abs() > 0.3
                || (spin / o_spin - 1.0).abs() > 0.015;
            assert!(moved, "shot {shot}: the old club {old} predicts the same launch");
        }
    }
}
