//! `[rig.input]`: NatNet and QTM clients feeding the rigs' queues directly. Rigs reading the same server share
//! one client (one body each). Each sample is serialised as the `ClubheadSampleMsg` a bridge would publish and
//! queued exactly as a zenoh sample is, so the worker parses, records and runs the same bytes either way.

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

/// Starts one client per server named by the rigs' inputs; gives each such rig its status source.
pub(super) fn start(
    config: &DaemonConfig,
    routes: &HashMap<String, Route>,
) -> Result<(Vec<InputHandle>, HashMap<String, StatusSource>), DaemonError> {
    let mut groups: Vec<(Source, Vec<(String, String)>)> = Vec::new();
    for rig in &config.rigs {
        let Some(input) = &rig.input else { continue };
        let source = input.source().map_err(|(field, reason)| DaemonError::Config {
            field: format!("rig {}: input.{field}", rig.name),
            reason,
        })?;
        // The rig's body, and with `[rig.clubs]` every club's body: each sample then names its body.
        let mut bodies = vec![input.body.clone()];
        bodies.extend(rig.clubs.keys().filter(|b| **b != input.body).cloned());
        let group = match groups.iter().position(|g| g.0 == source) {
            Some(i) => i,
            None => {
                groups.push((source, Vec::new()));
                groups.len() - 1
            }
        };
        groups[group].1.extend(bodies.into_iter().map(|b| (b, rig.name.clone())));
    }
    let mut handles = Vec::new();
    let mut sources = HashMap::new();
    for (source, group) in groups {
        let named = |rig: &str| config.rigs.iter().any(|r| r.name == rig && !r.clubs.is_empty());
        let targets: Vec<(Arc<str>, Option<Route>, Option<String>)> = group
            .iter()
            .map(|(body, rig)| (Arc::from(rig.as_str()), routes.get(rig).cloned(), named(rig).then(|| body.clone())))
            .collect();
        let encoding = MessageType::ClubheadSample.encoding();
        let deliver = Box::new(move |i: usize, sample: &crate::mocap::track::BodySample, received| {
            let Some((rig, Some((tx, dropped)), body)) = targets.get(i) else { return };
            let mut msg = sample.to_msg(rig);
            msg.body = body.clone();
            let incoming = Incoming {
                kind: InputKind::Sample,
                received,
                log_time_ns: wall_ns(),
                payload: serde_json::to_vec(&msg).unwrap_or_default(),
                encoding: encoding.clone(),
                club: None,
            };
            if tx.try_send(incoming).is_err() {
                dropped.fetch_add(1, Ordering::Relaxed);
            }
        });
        tracing::info!("reading {} at {} for {:?}", source.protocol(), source.address(), group);
        let handle = InputHandle::start(source, group.clone(), deliver)?;
        // A rig's status shows its first body's input (`[rig.input] body`).
        for (i, (_, rig)) in group.iter().enumerate() {
            sources.entry(rig.clone()).or_insert_with(|| handle.status_source(i));
        }
        handles.push(handle);
    }
    Ok((handles, sources))
}
