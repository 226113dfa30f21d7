//! An MCAP recording or a JSONL file of samples as a replay's input, streamed: opening it reads it once for its
//! [`ReplayIndex`]; each replay reads it again item by item. A recording is read a record at a time (a window
//! over the file; a pipe is read into memory, only when it starts with the MCAP magic and up to
//! [`MAX_STREAMED_RECORDING_BYTES`]), on a reader thread that hands the replay batches of items through a short
//! queue; a JSONL file a line at a time, each at most [`crate::jsonl::MAX_LINE_BYTES`] (so `/dev/zero` or a huge
//! file that is not JSONL is an error, not a whole-file read), and JSONL from a pipe is copied to an unnamed
//! temporary file as it is indexed, so it too is read twice without being held.

use std::io::{BufRead, Read, Seek, Write};
use std::path::{Path, PathBuf};
use std::sync::mpsc::{sync_channel, Receiver};
use std::sync::Arc;

use super::items::{Item, Items, ReplayIndex, ReplaySource};
use super::parse::{self, Parsed, Pass};
use crate::daemon::recording::reader::{ChannelDef, OnDamage, RawMessage};
use crate::daemon::recording::source::{is_mcap, MAX_STREAMED_RECORDING_BYTES};
use crate::daemon::recording::stream::{read_messages, read_slice};
use crate::daemon::{DaemonError, ReadError};

/// Items a reader thread hands over at a time, and batches in flight.
const BATCH: usize = 256;
const BATCHES_IN_FLIGHT: usize = 8;

/// An MCAP recording or a JSONL file of samples, indexed.
pub struct ReplayFile {
    path: PathBuf,
    body: Body,
    index: ReplayIndex,
}

enum Body {
    /// A regular MCAP file, read again from its path.
    McapFile,
    /// An MCAP recording that is not a regular file, read into memory once.
    McapBytes(Arc<Vec<u8>>),
    /// A regular JSONL file, read again from its path.
    JsonlFile,
    /// JSONL from a pipe, copied to an unnamed temporary file as it was indexed.
    JsonlSpool(std::fs::File),
}

impl ReplayFile {
    /// Opens and indexes `path`. With `times`, each recorded sample is parsed for its rig's earliest capture time
    /// (what `--start-offset` and `--duration` count from); without, a recording's samples are counted by their
    /// topic and publish time, unparsed (JSONL is parsed either way).
    pub fn open(path: &Path, times: bool) -> Result<ReplayFile, DaemonError> {
        Self::open_with(path, times, |_| {})
    }

    /// As [`open`](Self::open); `on_launch` sees each recorded prediction's bytes as they are indexed.
    pub fn open_with(path: &Path, times: bool, mut on_launch: impl FnMut(&[u8])) -> Result<ReplayFile, DaemonError> {
        let pass = if times { Pass::IndexParsed } else { Pass::Index };
        let io = |e| DaemonError::Io { what: format!("reading {}", path.display()), source: e };
        let mut file = std::io::BufReader::new(std::fs::File::open(path).map_err(io)?);
        let regular = file.get_ref().metadata().map_err(io)?.is_file();
        let mut index = ReplayIndex::default();
        if !is_mcap(file.fill_buf().map_err(io)?) {
            let body = if regular {
                jsonl_index(file, path, &mut index, None)?;
                Body::JsonlFile
            } else {
                let mut spool = spool_file().map_err(io)?;
                jsonl_index(file, path, &mut index, Some(&mut spool))?;
                Body::JsonlSpool(spool)
            };
            return Ok(ReplayFile { path: path.to_path_buf(), body, index });
        }
        let mut damage = Vec::new();
        let mut visit = |_: &_, channel: Option<&ChannelDef>, m: RawMessage| {
            let Some(channel) = channel else { return };
            match parse::recorded(&channel.topic, m.data, m.log_time, m.publish_time, pass) {
                Parsed::SampleAt { rig, t_ns, log_time_ns } => index.add_sample(&rig, t_ns, Some(log_time_ns)),
                Parsed::Launch { data, key, renamed } => {
                    on_launch(&data);
                    index.add_launch(&data, key);
                    if let Some(r) = renamed.filter(|r| !index.renamed_models.contains(r)) {
                        index.renamed_models.push(r);
                    }
                }
                Parsed::Bad(why) => damage.push(why),
                Parsed::Item(_) | Parsed::Other => {}
            }
        };
        let (scan, body) = if regular {
            drop(file);
            (read_messages(path, OnDamage::Stop, &mut visit)?, Body::McapFile)
        } else {
            let bytes = read_capped(file, path)?;
            (read_slice(&bytes, path, OnDamage::Stop, &mut visit)?, Body::McapBytes(Arc::new(bytes)))
        };
        index.damage = scan.problems();
        index.damage.extend(damage);
        index.config_toml =
            scan.metadata.iter().find(|(n, _)| n == "session").and_then(|(_, m)| m.get("config_toml").cloned());
        Ok(ReplayFile { path: path.to_path_buf(), body, index })
    }

