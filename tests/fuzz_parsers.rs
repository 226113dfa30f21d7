//! A fuzz target per parser a peer or a file reaches (cargo-fuzz needs a nightly toolchain; these run on stable
//! in CI in seconds): the Open Connect stream splitter and messages, the Foxglove client messages, the bay
//! screen's request heads and control messages, the wire sample, and the club and daemon configuration TOML.
//! Each is fed arbitrary bytes and mutations of a seed corpus (bytes flipped, inserted, removed, the input cut or
//! repeated); none may panic, and a counting allocator bounds what one input may allocate at once.

#![allow(clippy::unwrap_used)]
#![cfg(feature = "daemon")]

use std::alloc::{GlobalAlloc, Layout, System};
use std::collections::HashMap;
use std::sync::atomic::{AtomicUsize, Ordering};

use impactd::daemon::bridges::foxglove::live::on_client_text;
use impactd::daemon::bridges::open_connect::codec::ShotMessage;
use impactd::daemon::bridges::open_connect::splitter::{Frame, Splitter};
use impactd::daemon::DaemonConfig;
use impactd::equipment::ClubFile;
use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};

/// Counts the bytes allocated now and the peak since the last reset (one test runs at a time in this binary:
/// every target runs inside the single test below).
struct Counting;

static NOW: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            let now = NOW.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
            PEAK.fetch_max(now, Ordering::Relaxed);
        }
        p
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) };
        NOW.fetch_sub(layout.size(), Ordering::Relaxed);
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// Runs `f` and returns the most it had allocated at once beyond what was allocated before.
fn peak_of(f: impl FnOnce()) -> usize {
    let before = NOW.load(Ordering::Relaxed);
    PEAK.store(before, Ordering::Relaxed);
    f();
    PEAK.load(Ordering::Relaxed).saturating_sub(before)
}

/// What one input of `len` bytes may make a parser allocate at once.
fn allowed(len: usize) -> usize {
    (1 << 20) + 64 * len
}

const OPEN_CONNECT: &[&str] = &[
    r#"{"DeviceID":"LM 1","Units":"Yards","ShotNumber":3,"APIversion":"1","BallData":{"Speed":147.5,"SpinAxis":-2.0,"TotalSpin":2650.0,"HLA":2.3,"VLA":14.3,"CarryDistance":256.0},"ClubData":{"Speed":105.1,"AngleOfAttack":-1.2,"FaceToTarget":0.4,"Lie":0.0,"Loft":12.5,"Path":1.1,"SpeedAtImpact":105.1,"VerticalFaceImpact":2.0,"HorizontalFaceImpact":-3.0,"ClosureRate":0.0},"ShotDataOptions":{"ContainsBallData":true,"ContainsClubData":true,"LaunchMonitorIsReady":true,"LaunchMonitorBallDetected":true,"IsHeartBeat":false}}"#,
    r#"{"DeviceID":"LM 1","ShotNumber":0,"APIversion":"1","ShotDataOptions":{"IsHeartBeat":true}}"#,
    r#"{"Code":200,"Message":"Shot received successfully"}{"Code":201,"Player":{"Handed":"RH","Club":"DR"}}"#,
];
const FOXGLOVE: &[&str] = &[
    r#"{"op":"subscribe","subscriptions":[{"id":1,"channelId":1},{"id":2,"channelId":8}]}"#,
    r#"{"op":"unsubscribe","subscriptionIds":[1,2]}"#,
    r#"{"op":"advertise","channels":[]}"#,
];
const WEB: &[&str] = &[
    r#"{"op":"club","rig":"bay1","club":" iron7 "}"#,
    r#"{"op":"labels","rig":"bay1","player":"ann","tags":["fit"," "]}"#,
    r#"{"op":"exclude","rig":"bay1","shot":4,"excluded":true}"#,
    r#"{"op":"units","rig":"bay1","units":"metric"}"#,
    "GET /rig/bay1/session.csv HTTP/1.1\r\nHost: 127.0.0.1:8080\r\n\r\n",
    "GET /ws HTTP/1.1\r\nHost: 127.0.0.1\r\nUpgrade: websocket\r\nConnection: Upgrade\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n\r\n",
];
const SAMPLE: &str = r#"{"rig":"bay1","frame":17,"t_ns":1000000,"position_m":[0.1,0.0,-0.2],"orientation":{"x":0.0,"y":0.0,"z":0.0,"w":1.0},"occluded":false}"#;
const CONFIG: &str = "status_period_s = 1.0\n[[rig]]\nname = \"bay1\"\nclub = \"driver\"\nmodel = \"standard\"\n\
                      [rig.launch_monitor]\nopen_connect_listen = \"127.0.0.1:921\"\nmax_connections = 4\n";
