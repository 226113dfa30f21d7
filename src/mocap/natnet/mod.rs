//! OptiTrack NatNet 3.x and 4.x, the byte layouts Motive streams (pure decoding; the sockets are in
//! `daemon::bridges::natnet`).
//!
//! Every message is a 4-byte header (message id `u16`, payload byte count `u16`, little-endian) and its payload.
//! A client sends `NAT_CONNECT` to the server's command port (1510) and gets `NAT_SERVERINFO`: the server's
//! name, its version, the NatNet version its frames are laid out in, its clock's frequency and its data port.
//! `NAT_REQUEST_MODELDEF` is answered with `NAT_MODELDEF`, the data descriptions that name each rigid body's id.
//! Frames (`NAT_FRAMEOFDATA`) hold, in order: the frame number; marker sets; legacy unlabeled markers; rigid
//! bodies (id, position m, quaternion x y z w as f32, mean marker error, a flags word whose bit 0 is "tracking
//! valid"); skeletons; (4.1 and later) assets; labeled markers; force plates; devices; then a suffix with the
//! timecode, the frame's timestamp (f64 seconds), the camera mid-exposure, data-received and transmit stamps in
//! the server's high-resolution clock ticks, (4.x) a precision timestamp, and flags (bit 1: the tracked models
//! changed). From 4.1 every section's count is followed by its byte size, which this decoder uses to skip the
//! sections it does not read and to find the stride of a rigid body, so a newer 4.x minor that appends fields
//! still decodes.
//!
//! The layouts are those of OptiTrack's NatNet SDK (`NatNetTypes.h`, its PacketClient sample and its Python
//! client `natnetsdk`, which the tests run against the test server built on `natnet_encode`).
//!
//! Why not the `natnet` crate: it refuses servers newer than NatNet 4.1 (Motive 3.1 and later announce 4.2+,
//! with the same 4.1 layout plus byte counts this decoder relies on), it brings its own UDP clients where the
//! bridge needs one socket loop with counts by reason, and its decoder allocates a full frame (markers, force
//! plates) per datagram where this one reads the rigid bodies and labelled markers into reused buffers and skips
//! the rest by size.
//! Bounded allocation: nothing is reserved from a count; a body is pushed only after its bytes were read.

pub mod descriptions;
pub mod encode;
pub mod fit;
pub mod markers;
pub mod sample;

use self::descriptions::DescriptionError;
use self::markers::{LabeledMarker, LABELED_MARKER_BYTES};
use super::bytes::{Reader, Truncated};

pub const NAT_CONNECT: u16 = 0;
pub const NAT_SERVERINFO: u16 = 1;
pub const NAT_REQUEST: u16 = 2;
pub const NAT_RESPONSE: u16 = 3;
pub const NAT_REQUEST_MODELDEF: u16 = 4;
pub const NAT_MODELDEF: u16 = 5;
pub const NAT_REQUEST_FRAMEOFDATA: u16 = 6;
pub const NAT_FRAMEOFDATA: u16 = 7;
pub const NAT_MESSAGESTRING: u16 = 8;
pub const NAT_DISCONNECT: u16 = 9;
pub const NAT_KEEPALIVE: u16 = 10;
pub const NAT_UNRECOGNIZED_REQUEST: u16 = 100;

/// The largest datagram NatNet can describe: a 4-byte header and a `u16` payload count.
pub const MAX_DATAGRAM_BYTES: usize = 4 + u16::MAX as usize;

/// Bytes of one rigid body in a 3.x/4.x frame: id, position, quaternion, mean error, flags.
pub const RIGID_BODY_BYTES: usize = 4 + 12 + 16 + 4 + 2;

/// A NatNet bitstream version.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub struct Version {
    pub major: u8,
    pub minor: u8,
}

impl Version {
    pub const V3_0: Version = Version { major: 3, minor: 0 };
    pub const V3_1: Version = Version { major: 3, minor: 1 };
    pub const V4_0: Version = Version { major: 4, minor: 0 };
    pub const V4_1: Version = Version { major: 4, minor: 1 };

