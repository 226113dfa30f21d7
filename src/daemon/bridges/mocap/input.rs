//! What the NatNet and QTM clients share: the `[rig.input]` configuration, the server a group of rigs reads
//! (several rigs, one body each, share one connection), the counts behind each rig's `MocapInputStatus`, and
//! the handle that stops the client's threads.

use std::collections::BTreeMap;
use std::net::{Ipv4Addr, SocketAddr, ToSocketAddrs};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;

use serde::{Deserialize, Serialize};

use super::shared::{lock, Conn, Deliver, Shared};
use crate::daemon::stats::LatencyWindow;
use crate::daemon::DaemonError;
use crate::wire::{ConnectionState, MocapInputStatus};

pub const NATNET_COMMAND_PORT: u16 = 1510;
pub const NATNET_DATA_PORT: u16 = 1511;
/// Motive's default multicast group.
pub const NATNET_MULTICAST_GROUP: Ipv4Addr = Ipv4Addr::new(239, 255, 42, 99);
/// QTM's little-endian real-time port.
pub const QTM_PORT: u16 = 22223;

/// `[rig.input]`: the rig's samples come straight from a NatNet or QTM server.
///
/// ```toml
/// [rig.input]
/// natnet = "192.168.1.20"    # or qtm = "192.168.1.20"
/// body = "driver"            # the rigid body's name in Motive (6DOF body in QTM)
/// ball_body = "ball"         # optional: a body whose origin is the ball's centre (mocap/<rig>/ball)
/// markers = "club.toml"      # optional: fit this marker set to the labelled markers instead of a body
/// unicast = true             # NatNet: unicast (default: multicast on multicast_group)
/// # command_port = 1510; data_port = 1511; multicast_group = "239.255.42.99"; port = 22223 (QTM)
/// ```
#[derive(Debug, Clone, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MocapInputConfig {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub natnet: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub qtm: Option<String>,
    pub body: String,
    /// A body (a marker or a rigid body) whose origin is the ball's centre: its frames are the rig's tracked ball,
    /// which sets each shot's ball position (`mocap/<rig>/ball`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ball_body: Option<String>,
    /// A marker set file (`[markers]`, as `impactd import` takes): the club's pose is that set fitted to the
    /// server's labelled markers each frame, so the capture software needs no rigid body. QTM: the labels are
    /// its 3D labels and `body` names the route in the status; NatNet: `body` names Motive's asset (its marker
    /// set) and the labels are the marker names within it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub markers: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub command_port: Option<u16>,
    /// NatNet data port (0: any free port, for unicast).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub data_port: Option<u16>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub multicast_group: Option<String>,
    #[serde(default)]
    pub unicast: bool,
    /// QTM's port.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub port: Option<u16>,
}

/// The server a client reads.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum Source {
    NatNet { host: String, command_port: u16, data_port: u16, multicast_group: Option<Ipv4Addr> },
    Qtm { host: String, port: u16 },
}

impl Source {
    pub fn protocol(&self) -> &'static str {
        match self {
            Source::NatNet { .. } => "natnet",
            Source::Qtm { .. } => "qtm",
        }
    }

    pub fn address(&self) -> String {
        match self {
            Source::NatNet { host, command_port, .. } => format!("{host}:{command_port}"),
            Source::Qtm { host, port } => format!("{host}:{port}"),
        }
    }
}

