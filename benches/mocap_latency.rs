//! Datagram to prediction on loopback, through the native NatNet input: a NatNet server in this process sends
//! a synthetic rig's frames at 720 Hz over UDP on 127.0.0.1; for every shot, the time from sending the frame
//! that reveals the impact to `golf/rig1/launch` published on the daemon's zenoh session (a subscriber there is
//! called inside the put: the budget's measure, p99 <= 0.5 ms), and to a subscriber in another session one TCP
//! hop away. First through the daemon's `[rig.input]`, then through `impactd bridge natnet`'s library (one more
//! zenoh hop: bridge -> daemon), then through the daemon's Vicon DataStream input (TCP, the test server of
//! `tests/common/vicon_server.rs`). Prints p50/p99/max of each, and the daemon's own `latency_us`. Last, the
//! machine's floor: the same hops (datagram, reading thread, queue, worker thread, zenoh) with no work in them.
//! `cargo bench --bench mocap_latency [-- SHOTS]`.

#![allow(clippy::unwrap_used)]

use std::collections::HashMap;
use std::net::{SocketAddr, UdpSocket};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use impactd::daemon::bus::{free_loopback_port, ZenohArgs};
use impactd::daemon::inputs::{run_bridge, Source};
use impactd::daemon::sim::{SimOptions, SimRig};
use impactd::daemon::{DaemonConfig, RunOptions};
use impactd::mocap::natnet::encode as natnet_encode;
use impactd::mocap::natnet::{self, Frame, RigidBody, ServerInfo, Version};
use impactd::wire::LaunchPrediction;
use zenoh::Wait;

#[path = "../tests/common/vicon_scene.rs"]
mod scene;
#[path = "../tests/common/vicon_server.rs"]
mod vicon_server;

fn quantile(v: &mut [f64], q: f64) -> f64 {
    v.sort_by(f64::total_cmp);
    v[((q * v.len() as f64).ceil() as usize).clamp(1, v.len()) - 1]
}

/// One shot's latencies (us) from sending the frame that reveals its impact.
#[derive(Clone, Copy)]
struct Shot {
    /// To the launch received by a subscriber in another zenoh session (one TCP hop on loopback).
    remote_us: f64,
    /// To the launch published on the daemon's own session (a subscriber there is called inside the put).
    published_us: f64,
    /// The daemon's `latency_us`: the frame's arrival in the daemon to the launch built.
    daemon_us: f64,
}

type Received = Arc<Mutex<HashMap<u64, (f64, f64)>>>;

/// A subscriber to `golf/rig1/launch` on `session`: for each launch whose frame was sent, (us since sent,
/// `latency_us`).
fn listen(
    session: &zenoh::Session,
    sent: &Arc<Mutex<HashMap<u64, Instant>>>,
) -> (zenoh::pubsub::Subscriber<()>, Received) {
    let got: Received = Default::default();
    let (s, r) = (sent.clone(), got.clone());
    let sub = session
        .declare_subscriber("golf/rig1/launch")
        .callback(move |m| {
            let now = Instant::now();
            if let Ok(l) = serde_json::from_slice::<LaunchPrediction>(&m.payload().to_bytes()) {
                if let Some(t) = s.lock().unwrap().get(&l.frame) {
                    r.lock().unwrap().insert(l.frame, (now.duration_since(*t).as_secs_f64() * 1e6, l.latency_us));
                }
            }
        })
        .wait()
        .unwrap();
    (sub, got)
}

/// The shots both subscribers received.
fn shots_of(remote: &Received, local: &Received) -> Vec<Shot> {
    let (remote, local) = (remote.lock().unwrap(), local.lock().unwrap());
    remote
        .iter()
        .filter_map(|(frame, (remote_us, daemon_us))| {
            let published_us = local.get(frame)?.0;
            Some(Shot { remote_us: *remote_us, published_us, daemon_us: *daemon_us })
        })
        .collect()
}

