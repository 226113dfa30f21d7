//! Damaged recordings, made here from the example recording: every truncation point at a stride, and 1,000
//! seeded single-bit flips. `info`, `replay` and `recover` end on each within 5 s without a panic, and `recover`
//! keeps every chunk whose bytes are intact (compared with the original's chunks).

#![allow(clippy::unwrap_used)]
#![cfg(feature = "daemon")]

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::Duration;

use impactd::daemon::recording::reader::{scan, OnDamage, RawMessage};
use impactd::daemon::replay;
use impactd::daemon::DaemonConfig;

const RECORDING: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/recordings/driver.mcap");
const LIMIT: Duration = Duration::from_secs(5);

/// A message's identity: channel topic, log time, sequence and bytes.
type Key = (String, u64, u32, Vec<u8>);

fn keys_of(messages: &[RawMessage], topic: impl Fn(u16) -> String) -> Vec<Key> {
    messages.iter().map(|m| (topic(m.channel_id), m.log_time, m.sequence, m.data.clone())).collect()
}

/// Runs `info`, `replay` and `recover` on one file in a thread; fails if it panics or takes over 5 s.
fn run_all(path: PathBuf, out: PathBuf) -> Option<impactd::daemon::recording::recover::Recovered> {
    let (tx, rx) = mpsc::channel();
    let name = path.display().to_string();
    let label = name.clone();
    let worker = std::thread::spawn(move || {
        let _ = impactd::daemon::recording::info::info(&path);
        if let Ok(input) = replay::load(&path) {
            let setups = match input.config_toml.as_deref().map(DaemonConfig::parse) {
                Some(Ok((_, s))) => s,
                _ => DaemonConfig::default().setups().unwrap(),
            };
            let mut produced = Vec::new();
            replay::replay(
                &input,
                setups,
                |_| {},
                |e| {
                    if let impactd::pipeline::Event::Launch(l) = e {
                        produced.push(serde_json::to_vec(l).unwrap());
                    }
                },
            );
            let verdict = replay::Verdict::of(&input, &produced);
            if !input.damage.is_empty() {
                assert!(!verdict.success(), "{label}: a damaged file replayed as a success");
            }
        }
        // Only a file too short to hold the magic is refused as not MCAP.
        let r = impactd::daemon::recording::recover::recover(&path, &out, true);
        let short = std::fs::metadata(&path).map(|m| m.len() <= 8).unwrap_or(true);
        assert!(r.is_ok() || short, "{label}: recover: {r:?}");
        let r = r.ok();
        let _ = tx.send(());
        r
    });
    match rx.recv_timeout(LIMIT) {
        Ok(()) => {}
        Err(mpsc::RecvTimeoutError::Timeout) => panic!("{name}: not done within {LIMIT:?}"),
        Err(mpsc::RecvTimeoutError::Disconnected) => {}
    }
    worker.join().unwrap_or_else(|_| panic!("{name}: panicked"))
}

/// The original's chunks: byte range and messages.
fn original_chunks(bytes: &[u8]) -> Vec<(usize, usize, Vec<Key>)> {
    let s = scan(bytes, OnDamage::Stop);
    assert!(s.intact(), "{:?}", s.problems());
    let topic = |id: u16| s.channels[&id].topic.clone();
    let all = keys_of(&s.messages, topic);
    let mut out = Vec::new();
    let mut next = 0;
    for c in &s.chunks {
        let n = c.messages as usize;
        out.push((c.offset as usize, (c.offset + c.bytes) as usize, all[next..next + n].to_vec()));
        next += n;
    }
    assert_eq!(next, all.len(), "every message of the example recording is in a chunk");
    out
}

fn recovered_keys(path: &Path) -> Vec<Key> {
    let bytes = std::fs::read(path).unwrap();
    let s = scan(&bytes, OnDamage::Stop);
    assert!(s.intact(), "the recovered file is finished and readable: {:?}", s.problems());
    keys_of(&s.messages, |id| s.channels[&id].topic.clone())
}

fn check(original: &[u8], chunks: &[(usize, usize, Vec<Key>)], damaged: &[u8], dir: &Path, name: &str) {
    let path = dir.join(format!("{name}.mcap"));
    let out = dir.join(format!("{name}-recovered.mcap"));
    std::fs::write(&path, damaged).unwrap();
    if run_all(path.clone(), out.clone()).is_none() {
        return;
    }
    let kept: HashMap<Key, usize> = recovered_keys(&out).into_iter().fold(HashMap::new(), |mut m, k| {
        *m.entry(k).or_default() += 1;
        m
    });
    for (start, end, messages) in chunks {
        let intact = damaged.len() >= *end && damaged[*start..*end] == original[*start..*end];
        if intact {
            for k in messages {
                assert!(kept.contains_key(k), "{name}: a message of the intact chunk at {start}..{end} was lost");
            }
        }
    }
    std::fs::remove_file(&path).unwrap();
    let _ = std::fs::remove_file(&out);
}

#[test]
fn every_truncation_ends_and_keeps_every_whole_chunk() {
    let original = std::fs::read(RECORDING).unwrap();
    let chunks = original_chunks(&original);
    let dir = tempfile::tempdir().unwrap();
    let stride = 1999;
    let mut files = 0;
    for cut in (0..original.len()).step_by(stride) {
        check(&original, &chunks, &original[..cut], dir.path(), &format!("cut{cut}"));
        files += 1;
    }
    assert!(files > 150);
}

