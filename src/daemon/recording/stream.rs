//! A recording read a record at a time from its path: each message handed to the caller with its channel as
//! it is read, so reading a recording of any size holds one record (and the caller's own results) in memory.

use std::path::Path;

use super::reader::{scan_source, ChannelDef, OnDamage, RawMessage, Scan};
use super::source::Opened;
use crate::daemon::DaemonError;

/// Reads the MCAP recording at `path`, visiting every readable message with its channel. A message whose
/// channel record comes later in the file (its own was damaged) is visited at the end, with that channel, or
/// with `None` when there is none. With [`OnDamage::Stop`] a file that is not MCAP is an error.
pub fn read_messages(
    path: &Path,
    on_damage: OnDamage,
    visit: impl FnMut(&Scan, Option<&ChannelDef>, RawMessage),
) -> Result<Scan, DaemonError> {
    read_opened(Opened::open(path)?, path, on_damage, visit)
}

/// [`read_messages`] of a recording already opened.
pub fn read_opened(
    mut opened: Opened,
    path: &Path,
    on_damage: OnDamage,
    mut visit: impl FnMut(&Scan, Option<&ChannelDef>, RawMessage),
) -> Result<Scan, DaemonError> {
    if on_damage == OnDamage::Stop && !opened.is_mcap() {
        return Err(DaemonError::NotMcap { path: path.display().to_string() });
    }
    let mut late = Vec::new();
    let mut on_message = |s: &Scan, m: RawMessage| match s.channels.get(&m.channel_id) {
        Some(c) => visit(s, Some(c), m),
        None => late.push(m),
    };
    let scan = match &mut opened {
        Opened::File(f) => scan_source(f, on_damage, &mut on_message),
        Opened::Bytes(b) => scan_source(&mut b.as_slice(), on_damage, &mut on_message),
    };
    for m in late {
        visit(&scan, scan.channels.get(&m.channel_id), m);
    }
    Ok(scan)
}
