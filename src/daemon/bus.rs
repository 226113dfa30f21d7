//! Opening a zenoh session from zenoh's usual flags.
//!
//! Secure by default: with no zenoh configuration file and no endpoints given, a serving daemon listens on
//! loopback only ([`DEFAULT_ENDPOINT`]) and every other command connects there, with multicast scouting off.
//! Only a configuration file or the flags (`-l tcp/0.0.0.0:7447`, `--multicast-scouting`) open it to a network.
//! Client mode retries its router with backoff instead of giving up when the router is not up yet.

use crate::daemon::DaemonError;

/// How a zenoh session joins the bus: zenoh's `mode`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    Peer,
    Client,
    Router,
}

impl Mode {
    /// The mode by zenoh's name for it (`peer`, `client`, `router`), or `None`.
    pub fn from_name(name: &str) -> Option<Mode> {
        match name {
            "peer" => Some(Mode::Peer),
            "client" => Some(Mode::Client),
            "router" => Some(Mode::Router),
            _ => None,
        }
    }

    /// zenoh's name for the mode.
    pub fn name(self) -> &'static str {
        match self {
            Mode::Peer => "peer",
            Mode::Client => "client",
            Mode::Router => "router",
        }
    }
}

/// What zenoh's usual command-line flags say (the command line's `ZenohFlags` checked): a configuration file,
/// the mode, the endpoints and multicast scouting.
#[derive(Debug, Clone, Default)]
pub struct ZenohArgs {
    /// A zenoh configuration file (JSON5).
    pub zenoh_config: Option<std::path::PathBuf>,
    /// The session's mode; `None`: the configuration file's, else zenoh's default (peer).
    pub mode: Option<Mode>,
    /// Endpoints to connect to (e.g. tcp/192.168.1.10:7447).
    pub connect: Vec<String>,
    /// Endpoints to listen on (e.g. tcp/0.0.0.0:7447).
    pub listen: Vec<String>,
    /// Multicast scouting off (the default unless a zenoh configuration file or `multicast_scouting` says
    /// otherwise).
    pub no_multicast_scouting: bool,
    /// Multicast scouting on: peers on the network find each other (and this process) by themselves.
    pub multicast_scouting: bool,
}

/// The loopback endpoint a daemon listens on, and other commands connect to, when nothing else is said.
pub const DEFAULT_ENDPOINT: &str = "tcp/127.0.0.1:7447";

/// What a process does on the bus when no endpoint is given.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// Listens on [`DEFAULT_ENDPOINT`] (the daemon).
    Serve,
    /// Connects to [`DEFAULT_ENDPOINT`] (sim, replay --publish).
    Join,
}

impl ZenohArgs {
    /// Loopback only: peer mode, no multicast, listening or connecting on the given endpoints.
    pub fn loopback(listen: Vec<String>, connect: Vec<String>) -> Self {
        ZenohArgs {
            zenoh_config: None,
            mode: Some(Mode::Peer),
            connect,
            listen,
            no_multicast_scouting: true,
            multicast_scouting: false,
        }
    }

    /// The zenoh configuration these flags describe, for a process serving the daemon.
    pub fn config(&self) -> Result<zenoh::Config, DaemonError> {
        self.config_for(Role::Serve)
    }