const CLUB: &str = include_str!("../clubs/driver-one-cycle.toml");

/// A seed, mutated: some bytes flipped, some inserted, a range removed, the input cut and repeated.
fn mutated(seeds: &'static [&'static str]) -> impl Strategy<Value = Vec<u8>> {
    (
        prop::sample::select(seeds),
        prop::collection::vec((any::<prop::sample::Index>(), any::<u8>(), 0u8..3), 0..12),
        any::<prop::sample::Index>(),
        1usize..4,
    )
        .prop_map(|(seed, edits, cut, repeat)| {
            let mut b = seed.as_bytes().to_vec();
            for (at, byte, how) in edits {
                if b.is_empty() {
                    b.push(byte);
                    continue;
                }
                let i = at.index(b.len());
                match how {
                    0 => b[i] = byte,
                    1 => b.insert(i, byte),
                    _ => {
                        b.remove(i);
                    }
                }
            }
            let keep = if b.is_empty() { 0 } else { cut.index(b.len() + 1).max(b.len() / 2) };
            b.truncate(keep);
            b.repeat(repeat)
        })
}

fn input(seeds: &'static [&'static str]) -> impl Strategy<Value = Vec<u8>> {
    prop_oneof![prop::collection::vec(any::<u8>(), 0..2048), mutated(seeds)]
}

fn run(name: &str, strategy: impl Strategy<Value = Vec<u8>>, target: impl Fn(&[u8])) {
    let mut runner = TestRunner::new(Config { cases: 1500, failure_persistence: None, ..Config::default() });
    runner
        .run(&strategy, |bytes| {
            let peak = peak_of(|| target(&bytes));
            prop_assert!(peak <= allowed(bytes.len()), "{name}: {peak} bytes at once for {} bytes in", bytes.len());
            Ok(())
        })
        .unwrap_or_else(|e| panic!("{name}: {e}"));
}

fn open_connect(bytes: &[u8]) {
    let mut splitter = Splitter::new(impactd::daemon::bridges::open_connect::MAX_MESSAGE_BYTES);
    let mut frames = Vec::new();
    for read in bytes.chunks(97) {
        splitter.push(read, &mut |f| frames.push(f));
    }
    for f in frames {
        if let Frame::Object(text) = f {
            assert!(text.len() <= impactd::daemon::bridges::open_connect::MAX_MESSAGE_BYTES);
            if let Ok(m) = serde_json::from_slice::<ShotMessage>(&text) {
                let _ = m.is_heartbeat();
                let _ = m.to_measured("bay1", 1);
            }
        }
    }
}

fn foxglove(bytes: &[u8]) {
    let mut subscriptions = HashMap::new();
    let _ = on_client_text(&String::from_utf8_lossy(bytes), 8, &mut subscriptions);
    assert!(subscriptions.len() <= 8, "subscriptions beyond the channels advertised");
    assert!(subscriptions.keys().all(|c| (1..=8).contains(c)));
}

/// The bay screen's two parsers: a request head and a page's control message (and the put it makes).
fn web(bytes: &[u8]) {
    use impactd::daemon::bridges::web::{controls::Control, download::rig_of_path, http::classify};
    let _ = classify(bytes);
    let text = String::from_utf8_lossy(bytes);
    let _ = rig_of_path(&text);
    if let Ok(c) = Control::parse(&text, &["bay1".to_string()]) {
        assert_eq!(c.rig(), "bay1", "a control only for a rig served");
        let _ = c.put(&impactd::wire::ShotLabels::default());
    }
}

fn sample(bytes: &[u8]) {
    if let Ok(m) = impactd::wire::parse_sample("bay1", bytes, "application/json") {
        let _ = m.to_sample();
    }
}

fn toml(bytes: &[u8]) {
    let text = String::from_utf8_lossy(bytes);
    let _ = DaemonConfig::parse(&text);
    let _ = ClubFile::parse(&text);
}

#[test]
fn every_parser_takes_arbitrary_and_mutated_input_without_panic_or_unbounded_allocation() {
    run("open connect", input(OPEN_CONNECT), open_connect);
    // A stream of one endless object: answered at the cap, memory bounded by it.
    run("open connect: unclosed", (1usize..200_000).prop_map(|n| vec![b'{'; n]), open_connect);
    run("foxglove", input(FOXGLOVE), foxglove);
    run("web page", input(WEB), web);
    run("sample", input(&[SAMPLE]), sample);
    run("config and club toml", input(&[CONFIG, CLUB]), toml);
}