/// A NatNet server answering connects and model requests; returns its socket and the clients' addresses.
fn server(stop: Arc<AtomicBool>) -> (UdpSocket, Arc<Mutex<Vec<SocketAddr>>>) {
    let socket = UdpSocket::bind("127.0.0.1:0").unwrap();
    socket.set_read_timeout(Some(Duration::from_millis(20))).unwrap();
    let clients: Arc<Mutex<Vec<SocketAddr>>> = Default::default();
    let (s, c) = (socket.try_clone().unwrap(), clients.clone());
    std::thread::spawn(move || {
        let mut buf = vec![0u8; 70_000];
        while !stop.load(Ordering::Relaxed) {
            let Ok((n, from)) = s.recv_from(&mut buf) else { continue };
            match natnet::split(&buf[..n]).map(|m| m.0) {
                Ok(natnet::NAT_CONNECT) => {
                    c.lock().unwrap().push(from);
                    let info = ServerInfo {
                        app_name: "Motive".into(),
                        natnet_version: [4, 1, 0, 0],
                        clock_hz: Some(10_000_000),
                        ..ServerInfo::default()
                    };
                    s.send_to(&natnet_encode::server_info(&info), from).unwrap();
                }
                Ok(natnet::NAT_REQUEST_MODELDEF) => {
                    s.send_to(&natnet_encode::model_def(Version::V4_1, &[(3, "club")]).unwrap(), from).unwrap();
                }
                _ => {}
            }
        }
    });
    (socket, clients)
}

