#!/usr/bin/env python3
"""Each model's spin error on the validation sessions, split into three parts by the closed form of a ball struck
at rest (`I w = m R |v_t|`: the seed's homogeneous ball, I = 0.4 m R^2, leaves with `spin = 2.5 v sin(a) / R`, `a`
the angle between the face normal and the ball's direction):

  relation  the seed's ball at TrackMan's own launch and ball speed, against TrackMan's measured spin:
            2.5 v_tm sin(a_tm) / R - spin_tm (TrackMan's fixed relation, 1.136 x that, makes it about -12 %)
  launch    the model's launch (angle and direction) through the same closed form, at TrackMan's ball speed:
            2.5 v_tm (sin a_model - sin a_tm) / R
  speed     the model's ball speed through it: 2.5 (v_model - v_tm) sin(a_model) / R
  rest      the model's spin against the closed form at its own launch and speed: what the model's ball does
            that the homogeneous ball struck at its centre's normal would not (a ball CG off the normal, a layered
            ball, a contact point inside the radius, a face normal other than TrackMan's)

`a` is measured from TrackMan's face normal (dynamic loft, face angle): on a planar iron face the contact normal.
The sum of the four is the model's spin bias exactly. Located strokes with measured spin, each club on its
preset, the deliveries `compare --by-club` gives an iron (TrackMan's club data and impact location as they are).

Usage: research/scripts/spin-decomposition.py [--json] [--models standard,adjusted,...] [--append 'TOML']
                                    [--oblique FROM,FULL,E_T | --oblique none] [-- predict args]
  --append   lines added to a copy of every preset (`'[slip]\\ne_y = 0.1\\ne_z = 0.0'`)
  --oblique  the presets' obliquity law of the slip model replaced (`none`: Table 3.4's constants alone)

Besides the mean parts, each row has `shift_floor_mae_rpm`: the smallest spin MAE any one change of every stroke's
spin by the same amount could give (the MAE about the errors' median), a floor for any uniform correction.
The validation sessions only (tests/data/trackman/README.md): validation-8i-5i.csv and the third player's
report-2025-03-13, -07-11, -10-30 and 2026-02-14.
"""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
BIN = os.path.join(ROOT, "target", "release", "impactd")
DATA = os.path.join(ROOT, "tests", "data", "trackman")
R_M = 0.0213  # Table 3.1's ball radius
MPS_PER_MPH = 0.44704
RPM_PER_RADPS = 60.0 / (2.0 * math.pi)
VALIDATION_REPORTS = ["report-2025-03-13-pw-driver-5w-7i.json", "report-2025-07-11-driver-4i-5h-pw.json",
                      "report-2025-10-30-5w-driver-6i-9i.json", "report-2026-02-14-driver-7i.json"]
PRESETS = {"4 iron": "iron4", "5 iron": "iron5", "6 iron": "iron6", "7 iron": "iron7", "8 iron": "iron8",
           "9 iron": "iron9", "pitching wedge": "pw", "4iron": "iron4", "5iron": "iron5", "6iron": "iron6",
           "7iron": "iron7", "8iron": "iron8", "9iron": "iron9", "pitchingwedge": "pw"}
TMP = tempfile.mkdtemp()
MODELS = "standard,adjusted,slip,continuous,maw,arakawa,ground"


def csv_strokes(name):
    """(club, delivery, measured) of the CSV export's located rows with measured spin."""
    lines = open(os.path.join(DATA, name), encoding="utf-8-sig").read().splitlines()
    rows = list(csv.reader(lines[1:]))
    head = rows[0]
    out = []
    for r in rows[2:]:
        d = dict(zip(head, r))
        need = ["Club Speed", "Attack Angle", "Club Path", "Face Angle", "Dyn. Loft", "Impact Height"]
        if d.get("Spin Rate Type") != "Measured" or not all(d.get(k) for k in need):
            continue
        delivery = {"club_speed_mph": float(d["Club Speed"]), "attack_angle_deg": float(d["Attack Angle"]),
                    "club_path_deg": float(d["Club Path"]), "face_angle_deg": float(d["Face Angle"]),
                    "dynamic_loft_deg": float(d["Dyn. Loft"]), "impact_h_mm": float(d["Impact Offset"] or 0),
                    "impact_v_mm": float(d["Impact Height"])}
        if d.get("Dynamic Lie"):
            delivery["dynamic_lie_deg"] = float(d["Dynamic Lie"])
        measured = {"ball_speed_mps": float(d["Ball Speed"]) * MPS_PER_MPH, "launch_deg": float(d["Launch Angle"]),
                    "direction_deg": float(d["Launch Direction"]), "spin_rpm": float(d["Spin Rate"])}
        out.append((d["Club"], delivery, measured))
    return out


