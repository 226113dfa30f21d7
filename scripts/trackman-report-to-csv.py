#!/usr/bin/env python3
"""TrackMan report JSON (multiGroupReport, TrackMan's web API) -> CSV in TrackMan's TPS export layout, for
`impactd compare`. Measurement (not NormalizedMeasurement) values; SI units as TrackMan gives them, speeds
written in [m/s] (the reader converts), impact location converted m -> mm by a decimal shift. A stroke missing
any club or ball value has its club speed left empty (the reader skips it); clubs with no preset (5-wood,
5-hybrid) are left out; `Spin Rate Type` is `Estimated` where `ReducedAccuracy` names the spin rate or axis.
An independent reading of the layout: `tests/cli/trackman_report.rs` checks that `impactd compare` gives the same
numbers on a report and on this script's CSV of it.

Usage: scripts/trackman-report-to-csv.py REPORT.json OUT.csv"""
import json, sys, csv
from decimal import Decimal

NAMES = {"Driver": "Driver", "4Iron": "4 Iron", "5Iron": "5 Iron", "6Iron": "6 Iron", "7Iron": "7 Iron",
         "8Iron": "8 Iron", "9Iron": "9 Iron", "PitchingWedge": "Pitching Wedge", "SandWedge": "Sand Wedge",
         "GapWedge": "Gap Wedge", "LobWedge": "Lob Wedge", "3Wood": "3 Wood"}
COLS = [("Date", ""), ("Club", ""), ("Ball", ""), ("Club Speed", "[m/s]"), ("Attack Angle", "[deg]"),
        ("Club Path", "[deg]"), ("Dyn. Loft", "[deg]"), ("Face Angle", "[deg]"), ("Face To Path", "[deg]"),
        ("Ball Speed", "[m/s]"), ("Smash Factor", "[]"), ("Launch Angle", "[deg]"), ("Launch Direction", "[deg]"),
        ("Spin Rate", "[rpm]"), ("Spin Rate Type", ""), ("Spin Axis", "[deg]"), ("Dynamic Lie", "[deg]"),
        ("Impact Offset", "[mm]"), ("Impact Height", "[mm]")]
CLUB = ["ClubSpeed", "AttackAngle", "ClubPath", "DynamicLoft", "FaceAngle"]
BALL = ["BallSpeed", "LaunchAngle", "LaunchDirection", "SpinRate", "SpinAxis"]

def mm(x):
    return format(Decimal(repr(x)) * 1000, "f")

def convert(path, out):
    j = json.load(open(path, encoding="utf-8"))
    w = csv.writer(out, lineterminator="\n")
    w.writerow([c for c, _ in COLS]); w.writerow([u for _, u in COLS])
    stats = {"rows": 0, "no_preset": {}, "incomplete": 0}
    for g in j["StrokeGroups"]:
        for s in g["Strokes"]:
            m = s.get("Measurement") or {}
            stats["rows"] += 1
            name = NAMES.get(s["Club"])
            if name is None:
                stats["no_preset"][s["Club"]] = stats["no_preset"].get(s["Club"], 0) + 1
                continue
            complete = all(k in m for k in CLUB + BALL)
            if not complete:
                stats["incomplete"] += 1
            ra = m.get("ReducedAccuracy") or []
            spin_type = "Estimated" if ("SpinRate" in ra or "SpinAxis" in ra) else "Measured"
            v = lambda k: repr(m[k]) if k in m else ""
            w.writerow([s["Time"], name, s.get("Ball", ""),
                        v("ClubSpeed") if complete else "", v("AttackAngle"), v("ClubPath"), v("DynamicLoft"),
                        v("FaceAngle"), v("FaceToPath"), v("BallSpeed"), v("SmashFactor"), v("LaunchAngle"),
                        v("LaunchDirection"), v("SpinRate"), spin_type, v("SpinAxis"), v("DynamicLie"),
                        mm(m["ImpactOffset"]) if "ImpactOffset" in m else "",
                        mm(m["ImpactHeight"]) if "ImpactHeight" in m else ""])
    return stats

if __name__ == "__main__":
    st = convert(sys.argv[1], open(sys.argv[2], "w", encoding="utf-8"))
    print(sys.argv[1], st, file=sys.stderr)
