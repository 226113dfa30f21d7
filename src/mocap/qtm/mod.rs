//! Qualisys QTM's real-time protocol 1.2x over TCP, little-endian port (22223): pure decoding (the socket
//! client is `daemon::bridges::qtm`).
//!
//! Every packet is an 8-byte header (total size `u32` including the header, type `u32`) and its body. Strings
//! (commands, their replies, errors and XML) end with a NUL. The server greets with the command string
//! `QTM RT Interface connected`; the client asks `Version 1.25` (answered `Version set to 1.25`), then
//! `GetParameters 6D` (answered with XML whose `<The_6D>` lists each `<Body>` with its `<Name>`, in index
//! order) and `StreamFrames AllFrames 6D` (or `6DRes`). A data packet is the capture timestamp (`i64`
//! microseconds), the frame number (`u32`), a component count (`u32`) and the components, each with its own
//! size and type; a 6D component is the body count (`u32`), the 2D drop rate and out-of-sync rate (`u16`
//! each, per mille), then per body the position (3 `f32`, mm), the rotation matrix (9 `f32`, column-major)
//! and, for 6DRes, the residual (`f32`, mm). An untracked body's numbers are NaN. Events are one byte;
//! `NoMoreData` marks the end of a measurement.
//!
//! The layouts follow Qualisys' Python SDK (`qtm-rt`, `qtm_rt/packet.py`), which the tests run against the
//! test server built on `qtm_encode`. Bounded allocation: bodies are pushed only after their bytes
//! were read, and a packet's size is checked against [`MAX_PACKET_BYTES`] before anything is buffered.

pub mod encode;

use super::bytes::{Reader, Truncated};

pub const HEADER_BYTES: usize = 8;
/// The largest packet the client buffers: 6D of 10 000 bodies is under 500 KiB.
pub const MAX_PACKET_BYTES: usize = 1 << 20;

/// Packet types.
pub const PACKET_ERROR: u32 = 0;
pub const PACKET_COMMAND: u32 = 1;
pub const PACKET_XML: u32 = 2;
pub const PACKET_DATA: u32 = 3;
pub const PACKET_NO_MORE_DATA: u32 = 4;
pub const PACKET_EVENT: u32 = 6;

/// Component types read here.
pub const COMPONENT_3D: u32 = 1;
pub const COMPONENT_3D_RES: u32 = 2;
pub const COMPONENT_6D: u32 = 5;
pub const COMPONENT_6D_RES: u32 = 11;

/// Events that end a measurement or the server (the client reconnects after them).
pub const EVENT_CONNECTION_CLOSED: u8 = 2;
pub const EVENT_CAPTURE_STOPPED: u8 = 4;
pub const EVENT_RT_FROM_FILE_STOPPED: u8 = 9;
pub const EVENT_QTM_SHUTTING_DOWN: u8 = 12;

/// The protocol version the client asks for.
pub const PROTOCOL_VERSION: &str = "1.25";

/// Why a packet was not decoded; [`QtmError::reason`] is the key it is counted under.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum QtmError {
    #[error(transparent)]
    Truncated(#[from] Truncated),
    #[error("packet size {0} is smaller than its 8-byte header")]
    Undersized(u32),
    #[error("packet of {0} bytes is over the {MAX_PACKET_BYTES}-byte limit")]
    Oversized(u32),
    #[error("packet type {0} is not one this client reads")]
    UnknownPacket(u32),
    #[error("component of {size} bytes does not fit the {left} bytes left in the packet")]
    BadComponent { size: u32, left: usize },
    #[error("the data packet has neither a 6D nor a 3D component")]
    No6d,
}

impl QtmError {
    pub fn reason(&self) -> &'static str {
        match self {
            QtmError::Truncated(_) => "truncated",
            QtmError::Undersized(_) | QtmError::BadComponent { .. } => "malformed",
            QtmError::Oversized(_) => "oversized",
            QtmError::UnknownPacket(_) => "unknown_message",
            QtmError::No6d => "no_6d",
        }
    }
}

/// A packet's header: its total size (checked) and type.
pub fn header(bytes: &[u8; HEADER_BYTES]) -> Result<(usize, u32), QtmError> {
    let size = u32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]);
    let kind = u32::from_le_bytes([bytes[4], bytes[5], bytes[6], bytes[7]]);
    if (size as usize) < HEADER_BYTES {
        return Err(QtmError::Undersized(size));
    }
    if size as usize > MAX_PACKET_BYTES {
        return Err(QtmError::Oversized(size));
    }
    Ok((size as usize, kind))
}

/// The text of a command, error or XML packet body (without its NUL).
pub fn text(body: &[u8]) -> String {
    let end = body.iter().position(|&b| b == 0).unwrap_or(body.len());
    String::from_utf8_lossy(&body[..end]).into_owned()
}

/// One body of a 6D component, as sent.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Body6d {
    pub position_mm: [f32; 3],
    /// The rotation matrix, column-major as QTM sends it.
    pub rotation: [f32; 9],
    pub residual_mm: Option<f32>,
}