impl MocapInputConfig {
    /// The server, or the field that is wrong and why.
    pub fn source(&self) -> Result<Source, (&'static str, String)> {
        if self.body.trim().is_empty() {
            return Err(("body", "must name the rigid body".into()));
        }
        if let Some(b) = &self.ball_body {
            if b.trim().is_empty() || *b == self.body {
                return Err(("ball_body", "must name a body other than the club's".into()));
            }
        }
        let host = |h: &String, field| {
            if h.trim().is_empty() || h.contains(char::is_whitespace) {
                Err((field, format!("`{h}` is not a host name or address")))
            } else {
                Ok(h.clone())
            }
        };
        match (&self.natnet, &self.qtm) {
            (Some(h), None) => {
                if self.port.is_some() {
                    return Err(("port", "is QTM's; NatNet has command_port and data_port".into()));
                }
                let multicast_group = match (&self.multicast_group, self.unicast) {
                    (Some(_), true) => return Err(("multicast_group", "and unicast = true exclude each other".into())),
                    (Some(g), false) => Some(
                        g.parse::<Ipv4Addr>()
                            .ok()
                            .filter(Ipv4Addr::is_multicast)
                            .ok_or(("multicast_group", format!("`{g}` is not an IPv4 multicast address")))?,
                    ),
                    (None, false) => Some(NATNET_MULTICAST_GROUP),
                    (None, true) => None,
                };
                Ok(Source::NatNet {
                    host: host(h, "natnet")?,
                    command_port: self.command_port.unwrap_or(NATNET_COMMAND_PORT),
                    data_port: self.data_port.unwrap_or(NATNET_DATA_PORT),
                    multicast_group,
                })
            }
            (None, Some(h)) => {
                if self.command_port.is_some() || self.data_port.is_some() || self.multicast_group.is_some() {
                    return Err((
                        "qtm",
                        "takes `port` only (command_port, data_port, multicast_group are NatNet's)".into(),
                    ));
                }
                Ok(Source::Qtm { host: host(h, "qtm")?, port: self.port.unwrap_or(QTM_PORT) })
            }
            (Some(_), Some(_)) => Err(("natnet", "and qtm exclude each other".into())),
            (None, None) => Err(("natnet", "or qtm must name the server".into())),
        }
    }
}

/// A marker set file as a live fitter (3 mm rejection, as `impactd import`'s default), or why it cannot be read.
pub fn marker_fitter(path: &str) -> Result<crate::kinematics::MarkerFitter, MarkerFileError> {
    let text =
        std::fs::read_to_string(path).map_err(|source| MarkerFileError::Read { path: path.to_string(), source })?;
    let set = crate::kinematics::MarkerSet::from_toml(&text)
        .map_err(|source| MarkerFileError::Parse { path: path.to_string(), source })?;
    Ok(crate::kinematics::MarkerFitter::new(set).with_reject_m(3e-3))
}

/// A marker set file (`input.markers`, `bridge --markers`) that cannot be read or holds no marker set.
#[derive(Debug, thiserror::Error)]
pub enum MarkerFileError {
    #[error("reading {path}: {source}")]
    Read {
        path: String,
        #[source]
        source: std::io::Error,
    },
    #[error("{path}: {source}")]
    Parse {
        path: String,
        #[source]
        source: crate::kinematics::MarkerSetError,
    },
}

/// The server's first IPv4 address.
pub fn resolve(host: &str, port: u16) -> Result<SocketAddr, DaemonError> {
    let io = |source| DaemonError::Io { what: format!("resolving {host}"), source };
    (host, port)
        .to_socket_addrs()
        .map_err(io)?
        .find(SocketAddr::is_ipv4)
        .ok_or_else(|| io(std::io::Error::other("no IPv4 address")))
}

impl Shared {
    pub fn new(source: &Source, routes: &[(String, String)], deliver: Deliver) -> Self {
        let bodies = routes
            .iter()
            .map(|(body, rig)| MocapInputStatus {
                rig: rig.clone(),
                protocol: source.protocol().into(),
                server: source.address(),
                body: body.clone(),
                ..MocapInputStatus::default()
            })
            .collect();
        Shared {
            conn: Conn {
                state: ConnectionState::Connecting,
                connects: 0,
                reconnects: BTreeMap::new(),
                server_version: None,
                rejected: BTreeMap::new(),
                last_error: None,
                exposure_to_transmit_us: LatencyWindow::new(1024),
            },
            bodies,
            deliver,
            log: crate::daemon::peer_log::PeerLog::new(),
        }
    }
}

/// A running client: its threads, stop flag and counts.
pub struct InputHandle {
    pub source: Source,
    stop: Arc<AtomicBool>,
    threads: Vec<JoinHandle<()>>,
    shared: Arc<Mutex<Shared>>,
}

impl InputHandle {
    /// Starts a client of `source` for `routes` (`(body name, rig)`), handing samples to `deliver`.
    pub fn start(source: Source, routes: Vec<(String, String)>, deliver: Deliver) -> Result<Self, DaemonError> {
        let fitters = vec![None; routes.len()];
        Self::start_fitted(source, routes, fitters, deliver)
    }