    /// The zenoh configuration these flags describe, with the secure defaults of `role`.
    pub fn config_for(&self, role: Role) -> Result<zenoh::Config, DaemonError> {
        let mut c = match &self.zenoh_config {
            Some(path) => {
                let text = crate::capped::read_to_string(path, crate::daemon::config::MAX_CONFIG_BYTES)
                    .map_err(|e| DaemonError::Io { what: format!("reading {}", path.display()), source: e })?;
                zenoh::Config::from_json5(&text).map_err(DaemonError::zenoh)?
            }
            None => zenoh::Config::default(),
        };
        let json = |v: &[String]| serde_json::to_string(v).unwrap_or_else(|_| "[]".into());
        if let Some(mode) = self.mode {
            c.insert_json5("mode", &format!("\"{}\"", mode.name())).map_err(DaemonError::zenoh)?;
        }
        let own_file = self.zenoh_config.is_some();
        let client = self.mode == Some(Mode::Client);
        let mut listen = self.listen.clone();
        let mut connect = self.connect.clone();
        if !own_file && listen.is_empty() && connect.is_empty() {
            match role {
                Role::Serve if !client => listen.push(DEFAULT_ENDPOINT.into()),
                _ => connect.push(DEFAULT_ENDPOINT.into()),
            }
        }
        if !own_file && listen.is_empty() && !client {
            // zenoh's own default listens on every interface: a peer that only connects listens on loopback.
            listen.push("tcp/127.0.0.1:0".into());
        }
        if !connect.is_empty() {
            c.insert_json5("connect/endpoints", &json(&connect)).map_err(DaemonError::zenoh)?;
        }
        if !listen.is_empty() {
            c.insert_json5("listen/endpoints", &json(&listen)).map_err(DaemonError::zenoh)?;
        }
        if self.no_multicast_scouting || (!own_file && !self.multicast_scouting) {
            c.insert_json5("scouting/multicast/enabled", "false").map_err(DaemonError::zenoh)?;
        } else if self.multicast_scouting {
            c.insert_json5("scouting/multicast/enabled", "true").map_err(DaemonError::zenoh)?;
        }
        Ok(c)
    }

    /// Opens a session as the daemon would.
    pub async fn open(&self) -> Result<zenoh::Session, DaemonError> {
        self.open_as(Role::Serve).await
    }

    /// Opens a session; in client mode, retries the router with backoff (0.25 s doubling to 8 s, for about two
    /// minutes) while it is not up yet.
    pub async fn open_as(&self, role: Role) -> Result<zenoh::Session, DaemonError> {
        let config = self.config_for(role)?;
        let client = self.mode == Some(Mode::Client);
        let mut wait = std::time::Duration::from_millis(250);
        let mut waited = std::time::Duration::ZERO;
        loop {
            match zenoh::open(config.clone()).await {
                Ok(s) => return Ok(s),
                Err(e) if client && waited < std::time::Duration::from_secs(120) => {
                    tracing::warn!("zenoh router not reachable ({e}); retrying in {:.2} s", wait.as_secs_f64());
                    tokio::time::sleep(wait).await;
                    waited += wait;
                    wait = (wait * 2).min(std::time::Duration::from_secs(8));
                }
                Err(e) => return Err(DaemonError::zenoh(e)),
            }
        }
    }
}

/// A free TCP port on 127.0.0.1 (for in-process loopback sessions), below Linux's ephemeral range (32768-60999).
///
/// The port is free when checked but only bound later by zenoh; a port from the ephemeral range (what binding to
/// port 0 gives) can be taken in between by any outgoing connection on the machine. Ports below that range are
/// only taken by listeners: each process walks them from its own offset (its id), never handing out one twice.
pub fn free_loopback_port() -> Result<u16, DaemonError> {
    use std::sync::atomic::{AtomicU32, Ordering};
    const FIRST: u32 = 20_000;
    const COUNT: u32 = 12_000;
    static NEXT: AtomicU32 = AtomicU32::new(u32::MAX);
    let _ = NEXT.compare_exchange(
        u32::MAX,
        std::process::id().wrapping_mul(7919) % COUNT,
        Ordering::Relaxed,
        Ordering::Relaxed,
    );
    let mut last = None;
    for _ in 0..COUNT {
        let port = (FIRST + NEXT.fetch_add(1, Ordering::Relaxed) % COUNT) as u16;
        match std::net::TcpListener::bind(("127.0.0.1", port)) {
            Ok(_) => return Ok(port),
            Err(e) => last = Some(e),
        }
    }
    Err(DaemonError::Io {
        what: "finding a free port".into(),
        source: last.unwrap_or_else(|| std::io::Error::other("no free port")),
    })
}
