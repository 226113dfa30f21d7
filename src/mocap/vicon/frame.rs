//! The client's view of the stream: the last static objects (stream period, up axis, subjects) and the last
//! frame's dynamic ones, updated packet by packet with `Contents`' carry-over, as the SDK's
//! `ViconCGStreamClient::ReadObjects` does: a packet holding any object of a group (static or dynamic) replaces
//! that group; within it, a type the packet holds takes the new value, a type `Contents` lists unchanged keeps
//! the last one (even when also resent, as the SDK does), and any other type is emptied: a subject's
//! `GlobalSegments` not sent means its segments are occluded in this frame. A packet with no object of a group
//! leaves it as it was. A packet that fails to decode changes nothing.

use super::enums::*;
use super::framing;
use super::items::{self, Contents, LabeledRecon, LatencySample, SegmentPose, SubjectDef, Timecode, UpAxis};
use super::{ViconError, CLOCK_HZ};
use crate::mocap::bytes::Reader;

/// The static objects.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct StaticObjects {
    /// `StreamInfo`: ticks of the 135 MHz clock per frame.
    pub frame_period_ticks: Option<i64>,
    pub up_axis: Option<UpAxis>,
    pub subjects: Vec<SubjectDef>,
}

/// One frame's dynamic objects.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct DynamicObjects {
    /// `FrameInfo`'s id (the SDK's `GetFrameNumber` is this plus one).
    pub frame_id: Option<u32>,
    pub timecode: Option<Timecode>,
    pub latency: Vec<LatencySample>,
    /// Every subject's segments in this frame (`GlobalSegments`).
    pub segments: Vec<SegmentPose>,
    pub markers: Vec<LabeledRecon>,
}

/// What the client knows after the last packet.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Frame {
    pub statics: StaticObjects,
    pub dynamics: DynamicObjects,
}

impl Frame {
    /// Frames per second (`StreamInfo`).
    pub fn rate_hz(&self) -> Option<f64> {
        let p = self.statics.frame_period_ticks.filter(|&p| p > 0)?;
        Some(CLOCK_HZ as f64 / p as f64)
    }

    /// The frame number as Vicon's SDK reports it: `FrameInfo`'s id plus one.
    pub fn sdk_frame_number(&self) -> Option<u64> {
        self.dynamics.frame_id.map(|id| u64::from(id) + 1)
    }

    /// The frame's start on Vicon's clock (ns since its frame 0): id x period ticks at 135 MHz. `None` without
    /// a frame id or a positive period.
    pub fn t_ns(&self) -> Option<u64> {
        let id = u128::from(self.dynamics.frame_id?);
        let period = u128::try_from(self.statics.frame_period_ticks.filter(|&p| p > 0)?).ok()?;
        let ns = id * period * 1_000_000_000 / u128::from(CLOCK_HZ);
        u64::try_from(ns).ok()
    }

    /// The sum of `LatencyInfo`'s samples (s), as the SDK's `GetLatencyTotal` (without its network estimate).
    pub fn latency_total_s(&self) -> Option<f64> {
        (!self.dynamics.latency.is_empty()).then(|| self.dynamics.latency.iter().map(|s| s.latency_s).sum())
    }

    pub fn subject(&self, name: &str) -> Option<&SubjectDef> {
        self.statics.subjects.iter().find(|s| s.name == name)
    }

    /// A segment's pose in this frame (`None`: occluded).
    pub fn segment_pose(&self, subject_id: u32, segment_id: u32) -> Option<&SegmentPose> {
        self.dynamics.segments.iter().find(|p| p.subject_id == subject_id && p.segment_id == segment_id)
    }

    /// A labelled marker's position in this frame (mm; `None`: occluded).
    pub fn marker_mm(&self, subject_id: u32, marker_id: u32) -> Option<[f64; 3]> {
        let m = self.dynamics.markers.iter().find(|m| m.subject_id == subject_id && m.marker_id == marker_id)?;
        Some(m.position_mm)
    }
}

/// What one packet held besides the frame state.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct PacketSummary {
    /// An `ObjectEnums` set (in [`Decoder::object_enums`]).
    pub object_enums: bool,
    /// The static objects were replaced.
    pub statics: bool,
    /// The dynamic objects were replaced: a new frame.
    pub frame: bool,
    /// `Ping`s (their ids in [`Decoder::pings`]).
    pub pings: usize,
    /// A `RequestFrame` (a client's packet): streaming or not.
    pub request_frame: Option<bool>,
    /// A `RequestNextFrame` (a client's packet).
    pub request_next_frame: bool,
    /// Items of types not read here (skipped by size).
    pub other_items: u32,
}

/// Packets in, the stream's state out; every list reused from packet to packet.
#[derive(Debug, Default)]
pub struct Decoder {
    pub frame: Frame,
    next: Frame,
    contents: Contents,
    /// The last `ObjectEnums` set.
    pub object_enums: Vec<u32>,
    /// The last packet's pings.
    pub pings: Vec<u64>,
}

const B_STREAM: u32 = 1;
const B_APP: u32 = 2;
const B_SUBJECTS: u32 = 4;
const STATIC_BITS: u32 = B_STREAM | B_APP | B_SUBJECTS;
const B_FRAME: u32 = 8;
const B_TIMECODE: u32 = 16;
const B_LATENCY: u32 = 32;
const B_SEGMENTS: u32 = 64;
const B_MARKERS: u32 = 128;
const DYNAMIC_BITS: u32 = B_FRAME | B_TIMECODE | B_LATENCY | B_SEGMENTS | B_MARKERS;

