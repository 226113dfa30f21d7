//! A new input is its own folder and one entry: a toy motion-capture protocol written here (text datagrams over
//! UDP), behind `Protocol` alone, is read from a `[rig.input]` table (`protocol = "toy"`, its own key checked),
//! started, counted and its samples handed on with nothing outside this file knowing its type, from a list of
//! entries as `impactd::daemon::inputs::PROTOCOLS` holds them (in the crate, that entry is the one more line a
//! new protocol takes; its codec goes in `mocap/<name>/`, its client in `daemon/inputs/<name>/`).

#![allow(clippy::unwrap_used)]

use impactd::daemon::inputs::counters::InputRejection;
use std::net::UdpSocket;
use std::sync::atomic::Ordering;
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::Duration;

use impactd::daemon::inputs::natnet::protocol::NatNet;
use impactd::daemon::inputs::protocol::{typed, FieldError, Protocol, Source, Start};
use impactd::daemon::inputs::shared::lock;
use impactd::daemon::inputs::{InputHandle, MocapInputConfig, Route};
use impactd::daemon::DaemonError;
use impactd::mocap::track::{BodySample, BodyTrack, Sequence};
use impactd::wire::ConnectionState;

/// A datagram per frame: `BODY FRAME T_NS X Y Z` (metres, identity orientation); the client says `hello` first.
struct Toy;

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct ToyOptions {
    greeting: Option<String>,
}

impl Protocol for Toy {
    fn name(&self) -> &'static str {
        "toy"
    }
    fn summary(&self) -> &'static str {
        "A toy: text datagrams."
    }
    fn default_port(&self) -> u16 {
        9
    }
    fn body_help(&self) -> &'static str {
        "A body, NAME=RIG."
    }
    fn source(&self, host: &str, port: Option<u16>, options: &toml::Table) -> Result<Source, FieldError> {
        let o: ToyOptions = typed(options)?;
        Ok(Source::new("toy", host, port.unwrap_or(9)).with("greeting", o.greeting.unwrap_or_else(|| "hello".into())))
    }
    fn bridge_source(&self, host: &str, port: Option<u16>, _: &clap::ArgMatches) -> Result<Source, String> {
        Ok(Source::new("toy", host, port.unwrap_or(9)))
    }
    fn start(&self, s: Start) -> Result<Vec<JoinHandle<()>>, DaemonError> {
        let socket = UdpSocket::bind("127.0.0.1:0").unwrap();
        socket.set_read_timeout(Some(Duration::from_millis(50))).unwrap();
        socket.send_to(s.source.option("greeting").unwrap_or("hello").as_bytes(), s.server).unwrap();
        lock(&s.shared).conn.state = ConnectionState::Connected;
        lock(&s.shared).conn.connects += 1;
        Ok(vec![std::thread::spawn(move || {
            let mut tracks = vec![BodyTrack::default(); s.routes.len()];
            let mut buf = [0u8; 256];
            while !s.stop.load(Ordering::Relaxed) {
                let Ok(n) = socket.recv(&mut buf) else { continue };
                let text = String::from_utf8_lossy(&buf[..n]).into_owned();
                let w: Vec<&str> = text.split_whitespace().collect();
                let mut sh = lock(&s.shared);
                let Some(i) = s.routes.iter().position(|r| w.first() == Some(&r.body.as_str())) else {
                    sh.conn.reject(InputRejection::Decode("body_not_in_model"));
                    continue;
                };
                let num = |k: usize| w.get(k).and_then(|v| v.parse::<f64>().ok());
                let (Some(frame), Some(t), Some(x), Some(y), Some(z)) = (num(1), num(2), num(3), num(4), num(5)) else {
                    sh.conn.reject(InputRejection::Decode("malformed"));
                    continue;
                };
                let sample = BodySample {
                    frame: frame as u64,
                    t_ns: t as u64,
                    position_m: [x, y, z],
                    orientation_xyzw: [0.0, 0.0, 0.0, 1.0],
                    occluded: false,
                    exposure_t_ns: None,
                    fit_residual_m: None,
                    system_latency_us: None,
                };
                let sh = &mut *sh;
                if tracks[i].on_frame(&sample, None, &mut sh.bodies[i]) == Sequence::Publish {
                    (sh.deliver)(i, &sample, std::time::Instant::now());
                }
            }
        })])
    }
}

static TOY: Toy = Toy;

#[test]
fn a_toy_protocol_is_one_folder_and_one_entry() {
    // The entries: the crate's, plus the toy's one line.
    let entries: [&'static dyn Protocol; 2] = [&NatNet, &TOY];
    let server = UdpSocket::bind("127.0.0.1:0").unwrap();
    server.set_read_timeout(Some(Duration::from_secs(10))).unwrap();
    let port = server.local_addr().unwrap().port();

    let table: toml::Table = toml::from_str(&format!(
        "protocol = \"toy\"\nserver = \"127.0.0.1:{port}\"\nbody = \"club\"\ngreeting = \"hi\"\n"
    ))
    .unwrap();
    let input = MocapInputConfig::from_table(table);
    let source = input.source_in(&entries).unwrap();
    assert_eq!(
        (source.protocol(), source.address(), source.option("greeting")),
        ("toy", format!("127.0.0.1:{port}"), Some("hi"))
    );
    let bad: toml::Table = toml::from_str("protocol = \"toy\"\nserver = \"h\"\nbody = \"c\"\ncolour = 3\n").unwrap();
    let (field, _) = MocapInputConfig::from_table(bad).source_in(&entries).unwrap_err();
    assert_eq!(field, "colour", "the toy's own keys are checked by the toy");

    let got: Arc<Mutex<Vec<(usize, BodySample)>>> = Default::default();
    let g = got.clone();
    let deliver = Box::new(move |i: usize, s: &BodySample, _| g.lock().unwrap().push((i, *s)));
    let routes = vec![(Route { body: input.body.clone(), ..Route::default() }, "rig1".to_string())];
    let handle = InputHandle::start_with(&TOY, source, routes, deliver).unwrap();
    let mut buf = [0u8; 16];
    let (n, client) = server.recv_from(&mut buf).unwrap();
    assert_eq!(&buf[..n], b"hi");
    for (f, body) in [(1, "club"), (2, "club"), (4, "club"), (3, "club"), (5, "wand")] {
        server.send_to(format!("{body} {f} {} 0.5 1 -0.25", f * 1_000_000).as_bytes(), client).unwrap();
    }
    server.send_to(b"club x", client).unwrap();
    let t0 = std::time::Instant::now();
    while handle.status(0).rejected.values().sum::<u64>() < 2 && t0.elapsed() < Duration::from_secs(10) {
        std::thread::sleep(Duration::from_millis(10));
    }
    let status = handle.status(0);
    handle.stop();
    let frames: Vec<u64> = got.lock().unwrap().iter().map(|(_, s)| s.frame).collect();
    assert_eq!(frames, [1, 2, 4], "frame 3 came late");
    assert_eq!((status.protocol.as_str(), status.frames, status.dropped, status.out_of_order), ("toy", 4, 1, 1));
    assert_eq!((status.rejected.get("body_not_in_model"), status.rejected.get("malformed")), (Some(&1), Some(&1)));
    assert_eq!((status.connects, status.state), (1, ConnectionState::Connected));
}
