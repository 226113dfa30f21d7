//! A 2 GB C3D capture is streamed, never loaded whole: `impactd import` reads all of its frames with a peak
//! resident set of a few tens of MiB. The capture's header and parameters are the independent writer's (PyPI
//! `c3d`: 255 markers, 530,000 frames announced, so `POINT:LONG_FRAMES`), its data section grown to hold every
//! frame (a sparse file: the frames after the first read as markers at the origin, residual 0, valid; the set does
//! not fit them, so every frame is occluded: what is measured is the streaming, not the fit).

#![allow(clippy::unwrap_used)]

use crate::common;

/// Peak resident set allowed: the binary, one 4 KiB frame and buffers; a reader that loaded the file would
/// hold 2 GiB.
const MAX_RSS_KB: u64 = 200 * 1024;

/// PyPI `c3d` writes the header and parameters of a capture of `frames` frames of 255 markers, with only its
/// first frame's data; the caller grows the data section.
const WRITE: &str = r#"
import sys
import numpy as np
import c3d
frames, out = int(sys.argv[1]), sys.argv[2]
class Announced(list):
    # The writer counts the frames with len() (header, POINT:FRAMES, LONG_FRAMES) and writes those it holds.
    def __len__(self): return frames
w = c3d.Writer(point_rate=500.0, analog_rate=0.0, point_scale=-0.1)
w.set_point_labels(["M%d" % i for i in range(255)])
points = np.zeros((255, 5), dtype=np.float32)
points[:, 0] = np.arange(255) * 10.0
points[:, 1] = 500.0
w._frames = Announced([(points, np.zeros((0, 0), dtype=np.float32))])
with open(out, "wb") as h:
    w.write(h)
"#;

#[test]
fn a_2_gb_capture_is_imported_in_bounded_memory() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("large.c3d");
    let frames = 530_000u64;
    let written = common::python().args(["-c", WRITE, &frames.to_string()]).arg(&path).output().unwrap();
    assert!(written.status.success(), "{}", String::from_utf8_lossy(&written.stderr));
    let reader = impactd::daemon::recording::c3d::open(&path).unwrap();
    let (start, frame_bytes) = (reader.info.data_start_byte, reader.info.frame_bytes as u64);
    assert_eq!(frame_bytes, 255 * 16);
    assert!(
        reader.info.warnings.iter().any(|w| w.starts_with("truncated: 1 of the 530000")),
        "{:?}",
        reader.info.warnings
    );
    drop(reader);
    // Room for every frame (sparse: they read as markers at the origin, residual 0, valid).
    std::fs::OpenOptions::new().write(true).open(&path).unwrap().set_len(start + frames * frame_bytes).unwrap();
    let size = std::fs::metadata(&path).unwrap().len();
    assert!(size > 2_000_000_000, "{size} bytes");

    let set = dir.path().join("set.toml");
    std::fs::write(&set, "[markers]\nM1 = [0.0, 0.0, 0.0]\nM2 = [0.03, 0.0, 0.0]\nM3 = [0.0, 0.02, 0.0]\n").unwrap();
    let out = dir.path().join("samples.jsonl");
    const MEASURE: &str = r#"
import json, resource, subprocess, sys
p = subprocess.run(sys.argv[1:], capture_output=True, text=True)
print(json.dumps(dict(code=p.returncode, err=p.stderr, maxrss_kb=resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)))
"#;
    let args = ["import", path.to_str().unwrap(), "--markers", set.to_str().unwrap(), "--rig", "bay1", "-o"];
    let run =
        common::python().args(["-c", MEASURE, env!("CARGO_BIN_EXE_impactd")]).args(args).arg(&out).output().unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let v: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    let (code, err, rss) = (v["code"].as_i64().unwrap(), v["err"].as_str().unwrap(), v["maxrss_kb"].as_u64().unwrap());
    eprintln!("import of {size} bytes: exit {code}, peak RSS {} MiB; {err}", rss / 1024);
    assert_eq!(code, 0, "{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(err.contains(&format!("{frames} frames")), "every frame read: {err}");
    let lines = std::io::BufRead::lines(std::io::BufReader::new(std::fs::File::open(&out).unwrap())).count() as u64;
    assert_eq!(lines, frames, "one sample per frame");
    assert!(rss < MAX_RSS_KB, "import held {rss} KiB");
}
