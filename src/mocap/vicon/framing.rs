//! A DataStream packet's framing: the 8-byte header (`u32` tag [`OBJECTS`], `u32` byte count of the rest), the
//! items inside (`u32` type, `u32` byte count, payload), and the SDK's counted containers, read bounded and
//! written for the encoders.

use super::enums::OBJECTS;
use super::ViconError;
use crate::mocap::bytes::{Reader, Writer};

pub const HEADER_BYTES: usize = 8;
/// The largest packet the client buffers: a frame of 100 subjects with 100 labelled markers each is under 1.3 MiB.
pub const MAX_PACKET_BYTES: usize = 4 << 20;

/// A packet's header: the byte count of its items (checked against [`MAX_PACKET_BYTES`]).
pub fn header(bytes: &[u8; HEADER_BYTES]) -> Result<usize, ViconError> {
    let tag = u32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]);
    let len = u32::from_le_bytes([bytes[4], bytes[5], bytes[6], bytes[7]]);
    if tag != OBJECTS {
        return Err(ViconError::BadTag(tag));
    }
    if len as usize > MAX_PACKET_BYTES - HEADER_BYTES {
        return Err(ViconError::Oversized(len));
    }
    Ok(len as usize)
}

/// The items of a whole packet (header included), checked against its header.
pub fn items(packet: &[u8]) -> Result<Items<'_>, ViconError> {
    let head: &[u8; HEADER_BYTES] = packet
        .get(..HEADER_BYTES)
        .and_then(|h| h.try_into().ok())
        .ok_or(crate::mocap::bytes::Truncated { what: "packet header", at: 0, len: packet.len() })?;
    let declared = header(head)?;
    let actual = packet.len() - HEADER_BYTES;
    if declared != actual {
        return Err(ViconError::SizeMismatch { declared, actual });
    }
    Ok(Items { r: Reader::new(&packet[HEADER_BYTES..]) })
}

/// The items of a packet, each `(type, payload)`; an item that overruns the packet ends the iteration with an
/// error.
pub struct Items<'a> {
    r: Reader<'a>,
}

impl<'a> Iterator for Items<'a> {
    type Item = Result<(u32, &'a [u8]), ViconError>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.r.remaining() == 0 {
            return None;
        }
        Some(self.item())
    }
}

impl<'a> Items<'a> {
    fn item(&mut self) -> Result<(u32, &'a [u8]), ViconError> {
        let kind = self.r.u32("item type")?;
        let size = self.r.u32("item size")?;
        let left = self.r.remaining();
        if size as usize > left {
            // Nothing after an item that overruns can be trusted: the rest is dropped.
            self.r.skip(left, "item")?;
            return Err(ViconError::ItemOverrun { kind, size, left });
        }
        Ok((kind, self.r.take(size as usize, "item")?))
    }
}

/// A container's `u32` count, checked: `count` elements of at least `min` bytes each must fit what is left.
pub fn count(r: &mut Reader, min: usize, what: &'static str) -> Result<u32, ViconError> {
    let count = r.u32(what)?;
    let left = r.remaining();
    if (count as usize).checked_mul(min).filter(|&n| n <= left).is_none() {
        return Err(ViconError::BadCount { what, count, min, left });
    }
    Ok(count)
}

/// A string (`u32` byte count, bytes, no NUL) into `out`, reusing its allocation; invalid UTF-8 is replaced.
pub fn string_into(r: &mut Reader, out: &mut String, what: &'static str) -> Result<(), ViconError> {
    let n = r.u32(what)?;
    let bytes = r.take(n as usize, what)?;
    out.clear();
    match std::str::from_utf8(bytes) {
        Ok(s) => out.push_str(s),
        Err(_) => out.push_str(&String::from_utf8_lossy(bytes)),
    }
    Ok(())
}

/// Writes a packet: the header, then items, each framed by [`PacketWriter::item`]; [`PacketWriter::finish`]
/// fills in the byte counts.
#[derive(Debug, Default)]
pub struct PacketWriter {
    buf: Vec<u8>,
}

impl PacketWriter {
    pub fn new() -> Self {
        let mut buf = Vec::with_capacity(256);
        buf.put_u32(OBJECTS);
        buf.put_u32(0);
        PacketWriter { buf }
    }

    /// Appends an item of `kind` whose payload `write` puts.
    pub fn item(&mut self, kind: u32, write: impl FnOnce(&mut Vec<u8>)) -> &mut Self {
        self.buf.put_u32(kind);
        let at = self.buf.len();
        self.buf.put_u32(0);
        write(&mut self.buf);
        let n = (self.buf.len() - at - 4) as u32;
        self.buf[at..at + 4].copy_from_slice(&n.to_le_bytes());
        self
    }

    /// The packet.
    pub fn finish(mut self) -> Vec<u8> {
        let n = (self.buf.len() - HEADER_BYTES) as u32;
        self.buf[4..8].copy_from_slice(&n.to_le_bytes());
        self.buf
    }
}

/// A string as the SDK writes it.
pub fn put_string(out: &mut Vec<u8>, s: &str) {
    out.put_u32(s.len() as u32);
    out.extend_from_slice(s.as_bytes());
}

/// A set or vector of `u32`s.
pub fn put_u32s(out: &mut Vec<u8>, values: &[u32]) {
    out.put_u32(values.len() as u32);
    for &v in values {
        out.put_u32(v);
    }
}
