//! NatNet's entry in [`crate::daemon::inputs::PROTOCOLS`]: its `[rig.input]` keys (`unicast`, `data_port`,
//! `multicast_group`; `command_port` as the server's port), its bridge flags, and its client.

use std::net::Ipv4Addr;
use std::thread::JoinHandle;

use clap::{Arg, ArgAction, ArgMatches, Command};
use serde::Deserialize;

use super::super::protocol::{typed, FieldError, Protocol, Source, Start};
use crate::daemon::DaemonError;

pub const COMMAND_PORT: u16 = 1510;
pub const DATA_PORT: u16 = 1511;
/// Motive's default multicast group.
pub const MULTICAST_GROUP: Ipv4Addr = Ipv4Addr::new(239, 255, 42, 99);

pub struct NatNet;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Options {
    #[serde(default)]
    unicast: bool,
    data_port: Option<u16>,
    multicast_group: Option<String>,
    command_port: Option<u16>,
}

fn source(host: &str, port: u16, data_port: u16, unicast: bool, group: Option<&str>) -> Result<Source, FieldError> {
    let group = match (group, unicast) {
        (Some(_), true) => return Err(("multicast_group".into(), "and unicast = true exclude each other".into())),
        (Some(g), false) => Some(
            g.parse::<Ipv4Addr>()
                .ok()
                .filter(Ipv4Addr::is_multicast)
                .ok_or(("multicast_group".to_string(), format!("`{g}` is not an IPv4 multicast address")))?,
        ),
        (None, false) => Some(MULTICAST_GROUP),
        (None, true) => None,
    };
    if group.is_some() && data_port == 0 {
        return Err(("data_port".into(), "0 is for unicast: multicast frames arrive on Motive's data port".into()));
    }
    let s = Source::new("natnet", host, port).with("data_port", data_port);
    Ok(match group {
        Some(g) => s.with("multicast_group", g),
        None => s.with("unicast", true),
    })
}

impl Protocol for NatNet {
    fn name(&self) -> &'static str {
        "natnet"
    }

    fn summary(&self) -> &'static str {
        "OptiTrack Motive (NatNet 3.x/4.x): each mapped rigid body's frames on mocap/<RIG>/clubhead."
    }

    fn default_port(&self) -> u16 {
        COMMAND_PORT
    }

    fn body_help(&self) -> &'static str {
        "A rigid body and the rig it feeds, NAME=RIG (repeatable; several rigs share the connection)."
    }

    fn source(&self, host: &str, port: Option<u16>, options: &toml::Table) -> Result<Source, FieldError> {
        let o: Options = typed(options)?;
        if port.is_some() && o.command_port.is_some() {
            return Err(("command_port".into(), "and the server's :PORT both give the port".into()));
        }
        let port = port.or(o.command_port).unwrap_or(COMMAND_PORT);
        source(host, port, o.data_port.unwrap_or(DATA_PORT), o.unicast, o.multicast_group.as_deref())
    }

    fn bridge_args(&self, cmd: Command) -> Command {
        cmd.arg(
            Arg::new("command_port")
                .long("command-port")
                .value_name("PORT")
                .value_parser(clap::value_parser!(u16))
                .help("Motive's command port (default 1510; or --server HOST:PORT)."),
        )
        .arg(
            Arg::new("data_port")
                .long("data-port")
                .value_name("PORT")
                .value_parser(clap::value_parser!(u16))
                .default_value("1511")
                .help("The data port the bridge binds (frames; 0: any free port, unicast only)."),
        )
        .arg(
            Arg::new("unicast")
                .long("unicast")
                .action(ArgAction::SetTrue)
                .conflicts_with("multicast_group")
                .help("Unicast: Motive sends frames to this bridge's address (default: multicast, Motive's default)."),
        )
        .arg(
            Arg::new("multicast_group")
                .long("multicast-group")
                .value_name("ADDR")
                .default_value("239.255.42.99")
                .help("The multicast group Motive streams to."),
        )
    }

    fn bridge_source(&self, host: &str, port: Option<u16>, m: &ArgMatches) -> Result<Source, String> {
        let command_port = m.get_one::<u16>("command_port").copied();
        if port.is_some() && command_port.is_some() {
            return Err("--command-port and --server HOST:PORT both give the port".into());
        }
        let unicast = m.get_flag("unicast");
        let group = m.get_one::<String>("multicast_group").filter(|_| !unicast);
        let data_port = m.get_one::<u16>("data_port").copied().unwrap_or(DATA_PORT);
        let port = port.or(command_port).unwrap_or(COMMAND_PORT);
        source(host, port, data_port, unicast, group.map(String::as_str))
            .map_err(|(field, why)| format!("--{} {why}", field.replace('_', "-")))
    }

    fn start(&self, s: Start) -> Result<Vec<JoinHandle<()>>, DaemonError> {
        let data_port = s.source.option("data_port").and_then(|p| p.parse().ok()).unwrap_or(DATA_PORT);
        let multicast_group = s.source.option("multicast_group").and_then(|g| g.parse().ok());
        let (bodies, fitters) = s.routes.into_iter().map(|r| (r.body, r.fitter)).unzip();
        super::start(super::Options { server: s.server, data_port, multicast_group }, bodies, fitters, s.shared, s.stop)
    }
}
