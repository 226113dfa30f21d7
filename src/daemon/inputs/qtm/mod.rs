//! The QTM real-time client: one thread, one TCP connection at a time. It connects (with back-off while QTM
//! is not there), reads the greeting, asks for protocol 1.25, maps body names to 6D indices with
//! `GetParameters 6D` (again when QTM says the cameras or the measurement changed), then `StreamFrames
//! AllFrames 6D` (`6D 3D` when a route is a marker set, fitted to the labelled markers) and reads frames until the measurement stops or the connection ends, and then connects again
//! with back-off. A connection that goes quiet is asked `QTMVersion` after [`PROBE_AFTER`]; one that stays
//! silent for [`QUIET`] (as NatNet's) is ended and connected again (`reconnects.quiet`), so a QTM that stopped
//! answering after the handshake does not stay "connected".

pub mod protocol;

use crate::daemon::inputs::counters::{InputRejection, Reconnect};
use std::io::{Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use super::shared::{lock, sleep_unless_stopped, Shared, BACKOFF_FIRST, BACKOFF_LAST, POLL};
use crate::daemon::{peer_log, DaemonError};
use crate::kinematics::MarkerFitter;
use crate::mocap::qtm::encode as qtm_encode;
use crate::mocap::qtm::{self, Frame6d, QtmError, HEADER_BYTES};
use crate::mocap::track::{self, qtm_sample, BodyTrack, Sequence};
use crate::wire::ConnectionState;

/// How long a reply to a command may take.
const REPLY_WAIT: Duration = Duration::from_secs(5);

/// While streaming, a connection silent this long is asked for QTM's version (any packet is a sign of life).
pub const PROBE_AFTER: Duration = Duration::from_secs(1);
/// While streaming, a connection silent this long is ended and connected again (NatNet's [`super::shared::QUIET`]).
pub const QUIET: Duration = super::shared::QUIET;

/// Events after which the body list may have changed: ask for the parameters again.
const EVENTS_REMAP: [u8; 4] = [3, 7, 8, 11];

/// Starts the client thread for `bodies` (route `i` is the 6DOF body `bodies[i]`, or, when `fitters[i]` is
/// given, that marker set fitted to QTM's labelled 3D markers each frame).
pub fn start(
    server: SocketAddr,
    bodies: Vec<String>,
    fitters: Vec<Option<MarkerFitter>>,
    shared: Arc<Mutex<Shared>>,
    stop: Arc<AtomicBool>,
) -> Result<Vec<JoinHandle<()>>, DaemonError> {
    let thread = std::thread::Builder::new()
        .name("qtm".into())
        .spawn(move || run(server, &bodies, &fitters, &shared, &stop))
        .map_err(|source| DaemonError::Io { what: "starting the QTM thread".into(), source })?;
    Ok(vec![thread])
}

/// Why a session ended.
enum End {
    Stopped,
    Lost(String),
    /// Nothing came within the wait.
    Silent,
}

fn run(
    server: SocketAddr,
    bodies: &[String],
    fitters: &[Option<MarkerFitter>],
    shared: &Mutex<Shared>,
    stop: &AtomicBool,
) {
    let mut backoff = BACKOFF_FIRST;
    let mut tracks = vec![BodyTrack::default(); bodies.len()];
    let mut failures = 0u32;
    while !stop.load(Ordering::Relaxed) {
        let why = match TcpStream::connect_timeout(&server, Duration::from_secs(1)) {
            Ok(stream) => {
                let reader = PacketReader::default();
                let mut session = Session {
                    stream,
                    reader,
                    shared,
                    stop,
                    bodies,
                    fitters,
                    names: Vec::new(),
                    indices: vec![None; bodies.len()],
                    lab_m: Vec::new(),
                };
                match session.run(&mut tracks, &mut backoff) {
                    End::Stopped => return,
                    End::Lost(why) => why,
                    End::Silent => "QTM did not answer".into(),
                }
            }
            Err(e) => format!("no QTM real-time server at {server} ({e})"),
        };
        failures += 1;
        let note = format!("{why}; connecting again in {:.2} s", backoff.as_secs_f64());
        if failures == 1 || backoff == BACKOFF_LAST {
            tracing::warn!("{note}");
        }
        {
            let mut sh = lock(shared);
            sh.conn.state = ConnectionState::Disconnected;
            sh.conn.last_error = Some(note);
        }
        if !sleep_unless_stopped(backoff, stop) {
            return;
        }
        backoff = (backoff * 2).min(BACKOFF_LAST);
    }
}

/// Accumulates a TCP stream into whole packets across read timeouts.
#[derive(Default)]
struct PacketReader {
    buf: Vec<u8>,
    packet: Vec<u8>,
}

enum Got {
    /// A packet: its type (the body is in `PacketReader::packet`).
    Packet(u32),
    /// Nothing within one poll.
    Idle,
}

/// Why the stream cannot go on.
enum Broken {
    /// Closed or failed: the words say which.
    Closed(String),
    /// A header that desynchronises the stream.
    Bad(QtmError),
}

impl PacketReader {
    fn next(&mut self, stream: &mut TcpStream) -> Result<Got, Broken> {
        loop {
            if self.buf.len() >= HEADER_BYTES {
                let mut h = [0u8; HEADER_BYTES];
                h.copy_from_slice(&self.buf[..HEADER_BYTES]);
                // A bad size desynchronises the stream: the session ends and connects again.
                let (size, kind) = qtm::header(&h).map_err(Broken::Bad)?;
                if self.buf.len() >= size {
                    self.packet.clear();
                    self.packet.extend_from_slice(&self.buf[HEADER_BYTES..size]);
                    self.buf.drain(..size);
                    return Ok(Got::Packet(kind));
                }
            }
            let mut chunk = [0u8; 16 * 1024];
            match stream.read(&mut chunk) {
                Ok(0) => return Err(Broken::Closed("QTM closed the connection".into())),
                Ok(n) => self.buf.extend_from_slice(&chunk[..n]),
                Err(e) if matches!(e.kind(), std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut) => {
                    return Ok(Got::Idle)
                }
                Err(e) => return Err(Broken::Closed(format!("reading from QTM: {e}"))),
            }
        }
    }
}

struct Session<'a> {
    stream: TcpStream,
    reader: PacketReader,
    shared: &'a Mutex<Shared>,
    stop: &'a AtomicBool,
    bodies: &'a [String],
    fitters: &'a [Option<MarkerFitter>],
    /// QTM's 6D body names, in index order.
    names: Vec<String>,
    /// Per marker-set route, each of its markers' index among QTM's 3D labels (None: a label is missing).
    indices: Vec<Option<Vec<usize>>>,
    lab_m: Vec<Option<crate::math::Vector3>>,
}

