//! The seam every motion-capture protocol implements: its name in `[rig.input] protocol` and `impactd bridge`,
//! its own `[rig.input]` keys and bridge flags, and how its client starts. `PROTOCOLS` (registry.rs) lists them; a new
//! protocol is its folder (codec in `crate::mocap`, client here) and one entry there.

use std::net::SocketAddr;
use std::sync::atomic::AtomicBool;
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;

use super::shared::Shared;
use crate::daemon::DaemonError;
use crate::kinematics::MarkerFitter;

/// The server a client reads: the protocol, the host and port, and the protocol's connection settings as
/// `(key, value)` pairs in a fixed order (rigs naming an equal source share one connection).
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct Source {
    pub protocol: &'static str,
    pub host: String,
    pub port: u16,
    pub options: Vec<(&'static str, String)>,
}

impl Source {
    pub fn new(protocol: &'static str, host: &str, port: u16) -> Self {
        Source { protocol, host: host.to_string(), port, options: Vec::new() }
    }

    pub fn with(mut self, key: &'static str, value: impl ToString) -> Self {
        self.options.push((key, value.to_string()));
        self
    }

    pub fn protocol(&self) -> &'static str {
        self.protocol
    }

    pub fn address(&self) -> String {
        format!("{}:{}", self.host, self.port)
    }

    /// A connection setting.
    pub fn option(&self, key: &str) -> Option<&str> {
        self.options.iter().find(|(k, _)| *k == key).map(|(_, v)| v.as_str())
    }
}

/// One tracked thing a client reads for a rig: the body's name in the capture software, an optional part of it
/// (a Vicon subject's segment), and a marker set to fit instead of the body's own pose.
#[derive(Debug, Clone, Default)]
pub struct Route {
    pub body: String,
    pub segment: Option<String>,
    pub fitter: Option<MarkerFitter>,
}

/// What a client starts with.
pub struct Start {
    pub source: Source,
    pub server: SocketAddr,
    pub routes: Vec<Route>,
    pub shared: Arc<Mutex<Shared>>,
    pub stop: Arc<AtomicBool>,
}

/// A field of `[rig.input]` (or a bridge flag) that is wrong, and why.
pub type FieldError = (String, String);

/// A motion-capture protocol.
pub trait Protocol: Sync {
    /// `[rig.input] protocol = "..."` and `impactd bridge NAME`.
    fn name(&self) -> &'static str;
    /// One line for `impactd bridge --help`.
    fn summary(&self) -> &'static str;
    fn default_port(&self) -> u16;
    /// What `[rig.input]` calls the tracked body (`body`; Vicon: `subject`), also the bridge's `--KEY NAME=RIG`.
    fn body_key(&self) -> &'static str {
        "body"
    }
    /// `--KEY NAME=RIG`'s help.
    fn body_help(&self) -> &'static str;
    /// Whether a route may name a part of its body (`segment`: a Vicon subject's segment).
    fn segments(&self) -> bool {
        false
    }
    /// The source from `[rig.input]`: the server's host and port (`None`: the address gave none) and the
    /// protocol's own keys (anything else in the table; an unknown key is an error naming it).
    fn source(&self, host: &str, port: Option<u16>, options: &toml::Table) -> Result<Source, FieldError>;
    /// `impactd bridge NAME`'s own flags.
    fn bridge_args(&self, cmd: clap::Command) -> clap::Command {
        cmd
    }
    /// The source from `impactd bridge NAME`'s flags.
    fn bridge_source(&self, host: &str, port: Option<u16>, m: &clap::ArgMatches) -> Result<Source, String>;
    /// Starts the client's threads (they stop within a poll of `start.stop`).
    fn start(&self, start: Start) -> Result<Vec<JoinHandle<()>>, DaemonError>;
}

/// The protocol named `name` in a list of entries like `PROTOCOLS` (registry.rs) (a test's own, with a toy protocol).
pub fn protocol_in(list: &[&'static dyn Protocol], name: &str) -> Option<&'static dyn Protocol> {
    list.iter().copied().find(|p| p.name() == name)
}

/// `HOST[:PORT]` split (a trailing `:digits` is the port).
pub fn host_port(server: &str) -> Result<(&str, Option<u16>), String> {
    let (host, port) = match server.rsplit_once(':') {
        Some((h, p)) if !p.is_empty() && p.bytes().all(|b| b.is_ascii_digit()) => {
            (h, Some(p.parse::<u16>().map_err(|_| format!("`{p}` is not a port"))?))
        }
        _ => (server, None),
    };
    if host.trim().is_empty() || host.contains(char::is_whitespace) || host.contains(':') {
        return Err(format!("`{server}` is not HOST or HOST:PORT"));
    }
    Ok((host, port))
}

/// A protocol's `[rig.input]` keys as its typed options (`deny_unknown_fields` names a stray key).
pub fn typed<T: serde::de::DeserializeOwned>(options: &toml::Table) -> Result<T, FieldError> {
    toml::Value::Table(options.clone()).try_into::<T>().map_err(|e| {
        let text = e.to_string();
        let field = text.split('`').nth(1).unwrap_or("input").to_string();
        (field, text.lines().last().unwrap_or(&text).trim().to_string())
    })
}
