//! Open Connect v1, both ways: a client per rig that sends each shot's first prediction to a golf simulator
//! (GSPro, OpenGolfSim, ...), and a listener per rig that takes measured shots from a launch monitor's connector
//! as a simulator would and publishes them as `MeasuredLaunch`.
//!
//! The protocol (GSPro's "Open Connect v1" page): TCP, the simulator listens (port 921), JSON objects with no
//! delimiter between them both ways, no authentication. [`codec`] holds the messages, [`splitter`] cuts the
//! byte stream into objects, [`client`] and [`listener`] run the two ends on the daemon's tokio runtime.

pub mod client;
pub mod codec;
pub mod listener;
pub mod splitter;

use serde::{Deserialize, Serialize};

pub use client::{SimulatorClient, SimulatorOptions};
pub use listener::LaunchMonitorListener;

/// Largest Open Connect message kept (bytes); a shot is about 600.
pub const MAX_MESSAGE_BYTES: usize = 64 * 1024;

/// Errors of the Open Connect layer.
#[derive(Debug, thiserror::Error)]
pub enum OpenConnectError {
    /// A prediction that must not reach a simulator.
    #[error("shot {shot} not sent: {reason}")]
    Refused { shot: u64, reason: String },
    /// A received message that is not a usable shot.
    #[error("{0}")]
    Invalid(String),
    /// A message that could not be written as JSON.
    #[error("{0}")]
    Encode(#[source] serde_json::Error),
    #[error("{what} {address}: {source}")]
    Io {
        what: &'static str,
        address: String,
        #[source]
        source: std::io::Error,
    },
}

/// `[rig.simulator]`: where to send the rig's shots.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SimulatorConfig {
    /// The simulator's Open Connect address, `HOST:PORT` (GSPro listens on 921).
    #[serde(default)]
    pub open_connect: Option<String>,
    /// Or OpenGolfSim's developer API, `HOST:PORT` (it listens on 3111); one simulator per rig.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub opengolfsim: Option<String>,
    /// The `unit` of OpenGolfSim shots: `metric` (ball speed in m/s, the default) or `imperial` (mph).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub opengolfsim_unit: Option<String>,
    /// A shot older than this when the connection comes back is dropped and counted, never sent late.
    #[serde(default = "default_max_shot_age_s")]
    pub max_shot_age_s: f64,
    /// Heartbeat period while idle.
    #[serde(default = "default_heartbeat_s")]
    pub heartbeat_s: f64,
    /// `DeviceID` in every message.
    #[serde(default = "default_device_id")]
    pub device_id: String,
}

fn default_max_shot_age_s() -> f64 {
    5.0
}
fn default_heartbeat_s() -> f64 {
    2.0
}
fn default_device_id() -> String {
    format!("impactd {}", env!("CARGO_PKG_VERSION"))
}

impl Default for SimulatorConfig {
    fn default() -> Self {
        SimulatorConfig {
            open_connect: None,
            opengolfsim: None,
            opengolfsim_unit: None,
            max_shot_age_s: default_max_shot_age_s(),
            heartbeat_s: default_heartbeat_s(),
            device_id: default_device_id(),
        }
    }
}

/// `[rig.launch_monitor]`: where launch monitor connectors reach the rig.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LaunchMonitorConfig {
    /// Listen for Open Connect v1 clients here, `IP:PORT` (e.g. `127.0.0.1:921`).
    #[serde(default)]
    pub open_connect_listen: Option<String>,
    /// The delays (s) from a predicted impact to a measurement that pair them: `[min, max]`; default
    /// `[0.05, 5.0]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pair_window_s: Option<[f64; 2]>,
    /// Connectors connected at once; at the cap the longest-idle one is closed for a newcomer. Default 16.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_connections: Option<usize>,
    /// A connection that sends no shot or heartbeat this long after connecting is closed (s). Default 10.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub handshake_timeout_s: Option<f64>,
    /// A connection with no shot or heartbeat for this long is closed (s). Default 120.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub idle_timeout_s: Option<f64>,
}

/// Default connectors connected at once.
pub const DEFAULT_MAX_CONNECTIONS: usize = 16;
/// Default time to a first shot or heartbeat (s).
pub const DEFAULT_HANDSHAKE_TIMEOUT_S: f64 = 10.0;
/// Default longest time between shots or heartbeats (s).
pub const DEFAULT_IDLE_TIMEOUT_S: f64 = 120.0;