def report_strokes(name):
    """The same from a TrackMan report JSON (SI units: m/s, m)."""
    out = []
    for g in json.load(open(os.path.join(DATA, name), encoding="utf-8"))["StrokeGroups"]:
        for st in g["Strokes"]:
            m = st.get("Measurement") or {}
            keys = ["ClubSpeed", "AttackAngle", "ClubPath", "FaceAngle", "DynamicLoft", "ImpactHeight", "BallSpeed",
                    "LaunchAngle", "LaunchDirection", "SpinRate"]
            ra = m.get("ReducedAccuracy") or []
            if not all(k in m for k in keys) or "SpinRate" in ra or "SpinAxis" in ra:
                continue
            delivery = {"club_speed_mph": m["ClubSpeed"] / MPS_PER_MPH, "attack_angle_deg": m["AttackAngle"],
                        "club_path_deg": m["ClubPath"], "face_angle_deg": m["FaceAngle"],
                        "dynamic_loft_deg": m["DynamicLoft"], "impact_h_mm": m.get("ImpactOffset", 0.0) * 1e3,
                        "impact_v_mm": m["ImpactHeight"] * 1e3}
            if "DynamicLie" in m:
                delivery["dynamic_lie_deg"] = m["DynamicLie"]
            measured = {"ball_speed_mps": m["BallSpeed"], "launch_deg": m["LaunchAngle"],
                        "direction_deg": m["LaunchDirection"], "spin_rpm": m["SpinRate"]}
            out.append((st.get("Club") or g.get("Club"), delivery, measured))
    return out


def unit(elevation_deg, azimuth_deg):
    e, a = math.radians(elevation_deg), math.radians(azimuth_deg)
    return (math.cos(e) * math.cos(a), math.sin(e), math.cos(e) * math.sin(a))


def angle(p, q):
    return math.acos(max(-1.0, min(1.0, sum(x * y for x, y in zip(p, q)))))


def closed_rpm(speed_mps, a):
    return 2.5 * speed_mps * math.sin(a) / R_M * RPM_PER_RADPS


def with_oblique(text, oblique):
    """The preset's text with its `oblique_*` lines dropped (`none`) or given other values (FROM,FULL,E_T)."""
    lines = [line for line in text.splitlines() if not line.startswith("oblique_")]
    if oblique != "none" and "[slip]" in text:
        lo, full, e_t = oblique.split(",")
        at = lines.index("[slip]") + 1
        lines[at:at] = [f"oblique_from_deg = {lo}", f"oblique_full_deg = {full}", f"oblique_e_t = {e_t}"]
    return "\n".join(lines) + "\n"


def predict(preset, model, deliveries, extra, append="", oblique=None):
    if append or oblique:  # a copy of the preset with lines appended (a `[slip]` section, a field) or its law changed
        path = os.path.join(TMP, f"{preset}.toml")
        text = open(os.path.join(ROOT, "clubs", "presets", f"{preset}.toml")).read()
        if oblique:
            text = with_oblique(text, oblique)
        open(path, "w").write(text + "\n" + append.replace("\\n", "\n") + "\n")
        preset = path
    args = [BIN, "predict", "--club", preset, "--model", model] + (["--soil", "none"] if model == "ground" else [])
    out = []
    for d in deliveries:  # one at a time: a stroke the club refuses (a lie its face cannot have) is left out, as
        # `compare --by-club` leaves it out and counts it
        p = subprocess.run(args + extra, input=json.dumps(d) + "\n", capture_output=True, text=True)
        out.append(json.loads(p.stdout) if p.returncode == 0 else None)
    return out


