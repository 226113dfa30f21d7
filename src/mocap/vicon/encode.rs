//! DataStream packets as a server or a client writes them: the client's requests impactd sends, and the server
//! side the test server and the benchmarks use. The layouts are those [`super::items`] reads; Vicon's own C++
//! client (the SDK) checks them in the tests.

use super::enums::*;
use super::frame::{DynamicObjects, StaticObjects};
use super::framing::{put_string, put_u32s, PacketWriter};
use super::items::{LabeledRecon, LatencySample, SegmentPose, SubjectDef, Timecode};
use crate::mocap::bytes::Writer;

/// A packet holding one `ObjectEnums` set: the server's greeting (the types it can send), or the client's
/// request (the types it wants).
pub fn object_enums(types: &[u32]) -> Vec<u8> {
    let mut sorted = types.to_vec();
    sorted.sort_unstable();
    sorted.dedup();
    let mut p = PacketWriter::new();
    p.item(OBJECT_ENUMS, |b| put_u32s(b, &sorted));
    p.finish()
}

/// `RequestFrame`: streaming (ServerPush) or one frame (ClientPull).
pub fn request_frame(streaming: bool) -> Vec<u8> {
    let mut p = PacketWriter::new();
    p.item(REQUEST_FRAME, |b| b.push(u8::from(streaming)));
    p.finish()
}

/// `RequestNextFrame` (the SDK's ClientPullPreFetch).
pub fn request_next_frame() -> Vec<u8> {
    let mut p = PacketWriter::new();
    p.item(REQUEST_NEXT_FRAME, |b| b.put_u32(1));
    p.finish()
}

/// A packet of `Ping`s: a client's, or the server's answer with the same ids.
pub fn pings(ids: &[u64]) -> Vec<u8> {
    let mut p = PacketWriter::new();
    for &id in ids {
        p.item(PING, |b| b.put_u64(id));
    }
    p.finish()
}

pub fn put_subject_info(b: &mut Vec<u8>, s: &SubjectDef) {
    b.put_u32(s.subject_id);
    put_string(b, &s.name);
    b.put_u32(s.segments.len() as u32);
    for g in &s.segments {
        b.put_u32(g.parent_id);
        b.put_u32(g.segment_id);
        for &v in &g.bounds {
            b.put_f32(v);
        }
        put_string(b, &g.name);
    }
    b.put_u32(s.markers.len() as u32);
    for m in &s.markers {
        b.put_u32(m.marker_id);
        put_string(b, &m.name);
    }
    b.put_u32(s.attachments.len() as u32);
    for &(marker, segment) in &s.attachments {
        b.put_u32(marker);
        b.put_u32(segment);
    }
}

/// One subject's `GlobalSegments`.
pub fn put_global_segments(b: &mut Vec<u8>, subject_id: u32, poses: &[&SegmentPose]) {
    b.put_u32(subject_id);
    b.put_u32(poses.len() as u32);
    for p in poses {
        b.put_u32(p.segment_id);
        for &v in p.translation_mm.iter().chain(&p.rotation) {
            b.put_f64(v);
        }
    }
}

pub fn put_labeled_recons(b: &mut Vec<u8>, recons: &[LabeledRecon]) {
    b.put_u32(recons.len() as u32);
    for r in recons {
        b.put_u32(r.subject_id);
        b.put_u32(r.marker_id);
        b.put_f64(r.radius_mm);
        for &v in r.position_mm.iter().chain(&r.covariance) {
            b.put_f64(v);
        }
        b.put_u32(r.trajectory_id);
    }
}

pub fn put_latency(b: &mut Vec<u8>, samples: &[LatencySample]) {
    b.put_u32(samples.len() as u32);
    for s in samples {
        put_string(b, &s.name);
        b.put_f64(s.latency_s);
    }
}

pub fn put_timecode(b: &mut Vec<u8>, t: &Timecode) {
    b.extend_from_slice(&[t.hours, t.minutes, t.seconds, t.frames]);
    b.put_u16(t.subframe);
    b.put_u16(t.subframes_per_frame);
    b.put_u32(t.standard);
    b.put_u32(t.user_bits);
    b.push(t.field);
}

