//! Recordings larger than the memory they are read in: `info`, `replay`, `recover`, `session` and `compare` read
//! an MCAP file a record at a time, so a 512 MB recording (mostly another program's bulk channel beside a rig's
//! samples) is read in well under the 150 MB a hostile input may cost the daemon. Each command runs as the real
//! binary; its peak resident memory is measured by the kernel (`ru_maxrss` of the child, read by Python's
//! `resource` module).

#![allow(clippy::unwrap_used)]
#![cfg(feature = "daemon")]

use crate::common;
use crate::swing;

use std::collections::BTreeMap;
use std::path::Path;

/// The bound of issue "Nothing a peer sends can exhaust the daemon": 150 MB resident.
const MAX_RSS_KB: u64 = 150 * 1024;

/// Bulk messages of 1 MiB on `/camera/raw` (uncompressed chunks, so the file is as big as its data), with a
/// synthetic swing's samples on the rig's clubhead channel interleaved.
fn write_large_recording(path: &Path, bulk_mib: usize) -> usize {
    let file = std::io::BufWriter::new(std::fs::File::create(path).unwrap());
    let mut w = mcap::WriteOptions::new().compression(None).profile("").create(file).unwrap();
    let bulk = w.add_channel(0, "/camera/raw", "application/octet-stream", &BTreeMap::new()).unwrap();
    let samples_channel = w.add_channel(0, "/mocap/rig1/clubhead", "json", &BTreeMap::new()).unwrap();
    let samples = swing::samples(1, 720.0, 7);
    let payload = vec![0x5au8; 1 << 20];
    let per_bulk = samples.len().div_ceil(bulk_mib);
    let mut written = 0;
    for k in 0..bulk_mib {
        let t = 1_700_000_000_000_000_000u64 + k as u64 * 1_000_000;
        let header =
            mcap::records::MessageHeader { channel_id: bulk, sequence: k as u32, log_time: t, publish_time: t };
        w.write_to_known_channel(&header, &payload).unwrap();
        for s in samples.iter().skip(k * per_bulk).take(per_bulk) {
            let msg = serde_json::to_vec(&impactd::wire::ClubheadSampleMsg::from_sample("rig1", s)).unwrap();
            let header = mcap::records::MessageHeader {
                channel_id: samples_channel,
                sequence: written as u32,
                log_time: t + 1 + written as u64,
                publish_time: t,
            };
            w.write_to_known_channel(&header, &msg).unwrap();
            written += 1;
        }
    }
    w.finish().unwrap();
    written
}

/// Runs the binary with `args` through Python and returns (exit code, stdout, stderr, peak RSS in KiB).
fn run_measured(args: &[&str]) -> (i32, String, String, u64) {
    const MEASURE: &str = r#"
import json, resource, subprocess, sys
p = subprocess.run(sys.argv[1:], capture_output=True, text=True)
print(json.dumps(dict(code=p.returncode, out=p.stdout, err=p.stderr,
    maxrss_kb=resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)))
"#;
    let out = common::python().args(["-c", MEASURE, env!("CARGO_BIN_EXE_impactd")]).args(args).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let s = |k: &str| v[k].as_str().unwrap().to_string();
    (v["code"].as_i64().unwrap() as i32, s("out"), s("err"), v["maxrss_kb"].as_u64().unwrap())
}

#[test]
fn a_512_mb_recording_is_read_in_bounded_memory() {
    let dir = tempfile::tempdir().unwrap();
    let big = dir.path().join("big.mcap");
    let samples = write_large_recording(&big, 512);
    let size = std::fs::metadata(&big).unwrap().len();
    assert!(size > 512 << 20, "{size} bytes");

    let (code, out, err, rss) = run_measured(&["info", big.to_str().unwrap()]);
    eprintln!("info: exit {code}, peak RSS {} MiB", rss / 1024);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("/camera/raw") && out.contains("512"), "{out}");
    assert!(out.contains(&samples.to_string()), "every sample counted: {out}");
    assert!(rss < MAX_RSS_KB, "info held {rss} KiB");

    let replayed = dir.path().join("replayed.mcap");
    let args = ["replay", big.to_str().unwrap(), "-o", replayed.to_str().unwrap()];
    let (code, out, err, rss) = run_measured(&args);
    eprintln!("replay: exit {code}, peak RSS {} MiB", rss / 1024);
    assert!(err.contains(&format!("{samples} samples")) || out.contains(&format!("{samples} samples")), "{out}\n{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(rss < MAX_RSS_KB, "replay held {rss} KiB");

    let recovered = dir.path().join("recovered.mcap");
    let (code, _, err, rss) = run_measured(&["recover", big.to_str().unwrap(), "-o", recovered.to_str().unwrap()]);
    eprintln!("recover: exit {code}, peak RSS {} MiB", rss / 1024);
    assert_eq!(code, 0, "a finished file is recovered whole: {err}");
    assert!(err.contains(&format!("{} messages", 512 + samples)), "{err}");
    assert!(rss < MAX_RSS_KB, "recover held {rss} KiB");
}