async fn measure(shots: u64, bridge: bool) -> Vec<Shot> {
    let stop = Arc::new(AtomicBool::new(false));
    let (socket, clients) = server(stop.clone());
    let port = socket.local_addr().unwrap().port();
    let mut text = "[[rig]]\nname = \"rig1\"\n".to_string();
    if !bridge {
        text += &format!("[rig.input]\nnatnet = \"127.0.0.1\"\nbody = \"club\"\nunicast = true\ncommand_port = {port}\ndata_port = 0\n");
    }
    let (config, setups) = DaemonConfig::parse(&text).unwrap();
    let endpoint = format!("tcp/127.0.0.1:{}", free_loopback_port().unwrap());
    let daemon_session = ZenohArgs::loopback(vec![endpoint.clone()], vec![]).open().await.unwrap();
    let sub_session = ZenohArgs::loopback(vec![], vec![endpoint.clone()]).open().await.unwrap();
    let sent: Arc<Mutex<HashMap<u64, Instant>>> = Default::default();
    let (_remote, remote) = listen(&sub_session, &sent);
    let (_local, local) = listen(&daemon_session, &sent);
    let (stop_daemon, stopped) = tokio::sync::oneshot::channel::<()>();
    let daemon = tokio::spawn(async move {
        impactd::daemon::run(config, setups, &daemon_session, RunOptions::default(), async {
            let _ = stopped.await;
        })
        .await
        .unwrap();
        daemon_session.close().await.unwrap();
    });
    let (stop_bridge, bridge_stopped) = tokio::sync::oneshot::channel::<()>();
    let bridge_task = if bridge {
        let session = ZenohArgs::loopback(vec![], vec![endpoint]).open().await.unwrap();
        let source = Source::new("natnet", "127.0.0.1", port).with("data_port", 0).with("unicast", true);
        Some(tokio::spawn(async move {
            run_bridge(&session, source, vec![("club".into(), "rig1".into())], async {
                let _ = bridge_stopped.await;
            })
            .await
            .unwrap();
            session.close().await.unwrap();
        }))
    } else {
        None
    };
    while clients.lock().unwrap().is_empty() {
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    tokio::time::sleep(Duration::from_millis(1500)).await;
    let to = clients.lock().unwrap()[0];
    let sent_frames = sent.clone();
    tokio::task::spawn_blocking(move || {
        let options = SimOptions { shots, interval_s: 0.25, ..SimOptions::default() };
        let period = Duration::from_secs_f64(1.0 / options.rate_hz);
        let mut rig = SimRig::new("rig1", &options, 1_000_000_000, 1);
        let start = Instant::now();
        let mut k = 0u32;
        let mut frame = Frame::default();
        let mut bytes = Vec::new();
        while !rig.done() {
            let s = rig.next_sample().unwrap().0;
            frame.frame_number = s.frame as i32;
            frame.timestamp_s = s.t_ns as f64 * 1e-9;
            frame.rigid_bodies.clear();
            frame.rigid_bodies.push(RigidBody {
                id: 3,
                position_m: [s.position_m.x as f32, s.position_m.y as f32, s.position_m.z as f32],
                orientation_xyzw: s.orientation_xyzw.map(|v| v as f32),
                mean_error_m: 2e-4,
                tracking_valid: true,
            });
            bytes.clear();
            bytes.extend(natnet_encode::frame(Version::V4_1, &frame, "club", &[]).unwrap());
            let due = start + period * k;
            if let Some(wait) = due.checked_duration_since(Instant::now()) {
                std::thread::sleep(wait);
            }
            sent_frames.lock().unwrap().insert(s.frame, Instant::now());
            socket.send_to(&bytes, to).unwrap();
            k += 1;
        }
    })
    .await
    .unwrap();
    tokio::time::sleep(Duration::from_millis(500)).await;
    if let Some(task) = bridge_task {
        let _ = stop_bridge.send(());
        task.await.unwrap();
    }
    let _ = stop_daemon.send(());
    daemon.await.unwrap();
    stop.store(true, Ordering::Relaxed);
    sub_session.close().await.unwrap();
    shots_of(&remote, &local)
}

/// Frame sent by the Vicon test server -> `golf/rig1/launch` received, through the daemon's `[rig.input] vicon`.
async fn measure_vicon(shots: u64) -> Vec<Shot> {
    let server = vicon_server::ViconServer::start(scene::statics());
    let text =
        format!("[[rig]]\nname = \"rig1\"\n[rig.input]\nvicon = \"127.0.0.1:{}\"\nsubject = \"club\"\n", server.port);
    let (config, setups) = DaemonConfig::parse(&text).unwrap();
    let endpoint = format!("tcp/127.0.0.1:{}", free_loopback_port().unwrap());
    let daemon_session = ZenohArgs::loopback(vec![endpoint.clone()], vec![]).open().await.unwrap();
    let sub_session = ZenohArgs::loopback(vec![], vec![endpoint]).open().await.unwrap();
    let sent: Arc<Mutex<HashMap<u64, Instant>>> = Default::default();
    let (_remote, remote) = listen(&sub_session, &sent);
    let (_local, local) = listen(&daemon_session, &sent);
    let (stop_daemon, stopped) = tokio::sync::oneshot::channel::<()>();
    let daemon = tokio::spawn(async move {
        impactd::daemon::run(config, setups, &daemon_session, RunOptions::default(), async {
            let _ = stopped.await;
        })
        .await
        .unwrap();
        daemon_session.close().await.unwrap();
    });
    while server.streaming() == 0 {
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    tokio::time::sleep(Duration::from_millis(1500)).await;
    let server = Arc::new(server);
    let (srv, sent_frames) = (server.clone(), sent.clone());
    tokio::task::spawn_blocking(move || {
        let options = SimOptions { shots, interval_s: 0.25, ..SimOptions::default() };
        let period = Duration::from_secs_f64(1.0 / options.rate_hz);
        let mut rig = SimRig::new("rig1", &options, 1_000_000_000, 1);
        let start = Instant::now();
        let mut k = 0u32;
        while !rig.done() {
            let s = rig.next_sample().unwrap().0;
            let frame = scene::frame_of(&s);
            let due = start + period * k;
            if let Some(wait) = due.checked_duration_since(Instant::now()) {
                std::thread::sleep(wait);
            }
            sent_frames.lock().unwrap().insert(s.frame, Instant::now());
            srv.send_frame(&frame);
            k += 1;
        }
    })
    .await
    .unwrap();
    tokio::time::sleep(Duration::from_millis(500)).await;
    let _ = stop_daemon.send(());
    daemon.await.unwrap();
    sub_session.close().await.unwrap();
    shots_of(&remote, &local)
}

/// The machine's floor for the same hops with no work in them: a datagram on 127.0.0.1 read by a blocking
/// thread (as the native inputs read), handed over a bounded channel to a worker thread (as the rig's queue),
/// which puts it on zenoh to a subscriber in its own session and one in another. Returns (published, remote) us.
async fn measure_floor(shots: u64) -> Vec<(f64, f64)> {
    let endpoint = format!("tcp/127.0.0.1:{}", free_loopback_port().unwrap());
    let session = ZenohArgs::loopback(vec![endpoint.clone()], vec![]).open().await.unwrap();
    let remote_session = ZenohArgs::loopback(vec![], vec![endpoint]).open().await.unwrap();
    let sent: Arc<Mutex<HashMap<u64, Instant>>> = Default::default();
    let got = |session: &zenoh::Session| {
        let got: Arc<Mutex<HashMap<u64, f64>>> = Default::default();
        let (s, r) = (sent.clone(), got.clone());
        let sub = session
            .declare_subscriber("floor/launch")
            .callback(move |m| {
                let now = Instant::now();
                let frame = u64::from_le_bytes(m.payload().to_bytes()[..8].try_into().unwrap());
                if let Some(t) = s.lock().unwrap().get(&frame) {
                    r.lock().unwrap().insert(frame, now.duration_since(*t).as_secs_f64() * 1e6);
                }
            })
            .wait()
            .unwrap();
        (sub, got)
    };
    let ((_l, local), (_r, remote)) = (got(&session), got(&remote_session));
    tokio::time::sleep(Duration::from_millis(1000)).await;
    let publisher = session.declare_publisher("floor/launch").wait().unwrap();
    let rx_socket = UdpSocket::bind("127.0.0.1:0").unwrap();
    rx_socket.set_read_timeout(Some(Duration::from_millis(200))).unwrap();
    let to = rx_socket.local_addr().unwrap();
    let (tx, rx) = std::sync::mpsc::sync_channel::<[u8; 9]>(1024);
    let reader = std::thread::spawn(move || {
        let mut buf = [0u8; 64];
        while let Ok(n) = rx_socket.recv(&mut buf) {
            if n == 9 && tx.try_send(buf[..9].try_into().unwrap()).is_err() {
                break;
            }
        }
    });
    let worker = std::thread::spawn(move || {
        let payload = vec![b' '; 2500];
        while let Ok(m) = rx.recv() {
            if m[8] == 1 {
                let mut p = payload.clone();
                p[..8].copy_from_slice(&m[..8]);
                publisher.put(p).wait().unwrap();
            }
        }
    });
    let sent_frames = sent.clone();
    tokio::task::spawn_blocking(move || {
        let socket = UdpSocket::bind("127.0.0.1:0").unwrap();
        let period = Duration::from_secs_f64(1.0 / 720.0);
        let start = Instant::now();
        for k in 0..(shots * 180) {
            let due = start + period * k as u32;
            if let Some(wait) = due.checked_duration_since(Instant::now()) {
                std::thread::sleep(wait);
            }
            let mut m = [0u8; 9];
            m[..8].copy_from_slice(&k.to_le_bytes());
            m[8] = u8::from(k % 180 == 179);
            if m[8] == 1 {
                sent_frames.lock().unwrap().insert(k, Instant::now());
            }
            socket.send_to(&m, to).unwrap();
        }
    })
    .await
    .unwrap();
    tokio::time::sleep(Duration::from_millis(500)).await;
    reader.join().unwrap();
    worker.join().unwrap();
    let (local, remote) = (local.lock().unwrap(), remote.lock().unwrap());
    local.iter().filter_map(|(k, l)| Some((*l, *remote.get(k)?))).collect()
}

/// Prints one mode's shots: frame sent -> launch published on the daemon's session (the budget's measure),
/// -> received by a subscriber one TCP hop away, and the daemon's own `latency_us` (arrival -> launch built).
fn report(name: &str, shots: u64, v: &[Shot]) {
    let n = v.len();
    let stats = |f: fn(&Shot) -> f64| {
        let mut x: Vec<f64> = v.iter().map(f).collect();
        let max = x.iter().cloned().fold(0.0, f64::max);
        format!("p50 {:.0} us, p99 {:.0} us, max {max:.0} us", quantile(&mut x, 0.5), quantile(&mut x, 0.99))
    };
    println!("{name}: {n} of {shots} shots");
    println!("  frame sent -> launch published by the daemon: {}", stats(|s| s.published_us));
    println!("  frame sent -> launch received one zenoh hop away: {}", stats(|s| s.remote_us));
    println!("  arrival in the daemon -> launch built (latency_us): {}", stats(|s| s.daemon_us));
}

fn main() {
    let shots: u64 = std::env::args().skip(1).find_map(|a| a.parse().ok()).unwrap_or(100);
    let rt = tokio::runtime::Builder::new_multi_thread().enable_all().build().unwrap();
    rt.block_on(async {
        for (name, bridge) in [("daemon [rig.input] natnet", false), ("impactd bridge natnet -> daemon", true)] {
            let v = measure(shots, bridge).await;
            report(name, shots, &v);
        }
        let v = measure_vicon(shots).await;
        report("daemon [rig.input] vicon", shots, &v);
        let v = measure_floor(shots).await;
        let (mut published, mut remote): (Vec<f64>, Vec<f64>) = v.iter().cloned().unzip();
        println!("the same hops with no work in them (the machine's floor): {} of {shots} shots", v.len());
        for (what, x) in [("published", &mut published), ("received one zenoh hop away", &mut remote)] {
            let max = x.iter().cloned().fold(0.0, f64::max);
            println!(
                "  datagram sent -> {what}: p50 {:.0} us, p99 {:.0} us, max {max:.0} us",
                quantile(x, 0.5),
                quantile(x, 0.99)
            );
        }
    });
}