    /// Whether this decoder knows the layout (3.x and 4.x).
    pub fn supported(self) -> bool {
        self.major == 3 || self.major == 4
    }

    /// 4.1 and later: every section's count is followed by its byte size.
    pub fn sized_sections(self) -> bool {
        self >= Version::V4_1
    }
}

impl std::fmt::Display for Version {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        write!(f, "{}.{}", self.major, self.minor)
    }
}

/// Why a datagram was not decoded. [`NatNetError::reason`] is the key it is counted under.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum NatNetError {
    #[error(transparent)]
    Truncated(#[from] Truncated),
    #[error("the header counts {declared} payload bytes but the datagram holds only {actual}")]
    SizeMismatch { declared: usize, actual: usize },
    #[error("message id {0} is not a NatNet message")]
    UnknownMessage(u16),
    #[error("NatNet {0} is not a version this decoder knows (3.x, 4.x)")]
    UnsupportedVersion(Version),
    #[error("{what} count {count} is negative")]
    NegativeCount { what: &'static str, count: i32 },
    #[error("{what}: byte size {size} does not fit {count} items of at least {min} bytes")]
    BadSize { what: &'static str, size: i32, count: i32, min: usize },
}

impl From<DescriptionError> for NatNetError {
    fn from(e: DescriptionError) -> Self {
        match e {
            DescriptionError::Truncated(t) => NatNetError::Truncated(t),
            DescriptionError::NegativeCount { what, count } => NatNetError::NegativeCount { what, count },
        }
    }
}

impl NatNetError {
    /// The counting key.
    pub fn reason(&self) -> &'static str {
        match self {
            NatNetError::Truncated(_) => "truncated",
            NatNetError::SizeMismatch { .. } => "truncated",
            NatNetError::UnknownMessage(_) => "unknown_message",
            NatNetError::UnsupportedVersion(_) => "unknown_version",
            NatNetError::NegativeCount { .. } | NatNetError::BadSize { .. } => "malformed",
        }
    }
}

/// The message id and payload of a datagram, checked against the header's byte count. Bytes after the counted
/// payload are ignored: the NatNet SDK's own requests carry a NUL beyond their count.
pub fn split(datagram: &[u8]) -> Result<(u16, &[u8]), NatNetError> {
    let mut r = Reader::new(datagram);
    let id = r.u16("message id")?;
    let declared = r.u16("payload size")? as usize;
    let actual = r.remaining();
    if actual < declared {
        return Err(NatNetError::SizeMismatch { declared, actual });
    }
    Ok((id, &datagram[4..4 + declared]))
}

/// `NAT_SERVERINFO`: `sSender_Server` (the connection fields are absent from servers older than NatNet 3).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ServerInfo {
    pub app_name: String,
    pub app_version: [u8; 4],
    pub natnet_version: [u8; 4],
    /// Ticks per second of the server's clock (the frame suffix's stamps count these).
    pub clock_hz: Option<u64>,
    pub data_port: Option<u16>,
    pub multicast: Option<bool>,
    pub multicast_group: Option<[u8; 4]>,
}

impl ServerInfo {
    pub fn version(&self) -> Version {
        Version { major: self.natnet_version[0], minor: self.natnet_version[1] }
    }
}

pub fn decode_server_info(payload: &[u8]) -> Result<ServerInfo, NatNetError> {
    let mut r = Reader::new(payload);
    let mut info = ServerInfo {
        app_name: r.fixed_str(256, "server name")?,
        app_version: r.take(4, "server version")?.try_into().unwrap_or_default(),
        natnet_version: r.take(4, "natnet version")?.try_into().unwrap_or_default(),
        ..ServerInfo::default()
    };
    if r.remaining() >= 8 + 2 + 1 + 4 {
        info.clock_hz = Some(r.u64("clock frequency")?);
        info.data_port = Some(r.u16("data port")?);
        info.multicast = Some(r.u8("multicast")? != 0);
        info.multicast_group = r.take(4, "multicast group")?.try_into().ok();
    }
    Ok(info)
}

