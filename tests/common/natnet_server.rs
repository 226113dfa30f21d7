//! A NatNet server on 127.0.0.1 (UDP unicast only) that answers as Motive does: `NAT_SERVERINFO` to
//! `NAT_CONNECT`, `NAT_MODELDEF` to `NAT_REQUEST_MODELDEF`, and frames sent from its command port to every
//! address a connect came from. Its bytes come from `impactd::mocap::natnet::encode`; the tests check them with
//! OptiTrack's own Python client (`natnetsdk`).

#![allow(clippy::unwrap_used, dead_code)]

use std::net::{SocketAddr, UdpSocket};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use impactd::mocap::natnet::encode as natnet_encode;
use impactd::mocap::natnet::{self, Frame, ServerInfo, Version};

pub struct NatNetServer {
    pub port: u16,
    socket: UdpSocket,
    pub state: Arc<Mutex<ServerState>>,
    stop: Arc<AtomicBool>,
    thread: Option<std::thread::JoinHandle<()>>,
    pub model_requests: Arc<AtomicU64>,
}

pub struct ServerState {
    pub version: Version,
    pub bodies: Vec<(i32, String)>,
    /// Marker sets that are assets of their own (a club with markers, no rigid body): id, name, marker names.
    pub marker_assets: Vec<(i32, String, Vec<String>)>,
    pub clients: Vec<SocketAddr>,
    /// Answer NAT_CONNECT (false: a server that is not there yet).
    pub answering: bool,
    /// The NatNet version its answer to NAT_CONNECT announces, when not `version` (its frames stay `version`'s).
    pub announced: Option<[u8; 2]>,
}

/// Motive's clock: ticks per second of the frame suffix's stamps.
pub const CLOCK_HZ: u64 = 10_000_000;

impl NatNetServer {
    pub fn start(version: Version, bodies: &[(i32, &str)]) -> NatNetServer {
        let socket = UdpSocket::bind("127.0.0.1:0").unwrap();
        socket.set_read_timeout(Some(Duration::from_millis(20))).unwrap();
        let port = socket.local_addr().unwrap().port();
        let state = Arc::new(Mutex::new(ServerState {
            version,
            bodies: bodies.iter().map(|(i, n)| (*i, n.to_string())).collect(),
            marker_assets: Vec::new(),
            clients: Vec::new(),
            answering: true,
            announced: None,
        }));
        let stop = Arc::new(AtomicBool::new(false));
        let model_requests = Arc::new(AtomicU64::new(0));
        let (s, st, stp, mr) = (socket.try_clone().unwrap(), state.clone(), stop.clone(), model_requests.clone());
        let thread = std::thread::spawn(move || {
            let mut buf = vec![0u8; 70_000];
            while !stp.load(Ordering::Relaxed) {
                let Ok((n, from)) = s.recv_from(&mut buf) else { continue };
                let Ok((id, _payload)) = natnet::split(&buf[..n]) else { continue };
                let mut st = st.lock().unwrap();
                match id {
                    natnet::NAT_CONNECT if st.answering => {
                        if !st.clients.contains(&from) {
                            st.clients.push(from);
                        }
                        let info = ServerInfo {
                            app_name: "Motive".into(),
                            app_version: [3, 1, 0, 0],
                            natnet_version: match st.announced {
                                Some([major, minor]) => [major, minor, 0, 0],
                                None => [st.version.major, st.version.minor, 0, 0],
                            },
                            clock_hz: Some(CLOCK_HZ),
                            data_port: Some(1511),
                            multicast: Some(false),
                            multicast_group: Some([239, 255, 42, 99]),
                        };
                        s.send_to(&natnet_encode::server_info(&info), from).unwrap();
                    }
                    natnet::NAT_REQUEST_MODELDEF if st.answering => {
                        mr.fetch_add(1, Ordering::Relaxed);
                        let bodies: Vec<(i32, &str)> = st.bodies.iter().map(|(i, n)| (*i, n.as_str())).collect();
                        let names: Vec<Vec<&str>> =
                            st.marker_assets.iter().map(|a| a.2.iter().map(String::as_str).collect()).collect();
                        let assets: Vec<natnet_encode::MarkerAsset> = st
                            .marker_assets
                            .iter()
                            .zip(&names)
                            .map(|(a, markers)| natnet_encode::MarkerAsset { id: a.0, name: &a.1, markers })
                            .collect();
                        let def = natnet_encode::model_def_with_sets(st.version, &bodies, &assets).unwrap();
                        s.send_to(&def, from).unwrap();
                    }
                    _ => {}
                }
            }
        });
        NatNetServer { port, socket, state, stop, thread: Some(thread), model_requests }
    }

    pub fn clients(&self) -> usize {
        self.state.lock().unwrap().clients.len()
    }

    /// Sends raw bytes to every client.
    pub fn send_raw(&self, bytes: &[u8]) {
        for c in self.state.lock().unwrap().clients.clone() {
            self.socket.send_to(bytes, c).unwrap();
        }
    }

    /// Sends raw bytes to every client from another port of the server's address (a spoofer on its host).
    #[allow(dead_code)] // tests/inputs/natnet.rs, tests/inputs/hostile_rigs.rs
    pub fn send_from_other_port(&self, bytes: &[u8]) {
        let other = UdpSocket::bind("127.0.0.1:0").unwrap();
        for c in self.state.lock().unwrap().clients.clone() {
            other.send_to(bytes, c).unwrap();
        }
    }

    /// Sends a frame (with three markers of the first body) to every client.
    pub fn send_frame(&self, frame: &Frame) {
        let version = self.state.lock().unwrap().version;
        let p = frame.rigid_bodies.first().map_or([0.0; 3], |b| b.position_m);
        let markers = [p, [p[0] + 0.04, p[1], p[2]], [p[0], p[1] + 0.03, p[2]]];
        self.send_raw(&natnet_encode::frame(version, frame, "club", &markers).unwrap());
    }

    /// Sends a frame with its labeled markers, and `markers` as the marker set `set_name`'s positions.
    #[allow(dead_code)] // tests/inputs/natnet_markers.rs
    pub fn send_marker_frame(&self, frame: &Frame, set_name: &str, markers: &[[f32; 3]]) {
        let version = self.state.lock().unwrap().version;
        self.send_raw(&natnet_encode::frame(version, frame, set_name, markers).unwrap());
    }
}

impl Drop for NatNetServer {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}