#[test]
fn a_thousand_bit_flips_end_and_keep_every_intact_chunk() {
    let original = std::fs::read(RECORDING).unwrap();
    let chunks = original_chunks(&original);
    let dir = tempfile::tempdir().unwrap();
    let mut rng = impactd::rng::Rng::new(20);
    let bits: Vec<usize> = (0..1000).map(|_| (rng.next_u64() % (original.len() as u64 * 8)) as usize).collect();
    // Two lanes side by side: each flip is checked on its own copy.
    std::thread::scope(|scope| {
        for lane in 0..2 {
            let (original, chunks, bits, dir) = (&original, &chunks, &bits, dir.path());
            scope.spawn(move || {
                for (i, &bit) in bits.iter().enumerate().skip(lane).step_by(2) {
                    let mut damaged = original.clone();
                    damaged[bit / 8] ^= 1 << (bit % 8);
                    check(original, chunks, &damaged, dir, &format!("flip{i}-{bit}"));
                }
            });
        }
    });
    // The opening magic itself.
    let mut damaged = original.clone();
    damaged[3] ^= 0x04;
    check(&original, &chunks, &damaged, dir.path(), "flip-magic");
}

/// The real binary on a few damaged files: each ends at once with exit 3 and says why.
#[test]
fn the_binary_says_a_file_is_damaged() {
    let original = std::fs::read(RECORDING).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let cut = dir.path().join("cut.mcap");
    std::fs::write(&cut, &original[..original.len() / 2]).unwrap();
    let mut flipped = original.clone();
    flipped[original.len() / 3] ^= 0x10;
    let flip = dir.path().join("flip.mcap");
    std::fs::write(&flip, &flipped).unwrap();
    for file in [&cut, &flip] {
        for args in [vec!["info"], vec!["replay"], vec!["recover", "-o"]] {
            let mut cmd = std::process::Command::new(env!("CARGO_BIN_EXE_impactd"));
            cmd.args(&args[..1]).arg(file);
            if args.len() > 1 {
                // One output for every case: replacing it is asked for (`recover` never replaces silently).
                cmd.arg(args[1]).arg(dir.path().join("out.mcap")).arg("--overwrite");
            }
            let out = cmd.output().unwrap();
            let err = String::from_utf8_lossy(&out.stderr);
            let text = format!("{}{err}", String::from_utf8_lossy(&out.stdout));
            assert_eq!(out.status.code(), Some(3), "{args:?} {}: {text}", file.display());
            assert!(text.contains("damaged"), "{args:?}: {text}");
            assert!(!err.contains("byte for byte"), "{err}");
        }
    }
}

/// The reader's reasons are typed, with their causes: a chunk whose bytes changed is a `ChunkError` naming the
/// check that caught it, a length that points past the end stops a strict scan at that record's offset, and the
/// error `recover` returns for a file with nothing readable has the scan's stop as its source.
#[test]
fn damage_reasons_are_typed_with_causes() {
    use impactd::daemon::recording::damage::{ChunkError, DamageReason, ScanStop};
    use std::error::Error as _;
    let original = std::fs::read(RECORDING).unwrap();
    let intact = scan(&original, OnDamage::Stop);
    assert!(intact.intact());
    let chunk = intact.chunks[0];
    // The last byte of the first chunk's record is compressed data: the zstd frame or the CRC must refuse it.
    let mut flipped = original.clone();
    flipped[(chunk.offset + chunk.bytes - 1) as usize] ^= 0x01;
    let s = scan(&flipped, OnDamage::Resync);
    let d = s.damage.iter().find(|d| d.offset == chunk.offset).expect("the damaged chunk is reported");
    assert!(
        matches!(
            d.reason,
            DamageReason::Chunk(ChunkError::Crc { .. } | ChunkError::Zstd(_) | ChunkError::DecompressedSize { .. })
        ),
        "{:?}",
        d.reason
    );
    if let DamageReason::Chunk(ChunkError::Zstd(cause)) = &d.reason {
        assert!(cause.source().is_some() || !cause.to_string().is_empty());
    }
    // The first chunk's length claims more than the file holds: a strict scan stops there.
    let mut long = original.clone();
    let at = chunk.offset as usize + 1;
    long[at..at + 8].copy_from_slice(&u64::MAX.to_le_bytes());
    let s = scan(&long, OnDamage::Stop);
    match &s.stopped {
        Some(ScanStop::At { offset, reason: DamageReason::PastEnd { claimed_bytes, .. } }) => {
            assert_eq!((*offset, *claimed_bytes), (chunk.offset, u64::MAX));
        }
        other => panic!("{other:?}"),
    }
    assert_eq!(
        s.problems().last().unwrap(),
        &format!(
            "stopped: at byte {}: record 0x06 claims {} bytes; {} are left",
            chunk.offset,
            u64::MAX,
            original.len() as u64 - chunk.offset - 9
        )
    );
    // Nothing readable: `recover` refuses with the scan's stop as the cause.
    let dir = tempfile::tempdir().unwrap();
    let junk = dir.path().join("junk.mcap");
    std::fs::write(&junk, vec![0x5au8; 4096]).unwrap();
    let err = impactd::daemon::recording::recover::recover(&junk, &dir.path().join("out.mcap"), true).unwrap_err();
    let source = err.source().and_then(|s| s.downcast_ref::<ScanStop>());
    assert_eq!(source, Some(&ScanStop::NothingReadable), "{err}");
}