    /// [`InputHandle::start`] with a marker set per route (`Some`: the route's pose is that set fitted to the
    /// server's labelled markers each frame: QTM's 3D labels, or the labelled markers of Motive's asset named
    /// like the route's body).
    pub fn start_fitted(
        source: Source,
        routes: Vec<(String, String)>,
        fitters: Vec<Option<crate::kinematics::MarkerFitter>>,
        deliver: Deliver,
    ) -> Result<Self, DaemonError> {
        let stop = Arc::new(AtomicBool::new(false));
        let bodies: Vec<String> = routes.iter().map(|r| r.0.clone()).collect();
        let shared = Arc::new(Mutex::new(Shared::new(&source, &routes, deliver)));
        let threads = match &source {
            Source::NatNet { host, command_port, data_port, multicast_group } => super::natnet::start(
                super::natnet::Options {
                    server: resolve(host, *command_port)?,
                    data_port: *data_port,
                    multicast_group: *multicast_group,
                },
                bodies,
                fitters,
                shared.clone(),
                stop.clone(),
            )?,
            Source::Qtm { host, port } => {
                super::qtm::start(resolve(host, *port)?, bodies, fitters, shared.clone(), stop.clone())?
            }
        };
        Ok(InputHandle { source, stop, threads, shared })
    }

    /// The status of route `i` (its body's counts and the connection's).
    pub fn status(&self, i: usize) -> MocapInputStatus {
        status_of(&self.shared, i)
    }

    /// A cheap handle on the counts, for a rig's status.
    pub fn status_source(&self, i: usize) -> StatusSource {
        StatusSource { shared: self.shared.clone(), route: i }
    }

    pub fn routes(&self) -> usize {
        lock(&self.shared).bodies.len()
    }

    /// Stops the threads and waits for them (each within [`POLL`]); drops the delivery (and the rig queues it
    /// holds), so status sources that outlive the client keep no queue open.
    pub fn stop(self) {
        self.stop.store(true, Ordering::Relaxed);
        for t in self.threads {
            let _ = t.join();
        }
        lock(&self.shared).deliver = Box::new(|_, _, _| {});
    }
}

/// One rig's view of a client's counts.
#[derive(Clone)]
pub struct StatusSource {
    shared: Arc<Mutex<Shared>>,
    route: usize,
}

impl StatusSource {
    pub fn status(&self) -> MocapInputStatus {
        status_of(&self.shared, self.route)
    }
}

fn status_of(shared: &Mutex<Shared>, i: usize) -> MocapInputStatus {
    let s = lock(shared);
    let mut out = s.bodies.get(i).cloned().unwrap_or_default();
    out.state = s.conn.state;
    out.connects = s.conn.connects;
    out.reconnects = s.conn.reconnects.clone();
    out.server_version = s.conn.server_version.clone();
    out.last_error = s.conn.last_error.clone();
    for (k, v) in &s.conn.rejected {
        *out.rejected.entry(k.clone()).or_default() += v;
    }
    let w = &s.conn.exposure_to_transmit_us;
    let p99 = w.quantile(0.99);
    out.exposure_to_transmit_p99_us = (p99 > 0.0).then_some(p99);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A marker file that is not there, or is no marker set, keeps its cause: the IO error or the marker set's
    /// error, reachable from the daemon's error through `source()`, and says it once.
    #[test]
    fn a_bad_marker_file_keeps_its_cause() {
        use std::error::Error;
        let dir = tempfile::tempdir().unwrap();
        let missing = dir.path().join("none.toml");
        let e = marker_fitter(missing.to_str().unwrap()).unwrap_err();
        assert!(matches!(&e, MarkerFileError::Read { source, .. } if source.kind() == std::io::ErrorKind::NotFound));
        let bad = dir.path().join("bad.toml");
        std::fs::write(&bad, "[[marker]]\nname = 3\n").unwrap();
        let e = marker_fitter(bad.to_str().unwrap()).unwrap_err();
        assert!(matches!(&e, MarkerFileError::Parse { .. }), "{e:?}");
        let text = e.to_string();
        let daemon = DaemonError::Markers { field: "rig a: input.markers".into(), source: e };
        assert_eq!(daemon.to_string(), format!("config field `rig a: input.markers` {text}"));
        let cause = daemon.source().and_then(|s| s.source()).unwrap();
        assert!(cause.downcast_ref::<crate::kinematics::MarkerSetError>().is_some(), "{cause:?}");
    }
}
