//! Vicon DataStream, live: a DataStream server in this test (TCP on 127.0.0.1) that Vicon's own C++ client (the
//! DataStream SDK 1.11, built by scripts/vicon-sdk-client.sh) reads as it reads Nexus, Tracker or Shogun, in
//! ServerPush and ClientPull; and impactd's own decoder reading the same server.

#![allow(clippy::unwrap_used)]

use crate::common;
use crate::scene;
use crate::vicon_server;

use std::io::{Read, Write};
use std::time::{Duration, Instant};

use common::wait_for;
use impactd::mocap::vicon::enums::CLIENT_WANTS;
use impactd::mocap::vicon::{encode, framing, Decoder, DynamicObjects};
use serde_json::Value;
use vicon_server::ViconServer;

fn nums(v: &Value) -> Vec<f64> {
    v.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect()
}

/// Plays the scene at 720 Hz until `done`, at most 20 s (a hang guard).
fn play_until(server: &ViconServer, done: impl Fn() -> bool) -> u32 {
    let t0 = Instant::now();
    let mut i = 0;
    while !done() && t0.elapsed() < Duration::from_secs(20) {
        server.send_frame_with(&scene::frame(i), scene::unchanged(i));
        i += 1;
        std::thread::sleep(Duration::from_micros(1389));
    }
    i
}

/// Checks one frame the SDK printed against the scene's frame of that number: everything exactly.
fn check_frame(got: &Value) -> u32 {
    let number = got["frame_number"].as_u64().unwrap() as u32;
    let i = number - 1 - 5000;
    let want: DynamicObjects = scene::frame(i);
    assert_eq!(got["rate_hz"].as_f64(), Some(720.0));
    assert_eq!(got["up"], "Z");
    // The server's latency samples, by name; the SDK adds its own network estimate once it has 20 pings.
    let samples = got["latency"].as_array().unwrap();
    for w in &want.latency {
        let s = samples.iter().find(|s| s["name"] == w.name.as_str()).unwrap_or_else(|| panic!("{got}"));
        assert_eq!(s["s"].as_f64(), Some(w.latency_s));
    }
    let total: f64 = samples.iter().map(|s| s["s"].as_f64().unwrap()).sum();
    assert_eq!(got["latency_total_s"].as_f64(), Some(total));
    let tc = want.timecode.unwrap();
    let t = &got["timecode"];
    assert_eq!(
        [
            &t["hours"],
            &t["minutes"],
            &t["seconds"],
            &t["frames"],
            &t["subframe"],
            &t["subframes_per_frame"],
            &t["user_bits"]
        ]
        .map(|v| v.as_u64().unwrap()),
        [tc.hours as u64, tc.minutes as u64, tc.seconds as u64, tc.frames as u64, tc.subframe as u64, 24, 0xBEEF]
    );
    assert_eq!(t["field"].as_bool(), Some(tc.field != 0));
    assert_eq!(t["standard"], 2, "the SDK's NTSC is 2 (its None is 0)");

    let subjects = got["subjects"].as_array().unwrap();
    assert_eq!(subjects.len(), 2);
    let club = &subjects[0];
    assert_eq!((club["name"].as_str(), club["root"].as_str()), (Some("club"), Some("club")));
    let seg = &club["segments"][0];
    assert_eq!((seg["name"].as_str(), seg["parent"].as_str()), (Some("club"), Some("")));
    match want.segments.iter().find(|p| p.subject_id == scene::CLUB) {
        Some(p) => {
            assert_eq!(seg["occluded"], false);
            assert_eq!(nums(&seg["translation_mm"]), p.translation_mm);
            assert_eq!(nums(&seg["rotation"]), p.rotation, "row-major, exactly");
        }
        None => assert_eq!((&seg["occluded"], &seg["rotation_occluded"]), (&Value::Bool(true), &Value::Bool(true))),
    }
    let markers = club["markers"].as_array().unwrap();
    let names: Vec<&str> = markers.iter().map(|m| m["name"].as_str().unwrap()).collect();
    assert_eq!(names, scene::CLUB_MARKERS);
    for (k, m) in markers.iter().enumerate() {
        assert_eq!(m["parent"], "club");
        match want.markers.iter().find(|r| r.subject_id == scene::CLUB && r.marker_id == k as u32 + 1) {
            Some(r) => {
                assert_eq!(m["occluded"], false, "{got}");
                assert_eq!(nums(&m["translation_mm"]), r.position_mm);
            }
            None => assert_eq!(m["occluded"], true, "{got}"),
        }
    }
    let ball = &subjects[1];
    assert_eq!(ball["name"], "ball");
    assert_eq!(nums(&ball["segments"][0]["translation_mm"]), [0.0, 0.0, 21.335]);
    i
}

