//! A Vicon DataStream server on 127.0.0.1 (TCP) that answers as Nexus, Tracker and Shogun do: its
//! `ObjectEnums` greeting, then per client the object types it asked for (its `ObjectEnums`), ServerPush
//! (`RequestFrame` streaming: every frame sent) or ClientPull (`RequestFrame` not streaming, or
//! `RequestNextFrame`: the current frame sent per request), `Ping`s sent back. Static objects go in a client's
//! first frame and again when they change, otherwise `Contents` lists them unchanged. Its bytes come from
//! `impactd::mocap::vicon::encode`; the tests check them with Vicon's own DataStream SDK.

#![allow(clippy::unwrap_used)]
#![allow(dead_code)]

use std::io::{Read, Write};
use std::net::{TcpListener, TcpStream};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use impactd::mocap::vicon::encode::{self, FrameOut};
use impactd::mocap::vicon::enums::*;
use impactd::mocap::vicon::framing::{self, HEADER_BYTES};
use impactd::mocap::vicon::{Decoder, DynamicObjects, StaticObjects};

/// The types the server offers (a Tracker's set, less cameras, devices and video).
pub const OFFERED: [u32; 15] = [
    CONTENTS,
    STREAM_INFO,
    SUBJECT_INFO,
    FRAME_INFO,
    TIMECODE,
    LATENCY_INFO,
    APPLICATION_INFO,
    SUBJECT_HEALTH,
    OBJECT_QUALITY,
    FRAME_RATE_INFO,
    LABELED_RECONS,
    UNLABELED_RECONS,
    LOCAL_SEGMENTS,
    GLOBAL_SEGMENTS,
    PING,
];

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Mode {
    Idle,
    Push,
    Pull,
}

struct Conn {
    stream: TcpStream,
    wanted: Vec<u32>,
    mode: Mode,
    /// The version of the static objects this client last got.
    statics_sent: Option<u64>,
    /// The frame id it last got: types are listed unchanged only to a client that got the frame before.
    last_frame: Option<u32>,
    open: bool,
}

/// The frame ClientPull requests are answered with, and the dynamic types it lists unchanged.
type Current = Option<(DynamicObjects, Vec<u32>)>;

struct Shared {
    statics: Mutex<(u64, StaticObjects)>,
    current: Mutex<Current>,
    conns: Mutex<Vec<Conn>>,
    pings: AtomicU64,
    requests: AtomicU64,
    stop: AtomicBool,
}

pub struct ViconServer {
    pub port: u16,
    shared: Arc<Shared>,
}

fn frame_bytes(shared: &Shared, c: &mut Conn, d: &DynamicObjects, unchanged: &[u32]) -> Vec<u8> {
    let statics = shared.statics.lock().unwrap();
    let resend = c.statics_sent != Some(statics.0);
    c.statics_sent = Some(statics.0);
    let follows = matches!((c.last_frame, d.frame_id), (Some(a), Some(b)) if b == a.wrapping_add(1));
    c.last_frame = d.frame_id;
    encode::frame(&FrameOut {
        statics: &statics.1,
        resend_statics: resend,
        dynamics: d,
        unchanged_dynamics: if follows { unchanged } else { &[] },
        wanted: &c.wanted,
    })
}

fn send_current(shared: &Shared, id: usize) {
    let current = shared.current.lock().unwrap().clone();
    let Some((d, unchanged)) = current else { return };
    let mut conns = shared.conns.lock().unwrap();
    let Some(c) = conns.get_mut(id) else { return };
    let bytes = frame_bytes(shared, c, &d, &unchanged);
    let _ = c.stream.write_all(&bytes);
}

fn handle(mut stream: TcpStream, id: usize, shared: Arc<Shared>) {
    stream.set_read_timeout(Some(Duration::from_millis(50))).unwrap();
    let mut decoder = Decoder::new();
    let mut buf = Vec::new();
    let mut chunk = [0u8; 4096];
    while !shared.stop.load(Ordering::Relaxed) {
        match stream.read(&mut chunk) {
            Ok(0) => break,
            Ok(n) => buf.extend_from_slice(&chunk[..n]),
            Err(e) if matches!(e.kind(), std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut) => continue,
            Err(_) => break,
        }
        while buf.len() >= HEADER_BYTES {
            let Ok(len) = framing::header(buf[..HEADER_BYTES].try_into().unwrap()) else { return };
            if buf.len() < HEADER_BYTES + len {
                break;
            }
            let packet: Vec<u8> = buf.drain(..HEADER_BYTES + len).collect();
            let Ok(sum) = decoder.decode(&packet) else { continue };
            if sum.object_enums {
                let mut conns = shared.conns.lock().unwrap();
                if let Some(c) = conns.get_mut(id) {
                    c.wanted = decoder.object_enums.iter().copied().filter(|k| OFFERED.contains(k)).collect();
                    c.statics_sent = None;
                    c.last_frame = None;
                }
            }
            if sum.pings > 0 {
                shared.pings.fetch_add(sum.pings as u64, Ordering::Relaxed);
                let bytes = encode::pings(&decoder.pings);
                if let Some(c) = shared.conns.lock().unwrap().get_mut(id) {
                    let _ = c.stream.write_all(&bytes);
                }
            }
            let pull = match sum.request_frame {
                Some(streaming) => {
                    if let Some(c) = shared.conns.lock().unwrap().get_mut(id) {
                        c.mode = if streaming { Mode::Push } else { Mode::Pull };
                    }
                    !streaming
                }
                None => sum.request_next_frame,
            };
            if pull {
                shared.requests.fetch_add(1, Ordering::Relaxed);
                send_current(&shared, id);
            }
        }
    }
    if let Some(c) = shared.conns.lock().unwrap().get_mut(id) {
        c.open = false;
        c.mode = Mode::Idle;
    }
}

