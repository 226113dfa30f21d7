#!/usr/bin/env python3
"""Off-centre strikes on the kept measured sessions (research/offcentre-monitors.md): ball-speed error against
impact height and offset, the spin axis' partial slopes (face to path, offset, height held), axis MAE, spin MAE.

Reads only the VALIDATION sessions in tests/data/trackman/ (the third player's report JSON of 2025-03-13,
2025-07-11, 2025-10-30, 2026-02-14 and the validation CSV validation-8i-5i.csv); the held-out files in
research/data/trackman/ are not read. Each stroke with club data, an impact location and measured spin (as
`compare --by-club --located` selects it) is run through `impactd predict` on its club's preset. The delivery is
TrackMan's numbers as they stand (its loft and face at the contact point): on the flat faces of the irons that is
also the face centre's; for the driver both readings are reported, the face centre's (the number read as the face
centre's) and the contact point's (the face centre turned back by h / R_bulge and v / R_roll, first order, as
`compare --by-club` reads TrackMan).

Usage: research/scripts/offcentre-monitors.py [BIN] [LABEL] [PRESET=CLUB_FILE ...]   (BIN default
target/release/impactd)
Prints one JSON object per (clubs, reading, model); plain python3, no numpy.
"""
import csv
import json
import math
import subprocess
import sys

BIN = sys.argv[1] if len(sys.argv) > 1 else "target/release/impactd"
LABEL = sys.argv[2] if len(sys.argv) > 2 else ""
# PRESET=FILE pairs after the label run that preset's shots on a club file instead (a preset as it was or will be).
CLUB_FILES = dict(a.split("=", 1) for a in sys.argv[3:])
DATA = "tests/data/trackman"
REPORTS = ["2025-03-13-pw-driver-5w-7i", "2025-07-11-driver-4i-5h-pw", "2025-10-30-5w-driver-6i-9i",
           "2026-02-14-driver-7i"]
MPH = 1 / 0.44704
MODELS = ["standard", "adjusted", "slip", "continuous"]
PRESET = {"driver": "driver", "4 iron": "iron4", "5 iron": "iron5", "6 iron": "iron6", "7 iron": "iron7",
          "8 iron": "iron8", "9 iron": "iron9", "pitching wedge": "pw", "4iron": "iron4", "5iron": "iron5",
          "6iron": "iron6", "7iron": "iron7", "8iron": "iron8", "9iron": "iron9", "pitchingwedge": "pw"}
R_BULGE_MM = R_ROLL_MM = 305.0


def report_strokes(session):
    report = json.load(open(f"{DATA}/report-{session}.json", encoding="utf-8"))
    for g in report["StrokeGroups"]:
        for st in g["Strokes"]:
            club = PRESET.get((st.get("Club") or g.get("Club") or "").lower())
            m = st.get("Measurement") or {}
            need = ["ClubSpeed", "BallSpeed", "AttackAngle", "ClubPath", "FaceAngle", "DynamicLoft", "ImpactHeight",
                    "ImpactOffset", "SpinRate", "LaunchAngle", "LaunchDirection"]
            if club is None or not all(k in m for k in need):
                continue
            ra = m.get("ReducedAccuracy") or []
            if "SpinRate" in ra:
                continue
            yield dict(session=session, club=club, speed=m["ClubSpeed"] * MPH, attack=m["AttackAngle"],
                       path=m["ClubPath"], face=m["FaceAngle"], loft=m["DynamicLoft"], lie=m.get("DynamicLie"),
                       h=m["ImpactOffset"] * 1e3, v=m["ImpactHeight"] * 1e3, ball=m["BallSpeed"] * MPH,
                       spin=m["SpinRate"], axis=None if ("SpinAxis" in ra or "SpinAxis" not in m) else m["SpinAxis"])


def csv_strokes(name):
    rows = list(csv.reader(open(f"{DATA}/{name}", encoding="utf-8-sig")))
    header, units = rows[1], rows[2]
    col = {h: i for i, h in enumerate(header)}
    for r in rows[3:]:
        def g(k):
            c = r[col[k]].strip() if col.get(k) is not None and col[k] < len(r) else ""
            return float(c) if c else None
        club = PRESET.get(r[col["Club"]].strip().lower())
        vals = [g(k) for k in ["Club Speed", "Attack Angle", "Club Path", "Face Angle", "Dyn. Loft", "Ball Speed",
                               "Spin Rate", "Impact Height", "Impact Offset"]]
        if club is None or any(v is None for v in vals) or r[col["Spin Rate Type"]].strip().lower() != "measured":
            continue
        yield dict(session=name, club=club, speed=vals[0], attack=vals[1], path=vals[2], face=vals[3], loft=vals[4],
                   lie=g("Dynamic Lie"), h=vals[8], v=vals[7], ball=vals[5], spin=vals[6], axis=g("Spin Axis"))


