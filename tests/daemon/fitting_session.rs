//! A fitting session end to end: ten clubs and three players, swung by the synthetic rig (`daemon::sim`) into the
//! daemon (`daemon::run`, recording), labelled by puts on `golf/<rig>/session`; then `impactd session` and
//! `impactd export --format trackman-csv` on the recording, checked against an independent reader (Python's `mcap`
//! and `csv` modules, computing the statistics with `statistics`).
//!
//! `compare` on the export reproduces, shot by shot and number by number, the residuals the daemon recorded live
//! on `golf/<rig>/comparison` against a launch monitor's measurements.
//!
//! The ten clubs are the presets of a driver, 3-wood, hybrid, 4- to 9-iron and pitching wedge
//! (`clubs/presets/`); each rig holds one of them.

#![allow(clippy::unwrap_used)]

use crate::common;

use std::time::Duration;

use common::{client, python, start_daemon};
use impactd::daemon::sim::{run_sim, SimOptions};
use impactd::daemon::RunOptions;
use impactd::wire::keys;
use zenoh::Wait;

/// (rig, the fitter's club label, the club preset the rig holds).
const CLUBS: [(&str, &str, &str); 10] = [
    ("c1", "Driver", "driver"),
    ("c2", "3 Wood", "wood3"),
    ("c3", "Hybrid", "hybrid"),
    ("c4", "4 Iron", "iron4"),
    ("c5", "5 Iron", "iron5"),
    ("c6", "6 Iron", "iron6"),
    ("c7", "7 Iron", "iron7"),
    ("c8", "8 Iron", "iron8"),
    ("c9", "9 Iron", "iron9"),
    ("c10", "Pitching Wedge", "pw"),
];
const PLAYERS: [&str; 3] = ["ann", "bob", "cy"];
const SHOTS_PER_PLAYER: u64 = 2;

fn impactd(args: &[&str]) -> String {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_impactd")).args(args).output().unwrap();
    assert!(out.status.success(), "impactd {args:?}: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).unwrap()
}

/// The independent reader: every prediction of the recording (the first per rig and shot), grouped by the
/// club label, each metric's count, mean, sample SD and median; and the exported CSV read with `csv`.
const CHECK: &str = r#"
import csv, json, math, statistics, sys
from mcap.reader import make_reader

recording, session_json, by_player_json, export_csv = sys.argv[1:5]
shots = {}
with open(recording, "rb") as f:
    for _schema, channel, message in make_reader(f).iter_messages():
        if channel.topic.startswith("/golf/") and channel.topic.endswith("/launch"):
            p = json.loads(message.data)
            shots.setdefault((p["rig"], p["shot"]), p)

def arc(p, k):
    a = p["delivery"].get("swing_arc")
    return None if a is None else a[k]

METRICS = {
    "club_speed_mph": lambda p: p["delivery"]["club_speed_mph"],
    "attack_angle_deg": lambda p: p["delivery"]["attack_angle_deg"],
    "club_path_deg": lambda p: p["delivery"]["club_path_deg"],
    "face_angle_deg": lambda p: p["delivery"]["face_angle_deg"],
    "face_to_path_deg": lambda p: p["delivery"]["face_to_path_deg"],
    "dynamic_loft_deg": lambda p: p["delivery"]["dynamic_loft_deg"],
    "spin_loft_deg": lambda p: p["delivery"]["spin_loft_deg"],
    "swing_plane_deg": lambda p: arc(p, "swing_plane_deg"),
    "swing_direction_deg": lambda p: arc(p, "swing_direction_deg"),
    "low_point_in": lambda p: None if arc(p, "low_point_distance_mm") is None else arc(p, "low_point_distance_mm") / 25.4,
    "ball_speed_mph": lambda p: p["launch"]["ball_speed_mph"],
    "smash_factor": lambda p: p["launch"]["smash_factor"],
    "launch_angle_deg": lambda p: p["launch"]["launch_angle_deg"],
    "launch_direction_deg": lambda p: p["launch"]["launch_direction_deg"],
    "spin_rate_rpm": lambda p: p["launch"]["total_spin_rpm"],
    "spin_axis_deg": lambda p: p["launch"]["spin_axis_deg"],
    "carry_yd": lambda p: p["flight"]["carry_yd"],
    "total_yd": lambda p: p["flight"]["total_yd"],
    "side_yd": lambda p: p["flight"]["offline_yd"],
    "apex_ft": lambda p: p["flight"]["apex_m"] / 0.3048,
    "land_angle_deg": lambda p: p["flight"]["land_angle_deg"],
    "carry_m": lambda p: p["flight"]["carry_m"],
    "club_speed_mps": lambda p: p["delivery"]["club_speed_mps"],
}

def close(a, b):
    return math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-9)

