//! The items a rigid subject and its markers need, with their byte layouts (`ViconCGStream/*.h`; every number
//! little-endian, containers as in [`super::framing`]):
//!
//! | item | layout |
//! |---|---|
//! | `StreamInfo` (1) | `i64` frame period, ticks of the 135 MHz clock |
//! | `SubjectInfo` (2) | `u32` subject id, string name, vector of segments (`u32` parent id, `u32` segment id, 6 `f32` bounds, string name; the root's parent is 0), vector of markers (`u32` marker id, string name), vector of attachments (`u32` marker id, `u32` segment id) |
//! | `FrameInfo` (5) | `u32` frame id |
//! | `LabeledRecons` (6) | vector of (`u32` subject id, `u32` marker id, `f64` radius mm, 3 `f64` position mm, 9 `f64` covariance, `u32` trajectory id) |
//! | `GlobalSegments` (9) | `u32` subject id, vector of (`u32` segment id, 3 `f64` translation mm, 9 `f64` rotation, row-major) |
//! | `Timecode` (23) | `u8` hours, minutes, seconds, frames; `u16` subframe, subframes per frame; `u32` standard, user bits; `u8` field flag |
//! | `LatencyInfo` (26) | vector of (string name, `f64` seconds) |
//! | `ApplicationInfo` (37) | `u8` axis orientation: 0 Z-up, 1 Y-up |
//! | `Contents` (100004) | map `u32` type -> `u32` object count; set of `u32` types unchanged since the last packet |
//! | `ObjectEnums` (100001) | set of `u32` types |
//! | `RequestFrame` (100002) | `u8` streaming (bool) |
//! | `RequestNextFrame` (100008) | `u32` frames (1) |
//! | `Ping` (42) | `u64` ping id |
//!
//! An item may be longer than the fields read here (a newer server's additions): the rest is skipped.

use super::framing::{count, string_into};
use super::ViconError;
use crate::mocap::bytes::Reader;

/// Bytes of one `GlobalSegments` segment.
pub const SEGMENT_POSE_BYTES: usize = 4 + 24 + 72;
/// Bytes of one labelled marker.
pub const LABELED_RECON_BYTES: usize = 4 + 4 + 8 + 24 + 72 + 4;
/// The fewest bytes of a `SubjectInfo` segment, marker and attachment, and of a latency sample.
const SEGMENT_DEF_MIN: usize = 4 + 4 + 24 + 4;
const MARKER_DEF_MIN: usize = 4 + 4;
const ATTACHMENT_BYTES: usize = 8;
const LATENCY_MIN: usize = 4 + 8;

/// The server's up axis (`ApplicationInfo`). Nexus and Tracker are Z-up; Shogun may stream Y-up.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UpAxis {
    Z,
    Y,
    /// A value this protocol version does not define.
    Unknown(u8),
}

impl UpAxis {
    pub fn from_byte(b: u8) -> Self {
        match b {
            0 => UpAxis::Z,
            1 => UpAxis::Y,
            other => UpAxis::Unknown(other),
        }
    }

    pub fn byte(self) -> u8 {
        match self {
            UpAxis::Z => 0,
            UpAxis::Y => 1,
            UpAxis::Unknown(b) => b,
        }
    }

    /// `z` or `y` (`unknown` for an undefined value).
    pub fn name(self) -> &'static str {
        match self {
            UpAxis::Z => "z",
            UpAxis::Y => "y",
            UpAxis::Unknown(_) => "unknown",
        }
    }
}

/// A segment of a subject (`SubjectInfo`).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SegmentDef {
    pub segment_id: u32,
    /// 0 for the root segment.
    pub parent_id: u32,
    pub bounds: [f32; 6],
    pub name: String,
}

/// A marker of a subject (`SubjectInfo`).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MarkerDef {
    pub marker_id: u32,
    pub name: String,
}

