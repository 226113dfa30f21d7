//! A recording read a record at a time from its path: each message handed to the caller with its channel as
//! it is read, so reading a recording of any size holds one record (and the caller's own results) in memory.

use std::path::Path;

use super::reader::{scan_source, ChannelDef, OnDamage, RawMessage, Scan};
use super::source::Opened;
use crate::daemon::ReadError;

/// Reads the MCAP recording at `path`, visiting every readable message with its channel. A message whose
/// channel record comes later in the file (its own was damaged) is visited at the end, with that channel, or
/// with `None` when there is none. With [`OnDamage::Stop`] a file that is not MCAP is an error.
pub fn read_messages(
    path: &Path,
    on_damage: OnDamage,
    visit: impl FnMut(&Scan, Option<&ChannelDef>, RawMessage),
) -> Result<Scan, ReadError> {
    read_opened(Opened::open(path)?, path, on_damage, visit)
}

/// [`read_messages`] of a recording already opened.
pub fn read_opened(
    mut opened: Opened,
    path: &Path,
    on_damage: OnDamage,
    visit: impl FnMut(&Scan, Option<&ChannelDef>, RawMessage),
) -> Result<Scan, ReadError> {
    if on_damage == OnDamage::Stop && !opened.is_mcap() {
        return Err(ReadError::NotMcap { path: path.display().to_string() });
    }
    Ok(match &mut opened {
        Opened::File(f) => read_source(f, on_damage, visit),
        Opened::Bytes(b) => read_source(&mut b.as_slice(), on_damage, visit),
    })
}

/// [`read_messages`] of a recording in memory (a pipe read whole, shared by several passes).
pub fn read_slice(
    bytes: &[u8],
    path: &Path,
    on_damage: OnDamage,
    visit: impl FnMut(&Scan, Option<&ChannelDef>, RawMessage),
) -> Result<Scan, ReadError> {
    if on_damage == OnDamage::Stop && !super::source::is_mcap(bytes) {
        return Err(ReadError::NotMcap { path: path.display().to_string() });
    }
    Ok(read_source(&mut &bytes[..], on_damage, visit))
}

fn read_source<S: super::source::Source>(
    source: &mut S,
    on_damage: OnDamage,
    mut visit: impl FnMut(&Scan, Option<&ChannelDef>, RawMessage),
) -> Scan {
    let mut late = Vec::new();
    let mut on_message = |s: &Scan, m: RawMessage| match s.channels.get(&m.channel_id) {
        Some(c) => visit(s, Some(c), m),
        None => late.push(m),
    };
    let scan = scan_source(source, on_damage, &mut on_message);
    for m in late {
        visit(&scan, scan.channels.get(&m.channel_id), m);
    }
    scan
}