/// A rigid body's id and name from the data descriptions.
#[derive(Debug, Clone, PartialEq)]
pub struct RigidBodyDef {
    pub id: i32,
    pub name: String,
}

/// A marker set's name and its markers' names, in the order its labelled markers are numbered (from 1).
#[derive(Debug, Clone, PartialEq)]
pub struct MarkerSetDef {
    pub name: String,
    pub markers: Vec<String>,
}

/// `NAT_MODELDEF`: the rigid bodies it names, the marker sets, and the other assets with an id (skeletons,
/// NatNet 4.1's assets such as Trained Markersets) by name. `complete` is false when a data set of a kind this
/// decoder does not know (beyond the seven of NatNet 4.x) came before the end in a layout without byte sizes
/// (NatNet 3.x, 4.0): the data sets before it are kept.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ModelDef {
    pub rigid_bodies: Vec<RigidBodyDef>,
    pub marker_sets: Vec<MarkerSetDef>,
    /// Skeletons and assets: the ids their labelled markers carry as model id.
    pub assets: Vec<RigidBodyDef>,
    pub complete: bool,
}

impl ModelDef {
    /// The id a model named `name` (a rigid body, a skeleton or an asset) gives its labelled markers.
    pub fn model_id(&self, name: &str) -> Option<i32> {
        self.rigid_bodies.iter().chain(&self.assets).find(|b| b.name == name).map(|b| b.id)
    }
}

fn data_set(r: &mut Reader, version: Version, kind: i32, out: &mut ModelDef) -> Result<bool, NatNetError> {
    match kind {
        0 => {
            let (name, markers) = descriptions::marker_set(r)?;
            out.marker_sets.push(MarkerSetDef { name, markers });
        }
        1 => out.rigid_bodies.push(rigid_body_description(r, version)?),
        2 => {
            let name = r.cstr("skeleton name")?;
            let id = r.i32("skeleton id")?;
            for _ in 0..count(r, "skeleton bodies")? {
                rigid_body_description(r, version)?;
            }
            out.assets.push(RigidBodyDef { id, name });
        }
        3 => descriptions::skip_force_plate(r)?,
        4 => descriptions::skip_device(r)?,
        5 => descriptions::skip_camera(r)?,
        6 => {
            let (id, name) = descriptions::asset(r, |r| rigid_body_description(r, version).map(drop))?;
            out.assets.push(RigidBodyDef { id, name });
        }
        _ => return Ok(false),
    }
    Ok(true)
}

fn count(r: &mut Reader, what: &'static str) -> Result<usize, NatNetError> {
    let n = r.i32(what)?;
    usize::try_from(n).map_err(|_| NatNetError::NegativeCount { what, count: n })
}

fn size(r: &mut Reader, version: Version, what: &'static str) -> Result<Option<usize>, NatNetError> {
    if !version.sized_sections() {
        return Ok(None);
    }
    let n = r.i32(what)?;
    usize::try_from(n).map(Some).map_err(|_| NatNetError::NegativeCount { what, count: n })
}

fn rigid_body_description(r: &mut Reader, version: Version) -> Result<RigidBodyDef, NatNetError> {
    let name = r.cstr("rigid body name")?;
    let id = r.i32("rigid body id")?;
    r.skip(4 + 12, "rigid body parent and offset")?;
    let markers = count(r, "rigid body markers")?;
    r.skip(markers.saturating_mul(16), "rigid body marker offsets and labels")?;
    if version.major >= 4 {
        for _ in 0..markers {
            r.cstr("rigid body marker name")?;
        }
    }
    Ok(RigidBodyDef { id, name })
}