/// Starts what a rig's configuration asks for: its simulator client and its launch-monitor listener.
pub async fn start_rig(
    rig: &str,
    simulator: Option<&SimulatorConfig>,
    launch_monitor: Option<&LaunchMonitorConfig>,
    session: &zenoh::Session,
    recorder: &crate::daemon::recording::writer::RecorderHandle,
    clock: &crate::daemon::clock::Clock,
) -> Result<(Option<SimulatorClient>, Option<LaunchMonitorListener>), crate::daemon::DaemonError> {
    let simulator = simulator
        .and_then(|c| SimulatorOptions::from_config(rig, c))
        .map(|o| SimulatorClient::spawn(o, recorder.clone(), clock.clone()));
    let listener = match launch_monitor.and_then(|l| Some((l, l.open_connect_listen.as_ref()?))) {
        Some((config, address)) => {
            Some(LaunchMonitorListener::start(rig, config, address, session, recorder.clone(), clock.clone()).await?)
        }
        None => None,
    };
    Ok((simulator, listener))
}

/// Whether `address` reads as `HOST:PORT`.
pub fn valid_host_port(address: &str) -> bool {
    match address.rsplit_once(':') {
        Some((host, port)) => !host.is_empty() && !host.contains(char::is_whitespace) && port.parse::<u16>().is_ok(),
        None => false,
    }
}

impl SimulatorConfig {
    /// Checks every field; the error names the field (relative to `[rig.simulator]`) and the reason.
    pub fn check(&self) -> Result<(), (&'static str, String)> {
        for (field, address) in [("open_connect", &self.open_connect), ("opengolfsim", &self.opengolfsim)] {
            if let Some(a) = address.as_ref().filter(|a| !valid_host_port(a)) {
                return Err((field, format!("`{a}` is not HOST:PORT")));
            }
        }
        if self.open_connect.is_some() && self.opengolfsim.is_some() {
            return Err(("opengolfsim", "one simulator per rig: give open_connect or opengolfsim, not both".into()));
        }
        if let Some(u) = self.opengolfsim_unit.as_deref().filter(|u| !["metric", "imperial"].contains(u)) {
            return Err(("opengolfsim_unit", format!("`{u}` is neither `metric` nor `imperial`")));
        }
        if !(self.max_shot_age_s > 0.0 && self.max_shot_age_s <= 600.0) {
            return Err(("max_shot_age_s", "must be within 0 and 600 s".into()));
        }
        if !(self.heartbeat_s >= 0.1 && self.heartbeat_s <= 60.0) {
            return Err(("heartbeat_s", "must be within 0.1 and 60 s".into()));
        }
        if self.device_id.is_empty() || self.device_id.len() > 64 {
            return Err(("device_id", "must be 1 to 64 characters".into()));
        }
        Ok(())
    }
}

impl LaunchMonitorConfig {
    /// Checks every field; the error names the field (relative to `[rig.launch_monitor]`) and the reason.
    pub fn check(&self) -> Result<(), (&'static str, String)> {
        match &self.open_connect_listen {
            Some(a) if a.parse::<std::net::SocketAddr>().is_err() => {
                Err(("open_connect_listen", format!("`{a}` is not IP:PORT")))
            }
            _ => Ok(()),
        }?;
        match self.pair_window_s {
            Some([lo, hi]) if !(lo.is_finite() && hi.is_finite() && 0.0 <= lo && lo < hi && hi <= 600.0) => {
                Err(("pair_window_s", "must be [min, max] with 0 <= min < max <= 600 s".into()))
            }
            _ => Ok(()),
        }?;
        if self.max_connections.is_some_and(|n| !(1..=1024).contains(&n)) {
            return Err(("max_connections", "must be within 1 and 1024".into()));
        }
        for (field, v) in [("handshake_timeout_s", self.handshake_timeout_s), ("idle_timeout_s", self.idle_timeout_s)] {
            let bad = v.is_some_and(|s| !((0.01..=86_400.0).contains(&s)));
            if bad {
                return Err((field, "must be within 0.01 s and 86400 s".into()));
            }
        }
        Ok(())
    }

    /// The bounds of the listener's connections.
    pub fn peer_limits(&self) -> crate::daemon::bridges::peers::PeerLimits {
        let secs = |v: Option<f64>, default: f64| {
            std::time::Duration::try_from_secs_f64(v.unwrap_or(default))
                .unwrap_or(std::time::Duration::from_secs_f64(default))
        };
        crate::daemon::bridges::peers::PeerLimits {
            max_connections: self.max_connections.unwrap_or(DEFAULT_MAX_CONNECTIONS),
            handshake: secs(self.handshake_timeout_s, DEFAULT_HANDSHAKE_TIMEOUT_S),
            idle: secs(self.idle_timeout_s, DEFAULT_IDLE_TIMEOUT_S),
        }
    }

    /// The pairing window of measured launches with predictions.
    pub fn pair_window(&self) -> crate::pairing::PairWindow {
        match self.pair_window_s {
            Some([min_s, max_s]) => crate::pairing::PairWindow { min_s, max_s },
            None => crate::pairing::PairWindow::default(),
        }
    }
}