/// What a server writes for one frame.
#[derive(Debug, Clone, Copy)]
pub struct FrameOut<'a> {
    pub statics: &'a StaticObjects,
    /// Resend the static objects; otherwise `Contents` lists them unchanged.
    pub resend_statics: bool,
    pub dynamics: &'a DynamicObjects,
    /// Dynamic types listed unchanged instead of sent (a server that did not resend its labelled markers).
    pub unchanged_dynamics: &'a [u32],
    /// The client's `ObjectEnums`: only these types are written (with `Contents` always first).
    pub wanted: &'a [u32],
}

/// A frame packet: `Contents`, then the static objects (when resent), then the dynamic ones.
pub fn frame(out: &FrameOut) -> Vec<u8> {
    let wants = |k: u32| out.wanted.contains(&k);
    let s = out.statics;
    let d = out.dynamics;
    // Subjects with segments in this frame, in order of first appearance.
    let mut posed: Vec<u32> = Vec::new();
    for p in &d.segments {
        if !posed.contains(&p.subject_id) {
            posed.push(p.subject_id);
        }
    }
    let statics = [STREAM_INFO, APPLICATION_INFO, SUBJECT_INFO];
    let mut unchanged: Vec<u32> = Vec::new();
    if !out.resend_statics {
        unchanged.extend(statics.iter().copied().filter(|&k| wants(k)));
    }
    unchanged.extend(out.unchanged_dynamics.iter().copied().filter(|&k| wants(k)));
    unchanged.sort_unstable();
    let sent = |k: u32| wants(k) && !unchanged.contains(&k);
    let mut counts: Vec<(u32, u32)> = vec![
        (STREAM_INFO, u32::from(s.frame_period_ticks.is_some())),
        (APPLICATION_INFO, u32::from(s.up_axis.is_some())),
        (SUBJECT_INFO, s.subjects.len() as u32),
        (FRAME_INFO, u32::from(d.frame_id.is_some())),
        (TIMECODE, u32::from(d.timecode.is_some())),
        (LATENCY_INFO, 1),
        (GLOBAL_SEGMENTS, posed.len() as u32),
        (LABELED_RECONS, 1),
    ];
    counts.retain(|&(k, _)| wants(k));
    counts.sort_unstable();

    let mut p = PacketWriter::new();
    p.item(CONTENTS, |b| {
        b.put_u32(counts.len() as u32);
        for &(k, n) in &counts {
            b.put_u32(k);
            b.put_u32(n);
        }
        put_u32s(b, &unchanged);
    });
    if sent(STREAM_INFO) {
        if let Some(period) = s.frame_period_ticks {
            p.item(STREAM_INFO, |b| b.put_i64(period));
        }
    }
    if sent(APPLICATION_INFO) {
        if let Some(up) = s.up_axis {
            p.item(APPLICATION_INFO, |b| b.push(up.byte()));
        }
    }
    if sent(SUBJECT_INFO) {
        for subject in &s.subjects {
            p.item(SUBJECT_INFO, |b| put_subject_info(b, subject));
        }
    }
    if sent(FRAME_INFO) {
        if let Some(id) = d.frame_id {
            p.item(FRAME_INFO, |b| b.put_u32(id));
        }
    }
    if sent(TIMECODE) {
        if let Some(t) = &d.timecode {
            p.item(TIMECODE, |b| put_timecode(b, t));
        }
    }
    if sent(LATENCY_INFO) {
        p.item(LATENCY_INFO, |b| put_latency(b, &d.latency));
    }
    if sent(GLOBAL_SEGMENTS) {
        for &subject_id in &posed {
            let poses: Vec<&SegmentPose> = d.segments.iter().filter(|p| p.subject_id == subject_id).collect();
            p.item(GLOBAL_SEGMENTS, |b| put_global_segments(b, subject_id, &poses));
        }
    }
    if sent(LABELED_RECONS) {
        p.item(LABELED_RECONS, |b| put_labeled_recons(b, &d.markers));
    }
    p.finish()
}
