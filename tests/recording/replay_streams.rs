//! `impactd replay` streams its input: a C3D capture of 4 million frames and a JSONL file of 600,000 samples
//! (recorded with `-o` as it goes) replay with a peak resident set of a few tens of MiB, where holding every
//! sample (about 250 bytes each) took 1 GB and 150 MB; and a replay streamed from the file records exactly what
//! the same replay over the whole file in memory does, for the recordings the repository ships.

#![allow(clippy::unwrap_used)]
#![cfg(all(feature = "daemon", target_os = "linux"))]

use crate::common;
use crate::swing;

use std::io::Write;
use std::path::Path;

use impactd::daemon::replay::{self, ReplayOptions};

/// Peak resident set allowed to a replay: the binary and its buffers, not its input.
const MAX_RSS_KB: u64 = 100 * 1024;

/// Runs `impactd ARGS` under Python's `resource` (the child's peak resident set): exit code, stderr, stdout
/// lines, peak RSS (KiB).
fn measured(args: &[&str]) -> (i64, String, usize, u64) {
    const MEASURE: &str = r#"
import json, resource, subprocess, sys
p = subprocess.run(sys.argv[1:], capture_output=True, text=True)
print(json.dumps(dict(code=p.returncode, err=p.stderr, lines=len(p.stdout.splitlines()),
                      maxrss_kb=resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)))
"#;
    let out = common::python().args(["-c", MEASURE, env!("CARGO_BIN_EXE_impactd")]).args(args).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let err = v["err"].as_str().unwrap().to_string();
    (v["code"].as_i64().unwrap(), err, v["lines"].as_u64().unwrap() as usize, v["maxrss_kb"].as_u64().unwrap())
}

/// PyPI `c3d` writes the header and parameters of a capture of `frames` frames of 3 markers with only its first
/// frame's data; the test grows the data section (a sparse file: the other frames read as markers at the origin,
/// valid, which the set does not fit: every sample is occluded, and what is measured is the streaming).
const WRITE: &str = r#"
import sys
import numpy as np
import c3d
frames, out = int(sys.argv[1]), sys.argv[2]
class Announced(list):
    def __len__(self): return frames
w = c3d.Writer(point_rate=500.0, analog_rate=0.0, point_scale=-0.1)
w.set_point_labels(["M1", "M2", "M3"])
points = np.zeros((3, 5), dtype=np.float32)
points[:, 0] = np.arange(3) * 10.0
points[:, 1] = 500.0
w._frames = Announced([(points, np.zeros((0, 0), dtype=np.float32))])
with open(out, "wb") as h:
    w.write(h)
"#;

#[test]
fn a_capture_of_4_million_frames_replays_in_bounded_memory() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("large.c3d");
    let frames = 4_000_000u64;
    let written = common::python().args(["-c", WRITE, &frames.to_string()]).arg(&path).output().unwrap();
    assert!(written.status.success(), "{}", String::from_utf8_lossy(&written.stderr));
    let reader = impactd::daemon::recording::c3d::open(&path).unwrap();
    let (start, frame_bytes) = (reader.info.data_start_byte, reader.info.frame_bytes as u64);
    drop(reader);
    std::fs::OpenOptions::new().write(true).open(&path).unwrap().set_len(start + frames * frame_bytes).unwrap();
    let set = dir.path().join("set.toml");
    std::fs::write(&set, "[markers]\nM1 = [0.0, 0.0, 0.0]\nM2 = [0.03, 0.0, 0.0]\nM3 = [0.0, 0.02, 0.0]\n").unwrap();
    let (code, err, _, rss) =
        measured(&["replay", path.to_str().unwrap(), "--markers", set.to_str().unwrap(), "--rig", "bay1"]);
    eprintln!("replay of {frames} frames: exit {code}, peak RSS {} MiB; {err}", rss / 1024);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains(&format!("replayed {frames} samples")), "every frame replayed: {err}");
    assert!(err.contains(&format!("{frames} frames: {frames} occluded")), "the capture's counts: {err}");
    assert!(rss < MAX_RSS_KB, "replay held {rss} KiB");
}