impl Session<'_> {
    fn send(&mut self, command: &str) -> Result<(), End> {
        self.stream.write_all(&qtm_encode::command(command)).map_err(|e| End::Lost(format!("writing to QTM: {e}")))
    }

    /// The next packet, waiting up to `wait`.
    fn next(&mut self, wait: Duration) -> Result<(u32, usize), End> {
        let deadline = Instant::now() + wait;
        loop {
            if self.stop.load(Ordering::Relaxed) {
                return Err(End::Stopped);
            }
            match self.reader.next(&mut self.stream) {
                Ok(Got::Packet(kind)) => return Ok((kind, self.reader.packet.len())),
                Ok(Got::Idle) if Instant::now() > deadline => return Err(End::Silent),
                Ok(Got::Idle) => lock(self.shared).log.flush(),
                Err(Broken::Closed(why)) => return Err(End::Lost(why)),
                Err(Broken::Bad(e)) => {
                    lock(self.shared).conn.reject(InputRejection::Decode(e.reason()));
                    return Err(End::Lost(format!("{e}; the stream is out of step")));
                }
            }
        }
    }

    /// Sends `command` and waits for its reply (a command or XML string; an error packet is an error).
    fn ask(&mut self, command: &str, want: u32) -> Result<String, End> {
        self.send(command)?;
        loop {
            let (kind, _) = self.next(REPLY_WAIT)?;
            let text = qtm::text(&self.reader.packet);
            match kind {
                k if k == want => return Ok(text),
                qtm::PACKET_ERROR => {
                    return Err(End::Lost(format!("QTM refused `{command}`: {}", peer_log::escaped(&text, 120))))
                }
                _ => {}
            }
        }
    }

    /// Whether any route is a marker set (then 3D is asked for beside 6D).
    fn wants_3d(&self) -> bool {
        self.fitters.iter().any(Option::is_some)
    }

    fn components(&self) -> &'static str {
        if self.wants_3d() {
            "6D 3D"
        } else {
            "6D"
        }
    }

    fn map_bodies(&mut self, xml: &str) {
        if self.wants_3d() {
            let labels = qtm::label_names(xml);
            for (i, fitter) in self.fitters.iter().enumerate() {
                let Some(f) = fitter else { continue };
                self.indices[i] = match f.set.indices_in(&labels) {
                    Ok(found) => Some(found),
                    Err(missing) => {
                        let labels = peer_log::list(labels.iter().map(String::as_str));
                        let body = &self.bodies[i];
                        lock(self.shared).log.warn("markers_not_in_model", || {
                            format!("marker `{missing}` of `{body}` is not among QTM's 3D labels ({labels})")
                        });
                        None
                    }
                };
                lock(self.shared).bodies[i].body_found = self.indices[i].is_some();
            }
        }
        let names = qtm::body_names(xml);
        let mut sh = lock(self.shared);
        for (i, name) in self.bodies.iter().enumerate() {
            if self.fitters[i].is_some() {
                continue;
            }
            let found = names.iter().any(|n| n == name);
            if !found && (sh.bodies[i].body_found || sh.bodies[i].frames == 0) {
                let listed = || peer_log::list(names.iter().map(String::as_str));
                sh.log.warn("body_not_in_model", || {
                    format!("6DOF body `{name}` is not among QTM's bodies ({})", listed())
                });
            }
            sh.bodies[i].body_found = found;
        }
        self.names = names;
    }

    fn run(&mut self, tracks: &mut [BodyTrack], backoff: &mut Duration) -> End {
        match self.session(tracks, backoff) {
            Ok(()) => End::Stopped,
            Err(end) => end,
        }
    }

    fn session(&mut self, tracks: &mut [BodyTrack], backoff: &mut Duration) -> Result<(), End> {
        let _ = self.stream.set_nodelay(true);
        self.stream.set_read_timeout(Some(POLL)).map_err(|e| End::Lost(format!("socket: {e}")))?;
        let (kind, _) = self.next(REPLY_WAIT)?;
        if kind != qtm::PACKET_COMMAND {
            return Err(End::Lost("QTM did not greet".into()));
        }
        let version = format!("Version {}", qtm::PROTOCOL_VERSION);
        let reply = self.ask(&version, qtm::PACKET_COMMAND).inspect_err(|e| {
            // An error packet in answer: this QTM does not speak the version.
            if let End::Lost(why) = e {
                if why.starts_with("QTM refused") {
                    let mut sh = lock(self.shared);
                    sh.conn.reject(InputRejection::UnknownVersion);
                    sh.conn.last_error = Some(why.clone());
                }
            }
        })?;
        let xml = self.ask(&format!("GetParameters {}", self.components()), qtm::PACKET_XML)?;
        self.map_bodies(&xml);
        self.send(&format!("StreamFrames AllFrames {}", self.components()))?;
        {
            let mut sh = lock(self.shared);
            sh.conn.state = ConnectionState::Connected;
            sh.conn.connects += 1;
            sh.conn.server_version = Some(format!("QTM RT protocol {} ({reply})", qtm::PROTOCOL_VERSION));
            sh.conn.last_error = None;
        }
        tracing::info!("QTM at {}: streaming 6D", self.stream.peer_addr().map(|a| a.to_string()).unwrap_or_default());
        *backoff = BACKOFF_FIRST;
        let mut frame = Frame6d::default();
        loop {
            let kind = self.next_streaming()?;
            let received = Instant::now();
            match kind {
                qtm::PACKET_DATA => self.on_data(&mut frame, tracks, received),
                qtm::PACKET_XML => {
                    let xml = qtm::text(&self.reader.packet);
                    self.map_bodies(&xml);
                }
                qtm::PACKET_EVENT => {
                    let code = self.reader.packet.first().copied().unwrap_or(0);
                    if [
                        qtm::EVENT_CONNECTION_CLOSED,
                        qtm::EVENT_CAPTURE_STOPPED,
                        qtm::EVENT_RT_FROM_FILE_STOPPED,
                        qtm::EVENT_QTM_SHUTTING_DOWN,
                    ]
                    .contains(&code)
                    {
                        return Err(End::Lost(format!("QTM's measurement stopped (event {code})")));
                    }
                    if EVENTS_REMAP.contains(&code) {
                        self.send(&format!("GetParameters {}", self.components()))?;
                    }
                }
                qtm::PACKET_NO_MORE_DATA => return Err(End::Lost("QTM's measurement stopped (no more data)".into())),
                qtm::PACKET_ERROR => {
                    let text = peer_log::escaped(&qtm::text(&self.reader.packet), 120);
                    lock(self.shared).conn.last_error = Some(text);
                }
                qtm::PACKET_COMMAND => {}
                other => lock(self.shared).conn.reject(InputRejection::Decode(QtmError::UnknownPacket(other).reason())),
            }
        }
    }

    /// The next packet while streaming: after [`PROBE_AFTER`] of silence QTM is asked for its version (a live
    /// QTM between measurements answers); after [`QUIET`] the session ends and the client connects again.
    fn next_streaming(&mut self) -> Result<u32, End> {
        match self.next(PROBE_AFTER) {
            Ok((kind, _)) => return Ok(kind),
            Err(End::Silent) => {}
            Err(end) => return Err(end),
        }
        self.send("QTMVersion")?;
        match self.next(QUIET.saturating_sub(PROBE_AFTER)) {
            Ok((kind, _)) => Ok(kind),
            Err(End::Silent) => {
                let why = format!("QTM sent nothing for {} s, not even a reply; connecting again", QUIET.as_secs());
                lock(self.shared).conn.reconnect(Reconnect::Quiet, why.clone());
                Err(End::Lost(why))
            }
            Err(end) => Err(end),
        }
    }

    fn on_data(&mut self, frame: &mut Frame6d, tracks: &mut [BodyTrack], received: Instant) {
        let mut sh = lock(self.shared);
        let components = match qtm::decode_data(&self.reader.packet, frame) {
            Ok(c) => c,
            Err(e) => return sh.conn.reject(InputRejection::Decode(e.reason())),
        };
        // A route of a 6DOF body in a packet without 6D (or a marker set without 3D): counted once per packet.
        let wants_6d = self.fitters.iter().any(Option::is_none);
        if (wants_6d && !components.six_d) || (self.wants_3d() && !components.three_d) {
            return sh.conn.reject(InputRejection::Decode(QtmError::No6d.reason()));
        }
        let sh = &mut *sh;
        for (i, name) in self.bodies.iter().enumerate() {
            let status = &mut sh.bodies[i];
            if let Some(fitter) = &self.fitters[i] {
                let Some(indices) = &self.indices[i] else {
                    *status.rejected.entry("markers_not_in_model".into()).or_default() += 1;
                    continue;
                };
                let sample = track::qtm_fitted_sample(fitter, indices, frame, &mut self.lab_m);
                if tracks[i].on_frame(&sample, None, status) == Sequence::Publish {
                    (sh.deliver)(i, &sample, received);
                }
                continue;
            }
            let Some(index) = self.names.iter().position(|n| n == name) else {
                *status.rejected.entry("body_not_in_model".into()).or_default() += 1;
                continue;
            };
            let Some(body) = frame.bodies.get(index) else {
                *status.rejected.entry("body_missing_from_frame".into()).or_default() += 1;
                continue;
            };
            let (sample, bad) = qtm_sample(body, frame);
            if tracks[i].on_frame(&sample, bad, status) == Sequence::Publish {
                (sh.deliver)(i, &sample, received);
            }
        }
    }
}