fn sdk_reads(mode: &str) {
    let server = ViconServer::start(scene::statics());
    let frames = 60;
    let child = std::process::Command::new(scene::sdk_client())
        .args([format!("127.0.0.1:{}", server.port), mode.to_string(), frames.to_string()])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let pid = child.id();
    let exited = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    let e = exited.clone();
    let waiter = std::thread::spawn(move || {
        let out = child.wait_with_output().unwrap();
        e.store(true, std::sync::atomic::Ordering::Relaxed);
        out
    });
    assert!(wait_for(|| server.clients() > 0), "the SDK client {pid} did not connect");
    let played = play_until(&server, || exited.load(std::sync::atomic::Ordering::Relaxed));
    let out = waiter.join().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "the SDK client failed ({}): {stderr}", out.status);
    let lines: Vec<Value> =
        String::from_utf8_lossy(&out.stdout).lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    assert_eq!(lines.len(), frames);
    let mut last = None;
    let (mut occluded, mut marker_gaps) = (0, 0);
    for got in &lines {
        assert_eq!(got["mode"], mode);
        let i = check_frame(got);
        assert!(last.is_none_or(|l| i > l), "frame numbers increase");
        last = Some(i);
        occluded += usize::from(i % 7 == 3);
        marker_gaps += usize::from(i % 5 == 1 && scene::unchanged(i).is_empty());
    }
    eprintln!(
        "{mode}: {frames} frames checked of {played} played; {occluded} occluded, {marker_gaps} with a marker hidden"
    );
    assert!(occluded > 0 && marker_gaps > 0, "the frames read include occlusions");
    if mode == "pull" {
        assert!(server.pull_requests() >= frames as u64);
    } else {
        assert!(server.pings() > 0, "the SDK pings after each frame; the server answered");
    }
}

/// Vicon's SDK reads the test server in ServerPush: frame number (the id plus one), rate (135 MHz over the
/// period), latency samples, timecode, the up axis, subjects with their root segment, the segment's global
/// translation and row-major rotation exactly, occlusion, the labelled markers (one hidden every 5th frame;
/// every 11th frame's markers listed unchanged in `Contents` and carried over).
#[test]
fn vicon_sdk_reads_the_test_server_in_server_push() {
    sdk_reads("push");
}

/// The same in ClientPull: one frame per `RequestFrame`.
#[test]
fn vicon_sdk_reads_the_test_server_in_client_pull() {
    sdk_reads("pull");
}

/// impactd's decoder reads the same server: the handshake, `ObjectEnums` asked, ServerPush, and every frame's
/// objects equal to what the server sent (the unchanged markers carried over), pings answered.
#[test]
fn impactd_decoder_reads_the_test_server() {
    let server = ViconServer::start(scene::statics());
    let mut stream = std::net::TcpStream::connect(("127.0.0.1", server.port)).unwrap();
    stream.set_read_timeout(Some(Duration::from_secs(5))).unwrap();
    let mut decoder = Decoder::new();
    let read_packet = |stream: &mut std::net::TcpStream, decoder: &mut Decoder| {
        let mut head = [0u8; framing::HEADER_BYTES];
        stream.read_exact(&mut head).unwrap();
        let len = framing::header(&head).unwrap();
        let mut packet = head.to_vec();
        packet.resize(framing::HEADER_BYTES + len, 0);
        stream.read_exact(&mut packet[framing::HEADER_BYTES..]).unwrap();
        decoder.decode(&packet).unwrap()
    };
    let greeting = read_packet(&mut stream, &mut decoder);
    assert!(greeting.object_enums && !greeting.frame);
    assert!(CLIENT_WANTS.iter().all(|k| decoder.object_enums.contains(k)), "{:?}", decoder.object_enums);
    stream.write_all(&encode::object_enums(&CLIENT_WANTS)).unwrap();
    stream.write_all(&encode::request_frame(true)).unwrap();
    assert!(wait_for(|| server.streaming() == 1));
    stream.write_all(&encode::pings(&[77])).unwrap();
    let mut pinged = false;
    for i in 0..40 {
        server.send_frame_with(&scene::frame(i), scene::unchanged(i));
        loop {
            let sum = read_packet(&mut stream, &mut decoder);
            pinged |= decoder.pings == [77];
            if sum.frame {
                break;
            }
        }
        assert_eq!(decoder.frame.statics, scene::statics());
        assert_eq!(decoder.frame.dynamics, scene::frame(i), "frame {i}");
        assert_eq!(decoder.frame.sdk_frame_number(), Some(5001 + u64::from(i)));
        assert_eq!(decoder.frame.t_ns(), Some(u64::from(5000 + i) * 187_500 * 1000 / 135));
    }
    // The server answers the ping on its own thread: the answer may follow the last frame.
    stream.set_read_timeout(Some(std::time::Duration::from_secs(10))).unwrap();
    while !pinged {
        read_packet(&mut stream, &mut decoder);
        pinged |= decoder.pings == [77];
    }
    let mut wanted: Vec<u32> = CLIENT_WANTS.iter().copied().filter(|k| vicon_server::OFFERED.contains(k)).collect();
    wanted.sort_unstable();
    assert_eq!(server.wanted(), vec![wanted], "the server sends what the client asked for");
}
