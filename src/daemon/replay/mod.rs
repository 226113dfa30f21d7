//! `impactd replay`: the daemon's pipelines over a recording.
//!
//! Replay feeds the recorded clubhead samples, in file order (each rig's arrival order), through the same pure
//! pipeline as the daemon, so it reproduces the recorded predictions byte for byte. `latency_us` is a live
//! measurement: a replay carries the value recorded for the same rig and shot (0 for samples from JSONL).

use std::collections::HashMap;

use crate::pipeline::{Event, Pipeline, RigSetup};

mod capture;
mod load;
mod pause;
mod session;
mod verdict;

pub use capture::load_capture;
pub use load::{is_mcap, load, ReplayInput};
pub use pause::PauseControl;
pub use session::{resolve_config, run, Publish, ReplayOptions, ReplayReport};
pub use verdict::Verdict;

/// What a replay did.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ReplayStats {
    pub samples: u64,
    pub unknown_rig: u64,
    pub predictions: u64,
    pub failed: u64,
}

/// Runs the pipelines over the samples; `on_event` sees every event (launches with their latency filled in).
pub fn replay(
    input: &ReplayInput,
    setups: Vec<RigSetup>,
    mut pace: impl FnMut(u64),
    mut on_event: impl FnMut(&Event),
) -> ReplayStats {
    let mut pipelines: HashMap<String, Pipeline> =
        setups.into_iter().map(|s| (s.name.clone(), Pipeline::new(s))).collect();
    let mut stats = ReplayStats::default();
    let mut events = Vec::with_capacity(8);
    let mut labels = input.labels.iter().peekable();
    let mut balls = input.balls.iter().peekable();
    for (i, msg) in input.samples.iter().enumerate() {
        while let Some((_, rig, l)) = labels.next_if(|(at, ..)| *at <= i) {
            if let Some(p) = pipelines.get_mut(rig) {
                p.set_labels(l.clone());
            }
        }
        while let Some((_, ball, _)) = balls.next_if(|(at, ..)| *at <= i) {
            if let Some(p) = pipelines.get_mut(&ball.rig) {
                let _ = p.on_ball((!ball.occluded).then_some(ball.position_m));
            }
        }
        stats.samples += 1;
        let Some(p) = pipelines.get_mut(&msg.rig) else {
            stats.unknown_rig += 1;
            continue;
        };
        pace(msg.t_ns);
        events.clear();
        p.on_sample(&msg.to_sample(), &mut events);
        for e in events.iter_mut() {
            match e {
                Event::Launch(l) => {
                    l.latency_us = recorded_latency(input, l);
                    stats.predictions += 1;
                }
                Event::Failed { .. } => stats.failed += 1,
                _ => {}
            }
            on_event(e);
        }
    }
    stats
}

/// The latency recorded for the same rig, shot and model (a live measurement a replay cannot make), else 0.
fn recorded_latency(input: &ReplayInput, l: &crate::wire::LaunchPrediction) -> f64 {
    input.recorded_latency_us.get(&(l.rig.clone(), l.shot, l.model.clone())).copied().unwrap_or(0.0)
}
