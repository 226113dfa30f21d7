//! Opening a zenoh session from zenoh's usual flags.

use super::DaemonError;

/// zenoh's usual command-line flags.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct ZenohArgs {
    /// A zenoh configuration file (JSON5).
    #[arg(long = "zenoh-config", value_name = "FILE")]
    pub zenoh_config: Option<std::path::PathBuf>,
    /// peer or client.
    #[arg(short = 'm', long = "mode")]
    pub mode: Option<String>,
    /// Endpoints to connect to (e.g. tcp/192.168.1.10:7447); repeatable.
    #[arg(short = 'e', long = "connect")]
    pub connect: Vec<String>,
    /// Endpoints to listen on (e.g. tcp/0.0.0.0:7447); repeatable.
    #[arg(short = 'l', long = "listen")]
    pub listen: Vec<String>,
    /// Disable multicast scouting (discovery then needs --connect or a router).
    #[arg(long = "no-multicast-scouting")]
    pub no_multicast_scouting: bool,
}

impl ZenohArgs {
    /// Loopback only: peer mode, no multicast, listening or connecting on the given endpoints.
    pub fn loopback(listen: Vec<String>, connect: Vec<String>) -> Self {
        ZenohArgs { zenoh_config: None, mode: Some("peer".into()), connect, listen, no_multicast_scouting: true }
    }

    /// The zenoh configuration these flags describe.
    pub fn config(&self) -> Result<zenoh::Config, DaemonError> {
        let mut c = match &self.zenoh_config {
            Some(path) => zenoh::Config::from_file(path).map_err(DaemonError::zenoh)?,
            None => zenoh::Config::default(),
        };
        let json = |v: &[String]| serde_json::to_string(v).unwrap_or_else(|_| "[]".into());
        if let Some(mode) = &self.mode {
            if mode != "peer" && mode != "client" && mode != "router" {
                return Err(DaemonError::BadMode(mode.clone()));
            }
            c.insert_json5("mode", &format!("\"{mode}\"")).map_err(DaemonError::zenoh)?;
        }
        if !self.connect.is_empty() {
            c.insert_json5("connect/endpoints", &json(&self.connect)).map_err(DaemonError::zenoh)?;
        }
        if !self.listen.is_empty() {
            c.insert_json5("listen/endpoints", &json(&self.listen)).map_err(DaemonError::zenoh)?;
        }
        if self.no_multicast_scouting {
            c.insert_json5("scouting/multicast/enabled", "false").map_err(DaemonError::zenoh)?;
        }
        Ok(c)
    }

    /// Opens a session.
    pub async fn open(&self) -> Result<zenoh::Session, DaemonError> {
        zenoh::open(self.config()?).await.map_err(DaemonError::zenoh)
    }
}

/// A free TCP port on 127.0.0.1 (for in-process loopback sessions).
pub fn free_loopback_port() -> Result<u16, DaemonError> {
    let l = std::net::TcpListener::bind("127.0.0.1:0")
        .map_err(|e| DaemonError::Io { what: "finding a free port".into(), source: e })?;
    l.local_addr().map(|a| a.port()).map_err(|e| DaemonError::Io { what: "finding a free port".into(), source: e })
}
