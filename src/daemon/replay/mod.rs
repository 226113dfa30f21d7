//! `impactd replay`: the daemon's pipelines over a recording.
//!
//! Replay feeds the recorded clubhead samples, in file order (each rig's arrival order), through the same pure
//! pipeline as the daemon, so it reproduces the recorded predictions byte for byte. `latency_us` is a live
//! measurement: a replay carries the value recorded for the same rig and shot (0 for samples from JSONL).
//!
//! The input streams ([`ReplaySource`]: a recording or JSONL file, [`ReplayFile`]; a C3D capture,
//! [`ReplayCapture`]): it is indexed once, then read an item at a time as it replays, and a replay's recording
//! is written as it goes, so a replay's memory does not grow with its input. [`load`] reads a file whole instead,
//! for tools and tests that look at every sample ([`ReplayInput`], itself a source).

use std::collections::HashMap;

use crate::pipeline::{Event, Pipeline, RigSetup};

mod capture;
mod capture_layout;
mod file;
mod items;
mod load;
mod parse;
mod pause;
mod resolve;
mod session;
mod verdict;

pub use capture::{BallMarker, ReplayCapture};
pub use capture_layout::{face_from_markers_refusal, is_grip_label, CaptureLayout, MarkerLoss};
pub use file::ReplayFile;
pub use items::{Item, Items, ReplayIndex, ReplaySource, RigSpan, MAX_INDEXED_RIGS};
pub use load::{is_mcap, load, ReplayInput};
pub use pause::PauseControl;
pub use resolve::resolve_config;
pub use session::{run, Publish, ReplayOptions, ReplayReport, Selection};
pub use verdict::Verdict;

/// What a replay did.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ReplayStats {
    /// Samples replayed (unknown rigs' too).
    pub samples: u64,
    /// Samples left out by the selection (`--rig`, `--start-offset`, `--duration`).
    pub left_out: u64,
    pub unknown_rig: u64,
    pub predictions: u64,
    pub failed: u64,
    /// Swings that found no impact (`Event::Missed`).
    pub missed: u64,
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
        p.on_body_sample_with(msg.body.as_deref(), &msg.to_sample(), &mut |e| events.push(e));
        for e in events.iter_mut() {
            match e {
                Event::Launch(l) => {
                    l.latency_us = recorded_latency(input, l);
                    stats.predictions += 1;
                }
                Event::Failed { .. } => stats.failed += 1,
                Event::Missed(_) => stats.missed += 1,
                _ => {}
            }
            on_event(e);
        }
    }
    for p in pipelines.values_mut() {
        p.finish(&mut |e| {
            if let Event::Missed(_) = e {
                stats.missed += 1;
            }
            on_event(&e);
        });
    }
    stats
}

/// The latency recorded for the same rig, shot and model (a live measurement a replay cannot make), else 0.
fn recorded_latency(input: &ReplayInput, l: &crate::wire::LaunchPrediction) -> f64 {
    input.recorded_latency_us.get(&(l.rig.clone(), l.shot, l.model.clone())).copied().unwrap_or(0.0)
}
