//! C3D files written by an independent writer: PyPI `c3d` (pinned in scripts/test-requirements.txt), float
//! data in millimetres, Intel format; labels of different lengths come out padded with trailing spaces.

#![allow(clippy::unwrap_used, dead_code)]

use std::path::Path;

use impactd::math::Vector3;

/// Writes `frames` (per frame, per marker: lab position in metres and whether it is valid; an invalid marker
/// gets a -1 residual and keeps the coordinates given) at `rate_hz`.
pub fn write_c3d(labels: &[String], rate_hz: f64, frames: &[Vec<(Vector3, bool)>], path: &Path) {
    let rows: Vec<Vec<[f64; 4]>> = frames
        .iter()
        .map(|row| row.iter().map(|(p, v)| [p.x * 1e3, p.y * 1e3, p.z * 1e3, if *v { 0.1 } else { -1.0 }]).collect())
        .collect();
    let json = path.with_extension("json");
    std::fs::write(&json, serde_json::json!({ "rate": rate_hz, "labels": labels, "frames": rows }).to_string())
        .unwrap();
    let script = r#"
import json, sys
import numpy as np
import c3d
data = json.load(open(sys.argv[1]))
w = c3d.Writer(point_rate=data["rate"], analog_rate=0.0, point_scale=-0.1)
w.set_point_labels(data["labels"])
empty = np.zeros((0, 0), dtype=np.float32)
for row in data["frames"]:
    points = np.zeros((len(row), 5), dtype=np.float32)
    for i, (x, y, z, r) in enumerate(row):
        points[i] = (x, y, z, r, 1 if r >= 0 else 0)
    w.add_frames([(points, empty)])
with open(sys.argv[2], "wb") as h:
    w.write(h)
"#;
    let out = super::common::python().arg("-c").arg(script).arg(&json).arg(path).output().unwrap();
    assert!(out.status.success(), "c3d writer: {}", String::from_utf8_lossy(&out.stderr));
}