fn bit(kind: u32) -> u32 {
    match kind {
        STREAM_INFO => B_STREAM,
        APPLICATION_INFO => B_APP,
        SUBJECT_INFO => B_SUBJECTS,
        FRAME_INFO => B_FRAME,
        TIMECODE => B_TIMECODE,
        LATENCY_INFO => B_LATENCY,
        GLOBAL_SEGMENTS => B_SEGMENTS,
        LABELED_RECONS => B_MARKERS,
        _ => 0,
    }
}

/// The new group's field: kept from the last group when unchanged, else as decoded (or emptied when absent).
fn carry<T: Default>(present: bool, unchanged: bool, last: &mut T, new: &mut T) {
    if unchanged {
        std::mem::swap(last, new);
    } else if !present {
        *new = T::default();
    }
}

/// Like [`carry`], for a list whose allocation is worth keeping.
fn carry_vec<T>(present: bool, unchanged: bool, last: &mut Vec<T>, new: &mut Vec<T>) {
    if unchanged {
        std::mem::swap(last, new);
    } else if !present {
        new.clear();
    }
}

impl Decoder {
    pub fn new() -> Self {
        Self::default()
    }

    /// Decodes one whole packet (header included) into the state.
    pub fn decode(&mut self, packet: &[u8]) -> Result<PacketSummary, ViconError> {
        let mut sum = PacketSummary::default();
        self.pings.clear();
        self.contents.unchanged.clear();
        let mut present = 0u32;
        let mut subjects = 0usize;
        let next = &mut self.next;
        for item in framing::items(packet)? {
            let (kind, payload) = item?;
            let mut r = Reader::new(payload);
            let first = present & bit(kind) == 0;
            present |= bit(kind);
            match kind {
                CONTENTS => items::contents(&mut r, &mut self.contents)?,
                STREAM_INFO => next.statics.frame_period_ticks = Some(items::stream_info(&mut r)?),
                APPLICATION_INFO => next.statics.up_axis = Some(items::application_info(&mut r)?),
                SUBJECT_INFO => {
                    let list = &mut next.statics.subjects;
                    if subjects == list.len() {
                        list.push(SubjectDef::default());
                    }
                    items::subject_info(&mut r, &mut list[subjects])?;
                    subjects += 1;
                }
                FRAME_INFO => next.dynamics.frame_id = Some(items::frame_info(&mut r)?),
                TIMECODE => next.dynamics.timecode = Some(items::timecode(&mut r)?),
                LATENCY_INFO => items::latency_info(&mut r, &mut next.dynamics.latency)?,
                GLOBAL_SEGMENTS => {
                    if first {
                        next.dynamics.segments.clear();
                    }
                    items::global_segments(&mut r, &mut next.dynamics.segments)?;
                }
                LABELED_RECONS => items::labeled_recons(&mut r, &mut next.dynamics.markers)?,
                OBJECT_ENUMS => {
                    items::enum_set(&mut r, &mut self.object_enums)?;
                    sum.object_enums = true;
                }
                PING => {
                    self.pings.push(items::ping(&mut r)?);
                    sum.pings += 1;
                }
                REQUEST_FRAME => sum.request_frame = Some(items::request_frame(&mut r)?),
                REQUEST_NEXT_FRAME => sum.request_next_frame = true,
                _ => sum.other_items += 1,
            }
        }
        if present & B_SUBJECTS != 0 {
            self.next.statics.subjects.truncate(subjects);
        }
        let unchanged = |kind: u32| self.contents.unchanged.contains(&kind);
        let has = |b: u32| present & b != 0;
        if has(STATIC_BITS) {
            let (last, new) = (&mut self.frame.statics, &mut self.next.statics);
            carry(has(B_STREAM), unchanged(STREAM_INFO), &mut last.frame_period_ticks, &mut new.frame_period_ticks);
            carry(has(B_APP), unchanged(APPLICATION_INFO), &mut last.up_axis, &mut new.up_axis);
            carry_vec(has(B_SUBJECTS), unchanged(SUBJECT_INFO), &mut last.subjects, &mut new.subjects);
            std::mem::swap(last, new);
            sum.statics = true;
        }
        if has(DYNAMIC_BITS) {
            let (last, new) = (&mut self.frame.dynamics, &mut self.next.dynamics);
            carry(has(B_FRAME), unchanged(FRAME_INFO), &mut last.frame_id, &mut new.frame_id);
            carry(has(B_TIMECODE), unchanged(TIMECODE), &mut last.timecode, &mut new.timecode);
            carry_vec(has(B_LATENCY), unchanged(LATENCY_INFO), &mut last.latency, &mut new.latency);
            carry_vec(has(B_SEGMENTS), unchanged(GLOBAL_SEGMENTS), &mut last.segments, &mut new.segments);
            carry_vec(has(B_MARKERS), unchanged(LABELED_RECONS), &mut last.markers, &mut new.markers);
            std::mem::swap(last, new);
            sum.frame = true;
        }
        Ok(sum)
    }
}
