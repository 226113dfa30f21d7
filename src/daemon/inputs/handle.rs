//! A running client: its threads, its stop flag and the counts behind each route's `MocapInputStatus`, for
//! every protocol alike.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;

use super::config::resolve;
use super::protocol::{Protocol, Route, Source, Start};
use super::registry::protocol;
use super::shared::{lock, Conn, Deliver, Shared};
use crate::daemon::stats::LatencyWindow;
use crate::daemon::DaemonError;
use crate::wire::{ConnectionState, MocapInputStatus};

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
                reconnects: Default::default(),
                server_version: None,
                rejected: Default::default(),
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
    /// server's labelled markers each frame).
    pub fn start_fitted(
        source: Source,
        routes: Vec<(String, String)>,
        fitters: Vec<Option<crate::kinematics::MarkerFitter>>,
        deliver: Deliver,
    ) -> Result<Self, DaemonError> {
        let mut fitters = fitters.into_iter();
        let parts = routes
            .iter()
            .map(|(body, rig)| {
                (Route { body: body.clone(), segment: None, fitter: fitters.next().flatten() }, rig.clone())
            })
            .collect();
        Self::start_routes(source, parts, deliver)
    }

    /// Starts a client of `source` for `routes` (each a [`Route`] and the rig it feeds) with the protocol's
    /// client ([`super::PROTOCOLS`]).
    pub fn start_routes(source: Source, routes: Vec<(Route, String)>, deliver: Deliver) -> Result<Self, DaemonError> {
        let p = protocol(source.protocol)
            .ok_or_else(|| DaemonError::Config { field: "input.protocol".into(), reason: source.protocol.into() })?;
        Self::start_with(p, source, routes, deliver)
    }

    /// [`InputHandle::start_routes`] with the client of `p` (a protocol from any list of entries).
    pub fn start_with(
        p: &dyn Protocol,
        source: Source,
        routes: Vec<(Route, String)>,
        deliver: Deliver,
    ) -> Result<Self, DaemonError> {
        let stop = Arc::new(AtomicBool::new(false));
        let named: Vec<(String, String)> = routes.iter().map(|(r, rig)| (r.body.clone(), rig.clone())).collect();
        let shared = Arc::new(Mutex::new(Shared::new(&source, &named, deliver)));
        let server = resolve(&source.host, source.port)?;
        let threads = p.start(Start {
            source: source.clone(),
            server,
            routes: routes.into_iter().map(|(r, _)| r).collect(),
            shared: shared.clone(),
            stop: stop.clone(),
        })?;
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
    out.reconnects = s.conn.reconnects.to_wire();
    out.server_version = s.conn.server_version.clone();
    out.last_error = s.conn.last_error.clone();
    for (k, v) in s.conn.rejected.to_wire() {
        *out.rejected.entry(k).or_default() += v;
    }
    let w = &s.conn.exposure_to_transmit_us;
    let p99 = w.quantile(0.99);
    out.exposure_to_transmit_p99_us = (p99 > 0.0).then_some(p99);
    out
}