impl ViconServer {
    pub fn start(statics: StaticObjects) -> ViconServer {
        Self::start_on(0, statics)
    }

    /// On a given port of 127.0.0.1 (0: any).
    pub fn start_on(port: u16, statics: StaticObjects) -> ViconServer {
        let listener = TcpListener::bind(("127.0.0.1", port)).unwrap();
        listener.set_nonblocking(true).unwrap();
        let port = listener.local_addr().unwrap().port();
        let shared = Arc::new(Shared {
            statics: Mutex::new((0, statics)),
            current: Mutex::new(None),
            conns: Mutex::new(Vec::new()),
            pings: AtomicU64::new(0),
            requests: AtomicU64::new(0),
            stop: AtomicBool::new(false),
        });
        let sh = shared.clone();
        std::thread::spawn(move || {
            while !sh.stop.load(Ordering::Relaxed) {
                match listener.accept() {
                    Ok((mut stream, _)) => {
                        stream.set_nonblocking(false).unwrap();
                        stream.set_nodelay(true).unwrap();
                        let _ = stream.write_all(&encode::object_enums(&OFFERED));
                        let id = {
                            let mut conns = sh.conns.lock().unwrap();
                            conns.push(Conn {
                                stream: stream.try_clone().unwrap(),
                                wanted: Vec::new(),
                                mode: Mode::Idle,
                                statics_sent: None,
                                last_frame: None,
                                open: true,
                            });
                            conns.len() - 1
                        };
                        let sh = sh.clone();
                        std::thread::spawn(move || handle(stream, id, sh));
                    }
                    Err(_) => std::thread::sleep(Duration::from_millis(5)),
                }
            }
        });
        ViconServer { port, shared }
    }

    /// New static objects (subjects, rate, up axis): every client gets them with its next frame.
    pub fn set_statics(&self, statics: StaticObjects) {
        let mut s = self.shared.statics.lock().unwrap();
        *s = (s.0 + 1, statics);
    }

    /// A new frame: sent to every ServerPush client, and the one ClientPull requests get from now on.
    pub fn send_frame(&self, d: &DynamicObjects) {
        self.send_frame_with(d, &[]);
    }

    /// [`ViconServer::send_frame`], with dynamic types listed unchanged in `Contents` instead of sent (to a client
    /// that got the frame before this one; `d` holds them all the same, for the others).
    pub fn send_frame_with(&self, d: &DynamicObjects, unchanged: &[u32]) {
        *self.shared.current.lock().unwrap() = Some((d.clone(), unchanged.to_vec()));
        let mut conns = self.shared.conns.lock().unwrap();
        for c in conns.iter_mut().filter(|c| c.open && c.mode == Mode::Push) {
            let bytes = frame_bytes(&self.shared, c, d, unchanged);
            let _ = c.stream.write_all(&bytes);
        }
    }

    /// Raw bytes to every ServerPush client.
    pub fn send_raw(&self, bytes: &[u8]) {
        for c in self.shared.conns.lock().unwrap().iter_mut().filter(|c| c.open && c.mode == Mode::Push) {
            let _ = c.stream.write_all(bytes);
        }
    }

    /// Clients in ServerPush mode.
    pub fn streaming(&self) -> usize {
        self.shared.conns.lock().unwrap().iter().filter(|c| c.open && c.mode == Mode::Push).count()
    }

    /// Clients connected (any mode).
    pub fn clients(&self) -> usize {
        self.shared.conns.lock().unwrap().iter().filter(|c| c.open).count()
    }

    /// Pings answered.
    pub fn pings(&self) -> u64 {
        self.shared.pings.load(Ordering::Relaxed)
    }

    /// ClientPull requests answered.
    pub fn pull_requests(&self) -> u64 {
        self.shared.requests.load(Ordering::Relaxed)
    }

    /// The object types each open client asked for.
    pub fn wanted(&self) -> Vec<Vec<u32>> {
        self.shared.conns.lock().unwrap().iter().filter(|c| c.open).map(|c| c.wanted.clone()).collect()
    }

    /// Closes every connection, as a restarting Nexus does.
    pub fn drop_clients(&self) {
        for c in self.shared.conns.lock().unwrap().iter_mut() {
            let _ = c.stream.shutdown(std::net::Shutdown::Both);
            c.open = false;
            c.mode = Mode::Idle;
        }
    }
}

impl Drop for ViconServer {
    fn drop(&mut self) {
        self.shared.stop.store(true, Ordering::Relaxed);
        self.drop_clients();
    }
}
