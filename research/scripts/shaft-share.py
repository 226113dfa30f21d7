#!/usr/bin/env python3
"""The shaft's share of the heel-toe inertia of each iron preset, from the seed's flexible shaft.

A strike above or below the CG turns the head about its heel-toe axis; the hosel, 40-60 mm above the CG, then
swings fore and aft and the shaft's tip goes with it during the contact. The ground model carries the seed's
shaft (Table 4.1, beam elements, chapter 4); with --soil none it is the same strike on a tee. The share is the
inertia that, added to the free head's about its heel-toe axis, makes the continuous model lose as much ball
speed from the face centre to 10 mm above it as the head on the seed's shaft does (bisection on the drop).

Usage: research/scripts/shaft-share.py [PRESET...]   (default: iron4-iron9 but the seed's iron7, and the four wedges)
"""
import json
import re
import subprocess
import sys
import tempfile
from pathlib import Path

BIN = Path(__file__).resolve().parents[2] / "target" / "release" / "impactd"
PRESETS = Path(__file__).resolve().parents[2] / "clubs" / "presets"


def speeds(club, model, extra=()):
    """Ball speed (mph) at the face centre and 10 mm above it, 85 mph, attack -4 deg, 4 deg of shaft lean."""
    loft = float(re.search(r"^loft_deg = ([0-9.]+)", Path(club).read_text(), re.M).group(1))
    lines = "".join(
        json.dumps({"club_speed_mph": 85, "attack_angle_deg": -4, "dynamic_loft_deg": loft - 4, "impact_v_mm": v}) + "\n"
        for v in (0.0, 10.0)
    )
    out = subprocess.run([str(BIN), "predict", "--club", club, "--model", model, *extra], input=lines,
                         capture_output=True, text=True, check=True).stdout
    return [json.loads(l)["ball_speed_mph"] for l in out.splitlines()]


def with_share(text, share):
    text = re.sub(r"^shaft_heel_toe_inertia_g_cm2 = .*\n", "", text, flags=re.M)
    # Before any [section] table, where a top-level key belongs.
    return re.sub(r"^(name = .*\n)", lambda m: m.group(1) + f"shaft_heel_toe_inertia_g_cm2 = {share:.1f}\n", text,
                  count=1, flags=re.M)


def share_of(preset):
    text = (PRESETS / f"{preset}.toml").read_text()
    with tempfile.TemporaryDirectory() as d:
        head = Path(d) / "club.toml"
        head.write_text(with_share(text, 0.0))
        c, h = speeds(str(head), "ground", ("--soil", "none"))
        target = c - h
        lo, hi = 0.0, 5000.0
        for _ in range(30):
            mid = 0.5 * (lo + hi)
            head.write_text(with_share(text, mid))
            c, h = speeds(str(head), "continuous")
            if c - h > target:
                lo = mid
            else:
                hi = mid
        return 0.5 * (lo + hi), target


if __name__ == "__main__":
    names = sys.argv[1:] or ["iron4", "iron5", "iron6", "iron8", "iron9", "pw", "gw", "sw", "lw"]
    for p in names:
        share, drop = share_of(p)
        print(f"{p}: shaft_heel_toe_inertia_g_cm2 = {share:.0f}   # drop 0 -> 10 mm on the seed's shaft: {drop:.2f} mph")