def delivery(s, reading):
    face, loft = s["face"], s["loft"]
    if reading == "contact" and s["club"] == "driver":
        face -= math.degrees(s["h"] / R_BULGE_MM)
        loft -= math.degrees(s["v"] / R_ROLL_MM)
    d = dict(club_speed_mph=s["speed"], attack_angle_deg=s["attack"], club_path_deg=s["path"], face_angle_deg=face,
             dynamic_loft_deg=loft, impact_h_mm=s["h"], impact_v_mm=s["v"])
    if s["lie"] is not None:
        d["dynamic_lie_deg"] = s["lie"]
    return d


def predict(shots, club, model, reading):
    text = "".join(json.dumps(delivery(s, reading)) + "\n" for s in shots)
    out = subprocess.run([BIN, "predict", "--club", CLUB_FILES.get(club, club), "--model", model], input=text, capture_output=True,
                         text=True).stdout.splitlines()
    res = []
    for line in out:
        j = json.loads(line)
        res.append(None if "error" in j else j)
    return res if len(res) == len(shots) else [None] * len(shots)


def ols(ys, xs):
    """Least squares of ys on the columns xs with an intercept: the slopes."""
    rows = [[1.0] + list(x) for x in xs]
    k = len(rows[0])
    a = [[sum(r[i] * r[j] for r in rows) for j in range(k)] for i in range(k)]
    b = [sum(r[i] * y for r, y in zip(rows, ys)) for i in range(k)]
    for i in range(k):
        p = max(range(i, k), key=lambda r: abs(a[r][i]))
        a[i], a[p], b[i], b[p] = a[p], a[i], b[p], b[i]
        for r in range(k):
            if r != i and a[i][i] != 0:
                f = a[r][i] / a[i][i]
                a[r] = [x - f * y for x, y in zip(a[r], a[i])]
                b[r] -= f * b[i]
    return [b[i] / a[i][i] for i in range(1, k)]


def main():
    shots = [s for r in REPORTS for s in report_strokes(r)] + list(csv_strokes("validation-8i-5i.csv"))
    groups = {"irons": [s for s in shots if s["club"] != "driver"], "driver": [s for s in shots if s["club"] == "driver"]}
    for gname, group in groups.items():
        for reading in (["centre", "contact"] if gname == "driver" else ["centre"]):
            for model in MODELS:
                pairs = []
                for club in sorted({s["club"] for s in group}):
                    sub = [s for s in group if s["club"] == club]
                    pairs += [(s, p) for s, p in zip(sub, predict(sub, club, model, reading)) if p is not None]
                e = [p["ball_speed_mph"] - s["ball"] for s, p in pairs]
                slope_v, slope_h = ols(e, [(s["v"], s["h"]) for s, _ in pairs])
                spin_e = [p["total_spin_rpm"] - s["spin"] for s, p in pairs]
                sessions = sorted({s["session"] for s, _ in pairs})
                spin_mae = {ss: round(sum(abs(x) for (s, _), x in zip(pairs, spin_e) if s["session"] == ss)
                                      / max(1, sum(1 for s, _ in pairs if s["session"] == ss)), 0) for ss in sessions}
                out = dict(label=LABEL, clubs=gname, reading=reading, model=model, shots=len(pairs),
                           ball_mae_mph=round(sum(map(abs, e)) / len(e), 2), ball_bias_mph=round(sum(e) / len(e), 2),
                           ball_slope_height_mph_per_mm=round(slope_v, 3), ball_slope_offset_mph_per_mm=round(slope_h, 3),
                           spin_mae_rpm=round(sum(map(abs, spin_e)) / len(spin_e), 0), spin_mae_by_session=spin_mae)
                ax = [(s, p) for s, p in pairs if s["axis"] is not None]
                if gname == "driver" and len(ax) > 5:
                    ftp = [(s["face"] - s["path"], s["h"], s["v"]) for s, _ in ax]
                    out["axis_mae_deg"] = round(sum(abs(p["spin_axis_deg"] - s["axis"]) for s, p in ax) / len(ax), 2)
                    out["axis_slopes_measured"] = [round(x, 3) for x in ols([s["axis"] for s, _ in ax], ftp)]
                    out["axis_slopes_model"] = [round(x, 3) for x in ols([p["spin_axis_deg"] for _, p in ax], ftp)]
                print(json.dumps(out))


main()
