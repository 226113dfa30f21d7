//! `impactd bridge PROTOCOL`: a motion-capture server's bodies (or marker sets fitted to their labelled markers)
//! as clubhead samples on zenoh. One subcommand per entry of `daemon::inputs::PROTOCOLS`, each with the same
//! flags (`--server`, the body flag, `--ball`, `--markers`, zenoh's) and the protocol's own.

use std::process::ExitCode;

use anyhow::{anyhow, bail, Context, Result};
use clap::{Arg, ArgAction, ArgMatches, Args, Command, FromArgMatches, Subcommand};
use impactd::daemon::inputs::config::marker_fitter;
use impactd::daemon::inputs::protocol::host_port;
use impactd::daemon::inputs::registry::protocol;
use impactd::daemon::inputs::{run_bridge_routes, Protocol, Route, PROTOCOLS};

use super::args::ZenohFlags;
use super::run::{runtime, shutdown_signal};

/// The protocol chosen and its flags.
#[derive(Debug, Clone)]
pub struct BridgeCommand {
    pub protocol: &'static str,
    pub matches: ArgMatches,
}

fn subcommand(p: &'static dyn Protocol) -> Command {
    let key = p.body_key();
    let mut cmd = Command::new(p.name())
        .about(p.summary())
        .arg(
            Arg::new("server")
                .long("server")
                .value_name("HOST[:PORT]")
                .required(true)
                .help(format!("The server's address (host name or IPv4; port {} when none).", p.default_port())),
        )
        .arg(
            Arg::new("body")
                .long(key)
                .value_name("NAME=RIG")
                .required(true)
                .action(ArgAction::Append)
                .help(p.body_help()),
        )
        .arg(Arg::new("ball").long("ball").value_name("NAME=RIG").action(ArgAction::Append).help(
            "A body whose origin is a ball's centre and the rig whose ball it is, NAME=RIG (repeatable): \
             published on mocap/<RIG>/ball, it sets each shot's ball position.",
        ))
        .arg(Arg::new("markers").long("markers").value_name("NAME=SET.toml").action(ArgAction::Append).help(format!(
            "A {key} tracked as a marker set, NAME=SET.toml (repeatable; NAME one of --{key}'s): the set \
                 fitted to the server's labelled markers each frame, so NAME needs no rigid body in the \
                 capture software."
        )));
    if p.segments() {
        cmd = cmd.arg(
            Arg::new("segment")
                .long("segment")
                .value_name("NAME")
                .help(format!("The segment of each --{key} to read (default: the subject's root segment).")),
        );
    }
    // Zenoh's flags last; their group's doc would otherwise be the subcommand's about.
    ZenohFlags::augment_args(p.bridge_args(cmd)).about(p.summary()).long_about(None)
}

impl FromArgMatches for BridgeCommand {
    fn from_arg_matches(m: &ArgMatches) -> Result<Self, clap::Error> {
        let (name, sub) = m
            .subcommand()
            .ok_or_else(|| clap::Error::raw(clap::error::ErrorKind::MissingSubcommand, "a protocol is needed"))?;
        let p = protocol(name).ok_or_else(|| {
            clap::Error::raw(clap::error::ErrorKind::InvalidSubcommand, format!("no protocol `{name}`"))
        })?;
        Ok(BridgeCommand { protocol: p.name(), matches: sub.clone() })
    }

    fn update_from_arg_matches(&mut self, m: &ArgMatches) -> Result<(), clap::Error> {
        *self = Self::from_arg_matches(m)?;
        Ok(())
    }
}

impl Subcommand for BridgeCommand {
    fn augment_subcommands(cmd: Command) -> Command {
        PROTOCOLS.iter().fold(cmd.subcommand_required(true), |cmd, p| cmd.subcommand(subcommand(*p)))
    }

    fn augment_subcommands_for_update(cmd: Command) -> Command {
        Self::augment_subcommands(cmd)
    }

    fn has_subcommand(name: &str) -> bool {
        protocol(name).is_some()
    }
}

fn values<'a>(m: &'a ArgMatches, id: &str) -> Vec<&'a String> {
    m.get_many::<String>(id).map(|v| v.collect()).unwrap_or_default()
}

fn pairs(flag: &str, what: &str, values: &[&String]) -> Result<Vec<(String, String)>> {
    values
        .iter()
        .map(|b| match b.split_once('=') {
            Some((name, rig)) if !name.is_empty() && !rig.is_empty() => Ok((name.to_string(), rig.to_string())),
            _ => bail!("{flag} {b}: expected {what}"),
        })
        .collect()
}

pub fn run(command: &BridgeCommand) -> Result<ExitCode> {
    let p = protocol(command.protocol).ok_or_else(|| anyhow!("no protocol {}", command.protocol))?;
    let m = &command.matches;
    let key = p.body_key();
    let flag = format!("--{key}");
    let server = m.get_one::<String>("server").map(String::as_str).unwrap_or_default();
    let (host, port) = host_port(server).map_err(|e| anyhow!("--server {e}"))?;
    let source = p.bridge_source(host, port, m).map_err(|e| anyhow!("{e}"))?;
    let segment = m.try_get_one::<String>("segment").ok().flatten().cloned();
    let mut routes: Vec<(Route, String)> =
        pairs(&flag, "NAME=RIG (the name in the capture software, then the rig)", &values(m, "body"))?
            .into_iter()
            .map(|(body, rig)| (Route { body, segment: segment.clone(), fitter: None }, rig))
            .collect();
    for (name, path) in
        pairs("--markers", "NAME=SET.toml (a body name, then its marker set file)", &values(m, "markers"))?
    {
        let Some(route) = routes.iter_mut().find(|r| r.0.body == name) else {
            bail!("--markers {name}={path}: `{name}` is not one of the {flag} names")
        };
        route.0.fitter = Some(marker_fitter(&path).map_err(|e| anyhow!("--markers {name}={path}: {e}"))?);
    }
    let balls = pairs("--ball", "NAME=RIG (the ball's body, then the rig)", &values(m, "ball"))?
        .into_iter()
        .map(|(body, rig)| (Route { body, ..Route::default() }, rig))
        .collect();
    let zenoh = ZenohFlags::from_arg_matches(m).context("zenoh's flags")?;
    let rt = runtime()?;
    rt.block_on(async {
        let session = zenoh.args()?.open_as(impactd::daemon::bus::Role::Join).await?;
        let statuses = run_bridge_routes(&session, source, routes, balls, shutdown_signal()).await.context("bridge")?;
        let _ = session.close().await;
        for s in statuses {
            eprintln!(
                "{} -> {}: {} frames, {} published, {} occluded, {} dropped, {} out of order, rejected {:?}",
                s.body, s.rig, s.frames, s.published, s.occluded, s.dropped, s.out_of_order, s.rejected
            );
        }
        Ok(ExitCode::SUCCESS)
    })
}
