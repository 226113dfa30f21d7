"""Real captures through `impactd import`, as C3D and as TRC: GEARS Golf's "Tour average" driver and iron swings
(360 Hz C3D exports, 38 markers: the golfer's, three on the clubhead, three on the shaft), from the MIT-licensed
D-sorganization/Golf_Modeling_Suite repository
(`engines/Simscape_Multibody_Models/3D_Golf_Model/matlab/Data/Gears C3D Files/`).

For each capture: the TRC is written here from the C3D as read by PyPI `c3d` (in millimetres, empty cells for
invalid markers), independently of impactd; a marker set of the three clubhead markers is calibrated from the
first frame (`impactd calibrate body`); `impactd import` reads the C3D and the TRC with it; the two sample files
are compared, and the fitted body's peak speed is set against the capture's own: the peak speed of the three
head markers' centroid, by central differences over frames where all three are valid, from py-c3d's reading.

Usage: python research/scripts/real-captures.py IMPACTD CAPTURE.c3d [CAPTURE.c3d ...]
"""

import json
import os
import subprocess
import sys
import tempfile
import warnings

import numpy as np
import c3d

HEAD = ["Marker_2:2:1", "Marker_2:2:2", "Marker_2:2:3"]
MPH = 0.44704


def read(path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = c3d.Reader(open(path, "rb"))
        labels = [l.strip() for l in r.point_labels]
        frames = np.array([p.copy() for _, p, _ in r.read_frames()])
        units = r.get("POINT:UNITS").string_value.strip()
    return r.point_rate, labels, frames, units


def write_trc(path, rate, labels, frames, to_mm):
    n = len(frames)
    with open(path, "w", newline="") as h:
        h.write(f"PathFileType\t4\t(X/Y/Z)\t{os.path.basename(path)}\n")
        h.write("DataRate\tCameraRate\tNumFrames\tNumMarkers\tUnits\tOrigDataRate\tOrigDataStartFrame\tOrigNumFrames\n")
        h.write(f"{rate:g}\t{rate:g}\t{n}\t{len(labels)}\tmm\t{rate:g}\t1\t{n}\n")
        h.write("Frame#\tTime\t" + "\t".join(l + "\t\t" for l in labels) + "\n")
        h.write("\t\t" + "\t".join(f"X{k}\tY{k}\tZ{k}" for k in range(1, len(labels) + 1)) + "\n\n")
        for i, f in enumerate(frames):
            cells = [str(i + 1), f"{i / rate:.6f}"]
            for p in f:
                cells += ["", "", ""] if p[3] < 0 else [f"{v * to_mm:.4f}" for v in p[:3]]
            h.write("\t".join(cells) + "\n")


def peak_speed(times_s, points, valid):
    best = (0.0, -1)
    for i in range(1, len(points) - 1):
        if valid[i - 1] and valid[i + 1]:
            v = np.linalg.norm(points[i + 1] - points[i - 1]) / (times_s[i + 1] - times_s[i - 1])
            best = max(best, (v, i))
    return best


def run(impactd, *args):
    out = subprocess.run([impactd, *args], capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"impactd {' '.join(args)}: {out.stderr}")
    return out.stderr


def main():
    impactd, captures = sys.argv[1], sys.argv[2:]
    print("| capture | rate | frames | capture's own head speed (centroid) | import C3D: body speed | import TRC: body speed | C3D and TRC samples differ by |")
    print("|---|---|---|---|---|---|---|")
    for capture in captures:
        rate, labels, frames, units = read(capture)
        to_mm = {"m": 1e3, "mm": 1.0, "cm": 10.0}[units]
        idx = [labels.index(l) for l in HEAD]
        valid = (frames[:, idx, 3] >= 0).all(axis=1)
        centroid = frames[:, idx, :3].mean(axis=1) * to_mm * 1e-3
        times = np.arange(len(frames)) / rate
        own, at = peak_speed(times, centroid, valid)
        with tempfile.TemporaryDirectory() as d:
            trc = os.path.join(d, "capture.trc")
            write_trc(trc, rate, labels, frames, to_mm)
            first = int(np.argmax(valid))
            marker_set = os.path.join(d, "head.toml")
            run(impactd, "calibrate", "body", capture, "--labels", ",".join(HEAD), "--frame", str(first), "--frames", "1", "-o", marker_set)
            speeds, samples = [], []
            for f in (capture, trc):
                out = os.path.join(d, os.path.basename(f) + ".jsonl")
                run(impactd, "import", f, "--markers", marker_set, "--rig", "gears", "-o", out)
                s = [json.loads(l) for l in open(out)]
                samples.append(s)
                p = np.array([x["position_m"] for x in s])
                ok = np.array([not x["occluded"] for x in s])
                t = np.array([x["t_ns"] for x in s]) * 1e-9
                speeds.append(peak_speed(t, p, ok))
            diff = max(np.abs(np.array(a["position_m"]) - np.array(b["position_m"])).max() for a, b in zip(*samples))
        name = os.path.basename(capture)
        print(f"| `{name}` | {rate:g} Hz | {len(frames)} | {own / MPH:.1f} mph (frame {at + 1}) | "
              f"{speeds[0][0] / MPH:.1f} mph (frame {speeds[0][1] + 1}) | {speeds[1][0] / MPH:.1f} mph (frame {speeds[1][1] + 1}) | "
              f"{diff * 1e3:.4f} mm |")


if __name__ == "__main__":
    main()