pub fn decode_model_def(payload: &[u8], version: Version) -> Result<ModelDef, NatNetError> {
    if !version.supported() {
        return Err(NatNetError::UnsupportedVersion(version));
    }
    let mut r = Reader::new(payload);
    let datasets = count(&mut r, "data sets")?;
    let mut out = ModelDef::default();
    for _ in 0..datasets {
        let kind = r.i32("data set type")?;
        if let Some(bytes) = size(&mut r, version, "data set size")? {
            // Sized (4.1+): a data set of an unknown kind is skipped by its size.
            data_set(&mut Reader::new(r.take(bytes, "data set")?), version, kind, &mut out)?;
            continue;
        }
        if !data_set(&mut r, version, kind, &mut out)? {
            return Ok(out);
        }
    }
    out.complete = true;
    Ok(out)
}

/// One rigid body of a frame, as sent (lab frame, metres).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RigidBody {
    pub id: i32,
    pub position_m: [f32; 3],
    pub orientation_xyzw: [f32; 4],
    pub mean_error_m: f32,
    /// Bit 0 of the body's flags: Motive tracked it in this frame.
    pub tracking_valid: bool,
}

/// `NAT_FRAMEOFDATA`: what the bridge reads of it.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Frame {
    pub frame_number: i32,
    pub rigid_bodies: Vec<RigidBody>,
    /// The labeled-marker list (every asset's markers, labelled by model id and index).
    pub labeled_markers: Vec<LabeledMarker>,
    /// The frame's timestamp (s since Motive started).
    pub timestamp_s: f64,
    /// The cameras' mid-exposure instant, in the server's clock ticks ([`ServerInfo::clock_hz`]); 0 when unknown.
    pub mid_exposure_ticks: u64,
    pub data_received_ticks: u64,
    pub transmit_ticks: u64,
    /// Suffix flag bit 1: the tracked models changed (ask for the model definitions again).
    pub models_changed: bool,
}

fn rigid_body(r: &mut Reader) -> Result<RigidBody, NatNetError> {
    let id = r.i32("rigid body id")?;
    let position_m = r.vec3("rigid body position")?;
    let mut q = [0f32; 4];
    for v in &mut q {
        *v = r.f32("rigid body orientation")?;
    }
    let mean_error_m = r.f32("rigid body mean error")?;
    let flags = r.i16("rigid body flags")?;
    Ok(RigidBody { id, position_m, orientation_xyzw: q, mean_error_m, tracking_valid: flags & 1 != 0 })
}

/// Skips a section of `count` items by its byte size (4.1+), or by walking it with `item`.
fn skip_section(
    r: &mut Reader,
    version: Version,
    what: &'static str,
    mut item: impl FnMut(&mut Reader) -> Result<(), NatNetError>,
) -> Result<(), NatNetError> {
    let n = count(r, what)?;
    if let Some(bytes) = size(r, version, what)? {
        return Ok(r.skip(bytes, what)?);
    }
    for _ in 0..n {
        item(r)?;
    }
    Ok(())
}

fn channels(r: &mut Reader) -> Result<(), NatNetError> {
    r.skip(4, "device id")?;
    for _ in 0..count(r, "channels")? {
        let frames = count(r, "channel frames")?;
        r.skip(frames.saturating_mul(4), "channel values")?;
    }
    Ok(())
}

/// The bytes of each of a section's `items` entries: its byte size over its count (4.1+, so a later minor's
/// longer entries decode), else `min`.
fn entry_bytes(
    r: &mut Reader,
    version: Version,
    what: &'static str,
    items: usize,
    min: usize,
) -> Result<usize, NatNetError> {
    match size(r, version, what)? {
        Some(bytes) if items > 0 => {
            if bytes % items != 0 || bytes / items < min {
                return Err(NatNetError::BadSize { what, size: bytes as i32, count: items as i32, min });
            }
            Ok(bytes / items)
        }
        Some(bytes) => Ok(r.skip(bytes, what).map(|()| min)?),
        None => Ok(min),
    }
}

