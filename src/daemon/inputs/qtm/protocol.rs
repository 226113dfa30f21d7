//! QTM's entry in [`crate::daemon::inputs::PROTOCOLS`]: the server's port (`port`, or `server = "HOST:PORT"`),
//! its bridge flag, and its client.

use std::thread::JoinHandle;

use clap::{Arg, ArgMatches, Command};
use serde::Deserialize;

use super::super::protocol::{typed, FieldError, Protocol, Source, Start};
use crate::daemon::DaemonError;

/// QTM's little-endian real-time port.
pub const PORT: u16 = 22223;

pub struct Qtm;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Options {
    port: Option<u16>,
}

impl Protocol for Qtm {
    fn name(&self) -> &'static str {
        "qtm"
    }

    fn summary(&self) -> &'static str {
        "Qualisys QTM (real-time protocol 1.2x, 6D): each mapped body's frames on mocap/<RIG>/clubhead."
    }

    fn default_port(&self) -> u16 {
        PORT
    }

    fn body_help(&self) -> &'static str {
        "A 6DOF body and the rig it feeds, NAME=RIG (repeatable; several rigs share the connection)."
    }

    fn source(&self, host: &str, port: Option<u16>, options: &toml::Table) -> Result<Source, FieldError> {
        let o: Options = typed(options)?;
        if port.is_some() && o.port.is_some() {
            return Err(("port".into(), "and the server's :PORT both give the port".into()));
        }
        Ok(Source::new("qtm", host, port.or(o.port).unwrap_or(PORT)))
    }

    fn bridge_args(&self, cmd: Command) -> Command {
        cmd.arg(
            Arg::new("port")
                .long("port")
                .value_name("PORT")
                .value_parser(clap::value_parser!(u16))
                .help("QTM's little-endian real-time port (default 22223; or --server HOST:PORT)."),
        )
    }

    fn bridge_source(&self, host: &str, port: Option<u16>, m: &ArgMatches) -> Result<Source, String> {
        let flag = m.get_one::<u16>("port").copied();
        if port.is_some() && flag.is_some() {
            return Err("--port and --server HOST:PORT both give the port".into());
        }
        Ok(Source::new("qtm", host, port.or(flag).unwrap_or(PORT)))
    }

    fn start(&self, s: Start) -> Result<Vec<JoinHandle<()>>, DaemonError> {
        let (bodies, fitters) = s.routes.into_iter().map(|r| (r.body, r.fitter)).unzip();
        super::start(s.server, bodies, fitters, s.shared, s.stop)
    }
}
