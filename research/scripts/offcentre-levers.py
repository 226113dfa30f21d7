#!/usr/bin/env python3
"""What each physical lever would do on the kept sessions (research/offcentre-monitors.md, "Causes weighed"): copies
of the iron and driver presets with one number changed, run through research/scripts/offcentre-monitors.py (the
same strokes, the same measures). Nothing here is adopted by a preset: it says how large a change each target needs,
to set beside what published club data supports.

Irons (iron4-iron9, pw): the 7-iron with the shaft's share its sister presets carry (594 g cm2,
research/scripts/shaft-share.py iron7); the heel-toe inertia (head and share) scaled by k; the normal COR (seed
eq. 3.6) below the rules limit's 0.83 (`predict --cor`). Driver: the inertia about the vertical axis scaled by k.

Usage: research/scripts/offcentre-levers.py [BIN]   (BIN default target/release/impactd; prints markdown rows)
"""
import json
import os
import re
import subprocess
import sys
import tempfile

BIN = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else "target/release/impactd")
IRONS = ["iron4", "iron5", "iron6", "iron7", "iron8", "iron9", "pw"]
SHARE_IRON7_G_CM2 = 594.0
TMP = tempfile.mkdtemp()


def preset(club):
    return open(f"clubs/presets/{club}.toml", encoding="utf-8").read()


def with_share(club, text):
    if club == "iron7":
        text = re.sub(r"^(name = .*\n)", rf"\1shaft_heel_toe_inertia_g_cm2 = {SHARE_IRON7_G_CM2}\n", text, count=1,
                      flags=re.M)
    return text


def scaled(text, axis, k):
    m = re.search(r"^inertia_g_cm2 = (.*)$", text, re.M)
    inertia = json.loads(m.group(1))
    inertia[axis][axis] *= k
    text = text.replace(m.group(0), "inertia_g_cm2 = " + json.dumps(inertia))
    s = re.search(r"^shaft_heel_toe_inertia_g_cm2 = ([0-9.]+)", text, re.M)
    if s and axis == 2:
        text = text.replace(s.group(0), f"shaft_heel_toe_inertia_g_cm2 = {float(s.group(1)) * k:.1f}")
    return text


def files(tag, edit, clubs):
    args = []
    for c in clubs:
        path = os.path.join(TMP, f"{tag}-{c}.toml")
        open(path, "w", encoding="utf-8").write(edit(c, preset(c)))
        args.append(f"{c}={path}")
    return args


def binary(cor):
    if cor is None:
        return BIN
    path = os.path.join(TMP, f"cor{cor}.sh")
    open(path, "w").write(f'#!/bin/sh\nexec "{BIN}" "$@" --cor {cor}\n')
    os.chmod(path, 0o755)
    return path


def run(args, cor=None):
    out = subprocess.run([sys.executable, "research/scripts/offcentre-monitors.py", binary(cor), "", *args],
                         capture_output=True, text=True, check=True).stdout
    return [json.loads(line) for line in out.splitlines()]


def iron_rows():
    print("| irons: the change | model | ball speed MAE / bias (mph) | error vs height (mph/mm) | spin MAE (rpm) |")
    print("|---|---|---|---|---|")
    cases = [("the presets", lambda c, t: t, None), ("iron7 with its shaft share", with_share, None)]
    for k in (1.5, 2.0):
        cases.append((f"heel-toe inertia x {k}", lambda c, t, k=k: scaled(with_share(c, t), 2, k), None))
    for cor in ("0.80", "0.78"):
        cases.append((f"iron7 share, COR {cor}", with_share, cor))
        for k in (1.5, 2.0):
            cases.append((f"heel-toe inertia x {k}, COR {cor}", lambda c, t, k=k: scaled(with_share(c, t), 2, k), cor))
    for label, edit, cor in cases:
        for j in run(files(label.replace(" ", "_"), edit, IRONS), cor):
            if j["clubs"] == "irons" and j["model"] in ("standard", "adjusted", "slip"):
                print(f"| {label} | {j['model']} | {j['ball_mae_mph']:.2f} / {j['ball_bias_mph']:+.2f} | "
                      f"{j['ball_slope_height_mph_per_mm']:+.3f} | {j['spin_mae_rpm']:.0f} |")


def driver_rows():
    print()
    print("| driver: the change | face read at | model | axis MAE (deg) | axis vs offset, model (measured) (deg/mm) |"
          " axis vs face to path, model (measured) |")
    print("|---|---|---|---|---|---|")
    for k in (1.0, 1.2, 1.5):
        label = "the preset" if k == 1.0 else f"vertical-axis inertia x {k}"
        for j in run(files(f"iyy{k}", lambda c, t, k=k: scaled(t, 1, k), ["driver"])):
            if j["clubs"] == "driver" and j["model"] in ("standard", "slip", "continuous"):
                m, s = j["axis_slopes_model"], j["axis_slopes_measured"]
                print(f"| {label} | {'contact point' if j['reading'] == 'contact' else 'face centre'} | {j['model']} | "
                      f"{j['axis_mae_deg']:.2f} | {m[1]:+.3f} ({s[1]:+.3f}) | {m[0]:.2f} ({s[0]:.2f}) |")


iron_rows()
driver_rows()
