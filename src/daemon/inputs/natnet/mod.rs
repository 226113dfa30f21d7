//! The NatNet client: `NAT_CONNECT` to Motive's command port (again, with back-off, until the server answers
//! and whenever it goes quiet for [`QUIET`]), keep-alives, `NAT_REQUEST_MODELDEF` to map body names to ids
//! (again when a frame says the models changed or a mapped id goes missing), and frames from both the command
//! socket (where Motive sends unicast frames: to the address the connect came from) and the data socket
//! (multicast group, or the `data_port` bound for unicast). Two threads, one per socket, share the decoding
//! state behind one lock; each datagram is decoded into a reused frame (no allocation per frame once warm).
//! A route with a marker set is that set fitted to the labelled markers of Motive's asset named like the route's
//! body (`mocap::natnet::fit`), mapped again with every model definition.
//!
//! The server's version decides how every frame is decoded, so it is taken only from a `NAT_SERVERINFO` that
//! answers the client's own `NAT_CONNECT`, received on the command socket from the command port it was sent to;
//! any other (a datagram from another port of the server's host, or one nobody asked for) is counted
//! (`unsolicited_server_info`) and changes nothing, and so is a model definition from elsewhere. A stream of which
//! [`UNDECODABLE_FRAMES`] frames in a row decode to nothing ends the session: the client connects again, asks for
//! the version again, and counts it (`reconnects.undecodable`).

pub mod protocol;

use crate::daemon::inputs::counters::{InputRejection, Reconnect};
use std::net::{Ipv4Addr, SocketAddr, UdpSocket};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use super::shared::{lock, Shared, BACKOFF_FIRST, BACKOFF_LAST, POLL};
use crate::daemon::DaemonError;
use crate::kinematics::MarkerFitter;
use crate::mocap::natnet::encode as natnet_encode;
use crate::mocap::natnet::fit::{label_map, natnet_fitted_sample, LabelMap};
use crate::mocap::natnet::sample::natnet_sample;
use crate::mocap::natnet::{self, Frame, Version};
use crate::mocap::track::{BodyTrack, Sequence};
use crate::wire::ConnectionState;

/// A connected server silent this long is connected to again.
pub use super::shared::QUIET;
const KEEPALIVE: Duration = Duration::from_secs(1);
/// At most one model request per this long.
const MODEL_REQUEST_EVERY: Duration = Duration::from_secs(1);
/// Frames in a row that fail to decode after which the session is started again (a second at 100 Hz).
pub const UNDECODABLE_FRAMES: u32 = 100;

pub struct Options {
    pub server: SocketAddr,
    pub data_port: u16,
    pub multicast_group: Option<Ipv4Addr>,
}

/// The decoding state both sockets' threads share.
struct State {
    version: Option<Version>,
    clock_hz: Option<u64>,
    bodies: Vec<String>,
    ids: Vec<Option<i32>>,
    /// Per route: a marker set fitted to the labelled markers (None: the rigid body's pose), and its labels.
    fitters: Vec<Option<MarkerFitter>>,
    maps: Vec<Option<LabelMap>>,
    lab_m: Vec<Option<crate::math::Vector3>>,
    tracks: Vec<BodyTrack>,
    frame: Frame,
    last_rx: Option<Instant>,
    want_model: bool,
    model_seen: bool,
    /// A `NAT_CONNECT` was sent and its `NAT_SERVERINFO` has not come: the one time a version is taken.
    awaiting_server_info: bool,
    /// Frames in a row that did not decode.
    undecodable_run: u32,
}

struct Client {
    server: SocketAddr,
    state: Mutex<State>,
    shared: Arc<Mutex<Shared>>,
    stop: Arc<AtomicBool>,
}

fn io(what: String) -> impl FnOnce(std::io::Error) -> DaemonError {
    move |source| DaemonError::Io { what, source }
}