/// One subject (`SubjectInfo`): its segments, markers, and which segment each marker is attached to.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SubjectDef {
    pub subject_id: u32,
    pub name: String,
    pub segments: Vec<SegmentDef>,
    pub markers: Vec<MarkerDef>,
    /// `(marker id, segment id)`.
    pub attachments: Vec<(u32, u32)>,
}

impl SubjectDef {
    /// The root segment (the first whose parent is 0, as the SDK reads it).
    pub fn root(&self) -> Option<&SegmentDef> {
        self.segments.iter().find(|s| s.parent_id == 0)
    }

    pub fn segment(&self, name: &str) -> Option<&SegmentDef> {
        self.segments.iter().find(|s| s.name == name)
    }
}

/// A segment's global pose in one frame (`GlobalSegments`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SegmentPose {
    pub subject_id: u32,
    pub segment_id: u32,
    pub translation_mm: [f64; 3],
    /// Row-major: `rotation[3 * row + col]`, world from segment.
    pub rotation: [f64; 9],
}

/// A labelled marker in one frame (`LabeledRecons`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LabeledRecon {
    pub subject_id: u32,
    pub marker_id: u32,
    pub radius_mm: f64,
    pub position_mm: [f64; 3],
    pub covariance: [f64; 9],
    pub trajectory_id: u32,
}

/// A named latency (`LatencyInfo`): a stage of the server's pipeline, in seconds.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LatencySample {
    pub name: String,
    pub latency_s: f64,
}

/// `Timecode`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Timecode {
    pub hours: u8,
    pub minutes: u8,
    pub seconds: u8,
    pub frames: u8,
    pub subframe: u16,
    pub subframes_per_frame: u16,
    /// 0 PAL, 1 NTSC, 2 NTSC drop, 3 film, 4 NTSC film, 5 ATSC; anything else is none.
    pub standard: u32,
    pub user_bits: u32,
    pub field: u8,
}

/// `Contents`: the object count per requested type, and the types unchanged since the last packet.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Contents {
    pub counts: Vec<(u32, u32)>,
    pub unchanged: Vec<u32>,
}

pub fn stream_info(r: &mut Reader) -> Result<i64, ViconError> {
    Ok(r.i64("frame period")?)
}

pub fn frame_info(r: &mut Reader) -> Result<u32, ViconError> {
    Ok(r.u32("frame id")?)
}

pub fn application_info(r: &mut Reader) -> Result<UpAxis, ViconError> {
    Ok(UpAxis::from_byte(r.u8("axis orientation")?))
}

pub fn timecode(r: &mut Reader) -> Result<Timecode, ViconError> {
    Ok(Timecode {
        hours: r.u8("timecode")?,
        minutes: r.u8("timecode")?,
        seconds: r.u8("timecode")?,
        frames: r.u8("timecode")?,
        subframe: r.u16("timecode")?,
        subframes_per_frame: r.u16("timecode")?,
        standard: r.u32("timecode standard")?,
        user_bits: r.u32("timecode user bits")?,
        field: r.u8("timecode field")?,
    })
}

pub fn ping(r: &mut Reader) -> Result<u64, ViconError> {
    Ok(r.u64("ping id")?)
}

pub fn request_frame(r: &mut Reader) -> Result<bool, ViconError> {
    Ok(r.u8("streaming")? != 0)
}

/// A set of `u32` types (`ObjectEnums`) into `out`.
pub fn enum_set(r: &mut Reader, out: &mut Vec<u32>) -> Result<(), ViconError> {
    out.clear();
    let n = count(r, 4, "object types")?;
    for _ in 0..n {
        out.push(r.u32("object type")?);
    }
    Ok(())
}

pub fn contents(r: &mut Reader, out: &mut Contents) -> Result<(), ViconError> {
    out.counts.clear();
    let n = count(r, 8, "contents table")?;
    for _ in 0..n {
        out.counts.push((r.u32("contents type")?, r.u32("contents count")?));
    }
    enum_set(r, &mut out.unchanged)
}

