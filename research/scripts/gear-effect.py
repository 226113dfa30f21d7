#!/usr/bin/env python3
"""Regenerates the off-centre tables of research/models-notes.md (regions `gear-driver` and `gear-iron`, between
`<!-- generated: NAME -->` and `<!-- end -->`) from `impactd predict [--flight]` for the impulse-momentum and
continuous models, the continuous one with Table 3.5's ball and with the one-cycle ball: the one-cycle club files
of clubs/, and the same files with Table 3.5's core-cover spring and damping (written to a temporary directory,
so the rows say which ball they use whichever the presets default to).

Usage: research/scripts/gear-effect.py [path/to/impactd]   (default target/release/impactd; run from the repository)
"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from docs_regions import replace  # noqa: E402

BIN = sys.argv[1] if len(sys.argv) > 1 else "target/release/impactd"
DOC = "research/models-notes.md"
# The driver delivery of the gear-effect question: 100 mph, level, square, 10.5 deg of dynamic loft.
DRIVER = {"club_speed_mph": 100.0, "attack_angle_deg": 0.0, "club_path_deg": 0.0, "face_angle_deg": 0.0,
          "dynamic_loft_deg": 10.5}
DRIVER_H_MM = [-20.0, 0.0, 20.0, 30.0]
# The 7-iron delivery of research/offcentre-iron.md (85 mph, -4.5 deg attack, 32 deg dynamic loft).
IRON = {"club_speed_mph": 85.0, "attack_angle_deg": -4.5, "dynamic_loft_deg": 32.0}
IRON_V_MM = [-12.0, -10.0, -8.0, -6.0, -4.0, -2.0, 0.0, 2.0, 4.0]
# Table 3.5's values that the one-cycle club files change (seed Table 3.5, as TwoLayerParams::DRIVER and IRON7).
TABLE_3_5 = {
    "driver": {"k_ball_nm_per_rad": "13.5", "c_ball_nms_per_rad": "2.53e-3", "d_s_per_m": "6.42e-3"},
    "iron7": {"k_ball_nm_per_rad": "34.1", "c_ball_nms_per_rad": "13.2e-3", "d_s_per_m": "9.26e-3"},
}
TMP = tempfile.mkdtemp()


def table_club(club):
    """The one-cycle club file of `club` with Table 3.5's ball."""
    with open(f"clubs/{club}-one-cycle.toml") as f:
        text = f.read()
    for key, value in TABLE_3_5[club].items():
        text, n = re.subn(rf"(?m)^{key}\s*=.*$", f"{key} = {value}", text)
        if n != 1:
            sys.exit(f"clubs/{club}-one-cycle.toml: no single {key}")
    path = os.path.join(TMP, f"{club}-table-3-5.toml")
    with open(path, "w") as f:
        f.write(text)
    return path


# (label, model, club)
DRIVER_MODELS = [
    ("adjusted", "adjusted", "driver"),
    ("standard", "standard", "driver"),
    ("continuous, Table 3.5 ball", "continuous", table_club("driver")),
    ("continuous, one-cycle ball", "continuous", "clubs/driver-one-cycle.toml"),
]
IRON_MODELS = [
    ("adjusted", "adjusted", "iron7"),
    ("standard", "standard", "iron7"),
    ("continuous, Table 3.5 ball", "continuous", table_club("iron7")),
    ("continuous, one-cycle ball", "continuous", "clubs/iron7-one-cycle.toml"),
]


def predict(model, club, deliveries, flight=False):
    lines = "".join(json.dumps(d) + "\n" for d in deliveries)
    args = [BIN, "predict", "--club", club, "--model", model] + (["--flight"] if flight else [])
    out = subprocess.run(args, input=lines, text=True, capture_output=True, check=True).stdout
    return [json.loads(l) for l in out.splitlines() if l.strip()]


def driver_table():
    rows = ["| model | impact | launch direction (deg) | sidespin (rpm, + fade) | change from centre (rpm) "
            "| offline (yd, right +) |", "|---|---|---|---|---|---|"]
    for label, model, club in DRIVER_MODELS:
        shots = predict(model, club, [dict(DRIVER, impact_h_mm=h, impact_v_mm=0.0) for h in DRIVER_H_MM], True)
        centre = shots[DRIVER_H_MM.index(0.0)]["sidespin_rpm"]
        for h, s in zip(DRIVER_H_MM, shots):
            where = "centre" if h == 0 else f"{abs(h):.0f} mm {'toe' if h > 0 else 'heel'}"
            change = "" if h == 0 else f"{s['sidespin_rpm'] - centre:+.0f}"
            rows.append(f"| {label} | {where} | {s['launch_direction_deg']:+.2f} | {s['sidespin_rpm']:+.0f} | "
                        f"{change} | {s['offline_yd']:+.1f} |")
    return "\n".join(rows)


def iron_table():
    cols = []
    for _, model, club in IRON_MODELS:
        shots = predict(model, club, [dict(IRON, impact_h_mm=0.0, impact_v_mm=v) for v in IRON_V_MM])
        cols.append([s["ball_speed_mph"] for s in shots])
    rows = ["| up the face (mm) | " + " | ".join(label for label, _, _ in IRON_MODELS) + " |",
            "|---|" + "---|" * len(IRON_MODELS)]
    for i, v in enumerate(IRON_V_MM):
        cells = []
        for col in cols:
            cell = f"{col[i]:.1f}"
            cells.append(f"**{cell}**" if col[i] == max(col) else cell)
        rows.append(f"| {v:+.0f} | " + " | ".join(cells) + " |")
    return "\n".join(rows)


try:
    replace(DOC, {"gear-driver": driver_table(), "gear-iron": iron_table()})
finally:
    shutil.rmtree(TMP, ignore_errors=True)