    pub fn path(&self) -> &Path {
        &self.path
    }
}

/// A recording that is not a regular file, read into memory up to the limit.
fn read_capped(mut file: impl Read, path: &Path) -> Result<Vec<u8>, DaemonError> {
    let mut bytes = Vec::new();
    (&mut file)
        .take(MAX_STREAMED_RECORDING_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| DaemonError::Io { what: format!("reading {}", path.display()), source: e })?;
    if bytes.len() as u64 > MAX_STREAMED_RECORDING_BYTES {
        return Err(ReadError::StreamTooLarge {
            path: path.display().to_string(),
            limit_bytes: MAX_STREAMED_RECORDING_BYTES,
        }
        .into());
    }
    Ok(bytes)
}

/// A temporary file with no name left (removed at once where the system allows), gone with the process.
fn spool_file() -> std::io::Result<std::fs::File> {
    let nanos = crate::daemon::clock::Clock::system().wall_ns();
    let path = std::env::temp_dir().join(format!("impactd-replay-{}-{nanos}.jsonl", std::process::id()));
    let file = std::fs::OpenOptions::new().read(true).write(true).create_new(true).open(&path)?;
    if cfg!(unix) {
        let _ = std::fs::remove_file(&path);
    }
    Ok(file)
}

/// Reads every line of a JSONL input into the index (and, with `spool`, copies it there).
fn jsonl_index(
    mut input: impl BufRead,
    path: &Path,
    index: &mut ReplayIndex,
    mut spool: Option<&mut std::fs::File>,
) -> Result<(), DaemonError> {
    let io = |e| DaemonError::Io { what: format!("copying {} to a temporary file", path.display()), source: e };
    let mut out = spool.as_mut().map(|f| std::io::BufWriter::new(&**f));
    let mut line = Vec::new();
    for n in 1.. {
        if !read_line(&mut input, &mut line, path, n)? {
            break;
        }
        if let Some(out) = &mut out {
            out.write_all(&line).and_then(|_| out.write_all(b"\n")).map_err(io)?;
        }
        match parse::jsonl_line(&line) {
            Parsed::Item(Item::Sample { msg, log_time_ns }) => index.add_sample(&msg.rig, msg.t_ns, log_time_ns),
            Parsed::Bad(reason) => index.skip_line(format!("{} line {n}", path.display()), &reason),
            _ => {}
        }
    }
    if let Some(out) = out {
        out.into_inner().map_err(|e| io(e.into_error()))?;
    }
    Ok(())
}

fn read_line(input: &mut impl BufRead, line: &mut Vec<u8>, path: &Path, n: usize) -> Result<bool, DaemonError> {
    crate::jsonl::read_line(input, line, crate::jsonl::MAX_LINE_BYTES)
        .map_err(|source| ReadError::BadSampleLine { path: path.display().to_string(), line: n, source }.into())
}

/// The items of a JSONL input, a line at a time.
struct JsonlItems<R> {
    input: R,
    line: Vec<u8>,
    n: usize,
    path: PathBuf,
    done: bool,
}

impl<R: BufRead> Iterator for JsonlItems<R> {
    type Item = Result<Item, DaemonError>;

    fn next(&mut self) -> Option<Self::Item> {
        while !self.done {
            self.n += 1;
            match read_line(&mut self.input, &mut self.line, &self.path, self.n) {
                Ok(true) => {}
                Ok(false) => {
                    self.done = true;
                    continue;
                }
                Err(e) => {
                    self.done = true;
                    return Some(Err(e));
                }
            }
            if let Parsed::Item(item) = parse::jsonl_line(&self.line) {
                return Some(Ok(item));
            }
        }
        None
    }
}

/// The items a reader thread sends, a batch at a time; the thread ends when this is dropped (at its next
/// batch).
struct ThreadItems {
    rx: Receiver<Result<Vec<Item>, DaemonError>>,
    batch: std::vec::IntoIter<Item>,
}