/// `LatencyInfo`'s samples into `out`, reusing its names' allocations.
pub fn latency_info(r: &mut Reader, out: &mut Vec<LatencySample>) -> Result<(), ViconError> {
    let n = count(r, LATENCY_MIN, "latency samples")? as usize;
    for i in 0..n {
        let s = reuse(out, i);
        string_into(r, &mut s.name, "latency name")?;
        s.latency_s = r.f64("latency")?;
    }
    out.truncate(n);
    Ok(())
}

/// Little-endian numbers at fixed offsets of an element already taken whole (one bounds check per element).
fn u32_at(b: &[u8], at: usize) -> u32 {
    u32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]])
}

fn f64_at(b: &[u8], at: usize) -> f64 {
    let mut a = [0u8; 8];
    a.copy_from_slice(&b[at..at + 8]);
    f64::from_le_bytes(a)
}

fn f64s_at<const N: usize>(b: &[u8], at: usize) -> [f64; N] {
    std::array::from_fn(|k| f64_at(b, at + 8 * k))
}

/// One `GlobalSegments` item, appended to `out`.
pub fn global_segments(r: &mut Reader, out: &mut Vec<SegmentPose>) -> Result<(), ViconError> {
    let subject_id = r.u32("subject id")?;
    let n = count(r, SEGMENT_POSE_BYTES, "global segments")?;
    for _ in 0..n {
        let b = r.take(SEGMENT_POSE_BYTES, "global segment")?;
        out.push(SegmentPose {
            subject_id,
            segment_id: u32_at(b, 0),
            translation_mm: f64s_at(b, 4),
            rotation: f64s_at(b, 28),
        });
    }
    Ok(())
}

/// `LabeledRecons` into `out`.
pub fn labeled_recons(r: &mut Reader, out: &mut Vec<LabeledRecon>) -> Result<(), ViconError> {
    out.clear();
    let n = count(r, LABELED_RECON_BYTES, "labeled recons")?;
    for _ in 0..n {
        let b = r.take(LABELED_RECON_BYTES, "labeled recon")?;
        out.push(LabeledRecon {
            subject_id: u32_at(b, 0),
            marker_id: u32_at(b, 4),
            radius_mm: f64_at(b, 8),
            position_mm: f64s_at(b, 16),
            covariance: f64s_at(b, 40),
            trajectory_id: u32_at(b, 112),
        });
    }
    Ok(())
}

/// Element `i` of `v`, reusing what is there (its strings' and lists' allocations) or appending a default.
fn reuse<T: Default>(v: &mut Vec<T>, i: usize) -> &mut T {
    if i == v.len() {
        v.push(T::default());
    }
    &mut v[i]
}

/// One `SubjectInfo` item into `s`, reusing its allocations.
pub fn subject_info(r: &mut Reader, s: &mut SubjectDef) -> Result<(), ViconError> {
    s.subject_id = r.u32("subject id")?;
    string_into(r, &mut s.name, "subject name")?;
    let n = count(r, SEGMENT_DEF_MIN, "subject segments")? as usize;
    for i in 0..n {
        let g = reuse(&mut s.segments, i);
        g.parent_id = r.u32("segment parent id")?;
        g.segment_id = r.u32("segment id")?;
        for b in &mut g.bounds {
            *b = r.f32("segment bounds")?;
        }
        string_into(r, &mut g.name, "segment name")?;
    }
    s.segments.truncate(n);
    let n = count(r, MARKER_DEF_MIN, "subject markers")? as usize;
    for i in 0..n {
        let m = reuse(&mut s.markers, i);
        m.marker_id = r.u32("marker id")?;
        string_into(r, &mut m.name, "marker name")?;
    }
    s.markers.truncate(n);
    let n = count(r, ATTACHMENT_BYTES, "subject attachments")?;
    s.attachments.clear();
    for _ in 0..n {
        s.attachments.push((r.u32("attachment marker id")?, r.u32("attachment segment id")?));
    }
    Ok(())
}