def decompose(models, extra, append="", oblique=None):
    sessions = [("validation-8i-5i.csv", csv_strokes("validation-8i-5i.csv"))]
    sessions += [(name, report_strokes(name)) for name in VALIDATION_REPORTS]
    rows = []
    for session, strokes in sessions:
        clubs = {}
        for club, d, m in strokes:
            preset = PRESETS.get(club.strip().lower())
            if preset:
                clubs.setdefault((club, preset), []).append((d, m))
        for (club, preset), shots in clubs.items():
            for model in models:
                q = predict(preset, model, [d for d, _ in shots], extra, append, oblique)
                parts = []
                for (d, m), p in zip(shots, q):
                    if p is None:
                        continue
                    n = unit(d["dynamic_loft_deg"], d["face_angle_deg"])
                    a_tm = angle(n, unit(m["launch_deg"], m["direction_deg"]))
                    a_model = angle(n, unit(p["launch_angle_deg"], p["launch_direction_deg"]))
                    v_tm, v_model = m["ball_speed_mps"], p["ball_speed_mps"]
                    path = unit(d["attack_angle_deg"], d["club_path_deg"])
                    rel = closed_rpm(v_tm, a_tm) - m["spin_rpm"]
                    launch = closed_rpm(v_tm, a_model) - closed_rpm(v_tm, a_tm)
                    speed = closed_rpm(v_model, a_model) - closed_rpm(v_tm, a_model)
                    rest = p["total_spin_rpm"] - closed_rpm(v_model, a_model)
                    parts.append({"spin_error_rpm": p["total_spin_rpm"] - m["spin_rpm"], "relation_rpm": rel,
                                  "launch_rpm": launch, "speed_rpm": speed, "rest_rpm": rest,
                                  "launch_error_deg": p["launch_angle_deg"] - m["launch_deg"],
                                  "spin_loft_deg": math.degrees(angle(n, path))})
                mean = lambda k: sum(x[k] for x in parts) / len(parts)
                errors = sorted(x["spin_error_rpm"] for x in parts)
                median = (errors[(len(errors) - 1) // 2] + errors[len(errors) // 2]) / 2
                rows.append({"session": session, "club": club, "preset": preset, "model": model, "shots": len(parts),
                             "refused": sum(p is None for p in q),
                             "measured_spin_rpm": sum(m["spin_rpm"] for (_, m), p in zip(shots, q) if p) / len(parts),
                             "spin_mae_rpm": sum(abs(x["spin_error_rpm"]) for x in parts) / len(parts),
                             "shift_floor_mae_rpm": sum(abs(e - median) for e in errors) / len(errors),
                             "launch_mae_deg": sum(abs(x["launch_error_deg"]) for x in parts) / len(parts),
                             **{k: mean(k) for k in ["spin_error_rpm", "relation_rpm", "launch_rpm", "speed_rpm",
                                                     "rest_rpm", "launch_error_deg", "spin_loft_deg"]}})
    return rows


def main():
    argv = sys.argv[1:]
    extra = argv[argv.index("--") + 1:] if "--" in argv else []
    argv = argv[:argv.index("--")] if "--" in argv else argv
    models = argv[argv.index("--models") + 1].split(",") if "--models" in argv else MODELS.split(",")
    append = argv[argv.index("--append") + 1] if "--append" in argv else ""
    oblique = argv[argv.index("--oblique") + 1] if "--oblique" in argv else None
    rows = decompose(models, extra, append, oblique)
    if "--json" in argv:
        json.dump(rows, sys.stdout, indent=1)
        print()
        return
    print("| session | club | model | spins | measured (rpm) | spin bias | relation | launch | speed | rest | "
          "spin MAE (rpm) | launch MAE / bias (deg) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['session'][:17].replace('.csv', '')} | {r['club']} | {r['model']} | {r['shots']} | "
              f"{r['measured_spin_rpm']:.0f} | {r['spin_error_rpm']:+.0f} | {r['relation_rpm']:+.0f} | "
              f"{r['launch_rpm']:+.0f} | {r['speed_rpm']:+.0f} | {r['rest_rpm']:+.0f} | {r['spin_mae_rpm']:.0f} | "
              f"{r['launch_mae_deg']:.2f} / {r['launch_error_deg']:+.2f} |")


if __name__ == "__main__":
    main()
