#!/usr/bin/env python3
"""Regenerates the table of research/offcentre-iron.md (between `<!-- generated: offcentre -->` and `<!-- end -->`)
from `impactd predict --club iron7 --model M` for the adjusted and continuous models.

Usage: research/scripts/offcentre-iron.py [path/to/impactd]   (default target/release/impactd; run from the repository)
"""
import json
import re
import subprocess
import sys

BIN = sys.argv[1] if len(sys.argv) > 1 else "target/release/impactd"
DOC = "research/offcentre-iron.md"
# The measured shot pair's delivery: 85 mph club speed (Golf Australia 2019); attack -4.5 deg (TrackMan's tour
# 8-iron average, reference/trackman-pga-tour-averages.csv); dynamic loft 32 deg, which gives the measured
# centre strike's ball speed and backspin within 2 % and 4 % with the adjusted model.
DELIVERY = {"club_speed_mph": 85.0, "attack_angle_deg": -4.5, "dynamic_loft_deg": 32.0}
# Impact locations (toe +, up +, mm) and the measured change of ball speed from the centre, where one exists.
ROWS = [
    ("centre", 0.0, 0.0, None),
    ("17 mm toe", 17.0, 0.0, -5.7),
    ("17 mm toe, 3 mm low", 17.0, -3.0, -5.7),
    ("17 mm heel", -17.0, 0.0, None),
    ("19 mm toe (3/4 in)", 19.0, 0.0, None),
    ("19 mm heel (3/4 in)", -19.0, 0.0, None),
    ("8 mm low", 0.0, -8.0, None),
    ("8 mm high", 0.0, 8.0, None),
]
MODELS = ["adjusted", "continuous"]


def predict(model):
    lines = "".join(json.dumps(dict(DELIVERY, impact_h_mm=h, impact_v_mm=v)) + "\n" for _, h, v, _ in ROWS)
    out = subprocess.run([BIN, "predict", "--club", "iron7", "--model", model], input=lines, text=True,
                         capture_output=True, check=True).stdout
    return [json.loads(l) for l in out.splitlines() if l.strip()]


def table():
    out = ["| model | impact | ball speed (mph) | change | measured change | difference | backspin (rpm) | "
           "change | sidespin (rpm, + fade) |", "|---|---|---|---|---|---|---|---|---|"]
    for model in MODELS:
        res = predict(model)
        c = res[0]
        for (name, _, _, measured), r in zip(ROWS, res):
            dv = 100.0 * (r["ball_speed_mph"] / c["ball_speed_mph"] - 1.0)
            ds = 100.0 * (r["backspin_rpm"] / c["backspin_rpm"] - 1.0)
            meas = "" if measured is None else f"{measured:+.1f} %"
            diff = "" if measured is None else f"{dv - measured:+.1f} points"
            base = name == "centre"
            out.append(
                f"| {model} | {name} | {r['ball_speed_mph']:.1f} | {'' if base else f'{dv:+.1f} %'} | {meas} | "
                f"{diff} | {r['backspin_rpm']:.0f} | {'' if base else f'{ds:+.1f} %'} | {r['sidespin_rpm']:+.0f} |")
    return "\n".join(out)


text = open(DOC).read()
new = re.sub(r"(<!-- generated: offcentre -->\n).*?(<!-- end -->)", lambda m: m.group(1) + table() + "\n" + m.group(2),
             text, flags=re.S)
open(DOC, "w").write(new)
print(f"wrote {DOC}", file=sys.stderr)