/// Binds the sockets and starts the two threads.
pub fn start(
    options: Options,
    bodies: Vec<String>,
    fitters: Vec<Option<MarkerFitter>>,
    shared: Arc<Mutex<Shared>>,
    stop: Arc<AtomicBool>,
) -> Result<Vec<JoinHandle<()>>, DaemonError> {
    let local: Ipv4Addr = if options.server.ip().is_loopback() { Ipv4Addr::LOCALHOST } else { Ipv4Addr::UNSPECIFIED };
    let command = UdpSocket::bind((local, 0)).map_err(io("binding the NatNet command socket".into()))?;
    let data = data_socket(local, options.data_port, options.multicast_group)?;
    for s in [&command, &data] {
        s.set_read_timeout(Some(POLL)).map_err(io("setting a socket timeout".into()))?;
    }
    let n = bodies.len();
    let client = Arc::new(Client {
        server: options.server,
        state: Mutex::new(State {
            version: None,
            clock_hz: None,
            bodies,
            ids: vec![None; n],
            fitters,
            maps: vec![None; n],
            lab_m: Vec::new(),
            tracks: vec![BodyTrack::default(); n],
            frame: Frame::default(),
            last_rx: None,
            want_model: true,
            model_seen: false,
            awaiting_server_info: false,
            undecodable_run: 0,
        }),
        shared,
        stop,
    });
    let spawn = |name: &str, f: Box<dyn FnOnce() + Send>| {
        std::thread::Builder::new().name(name.into()).spawn(f).map_err(io("starting a NatNet thread".into()))
    };
    let (c1, c2) = (client.clone(), client);
    Ok(vec![
        spawn("natnet-command", Box::new(move || c1.command_loop(command)))?,
        spawn("natnet-data", Box::new(move || c2.receive_loop(&data)))?,
    ])
}

fn data_socket(local: Ipv4Addr, port: u16, group: Option<Ipv4Addr>) -> Result<UdpSocket, DaemonError> {
    let what = format!("binding the NatNet data port {port}");
    let Some(group) = group else { return UdpSocket::bind((local, port)).map_err(io(what)) };
    use socket2::{Domain, Protocol, Socket, Type};
    let s = Socket::new(Domain::IPV4, Type::DGRAM, Some(Protocol::UDP)).map_err(io(what.clone()))?;
    s.set_reuse_address(true).map_err(io(what.clone()))?;
    s.bind(&SocketAddr::from((Ipv4Addr::UNSPECIFIED, port)).into()).map_err(io(what.clone()))?;
    s.join_multicast_v4(&group, &Ipv4Addr::UNSPECIFIED).map_err(io(format!("joining multicast group {group}")))?;
    Ok(s.into())
}

impl Client {
    fn lock_state(&self) -> std::sync::MutexGuard<'_, State> {
        self.state.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    fn send(&self, socket: &UdpSocket, bytes: &[u8]) {
        if let Err(e) = socket.send_to(bytes, self.server) {
            lock(&self.shared).conn.last_error = Some(format!("sending to {}: {e}", self.server));
        }
    }

    /// Connects, keeps alive, asks for the model, and reads the command socket.
    fn command_loop(&self, socket: UdpSocket) {
        let mut backoff = BACKOFF_FIRST;
        let mut next_connect = Instant::now();
        let mut last_keepalive = Instant::now();
        let mut last_model_request: Option<Instant> = None;
        let mut attempts = 0u32;
        let mut buf = vec![0u8; natnet::MAX_DATAGRAM_BYTES + 1];
        while !self.stop.load(Ordering::Relaxed) {
            let now = Instant::now();
            let (connected, want_model) = {
                let st = self.lock_state();
                (st.version.is_some() && st.last_rx.is_some_and(|t| now - t < QUIET), st.want_model)
            };
            if !connected {
                if self.lock_state().version.take().is_some() {
                    let why = format!("NatNet server at {} went quiet; connecting again", self.server);
                    tracing::warn!("{why}");
                    lock(&self.shared).conn.reconnect(Reconnect::Quiet, why);
                    backoff = BACKOFF_FIRST;
                    next_connect = now;
                }
                if now >= next_connect {
                    if attempts > 0 {
                        let note = format!(
                            "no answer from a NatNet server at {} yet; asking again in {:.2} s",
                            self.server,
                            backoff.as_secs_f64()
                        );
                        if attempts == 1 || backoff == BACKOFF_LAST {
                            tracing::warn!("{note}");
                        }
                        lock(&self.shared).conn.last_error = Some(note);
                    }
                    self.lock_state().awaiting_server_info = true;
                    self.send(&socket, &natnet_encode::connect("impactd", None));
                    attempts += 1;
                    next_connect = now + backoff;
                    backoff = (backoff * 2).min(BACKOFF_LAST);
                }
            } else {
                attempts = 0;
                backoff = BACKOFF_FIRST;
                if now - last_keepalive >= KEEPALIVE {
                    self.send(&socket, &natnet_encode::request(natnet::NAT_KEEPALIVE));
                    last_keepalive = now;
                }
                if want_model && last_model_request.is_none_or(|t| now - t >= MODEL_REQUEST_EVERY) {
                    self.send(&socket, &natnet_encode::request(natnet::NAT_REQUEST_MODELDEF));
                    last_model_request = Some(now);
                }
            }
            self.receive_one(&socket, &mut buf, true);
        }
        self.send(&socket, &natnet_encode::request(natnet::NAT_DISCONNECT));
    }