/// A data packet: what the bridge reads of it.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Frame6d {
    pub timestamp_us: i64,
    pub frame_number: u32,
    pub bodies: Vec<Body6d>,
    /// Per mille.
    pub drop_rate_2d: u16,
    pub out_of_sync_rate_2d: u16,
    /// The labelled markers of a 3D (or 3DRes) component, in the order of `GetParameters 3D`'s labels (mm;
    /// NaN when the marker is not seen in this frame).
    pub markers_mm: Vec<[f32; 3]>,
}

/// The components a data packet held.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Components {
    pub six_d: bool,
    pub three_d: bool,
}

/// Decodes the body of a data packet (after the 8-byte header) into `frame`, reusing its lists; says which of
/// 6D and 3D it held (at least one, else [`QtmError::No6d`]).
pub fn decode_data(body: &[u8], frame: &mut Frame6d) -> Result<Components, QtmError> {
    frame.bodies.clear();
    frame.markers_mm.clear();
    let mut r = Reader::new(body);
    frame.timestamp_us = r.i64("timestamp")?;
    frame.frame_number = r.u32("frame number")?;
    let components = r.u32("component count")?;
    let (mut found_6d, mut found_3d) = (false, false);
    for _ in 0..components {
        let size = r.u32("component size")?;
        let kind = r.u32("component type")?;
        let len = (size as usize).checked_sub(HEADER_BYTES).filter(|&n| n <= r.remaining());
        let Some(len) = len else { return Err(QtmError::BadComponent { size, left: r.remaining() }) };
        let data = r.take(len, "component")?;
        let mut c = Reader::new(data);
        match kind {
            COMPONENT_6D | COMPONENT_6D_RES if !found_6d => {
                found_6d = true;
                let count = c.u32("6D body count")?;
                frame.drop_rate_2d = c.u16("2D drop rate")?;
                frame.out_of_sync_rate_2d = c.u16("2D out-of-sync rate")?;
                for _ in 0..count {
                    let position_mm = c.vec3("6D position")?;
                    let mut rotation = [0f32; 9];
                    for v in &mut rotation {
                        *v = c.f32("6D rotation")?;
                    }
                    let residual_mm = if kind == COMPONENT_6D_RES { Some(c.f32("6D residual")?) } else { None };
                    frame.bodies.push(Body6d { position_mm, rotation, residual_mm });
                }
            }
            // 3D: the marker count, the 2D rates, then per marker its position (3 `f32`, mm) and, for 3DRes, its
            // residual (`f32`, mm).
            COMPONENT_3D | COMPONENT_3D_RES if !found_3d => {
                found_3d = true;
                let count = c.u32("3D marker count")?;
                frame.drop_rate_2d = c.u16("2D drop rate")?;
                frame.out_of_sync_rate_2d = c.u16("2D out-of-sync rate")?;
                for _ in 0..count {
                    let p = c.vec3("3D position")?;
                    if kind == COMPONENT_3D_RES {
                        c.f32("3D residual")?;
                    }
                    frame.markers_mm.push(p);
                }
            }
            _ => {}
        }
    }
    if found_6d || found_3d {
        Ok(Components { six_d: found_6d, three_d: found_3d })
    } else {
        Err(QtmError::No6d)
    }
}

/// The 3D marker labels of a `GetParameters 3D` reply, in index order (each `<Label>`'s `<Name>` inside
/// `<The_3D>`).
pub fn label_names(xml: &str) -> Vec<String> {
    names_in(xml, "<The_3D>", "</The_3D>", "<Label>", "</Label>")
}

/// The 6D body names of a `GetParameters 6D` reply, in index order (each `<Body>`'s `<Name>` inside
/// `<The_6D>`). A small scanner rather than an XML crate: the reply's structure is fixed and only this list
/// is needed; the five predefined entities are decoded.
pub fn body_names(xml: &str) -> Vec<String> {
    names_in(xml, "<The_6D>", "</The_6D>", "<Body>", "</Body>")
}

/// Each item's `<Name>` inside a section, in order.
fn names_in(xml: &str, open: &str, close: &str, item: &str, item_end: &str) -> Vec<String> {
    let section = match (xml.find(open), xml.find(close)) {
        (Some(a), Some(b)) if b > a => &xml[a..b],
        _ => return Vec::new(),
    };
    let mut names = Vec::new();
    let mut rest = section;
    while let Some(start) = rest.find(item) {
        let after = &rest[start + item.len()..];
        let end = after.find(item_end).unwrap_or(after.len());
        let body = &after[..end];
        if let (Some(a), Some(b)) = (body.find("<Name>"), body.find("</Name>")) {
            if b > a + 6 {
                names.push(unescape(&body[a + 6..b]));
            } else {
                names.push(String::new());
            }
        }
        rest = &after[end..];
    }
    names
}

fn unescape(s: &str) -> String {
    s.replace("&lt;", "<").replace("&gt;", ">").replace("&quot;", "\"").replace("&apos;", "'").replace("&amp;", "&")
}
