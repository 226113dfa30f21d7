//! A QTM real-time server on 127.0.0.1 (TCP) that answers as QTM does: the greeting, `Version` (1.20-1.25),
//! `GetParameters 6D|3D|6D 3D` (the XML naming its bodies and marker labels), `StreamFrames AllFrames 6D|6DRes
//! [3D]` and `StreamFrames Stop`,
//! then data packets to every streaming client. Its bytes come from `impactd::mocap::qtm::encode`; the tests
//! check them with Qualisys' own Python SDK (`qtm-rt`).

#![allow(clippy::unwrap_used, dead_code)]

use std::io::{Read, Write};
use std::net::{TcpListener, TcpStream};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use impactd::mocap::qtm::encode as qtm_encode;
use impactd::mocap::qtm::{self, Frame6d};

struct Conn {
    stream: TcpStream,
    /// Streaming: (6DRes rather than 6D, 3D markers too).
    streaming: Option<(bool, bool)>,
}

pub struct QtmServer {
    pub port: u16,
    pub bodies: Arc<Mutex<Vec<String>>>,
    /// The 3D marker labels (`GetParameters 3D`), in index order.
    pub labels: Arc<Mutex<Vec<String>>>,
    conns: Arc<Mutex<Vec<Conn>>>,
    /// `StreamFrames` commands received.
    pub stream_requests: Arc<AtomicU64>,
    /// Answer `Version` with an error (a QTM that does not speak 1.2x).
    pub refuse_version: Arc<AtomicBool>,
    /// Say nothing at all, not even the greeting (a QTM gone silent after the handshake).
    pub mute: Arc<AtomicBool>,
    stop: Arc<AtomicBool>,
}

struct Ctx {
    bodies: Arc<Mutex<Vec<String>>>,
    labels: Arc<Mutex<Vec<String>>>,
    conns: Arc<Mutex<Vec<Conn>>>,
    streams: Arc<AtomicU64>,
    refuse: Arc<AtomicBool>,
    mute: Arc<AtomicBool>,
    stop: Arc<AtomicBool>,
}

fn handle(mut stream: TcpStream, id: usize, ctx: Ctx) {
    let Ctx { bodies, labels, conns, streams, refuse, mute, stop } = ctx;
    stream.set_read_timeout(Some(Duration::from_millis(50))).unwrap();
    let reply = |bytes: Vec<u8>| {
        if mute.load(Ordering::Relaxed) {
            return;
        }
        if let Some(c) = conns.lock().unwrap().get_mut(id) {
            let _ = c.stream.write_all(&bytes);
        }
    };
    reply(qtm_encode::command("QTM RT Interface connected"));
    let mut buf = Vec::new();
    let mut chunk = [0u8; 4096];
    while !stop.load(Ordering::Relaxed) {
        match stream.read(&mut chunk) {
            Ok(0) => return,
            Ok(n) => buf.extend_from_slice(&chunk[..n]),
            Err(_) => continue,
        }
        while buf.len() >= 8 {
            let h: [u8; 8] = buf[..8].try_into().unwrap();
            let Ok((size, _kind)) = qtm::header(&h) else { return };
            if buf.len() < size {
                break;
            }
            let text = qtm::text(&buf[8..size]).to_lowercase();
            buf.drain(..size);
            let words: Vec<&str> = text.split_whitespace().collect();
            match words.as_slice() {
                ["version", _] if refuse.load(Ordering::Relaxed) => reply(qtm_encode::error("Version NOT supported")),
                ["version", v] if ["1.20", "1.21", "1.22", "1.23", "1.24", "1.25"].contains(v) => {
                    reply(qtm_encode::command(&format!("Version set to {v}")))
                }
                ["version", _] => reply(qtm_encode::error("Version NOT supported")),
                ["qtmversion"] => reply(qtm_encode::command("QTM Version is 2023.3 (build 0)")),
                ["byteorder"] => reply(qtm_encode::command("Byte order is little endian")),
                ["getparameters", "6d"] => {
                    let names = bodies.lock().unwrap().clone();
                    let names: Vec<&str> = names.iter().map(String::as_str).collect();
                    reply(qtm_encode::xml(&qtm_encode::parameters_6d(&names)))
                }
                ["getparameters", "3d"] => {
                    let names = labels.lock().unwrap().clone();
                    let names: Vec<&str> = names.iter().map(String::as_str).collect();
                    reply(qtm_encode::xml(&qtm_encode::parameters_3d(&names)))
                }
                ["getparameters", "6d", "3d"] | ["getparameters", "3d", "6d"] => {
                    let (b, l) = (bodies.lock().unwrap().clone(), labels.lock().unwrap().clone());
                    let b: Vec<&str> = b.iter().map(String::as_str).collect();
                    let l: Vec<&str> = l.iter().map(String::as_str).collect();
                    // One document with both sections, as QTM answers a request for several components.
                    let six = qtm_encode::parameters_6d(&b);
                    let at = six.find("  <The_6D>").unwrap();
                    reply(qtm_encode::xml(&format!("{}{}{}", &six[..at], qtm_encode::the_3d(&l), &six[at..])))
                }
                ["streamframes", "stop"] => {
                    if let Some(c) = conns.lock().unwrap().get_mut(id) {
                        c.streaming = None;
                    }
                }
                ["streamframes", "allframes", components @ ..]
                    if !components.is_empty() && components.iter().all(|c| ["6d", "6dres", "3d"].contains(c)) =>
                {
                    streams.fetch_add(1, Ordering::Relaxed);
                    if let Some(c) = conns.lock().unwrap().get_mut(id) {
                        c.streaming = Some((components.contains(&"6dres"), components.contains(&"3d")));
                    }
                }
                _ => reply(qtm_encode::error("Parse error")),
            }
        }
    }
}