    fn receive_loop(&self, socket: &UdpSocket) {
        let mut buf = vec![0u8; natnet::MAX_DATAGRAM_BYTES + 1];
        while !self.stop.load(Ordering::Relaxed) {
            self.receive_one(socket, &mut buf, false);
        }
    }

    /// One datagram from `socket`; `command` says it is the command socket (where answers come).
    fn receive_one(&self, socket: &UdpSocket, buf: &mut [u8], command: bool) {
        match socket.recv_from(buf) {
            Ok((n, from)) => {
                let received = Instant::now();
                if from.ip() != self.server.ip() {
                    lock(&self.shared).conn.reject(InputRejection::ForeignSender);
                } else if n > natnet::MAX_DATAGRAM_BYTES {
                    lock(&self.shared).conn.reject(InputRejection::Oversized);
                } else {
                    // An answer counts only on the command socket, from the command port it was asked of.
                    self.on_datagram(&buf[..n], received, command && from == self.server);
                }
            }
            Err(e) if matches!(e.kind(), std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut) => {}
            // An ICMP error from an earlier send (the server's port was closed): retried by the connect loop.
            Err(e) if e.kind() == std::io::ErrorKind::ConnectionRefused => {}
            Err(e) => {
                lock(&self.shared).conn.last_error = Some(format!("receiving: {e}"));
                std::thread::sleep(POLL);
            }
        }
    }