#[test]
fn a_jsonl_file_of_600000_samples_replays_in_bounded_memory_recording_as_it_goes() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("samples.jsonl");
    // A swing of 4 shots, again and again, each time later in frames and capture time.
    let base = swing::samples(4, 720.0, 31);
    let span_ns = base.last().unwrap().t_ns - base[0].t_ns + 1_000_000_000;
    let span_frames = base.last().unwrap().frame - base[0].frame + 1000;
    let reps = 600_000 / base.len() + 1;
    let mut out = std::io::BufWriter::new(std::fs::File::create(&path).unwrap());
    let mut samples = 0u64;
    for r in 0..reps as u64 {
        for s in &base {
            let mut msg = impactd::wire::ClubheadSampleMsg::from_sample("bay1", s);
            msg.frame += r * span_frames;
            msg.t_ns += r * span_ns;
            serde_json::to_writer(&mut out, &msg).unwrap();
            out.write_all(b"\n").unwrap();
            samples += 1;
        }
    }
    out.flush().unwrap();
    drop(out);
    let size = std::fs::metadata(&path).unwrap().len();
    let recording = dir.path().join("replayed.mcap");
    let (code, err, lines, rss) =
        measured(&["replay", path.to_str().unwrap(), "--club", "driver", "-o", recording.to_str().unwrap()]);
    eprintln!("replay of {samples} samples ({size} bytes) with -o: exit {code}, peak RSS {} MiB; {err}", rss / 1024);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains(&format!("replayed {samples} samples")), "{err}");
    assert_eq!(lines as u64, 4 * reps as u64, "every shot predicted");
    assert!(rss < MAX_RSS_KB, "replay held {rss} KiB");
    // The recording holds every sample: its queue waited for the writer rather than drop.
    let info = std::process::Command::new(env!("CARGO_BIN_EXE_impactd")).arg("info").arg(&recording).output().unwrap();
    let text = String::from_utf8_lossy(&info.stdout);
    // `  /mocap/bay1/clubhead   impactd.ClubheadSample   600000 msgs   ...`
    let count = text.lines().find_map(|l| {
        let words: Vec<&str> = l.split_whitespace().collect();
        (words.first() == Some(&"/mocap/bay1/clubhead")).then(|| words[2].parse::<u64>().unwrap())
    });
    assert_eq!(count, Some(samples), "{text}");
}

/// Every message of a recording: topic, log time, publish time, bytes.
fn messages(path: &Path) -> Vec<(String, u64, u64, Vec<u8>)> {
    let bytes = std::fs::read(path).unwrap();
    mcap::MessageStream::new(&bytes)
        .unwrap()
        .map(|m| {
            let m = m.unwrap();
            (m.channel.topic.clone(), m.log_time, m.publish_time, m.data.into_owned())
        })
        .collect()
}

/// The replay streamed from the file (`impactd replay -o`) and the same replay over the file read whole
/// (`replay::load`, the in-memory input) record the same messages, with the same times, and reproduce the
/// recorded predictions.
#[tokio::test(flavor = "multi_thread")]
async fn a_streamed_replay_records_what_the_whole_file_replayed_in_memory_does() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = tempfile::tempdir().unwrap();
    for file in ["recordings/driver.mcap", "recordings/iron7.mcap", "tests/data/driver-former-names.mcap"] {
        let input = root.join(file);
        let streamed = dir.path().join("streamed.mcap");
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_impactd"))
            .arg("replay")
            .arg(&input)
            .arg("-o")
            .arg(&streamed)
            .arg("--overwrite")
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{file}: {err}");
        assert!(err.contains("recorded predictions reproduced byte for byte"), "{file}: {err}");

        let whole = replay::load(&input).unwrap();
        let (config, setups) = replay::resolve_config(&whole, None).unwrap();
        let in_memory = dir.path().join("in-memory.mcap");
        let options = ReplayOptions { output: Some(in_memory.clone()), overwrite: true, ..Default::default() };
        let report = replay::run(&whole, &config, setups, None, &options, |_, _| {}).await.unwrap();
        assert!(report.reproduces_recording(), "{file}: {report:?}");
        let (a, b) = (messages(&streamed), messages(&in_memory));
        assert_eq!(a.len(), b.len(), "{file}");
        for (i, (x, y)) in a.iter().zip(&b).enumerate() {
            assert_eq!(x, y, "{file}: message {i}");
        }
    }
}
