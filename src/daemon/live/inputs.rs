//! `[rig.input]`: NatNet and QTM clients feeding the rigs' queues directly. Rigs reading the same server share
//! one client (one body each). Each sample is serialised as the `ClubheadSampleMsg` a bridge would publish and
//! queued exactly as a zenoh sample is, so the worker parses, records and runs the same bytes either way. A rig's
//! `ball_body` is read the same way and queued as the rig's tracked ball (`mocap/<rig>/ball`).

use std::collections::HashMap;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::SyncSender;
use std::sync::Arc;

use super::{Incoming, InputKind};
use crate::daemon::bridges::mocap::{InputHandle, Source, StatusSource};
use crate::daemon::{wall_ns, DaemonConfig, DaemonError};
use crate::wire::MessageType;

/// A rig's queue and its count of samples the full queue refused.
pub(super) type Route = (SyncSender<Incoming>, Arc<AtomicU64>);

/// A server, its routes `(body, rig)`, and what each route feeds (the club's samples or the rig's ball).
type Group = (Source, Vec<(String, String)>, Vec<InputKind>);

/// Starts one client per server named by the rigs' inputs; gives each such rig its status source.
pub(super) fn start(
    config: &DaemonConfig,
    routes: &HashMap<String, Route>,
) -> Result<(Vec<InputHandle>, HashMap<String, StatusSource>), DaemonError> {
    let mut groups: Vec<Group> = Vec::new();
    for rig in &config.rigs {
        let Some(input) = &rig.input else { continue };
        let source = input.source().map_err(|(field, reason)| DaemonError::Config {
            field: format!("rig {}: input.{field}", rig.name),
            reason,
        })?;
        let mut routes = vec![((input.body.clone(), rig.name.clone()), InputKind::Sample)];
        if let Some(ball) = &input.ball_body {
            routes.push(((ball.clone(), rig.name.clone()), InputKind::Ball));
        }
        let at = match groups.iter().position(|g| g.0 == source) {
            Some(at) => at,
            None => {
                groups.push((source, Vec::new(), Vec::new()));
                groups.len() - 1
            }
        };
        for (route, kind) in routes {
            groups[at].1.push(route);
            groups[at].2.push(kind);
        }
    }
    let mut handles = Vec::new();
    let mut sources = HashMap::new();
    for (source, group, kinds) in groups {
        let targets: Vec<(Arc<str>, Option<Route>, InputKind)> = group
            .iter()
            .zip(&kinds)
            .map(|((_, rig), kind)| (Arc::from(rig.as_str()), routes.get(rig).cloned(), *kind))
            .collect();
        let (sample_encoding, ball_encoding) =
            (MessageType::ClubheadSample.encoding(), MessageType::BallSample.encoding());
        let deliver = Box::new(move |i: usize, sample: &crate::mocap::track::BodySample, received| {
            let Some((rig, Some((tx, dropped)), kind)) = targets.get(i) else { return };
            let (payload, encoding) = match kind {
                InputKind::Ball => (serde_json::to_vec(&sample.to_ball_msg(rig)), ball_encoding.clone()),
                _ => (serde_json::to_vec(&sample.to_msg(rig)), sample_encoding.clone()),
            };
            let incoming = Incoming {
                kind: *kind,
                received,
                log_time_ns: wall_ns(),
                payload: payload.unwrap_or_default(),
                encoding,
            };
            if tx.try_send(incoming).is_err() {
                dropped.fetch_add(1, Ordering::Relaxed);
            }
        });
        tracing::info!("reading {} at {} for {:?}", source.protocol(), source.address(), group);
        let handle = InputHandle::start(source, group.clone(), deliver)?;
        for (i, ((_, rig), kind)) in group.iter().zip(&kinds).enumerate() {
            if *kind == InputKind::Sample {
                sources.insert(rig.clone(), handle.status_source(i));
            }
        }
        handles.push(handle);
    }
    Ok((handles, sources))
}