impl QtmServer {
    pub fn start(bodies: &[&str]) -> QtmServer {
        Self::start_on(0, bodies)
    }

    /// On a given port of 127.0.0.1 (0: any).
    pub fn start_on(port: u16, bodies: &[&str]) -> QtmServer {
        let listener = TcpListener::bind(("127.0.0.1", port)).unwrap();
        listener.set_nonblocking(true).unwrap();
        let port = listener.local_addr().unwrap().port();
        let bodies = Arc::new(Mutex::new(bodies.iter().map(|s| s.to_string()).collect::<Vec<_>>()));
        let labels: Arc<Mutex<Vec<String>>> = Default::default();
        let conns: Arc<Mutex<Vec<Conn>>> = Default::default();
        let stream_requests = Arc::new(AtomicU64::new(0));
        let stop = Arc::new(AtomicBool::new(false));
        let refuse_version = Arc::new(AtomicBool::new(false));
        let mute = Arc::new(AtomicBool::new(false));
        let (b, c, s, st, rf, mu) = (
            bodies.clone(),
            conns.clone(),
            stream_requests.clone(),
            stop.clone(),
            refuse_version.clone(),
            mute.clone(),
        );
        let l = labels.clone();
        std::thread::spawn(move || {
            while !st.load(Ordering::Relaxed) {
                match listener.accept() {
                    Ok((stream, _)) => {
                        stream.set_nonblocking(false).unwrap();
                        stream.set_nodelay(true).unwrap();
                        let id = {
                            let mut conns = c.lock().unwrap();
                            conns.push(Conn { stream: stream.try_clone().unwrap(), streaming: None });
                            conns.len() - 1
                        };
                        let ctx = Ctx {
                            bodies: b.clone(),
                            labels: l.clone(),
                            conns: c.clone(),
                            streams: s.clone(),
                            refuse: rf.clone(),
                            mute: mu.clone(),
                            stop: st.clone(),
                        };
                        std::thread::spawn(move || handle(stream, id, ctx));
                    }
                    Err(_) => std::thread::sleep(Duration::from_millis(10)),
                }
            }
        });
        QtmServer { port, bodies, labels, conns, stream_requests, refuse_version, mute, stop }
    }

    /// Sends raw bytes to every streaming client.
    pub fn send_raw(&self, bytes: &[u8]) {
        for c in self.conns.lock().unwrap().iter_mut().filter(|c| c.streaming.is_some()) {
            let _ = c.stream.write_all(bytes);
        }
    }

    /// Sends a frame as 6D or 6DRes (with its 3D markers when the client asked for 3D), as each streaming
    /// client asked.
    pub fn send_frame(&self, frame: &Frame6d) {
        if self.mute.load(Ordering::Relaxed) {
            return;
        }
        for c in self.conns.lock().unwrap().iter_mut() {
            let Some((residual, with_3d)) = c.streaming else { continue };
            let mut f = frame.clone();
            if !with_3d {
                f.markers_mm.clear();
            }
            for b in &mut f.bodies {
                b.residual_mm = residual.then_some(0.4);
            }
            let _ = c.stream.write_all(&qtm_encode::data(&f));
        }
    }

    /// Closes every connection, as a restarting QTM does.
    pub fn drop_clients(&self) {
        for c in self.conns.lock().unwrap().iter_mut() {
            let _ = c.stream.shutdown(std::net::Shutdown::Both);
            c.streaming = None;
        }
    }

    pub fn streaming(&self) -> usize {
        self.conns.lock().unwrap().iter().filter(|c| c.streaming.is_some()).count()
    }
}

impl Drop for QtmServer {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        self.drop_clients();
    }
}
