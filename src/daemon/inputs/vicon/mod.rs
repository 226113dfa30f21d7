//! The Vicon DataStream client: one thread, one TCP connection at a time (port 801). It connects (with back-off
//! while the server is not there), reads the server's `ObjectEnums`, asks for the types a rigid subject and its
//! labelled markers need (those the server offers), streams in ServerPush, pings once a second, and reads
//! frames until the connection ends or goes silent for [`QUIET`] (as NatNet's and QTM's: counted as
//! `reconnects.quiet`); then connects again with back-off. Each route is a subject's segment (its
//! root unless `segment` names one) or a marker set fitted to the subject's labelled markers, resolved again
//! whenever the subjects change.

pub mod protocol;

use crate::daemon::inputs::counters::{InputRejection, Reconnect};
use std::io::{Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use super::protocol::Route;
use super::shared::{lock, sleep_unless_stopped, Shared, BACKOFF_FIRST, BACKOFF_LAST, POLL};
use crate::daemon::{peer_log, DaemonError};
use crate::math::Vector3;
use crate::mocap::track::{BodyTrack, Sequence};
use crate::mocap::vicon::sample::{fitted_sample, resolve_markers, resolve_segment, segment_sample, RouteIds};
use crate::mocap::vicon::{encode, enums, framing, Decoder};
use crate::wire::ConnectionState;

/// How long the server's greeting may take.
const GREETING_WAIT: Duration = Duration::from_secs(5);
/// How often the client pings.
const PING_EVERY: Duration = Duration::from_secs(1);
/// While streaming, a connection silent this long (no frame, no answer to the pings) is ended and connected
/// again (NatNet's [`super::shared::QUIET`]).
pub const QUIET: Duration = super::shared::QUIET;

/// Starts the client thread for `routes`.
pub fn start(
    server: SocketAddr,
    routes: Vec<Route>,
    shared: Arc<Mutex<Shared>>,
    stop: Arc<AtomicBool>,
) -> Result<Vec<JoinHandle<()>>, DaemonError> {
    let thread = std::thread::Builder::new()
        .name("vicon".into())
        .spawn(move || run(server, &routes, &shared, &stop))
        .map_err(|source| DaemonError::Io { what: "starting the Vicon thread".into(), source })?;
    Ok(vec![thread])
}

/// Why a session ended.
enum End {
    Stopped,
    Lost(String),
}

fn run(server: SocketAddr, routes: &[Route], shared: &Mutex<Shared>, stop: &AtomicBool) {
    let mut backoff = BACKOFF_FIRST;
    let mut tracks = vec![BodyTrack::default(); routes.len()];
    let mut failures = 0u32;
    while !stop.load(Ordering::Relaxed) {
        let why = match TcpStream::connect_timeout(&server, Duration::from_secs(1)) {
            Ok(stream) => {
                let mut session = Session {
                    stream,
                    buf: Vec::new(),
                    packet: Vec::new(),
                    decoder: Decoder::new(),
                    shared,
                    stop,
                    routes,
                    ids: vec![Err("awaiting_server_info"); routes.len()],
                    lab_m: Vec::new(),
                };
                match session.run(&mut tracks, &mut backoff) {
                    Ok(()) | Err(End::Stopped) => return,
                    Err(End::Lost(why)) => why,
                }
            }
            Err(e) => format!("no Vicon DataStream server at {server} ({e})"),
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

struct Session<'a> {
    stream: TcpStream,
    /// Bytes read and not yet a whole packet.
    buf: Vec<u8>,
    /// The last whole packet.
    packet: Vec<u8>,
    decoder: Decoder,
    shared: &'a Mutex<Shared>,
    stop: &'a AtomicBool,
    routes: &'a [Route],
    /// Each route resolved against the current subjects, or the reason its frames are counted under.
    ids: Vec<Result<RouteIds, &'static str>>,
    lab_m: Vec<Option<Vector3>>,
}

impl Session<'_> {
    fn send(&mut self, bytes: &[u8]) -> Result<(), End> {
        self.stream.write_all(bytes).map_err(|e| End::Lost(format!("writing to the Vicon server: {e}")))
    }

    /// The next whole packet into `self.packet`: `Ok(false)` when none came within one poll.
    fn next(&mut self) -> Result<bool, End> {
        loop {
            if self.stop.load(Ordering::Relaxed) {
                return Err(End::Stopped);
            }
            if self.buf.len() >= framing::HEADER_BYTES {
                let mut h = [0u8; framing::HEADER_BYTES];
                h.copy_from_slice(&self.buf[..framing::HEADER_BYTES]);
                // A bad header desynchronises the stream: the session ends and connects again.
                let len = framing::header(&h).map_err(|e| {
                    lock(self.shared).conn.reject(InputRejection::Decode(e.reason()));
                    End::Lost(format!("{e}; the stream is out of step"))
                })?;
                let size = framing::HEADER_BYTES + len;
                if self.buf.len() >= size {
                    self.packet.clear();
                    self.packet.extend_from_slice(&self.buf[..size]);
                    self.buf.drain(..size);
                    return Ok(true);
                }
            }
            let mut chunk = [0u8; 64 * 1024];
            match self.stream.read(&mut chunk) {
                Ok(0) => return Err(End::Lost("the Vicon server closed the connection".into())),
                Ok(n) => self.buf.extend_from_slice(&chunk[..n]),
                Err(e) if matches!(e.kind(), std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut) => {
                    return Ok(false)
                }
                Err(e) => return Err(End::Lost(format!("reading from the Vicon server: {e}"))),
            }
        }
    }

    fn run(&mut self, tracks: &mut [BodyTrack], backoff: &mut Duration) -> Result<(), End> {
        let _ = self.stream.set_nodelay(true);
        self.stream.set_read_timeout(Some(POLL)).map_err(|e| End::Lost(format!("socket: {e}")))?;
        let deadline = Instant::now() + GREETING_WAIT;
        loop {
            if self.next()? {
                match self.decoder.decode(&self.packet) {
                    Ok(sum) if sum.object_enums => break,
                    Ok(_) => {}
                    Err(e) => lock(self.shared).conn.reject(InputRejection::Decode(e.reason())),
                }
            } else if Instant::now() > deadline {
                return Err(End::Lost("the Vicon server did not send its object types".into()));
            }
        }
        let offered = self.decoder.object_enums.clone();
        let wanted: Vec<u32> = enums::CLIENT_WANTS.iter().copied().filter(|k| offered.contains(k)).collect();
        let lacking: Vec<&str> = [enums::STREAM_INFO, enums::FRAME_INFO, enums::SUBJECT_INFO, enums::GLOBAL_SEGMENTS]
            .into_iter()
            .filter(|k| !offered.contains(k))
            .map(enums::name)
            .collect();
        if !lacking.is_empty() {
            tracing::warn!("the Vicon server does not offer {lacking:?}: its frames cannot all be read");
        }
        self.send(&encode::object_enums(&wanted))?;
        self.send(&encode::request_frame(true))?;
        {
            let mut sh = lock(self.shared);
            sh.conn.state = ConnectionState::Connected;
            sh.conn.connects += 1;
            sh.conn.server_version = Some("Vicon DataStream".into());
            sh.conn.last_error = None;
        }
        tracing::info!(
            "Vicon DataStream at {}: streaming (ServerPush)",
            self.stream.peer_addr().map(|a| a.to_string()).unwrap_or_default()
        );
        *backoff = BACKOFF_FIRST;
        let (mut ping, mut last_ping, mut last_packet) = (0u64, Instant::now(), Instant::now());
        loop {
            if last_ping.elapsed() >= PING_EVERY {
                ping += 1;
                last_ping = Instant::now();
                self.send(&encode::pings(&[ping]))?;
            }
            if !self.next()? {
                if last_packet.elapsed() >= QUIET {
                    let why = format!("the Vicon server sent nothing for {} s; connecting again", QUIET.as_secs());
                    lock(self.shared).conn.reconnect(Reconnect::Quiet, why.clone());
                    return Err(End::Lost(why));
                }
                lock(self.shared).log.flush();
                continue;
            }
            let received = Instant::now();
            last_packet = received;
            match self.decoder.decode(&self.packet) {
                Ok(sum) => {
                    if sum.statics {
                        self.resolve();
                    }
                    if sum.frame {
                        self.on_frame(tracks, received);
                    }
                }
                Err(e) => lock(self.shared).conn.reject(InputRejection::Decode(e.reason())),
            }
        }
    }

    /// Maps each route to its ids in the new subjects; says what is missing once per change.
    fn resolve(&mut self) {
        let frame = &self.decoder.frame;
        let mut sh = lock(self.shared);
        let up = frame.statics.up_axis.map_or("unknown", |u| u.name());
        let rate = frame.rate_hz().map(|r| format!("{r} Hz")).unwrap_or_else(|| "no frame rate".into());
        sh.conn.server_version = Some(format!("Vicon DataStream, {up}-up, {rate}"));
        for (i, route) in self.routes.iter().enumerate() {
            let ids = match &route.fitter {
                Some(f) => resolve_markers(frame, &route.body, f),
                None => resolve_segment(frame, &route.body, route.segment.as_deref()),
            };
            let found = ids.is_ok();
            if let Err(e) = &ids {
                if sh.bodies[i].body_found || sh.bodies[i].frames == 0 {
                    let names = peer_log::list(frame.statics.subjects.iter().map(|s| s.name.as_str()));
                    sh.log.warn("subject_not_in_model", || format!("{e} (subjects: {names})"));
                }
            }
            sh.bodies[i].body_found = found;
            self.ids[i] = ids.map_err(|e| e.reason());
        }
    }

    fn on_frame(&mut self, tracks: &mut [BodyTrack], received: Instant) {
        let frame = &self.decoder.frame;
        let mut sh = lock(self.shared);
        if frame.t_ns().is_none() {
            return sh.conn.reject(InputRejection::NoFramePeriod);
        }
        if let Some(s) = frame.latency_total_s() {
            sh.conn.exposure_to_transmit_us.push(s * 1e6);
        }
        let sh = &mut *sh;
        for (i, route) in self.routes.iter().enumerate() {
            let status = &mut sh.bodies[i];
            let (sample, bad) = match (&self.ids[i], &route.fitter) {
                (Ok(RouteIds::Segment { subject_id, segment_id }), _) => {
                    match segment_sample(frame, *subject_id, *segment_id) {
                        Some(s) => s,
                        None => continue,
                    }
                }
                (Ok(RouteIds::Markers { subject_id, marker_ids }), Some(f)) => {
                    match fitted_sample(frame, f, *subject_id, marker_ids, &mut self.lab_m) {
                        Some(s) => (s, None),
                        None => continue,
                    }
                }
                (Err(reason), _) => {
                    *status.rejected.entry((*reason).into()).or_default() += 1;
                    continue;
                }
                (Ok(RouteIds::Markers { .. }), None) => continue,
            };
            if tracks[i].on_frame(&sample, bad, status) == Sequence::Publish {
                (sh.deliver)(i, &sample, received);
            }
        }
    }
}