impl Iterator for ThreadItems {
    type Item = Result<Item, DaemonError>;

    fn next(&mut self) -> Option<Self::Item> {
        loop {
            if let Some(item) = self.batch.next() {
                return Some(Ok(item));
            }
            match self.rx.recv().ok()? {
                Ok(batch) => self.batch = batch.into_iter(),
                Err(e) => return Some(Err(e)),
            }
        }
    }
}

/// Reads `items` on a thread of its own (parsing beside the replay's pipelines), sending them in batches.
fn threaded(
    items: impl Iterator<Item = Result<Item, DaemonError>> + Send + 'static,
) -> Result<ThreadItems, DaemonError> {
    let (tx, rx) = sync_channel::<Result<Vec<Item>, DaemonError>>(BATCHES_IN_FLIGHT);
    std::thread::Builder::new()
        .name("impactd-replay-read".into())
        .spawn(move || {
            let mut batch = Vec::with_capacity(BATCH);
            for item in items {
                match item {
                    Ok(item) => batch.push(item),
                    Err(e) => {
                        let _ = tx.send(Ok(std::mem::take(&mut batch)));
                        let _ = tx.send(Err(e));
                        return;
                    }
                }
                if batch.len() == BATCH
                    && tx.send(Ok(std::mem::replace(&mut batch, Vec::with_capacity(BATCH)))).is_err()
                {
                    return;
                }
            }
            let _ = tx.send(Ok(batch));
        })
        .map_err(|e| DaemonError::Io { what: "starting the replay's reader".into(), source: e })?;
    Ok(ThreadItems { rx, batch: Vec::new().into_iter() })
}

/// Reads the recording (its path, or its bytes) on a thread of its own, sending its items in batches.
fn mcap_items(path: PathBuf, bytes: Option<Arc<Vec<u8>>>) -> Result<ThreadItems, DaemonError> {
    let (tx, rx) = sync_channel::<Result<Vec<Item>, DaemonError>>(BATCHES_IN_FLIGHT);
    std::thread::Builder::new()
        .name("impactd-replay-read".into())
        .spawn(move || {
            let mut batch = Vec::with_capacity(BATCH);
            let mut gone = false;
            let mut visit = |_: &_, channel: Option<&ChannelDef>, m: RawMessage| {
                let Some(channel) = channel.filter(|_| !gone) else { return };
                let parsed = parse::recorded(&channel.topic, m.data, m.log_time, m.publish_time, Pass::Replay);
                if let Parsed::Item(item) = parsed {
                    batch.push(item);
                    if batch.len() == BATCH {
                        gone = tx.send(Ok(std::mem::replace(&mut batch, Vec::with_capacity(BATCH)))).is_err();
                    }
                }
            };
            let read = match &bytes {
                Some(b) => read_slice(b, &path, OnDamage::Stop, &mut visit),
                None => read_messages(&path, OnDamage::Stop, &mut visit),
            };
            let _ = match read {
                Ok(_) if !batch.is_empty() => tx.send(Ok(batch)),
                Ok(_) => Ok(()),
                Err(e) => tx.send(Err(e.into())),
            };
        })
        .map_err(|e| DaemonError::Io { what: "starting the replay's reader".into(), source: e })?;
    Ok(ThreadItems { rx, batch: Vec::new().into_iter() })
}

impl ReplaySource for ReplayFile {
    fn index(&self) -> std::borrow::Cow<'_, ReplayIndex> {
        std::borrow::Cow::Borrowed(&self.index)
    }

    fn items(&self) -> Result<Items<'_>, DaemonError> {
        let io = |e| DaemonError::Io { what: format!("reading {}", self.path.display()), source: e };
        let jsonl = |input| JsonlItems { input, line: Vec::new(), n: 0, path: self.path.clone(), done: false };
        Ok(match &self.body {
            Body::McapFile => Box::new(mcap_items(self.path.clone(), None)?),
            Body::McapBytes(bytes) => Box::new(mcap_items(self.path.clone(), Some(bytes.clone()))?),
            Body::JsonlFile => {
                let file = std::fs::File::open(&self.path).map_err(io)?;
                Box::new(threaded(jsonl(std::io::BufReader::with_capacity(1 << 16, file)))?)
            }
            Body::JsonlSpool(spool) => {
                let mut file = spool.try_clone().map_err(io)?;
                file.rewind().map_err(io)?;
                Box::new(threaded(jsonl(std::io::BufReader::with_capacity(1 << 16, file)))?)
            }
        })
    }
}