def check(summary, key_of, expect_groups):
    assert summary["excluded"] == [], summary["excluded"]
    groups = {}
    for p in shots.values():
        groups.setdefault(key_of(p), []).append(p)
    assert sorted(groups) == sorted(expect_groups), (sorted(groups), expect_groups)
    got = {g["group"]: g for g in summary["groups"]}
    assert sorted(got) == sorted(groups), (sorted(got), sorted(groups))
    for name, members in groups.items():
        g = got[name]
        assert g["shots"] == len(members), (name, g["shots"], len(members))
        for key, value in METRICS.items():
            values = [v for v in (value(p) for p in members) if v is not None]
            m = g["metrics"][key]
            assert m["count"] == len(values), (name, key, m["count"], len(values))
            if not values:
                continue
            sd = statistics.stdev(values) if len(values) > 1 else 0.0
            for stat, want in (("mean", statistics.fmean(values)), ("sd", sd), ("median", statistics.median(values))):
                assert close(m[stat], want), (name, key, stat, m[stat], want)

clubs = json.loads(sys.argv[5])
players = json.loads(sys.argv[6])
check(json.load(open(session_json)), lambda p: p["labels"]["club"], clubs)
check(json.load(open(by_player_json)), lambda p: p["labels"]["player"], players)

# The TrackMan export: the sep line, the header, the units row, one row per shot with the recorded numbers.
with open(export_csv, newline="") as f:
    assert f.readline().strip() == "sep=,"
    rows = list(csv.reader(f))
header, units, data = rows[0], rows[1], rows[2:]
expected_header = json.loads(sys.argv[7])
assert header == expected_header, header
assert units[header.index("Club Speed")] == "[mph]" and units[header.index("Carry Flat - Length")] == "[yds]"
assert len(data) == len(shots), (len(data), len(shots))
col = {h: i for i, h in enumerate(header)}
by_key = {}
for r in data:
    by_key[(r[col["Player"]], r[col["Club"]], int(r[col["TMD No"]]))] = r
for (rig, shot), p in shots.items():
    r = by_key[(p["labels"]["player"], p["labels"]["club"], shot)]
    pairs = [("Club Speed", p["delivery"]["club_speed_mph"]), ("Club Path", p["delivery"]["club_path_deg"]),
             ("Face Angle", p["delivery"]["face_angle_deg"]), ("Ball Speed", p["launch"]["ball_speed_mph"]),
             ("Launch Direction", p["launch"]["launch_direction_deg"]), ("Spin Rate", p["launch"]["total_spin_rpm"]),
             ("Spin Axis", p["launch"]["spin_axis_deg"]), ("Carry Flat - Length", p["flight"]["carry_yd"]),
             ("Carry Flat - Side", p["flight"]["offline_yd"]), ("Impact Offset", p["delivery"]["impact_h_mm"])]
    for name, want in pairs:
        assert abs(float(r[col[name]]) - want) <= 1e-3, (rig, shot, name, r[col[name]], want)
print(len(shots))
"#;

