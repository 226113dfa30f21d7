"""A synthetic capture of a swing with a known truth, written as a lab would have it: C3D (by PyPI `c3d`), TRC and a
pose table (both written here, by nothing of impactd's), from the club's true poses.

Input: a JSONL file of the club frame's true poses in the world (one line a frame at the capture's rate:
`{"position_m": [x, y, z], "xyzw": [x, y, z, w]}`; the world is TrackMan's: x toward the target, y up, the ball's
centre at the origin). Output, in OUT_DIR:

- `swing.c3d`, `swing.trc`: markers in the lab's axes (a Y-up or a Z-up lab, somewhere else than the ball), in
  millimetres (the TRC in `--trc-units`): four on the head (CROWN, TOE, HOSEL, BACK, at unequal distances), two on
  the shaft (SHAFT_LO, SHAFT_HI; with `--grip-m D` a third, HANDLE, D up the shaft's axis from the hosel), three on the floor (FLOOR_A/B/C), a target-line pair (TARGET_REAR/FRONT) and
  one on top of the ball (BALL, gone once the ball is struck); marker noise `--noise-mm`, BACK lost for 30 ms on
  the downswing, CROWN for 3 frames after impact, and TOE a ghost 12 mm off in the frame before impact.
- `swing.csv` and its sidecar `swing.csv.columns`: the face centre's pose in the lab (mm, the orientation as
  `--orientation`), the ball's centre, at the same rate, two rows before impact empty (not seen).
- `markers.toml`: the head markers in the club frame (the body is the club frame: `club_from_body` identity).
- `lab.json`: `world_from_lab` (`rotation_xyzw`, `translation_m`) and the ball marker's offset to the ball's centre
  in the lab's axes (`ball_offset_mm`).

Usage: synth_capture.py TRUTH.jsonl OUT_DIR --rate HZ --lab y-up|z-up --noise-mm MM --seed N
       --face-centre X,Y,Z --impact-frame I [--trc-units mm|cm|m] [--orientation quaternion|matrix|euler-ZYX]
       [--grip-m D]
"""

import argparse
import json
import math
import os

import numpy as np
import c3d

BALL_RADIUS_M = 0.021335
MARKER_RADIUS_M = 0.007
# The head markers in the club frame (m: x toward the target at a square address, y up, z toward the toe; origin
# at the head's CG).
HEAD = {
    "CROWN": (-0.040, 0.030, 0.005),
    "TOE": (-0.010, 0.012, 0.055),
    "HOSEL": (0.005, 0.040, -0.045),
    "BACK": (-0.085, 0.015, 0.012),
}
LIE_RAD = math.radians(58.0)
SHAFT_DIR = np.array([0.0, math.sin(LIE_RAD), -math.cos(LIE_RAD)])
FLOOR_Y = -BALL_RADIUS_M + MARKER_RADIUS_M
STATIC_WORLD = {
    "FLOOR_A": (-0.9, FLOOR_Y, 0.7),
    "FLOOR_B": (0.8, FLOOR_Y, 0.9),
    "FLOOR_C": (0.2, FLOOR_Y, -1.1),
    "TARGET_REAR": (-1.6, FLOOR_Y, 0.0),
    "TARGET_FRONT": (1.7, FLOOR_Y, 0.0),
}
BALL_MARKER_WORLD = np.array([0.0, BALL_RADIUS_M + MARKER_RADIUS_M, 0.0])


def quat_to_matrix(x, y, z, w):
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])