    /// A datagram from the server's host; `answer`: from its command port, on the command socket.
    fn on_datagram(&self, bytes: &[u8], received: Instant, answer: bool) {
        let mut st = self.lock_state();
        let mut sh = lock(&self.shared);
        let (id, payload) = match natnet::split(bytes) {
            Ok(v) => v,
            Err(e) => return sh.conn.reject(InputRejection::Decode(e.reason())),
        };
        st.last_rx = Some(received);
        match id {
            natnet::NAT_SERVERINFO if !(answer && st.awaiting_server_info) => {
                // Motive answers each connect; a repeat of the version in use (a second connect's answer) is
                // no news, anything else is not an answer to this client and changes nothing.
                let same = natnet::decode_server_info(payload).is_ok_and(|i| Some(i.version()) == st.version);
                if !(answer && same) {
                    sh.conn.reject(InputRejection::UnsolicitedServerInfo);
                }
            }
            natnet::NAT_MODELDEF if !answer => sh.conn.reject(InputRejection::UnsolicitedModelDef),
            natnet::NAT_SERVERINFO => match natnet::decode_server_info(payload) {
                Ok(info) => {
                    st.awaiting_server_info = false;
                    st.undecodable_run = 0;
                    let v = info.version();
                    let [a, b, c, d] = info.app_version;
                    sh.conn.server_version = Some(format!("{} {a}.{b}.{c}.{d}, NatNet {v}", info.app_name));
                    if !v.supported() {
                        sh.conn.reject(InputRejection::UnknownVersion);
                        sh.conn.last_error = Some(natnet::NatNetError::UnsupportedVersion(v).to_string());
                    }
                    if st.version.is_none() {
                        sh.conn.connects += 1;
                        tracing::info!(
                            "NatNet server at {}: {}",
                            self.server,
                            sh.conn.server_version.as_deref().unwrap_or("")
                        );
                    }
                    sh.conn.state = ConnectionState::Connected;
                    st.version = Some(v);
                    st.clock_hz = info.clock_hz.filter(|&hz| hz > 0);
                    st.want_model = true;
                }
                Err(e) => sh.conn.reject(InputRejection::Decode(e.reason())),
            },
            natnet::NAT_MODELDEF => {
                let Some(version) = st.version else { return sh.conn.reject(InputRejection::AwaitingServerInfo) };
                match natnet::decode_model_def(payload, version) {
                    Ok(model) => {
                        st.want_model = false;
                        let st = &mut *st;
                        for (i, name) in st.bodies.iter().enumerate() {
                            if let Some(fitter) = &st.fitters[i] {
                                let map = label_map(&model, name, &fitter.set);
                                if let Err(e) = &map {
                                    if sh.bodies[i].body_found || !st.model_seen {
                                        sh.log.warn("markers_not_in_model", || format!("marker set of `{name}`: {e}"));
                                    }
                                }
                                st.maps[i] = map.ok();
                                sh.bodies[i].body_found = st.maps[i].is_some();
                                continue;
                            }
                            let id = model.rigid_bodies.iter().find(|b| &b.name == name).map(|b| b.id);
                            if id.is_none() && (sh.bodies[i].body_found || !st.model_seen) {
                                let names =
                                    crate::daemon::peer_log::list(model.rigid_bodies.iter().map(|b| b.name.as_str()));
                                sh.log.warn("body_not_in_model", || {
                                    format!("rigid body `{name}` is not in the NatNet server's model (it has {names})")
                                });
                            }
                            st.ids[i] = id;
                            sh.bodies[i].body_found = id.is_some();
                        }
                        st.model_seen = true;
                    }
                    Err(e) => sh.conn.reject(InputRejection::Decode(e.reason())),
                }
            }
            natnet::NAT_FRAMEOFDATA => {
                let Some(version) = st.version else { return sh.conn.reject(InputRejection::AwaitingServerInfo) };
                let st = &mut *st;
                if let Err(e) = natnet::decode_frame(payload, version, &mut st.frame) {
                    sh.conn.reject(InputRejection::Decode(e.reason()));
                    st.undecodable_run += 1;
                    if st.undecodable_run >= UNDECODABLE_FRAMES {
                        // The version in use (or the server) decodes nothing: start the session again.
                        st.undecodable_run = 0;
                        st.version = None;
                        let why = format!(
                            "{UNDECODABLE_FRAMES} frames in a row from the NatNet server at {} did not decode as \
                             NatNet {version} (last: {e}); connecting again",
                            self.server
                        );
                        tracing::warn!("{why}");
                        sh.conn.reconnect(Reconnect::Undecodable, why);
                    }
                    return;
                }
                st.undecodable_run = 0;
                if st.frame.models_changed {
                    st.want_model = true;
                }
                if let Some(hz) = st.clock_hz {
                    let f = &st.frame;
                    if f.mid_exposure_ticks > 0 && f.transmit_ticks > f.mid_exposure_ticks {
                        let us = (f.transmit_ticks - f.mid_exposure_ticks) as f64 * 1e6 / hz as f64;
                        sh.conn.exposure_to_transmit_us.push(us);
                    }
                }
                let sh = &mut *sh;
                for i in 0..st.bodies.len() {
                    let status = &mut sh.bodies[i];
                    if let Some(fitter) = &st.fitters[i] {
                        let Some(map) = &st.maps[i] else {
                            *status.rejected.entry("markers_not_in_model".into()).or_default() += 1;
                            st.want_model = true;
                            continue;
                        };
                        let sample = natnet_fitted_sample(fitter, map, &st.frame, st.clock_hz, &mut st.lab_m);
                        if st.tracks[i].on_frame(&sample, None, status) == Sequence::Publish {
                            (sh.deliver)(i, &sample, received);
                        }
                        continue;
                    }
                    let Some(id) = st.ids[i] else {
                        *status.rejected.entry("body_not_in_model".into()).or_default() += 1;
                        st.want_model = true;
                        continue;
                    };
                    let Some(body) = st.frame.rigid_bodies.iter().find(|b| b.id == id) else {
                        *status.rejected.entry("body_missing_from_frame".into()).or_default() += 1;
                        st.want_model = true;
                        continue;
                    };
                    let (sample, bad) = natnet_sample(body, &st.frame, st.clock_hz);
                    if st.tracks[i].on_frame(&sample, bad, status) == Sequence::Publish {
                        (sh.deliver)(i, &sample, received);
                    }
                }
            }
            natnet::NAT_RESPONSE
            | natnet::NAT_MESSAGESTRING
            | natnet::NAT_KEEPALIVE
            | natnet::NAT_UNRECOGNIZED_REQUEST
            | natnet::NAT_DISCONNECT => {}
            _ => sh.conn.reject(InputRejection::UnknownMessage),
        }
    }
}