#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn ten_clubs_three_players_session_and_export_match_an_independent_reader() {
    let dir = tempfile::tempdir().unwrap();
    let mut config = String::from("status_period_s = 1.0\n");
    let mut clubs = Vec::new();
    for (rig, name, preset) in CLUBS {
        config += &format!("[[rig]]\nname = \"{rig}\"\nclub = \"{preset}\"\nmodel = \"adjusted\"\n");
        clubs.push((rig, name, impactd::equipment::load_club(preset).unwrap().club));
    }
    let recording = dir.path().join("fitting.mcap");
    let options = RunOptions { record: Some(recording.clone()), ..Default::default() };
    let daemon = start_daemon(&config, options).await;
    let session = client(&daemon.endpoint).await;
    let received = common::Received::watch(&session);
    let swings = clubs.iter().enumerate().map(|(i, (rig, name, club))| {
        let session = &session;
        async move {
            let mut sent = 0;
            // Puts reach only subscribers the session knows of: wait until the daemon's is matched.
            let publisher = session.declare_publisher(keys::session(rig)).await.unwrap();
            assert!(
                common::wait_until(Duration::from_secs(10), || publisher
                    .matching_status()
                    .wait()
                    .is_ok_and(|m| m.matching()))
                .await
            );
            for (j, player) in PLAYERS.iter().enumerate() {
                let labels =
                    serde_json::json!({"player": player, "club": name, "tags": ["fitting", format!("set{j}")]});
                publisher.put(labels.to_string()).await.unwrap();
                tokio::time::sleep(Duration::from_millis(200)).await;
                let options = SimOptions {
                    rigs: vec![rig.to_string()],
                    club: club.clone(),
                    shots: SHOTS_PER_PLAYER,
                    interval_s: 0.6,
                    seed: 100 + 10 * i as u64 + j as u64,
                    ..SimOptions::default()
                };
                sent += run_sim(session, options, std::future::pending()).await.unwrap().samples;
                tokio::time::sleep(Duration::from_millis(300)).await;
            }
            (rig.to_string(), sent)
        }
    });
    let sent = futures_util::future::join_all(swings).await.into_iter().collect();
    assert!(received.all(&sent).await, "the daemon received every sample sent: {sent:?}");
    let summary = daemon.stop().await;
    session.close().await.unwrap();
    let predicted: u64 = summary.rigs.values().map(|c| c.predictions).sum();
    let expected = CLUBS.len() as u64 * PLAYERS.len() as u64 * SHOTS_PER_PLAYER;
    assert_eq!(predicted, expected, "{:?}", summary.rigs);

    // The synthetic rig's truth is recorded beside the predictions, so the session can be scored afterwards.
    let topics = common::recorded(&recording);
    let truths: usize = topics.iter().filter(|(t, _)| t.starts_with("/sim/")).map(|(_, m)| m.len()).sum();
    assert_eq!(truths as u64, expected, "{:?}", topics.keys().collect::<Vec<_>>());
    let labels: usize = topics.iter().filter(|(t, _)| t.ends_with("/session")).map(|(_, m)| m.len()).sum();
    assert_eq!(labels, CLUBS.len() * PLAYERS.len(), "every put recorded");
    let rec = recording.to_str().unwrap();
    let by_club = dir.path().join("by_club.json");
    std::fs::write(&by_club, impactd(&["session", rec, "--json"])).unwrap();
    let by_player = dir.path().join("by_player.json");
    std::fs::write(&by_player, impactd(&["session", rec, "--by", "player", "--json"])).unwrap();
    let csv = dir.path().join("export.csv");
    impactd(&["export", rec, "--format", "trackman-csv", "-o", csv.to_str().unwrap()]);
    let club_names: Vec<&str> = CLUBS.iter().map(|c| c.1).collect();
    // TrackMan's header, then impactd's columns after it.
    let (trackman, ours) = (impactd::session::trackman_csv::COLUMNS, impactd::session::trackman_csv::IMPACTD_COLUMNS);
    let header: Vec<&str> = trackman.iter().chain(ours.iter()).map(|c| c.0).collect();
    let out = python()
        .args(["-c", CHECK, rec, by_club.to_str().unwrap(), by_player.to_str().unwrap(), csv.to_str().unwrap()])
        .arg(serde_json::to_string(&club_names).unwrap())
        .arg(serde_json::to_string(&PLAYERS).unwrap())
        .arg(serde_json::to_string(&header).unwrap())
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert_eq!(String::from_utf8_lossy(&out.stdout).trim(), expected.to_string());

    // The table shows gapping longest club first, and compare reads the export as measured shots.
    let table = impactd(&["session", rec]);
    let gaps = table.split("gapping (mean carry)").nth(1).unwrap();
    assert!(gaps.trim_start().starts_with("Driver"), "{table}");
    let compared = impactd(&["compare", csv.to_str().unwrap(), "--models", "adjusted", "--club", "iron7", "--json"]);
    assert!(compared.contains("adjusted"), "{compared}");

    // `plot dispersion` draws every club, the target line and the axes' units.
    let svg = dir.path().join("dispersion.svg");
    impactd(&["plot", "dispersion", rec, "--units", "metric", "-o", svg.to_str().unwrap()]);
    let svg = std::fs::read_to_string(svg).unwrap();
    for (_, name, _) in CLUBS {
        assert!(svg.contains(&format!("{name} ({} shots)", PLAYERS.len() as u64 * SHOTS_PER_PLAYER)), "{name}");
    }
    assert!(
        svg.contains("target line") && svg.contains("carry (m)") && svg.contains("side (m; right of the target +)")
    );
}

/// What the test's "launch monitor" adds to each predicted field (ball speed mph, launch deg, direction deg,
/// backspin rpm, sidespin rpm), so each recorded residual (predicted - measured) is known: minus these.
const OFFSET: [f64; 5] = [1.25, -0.5, 0.75, 120.0, -45.0];