def matrix_to_quat(m):
    """xyzw, w >= 0 (Shepperd's method)."""
    t = np.trace(m)
    if t > 0:
        s = math.sqrt(t + 1.0) * 2
        q = ((m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s, 0.25 * s)
    elif m[0, 0] > m[1, 1] and m[0, 0] > m[2, 2]:
        s = math.sqrt(1.0 + m[0, 0] - m[1, 1] - m[2, 2]) * 2
        q = (0.25 * s, (m[0, 1] + m[1, 0]) / s, (m[0, 2] + m[2, 0]) / s, (m[2, 1] - m[1, 2]) / s)
    elif m[1, 1] > m[2, 2]:
        s = math.sqrt(1.0 + m[1, 1] - m[0, 0] - m[2, 2]) * 2
        q = ((m[0, 1] + m[1, 0]) / s, 0.25 * s, (m[1, 2] + m[2, 1]) / s, (m[0, 2] - m[2, 0]) / s)
    else:
        s = math.sqrt(1.0 + m[2, 2] - m[0, 0] - m[1, 1]) * 2
        q = ((m[0, 2] + m[2, 0]) / s, (m[1, 2] + m[2, 1]) / s, 0.25 * s, (m[1, 0] - m[0, 1]) / s)
    q = np.array(q)
    return q if q[3] >= 0 else -q


def euler_zyx(m):
    """Intrinsic Z, Y, X angles (rad) of a rotation matrix: m = Rz(a) Ry(b) Rx(c)."""
    b = math.asin(max(-1.0, min(1.0, -m[2, 0])))
    a = math.atan2(m[1, 0], m[0, 0])
    c = math.atan2(m[2, 1], m[2, 2])
    return a, b, c


def lab_from_world(lab):
    """The lab's axes and origin: a Y-up lab (Motive's) facing across the target line, or a Z-up lab (Vicon's,
    Qualisys's) with x along it; neither has its origin at the ball."""
    if lab == "y-up":
        # lab x = -world z, lab y = world y, lab z = world x; the ball's centre at lab (1.2, 0, 0.8).
        r = np.array([[0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]])
        t = np.array([1.2, 0.0, 0.8])
    else:
        # lab x = world x, lab y = -world z, lab z = world y; the ball's centre at lab (2.0, -0.5, 0).
        r = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]])
        t = np.array([2.0, -0.5, 0.0])
    return r, t


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("truth")
    ap.add_argument("out")
    ap.add_argument("--rate", type=float, required=True)
    ap.add_argument("--lab", choices=["y-up", "z-up"], required=True)
    ap.add_argument("--noise-mm", type=float, default=0.2)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--face-centre", required=True)
    ap.add_argument("--impact-frame", type=int, required=True)
    ap.add_argument("--trc-units", choices=["mm", "cm", "m"], default="mm")
    ap.add_argument("--orientation", choices=["quaternion", "matrix", "euler-ZYX"], default="quaternion")
    ap.add_argument("--grip-m", type=float, default=None)
    a = ap.parse_args()
    rng = np.random.default_rng(a.seed)
    face_centre = np.array([float(v) for v in a.face_centre.split(",")])
    poses = [json.loads(line) for line in open(a.truth) if line.strip()]
    r_lw, t_lw = lab_from_world(a.lab)
    to_lab = lambda p_world: r_lw @ p_world + t_lw
    dt = 1.0 / a.rate
    i_impact = a.impact_frame

    shaft = ["SHAFT_LO", "SHAFT_HI"] + (["HANDLE"] if a.grip_m is not None else [])
    labels = list(HEAD) + shaft + list(STATIC_WORLD) + ["BALL"]
    frames = []  # per frame, per label: lab position (m) or None
    table = []  # per frame: (time_s, face centre lab m, lab_from_club rotation, ball lab m) or None cells
    for i, pose in enumerate(poses):
        r_wc = quat_to_matrix(*pose["xyzw"])
        p_wc = np.array(pose["position_m"])
        club_to_lab = lambda p_club: to_lab(r_wc @ np.array(p_club) + p_wc)
        row = {}
        for name, p in HEAD.items():
            row[name] = club_to_lab(p)
        hosel = np.array(HEAD["HOSEL"])
        row["SHAFT_LO"] = club_to_lab(hosel + 0.22 * SHAFT_DIR)
        row["SHAFT_HI"] = club_to_lab(hosel + 0.61 * SHAFT_DIR)
        if a.grip_m is not None:
            row["HANDLE"] = club_to_lab(hosel + a.grip_m * SHAFT_DIR)
        for name, p in STATIC_WORLD.items():
            row[name] = to_lab(np.array(p))
        row["BALL"] = to_lab(BALL_MARKER_WORLD) if i < i_impact else None
        for name in labels:
            if row[name] is not None:
                row[name] = row[name] + rng.normal(0.0, a.noise_mm * 1e-3, 3)
        t_rel = (i - i_impact) * dt
        if -0.060 <= t_rel < -0.030:
            row["BACK"] = None
        if i_impact + 4 <= i < i_impact + 7:
            row["CROWN"] = None
        if i == i_impact - 1:
            row["TOE"] = row["TOE"] + r_lw @ np.array([0.012, 0.0, 0.0])
        frames.append([row[name] for name in labels])
        # The face centre's pose, with a tracker's noise (about what a four-marker fit gives).
        if i in (i_impact - 9, i_impact - 8):
            table.append((i * dt, None, None, to_lab(np.zeros(3))))
            continue
        r_lc = r_lw @ r_wc
        noise_rot = rng.normal(0.0, math.radians(0.05), 3)
        k = np.array([[0, -noise_rot[2], noise_rot[1]], [noise_rot[2], 0, -noise_rot[0]], [-noise_rot[1], noise_rot[0], 0]])
        r_lc = (np.eye(3) + k + 0.5 * k @ k) @ r_lc
        u, _, vt = np.linalg.svd(r_lc)
        r_lc = u @ vt
        fc = club_to_lab(face_centre) + rng.normal(0.0, a.noise_mm * 0.5e-3, 3)
        ball = to_lab(np.zeros(3)) if i < i_impact else None
        table.append((i * dt, fc, r_lc, ball))

    os.makedirs(a.out, exist_ok=True)
    # C3D, by PyPI c3d: float data in millimetres, a lost marker's residual -1.
    w = c3d.Writer(point_rate=a.rate, analog_rate=0.0, point_scale=-0.1, point_units="mm  ")
    w.set_point_labels(labels)
    empty = np.zeros((0, 0), dtype=np.float32)
    for row in frames:
        points = np.zeros((len(row), 5), dtype=np.float32)
        for j, p in enumerate(row):
            if p is None:
                points[j] = (0.0, 0.0, 0.0, -1.0, 0)
            else:
                points[j] = (p[0] * 1e3, p[1] * 1e3, p[2] * 1e3, 0.1, 1)
        w.add_frames([(points, empty)])
    with open(os.path.join(a.out, "swing.c3d"), "wb") as h:
        w.write(h)

    # TRC, as OpenSim writes it: five header lines, tab-separated, empty cells for a lost marker.
    scale = {"mm": 1e3, "cm": 1e2, "m": 1.0}[a.trc_units]
    n = len(frames)
    with open(os.path.join(a.out, "swing.trc"), "w", newline="") as h:
        h.write("PathFileType\t4\t(X/Y/Z)\tswing.trc\n")
        h.write("DataRate\tCameraRate\tNumFrames\tNumMarkers\tUnits\tOrigDataRate\tOrigDataStartFrame\tOrigNumFrames\n")
        h.write(f"{a.rate:.2f}\t{a.rate:.2f}\t{n}\t{len(labels)}\t{a.trc_units}\t{a.rate:.2f}\t1\t{n}\n")
        h.write("Frame#\tTime\t" + "\t".join(name + "\t\t" for name in labels) + "\n")
        h.write("\t\t" + "\t".join(f"X{k + 1}\tY{k + 1}\tZ{k + 1}" for k in range(len(labels))) + "\n")
        h.write("\n")
        for i, row in enumerate(frames):
            cells = [str(i + 1), f"{i * dt:.6f}"]
            for p in row:
                cells += ["", "", ""] if p is None else [f"{v * scale:.5f}" for v in p]
            h.write("\t".join(cells) + "\n")

    # The pose table and its sidecar column spec.
    if a.orientation == "quaternion":
        o_names = ["qw", "qx", "qy", "qz"]
        o_spec = "quaternion-wxyz=qw,qx,qy,qz"
    elif a.orientation == "matrix":
        o_names = [f"r{r}{c}" for r in range(1, 4) for c in range(1, 4)]
        o_spec = "matrix=" + ",".join(o_names)
    else:
        o_names = ["yaw_deg", "pitch_deg", "roll_deg"]
        o_spec = "euler-ZYX=yaw_deg,pitch_deg,roll_deg:deg"
    with open(os.path.join(a.out, "swing.csv"), "w", newline="") as h:
        h.write("# face-centre poses, synthetic\n")
        h.write(",".join(["time_s", "fc_x_mm", "fc_y_mm", "fc_z_mm"] + o_names + ["ball_x_mm", "ball_y_mm", "ball_z_mm"]) + "\n")
        for t, fc, r, ball in table:
            cells = [f"{t:.6f}"]
            if fc is None:
                cells += [""] * (3 + len(o_names))
            else:
                cells += [f"{v * 1e3:.4f}" for v in fc]
                if a.orientation == "quaternion":
                    x, y, z, qw = matrix_to_quat(r)
                    cells += [f"{v:.9f}" for v in (qw, x, y, z)]
                elif a.orientation == "matrix":
                    cells += [f"{r[i, j]:.9f}" for i in range(3) for j in range(3)]
                else:
                    cells += [f"{math.degrees(v):.7f}" for v in euler_zyx(r)]
            cells += [""] * 3 if ball is None else [f"{v * 1e3:.4f}" for v in ball]
            h.write(",".join(cells) + "\n")
    with open(os.path.join(a.out, "swing.csv.columns"), "w") as h:
        h.write("# the face centre's pose in the lab\n")
        h.write(f"time=time_s:s\nposition=fc_x_mm,fc_y_mm,fc_z_mm:mm\n{o_spec}\nball=ball_x_mm,ball_y_mm,ball_z_mm\norigin=face-centre\n")

    with open(os.path.join(a.out, "markers.toml"), "w") as h:
        h.write("[markers]\n")
        for name, p in HEAD.items():
            h.write(f"{name} = [{p[0]}, {p[1]}, {p[2]}]\n")
    r_wl = r_lw.T
    t_wl = -r_wl @ t_lw
    ball_offset_lab_mm = r_lw @ (np.zeros(3) - BALL_MARKER_WORLD) * 1e3
    with open(os.path.join(a.out, "lab.json"), "w") as h:
        json.dump({
            "rotation_xyzw": list(matrix_to_quat(r_wl)),
            "translation_m": list(t_wl),
            "ball_offset_mm": list(ball_offset_lab_mm),
        }, h)


if __name__ == "__main__":
    main()