/// Decodes a frame's payload into `frame` (its body and marker lists are cleared and reused).
pub fn decode_frame(payload: &[u8], version: Version, frame: &mut Frame) -> Result<(), NatNetError> {
    if !version.supported() {
        return Err(NatNetError::UnsupportedVersion(version));
    }
    frame.rigid_bodies.clear();
    frame.labeled_markers.clear();
    let mut r = Reader::new(payload);
    frame.frame_number = r.i32("frame number")?;
    skip_section(&mut r, version, "marker sets", |r| {
        r.cstr("marker set name")?;
        let n = count(r, "marker set markers")?;
        Ok(r.skip(n.saturating_mul(12), "marker positions")?)
    })?;
    let legacy = count(&mut r, "legacy markers")?;
    let legacy_bytes = size(&mut r, version, "legacy markers")?.unwrap_or(legacy.saturating_mul(12));
    r.skip(legacy_bytes, "legacy markers")?;
    let bodies = count(&mut r, "rigid bodies")?;
    let stride = entry_bytes(&mut r, version, "rigid bodies", bodies, RIGID_BODY_BYTES)?;
    for _ in 0..bodies {
        let body = r.take(stride, "rigid body")?;
        frame.rigid_bodies.push(rigid_body(&mut Reader::new(body))?);
    }
    skip_section(&mut r, version, "skeletons", |r| {
        r.skip(4, "skeleton id")?;
        let n = count(r, "skeleton bodies")?;
        Ok(r.skip(n.saturating_mul(RIGID_BODY_BYTES), "skeleton bodies")?)
    })?;
    if version.sized_sections() {
        skip_section(&mut r, version, "assets", |_| Ok(()))?;
    }
    let labeled = count(&mut r, "labeled markers")?;
    let stride = entry_bytes(&mut r, version, "labeled markers", labeled, LABELED_MARKER_BYTES)?;
    for _ in 0..labeled {
        let marker = r.take(stride, "labeled marker")?;
        frame.labeled_markers.push(markers::labeled_marker(&mut Reader::new(marker))?);
    }
    skip_section(&mut r, version, "force plates", channels)?;
    skip_section(&mut r, version, "devices", channels)?;
    r.skip(8, "timecode")?;
    frame.timestamp_s = r.f64("timestamp")?;
    frame.mid_exposure_ticks = r.u64("mid-exposure stamp")?;
    frame.data_received_ticks = r.u64("data-received stamp")?;
    frame.transmit_ticks = r.u64("transmit stamp")?;
    if version.major >= 4 {
        r.skip(8, "precision timestamp")?;
    }
    let flags = r.i16("frame flags")?;
    frame.models_changed = flags & 2 != 0;
    Ok(())
}

/// A decoded datagram (a frame is decoded into the caller's buffer).
#[derive(Debug, Clone, PartialEq)]
pub enum Message {
    Frame,
    ServerInfo(ServerInfo),
    ModelDef(ModelDef),
    /// A reply to a request, a message string, a keep-alive or an unrecognized-request answer: nothing to do.
    Other(u16),
}

/// Decodes one datagram of a server speaking `version`.
pub fn decode(datagram: &[u8], version: Version, frame: &mut Frame) -> Result<Message, NatNetError> {
    let (id, payload) = split(datagram)?;
    match id {
        NAT_FRAMEOFDATA => decode_frame(payload, version, frame).map(|()| Message::Frame),
        NAT_SERVERINFO => decode_server_info(payload).map(Message::ServerInfo),
        NAT_MODELDEF => decode_model_def(payload, version).map(Message::ModelDef),
        NAT_RESPONSE | NAT_MESSAGESTRING | NAT_KEEPALIVE | NAT_UNRECOGNIZED_REQUEST | NAT_DISCONNECT => {
            Ok(Message::Other(id))
        }
        other => Err(NatNetError::UnknownMessage(other)),
    }
}