#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn compare_on_the_export_reproduces_the_recorded_residuals() {
    let dir = tempfile::tempdir().unwrap();
    let config = "status_period_s = 1.0\n[[rig]]\nname = \"bay1\"\nclub = \"driver\"\nmodel = \"adjusted\"\n";
    let recording = dir.path().join("measured.mcap");
    let options = RunOptions { record: Some(recording.clone()), ..Default::default() };
    let daemon = start_daemon(config, options).await;
    let session = client(&daemon.endpoint).await;
    // The launch monitor: each prediction measured 0.2 s after its impact, every field offset by OFFSET.
    let lm = session.declare_publisher(keys::measured_launch("bay1")).await.unwrap();
    assert!(
        common::wait_until(Duration::from_secs(10), || lm.matching_status().wait().is_ok_and(|m| m.matching())).await
    );
    let (tx, mut rx) = tokio::sync::mpsc::unbounded_channel::<impactd::wire::LaunchPrediction>();
    let _sub = session
        .declare_subscriber(keys::launch("bay1"))
        .callback(move |s| {
            let _ = tx.send(serde_json::from_slice(&s.payload().to_bytes()).unwrap());
        })
        .wait()
        .unwrap();
    let shots = 8u64;
    let measure = async {
        for _ in 0..shots {
            let p = rx.recv().await.unwrap();
            let m = &p.launch.launch;
            let measured = serde_json::json!({
                "rig": "bay1", "t_ns": p.t_impact_ns + 200_000_000, "device": "test monitor", "shot_number": p.shot,
                "ball_speed_mph": m.ball_speed_mph + OFFSET[0], "launch_angle_deg": m.launch_angle_deg + OFFSET[1],
                "launch_direction_deg": m.launch_direction_deg + OFFSET[2],
                "backspin_rpm": m.backspin_rpm + OFFSET[3], "sidespin_rpm": m.sidespin_rpm + OFFSET[4]});
            lm.put(measured.to_string()).await.unwrap();
        }
    };
    let sim = SimOptions {
        rigs: vec!["bay1".into()],
        club: impactd::equipment::ClubSpec::driver(),
        shots,
        interval_s: 0.6,
        seed: 21,
        ..SimOptions::default()
    };
    let (swung, ()) = tokio::join!(run_sim(&session, sim, std::future::pending()), measure);
    swung.unwrap();
    tokio::time::sleep(Duration::from_millis(500)).await;
    daemon.stop().await;
    session.close().await.unwrap();

    let topics = common::recorded(&recording);
    let recorded = &topics["/golf/bay1/comparison"];
    assert_eq!(recorded.len() as u64, shots, "one comparison per shot");
    let rec = recording.to_str().unwrap();
    let csv_path = dir.path().join("export.csv");
    impactd(&["export", rec, "--format", "trackman-csv", "-o", csv_path.to_str().unwrap()]);
    let out = impactd(&[
        "compare",
        csv_path.to_str().unwrap(),
        "--models",
        "adjusted",
        "--club",
        "driver",
        "--json",
        "--residuals",
    ]);
    let out: serde_json::Value = serde_json::from_str(&out).unwrap();
    let residuals = out["residuals"].as_array().unwrap();
    assert_eq!(residuals.len() as u64, shots);
    // The export's rows, in compare's order: each row's shot number.
    let text = std::fs::read_to_string(&csv_path).unwrap();
    let mut rows =
        csv::ReaderBuilder::new().has_headers(false).from_reader(text.split_once('\n').unwrap().1.as_bytes());
    let records: Vec<csv::StringRecord> = rows.records().map(Result::unwrap).collect();
    let tmd_no = records[0].iter().position(|h| h == "TMD No").unwrap();
    let fields = ["ball_speed_mph", "launch_angle_deg", "launch_direction_deg", "backspin_rpm", "sidespin_rpm"];
    // Tolerances: the export writes the delivery to 6 decimals (1e-6 deg, mph, mm), which moves a launch by
    // far less than these (about 1e-5 mph, 1e-5 deg, 1e-3 rpm per 1e-6 deg of face or loft).
    let tolerance = [1e-4, 1e-4, 1e-4, 0.02, 0.02];
    let mut worst = [0.0f64; 5];
    for (row, r) in records[2..].iter().zip(residuals) {
        let shot: u64 = row[tmd_no].parse().unwrap();
        let c = recorded.iter().find(|c| c["shot"] == shot).unwrap();
        for (k, field) in fields.iter().enumerate() {
            let live = c["residual"][field].as_f64().unwrap();
            // The recorded residual is the launch monitor's offset, as sent.
            assert!((live + OFFSET[k]).abs() < 1e-6, "shot {shot} {field}: recorded {live}");
            let again = r["residual"][field].as_f64().unwrap();
            worst[k] = worst[k].max((again - live).abs());
            assert!((again - live).abs() <= tolerance[k], "shot {shot} {field}: compare {again}, recorded {live}");
        }
    }
    eprintln!("compare on the export against the recorded residuals, largest differences: {worst:?}");
}
