#!/usr/bin/env python3
"""The irons of two players at matched deliveries, and the ball-speed error against impact height per player.

Usage: research/scripts/matched-deliveries.py BIN DATA OUT SPLIT
  BIN    the impactd binary
  DATA   tests/data/trackman (validation) or research/data/trackman (heldout)
  OUT    a directory: writes matched-SPLIT.json and height-errors-SPLIT.json (markdown rows for
         research/scripts/real-shots-docs.sh)
  SPLIT  validation (the first player's session and the third player's validation report sessions) or heldout
         (the second player's session and the third player's held-out report sessions)

Every stroke with club data, an impact location and an iron preset (4- to 9-iron) is run through `impactd predict
--model adjusted` on its preset. Two strokes of different players are matched when their spin loft (dynamic loft
minus attack angle) is within 2 deg, their impact height within 3 mm, their impact offset within 10 mm and their
face to path within 5 deg. For a matched pair (a, b) and any model f, |f(a) - v_a| + |f(b) - v_b| >=
|(v_a - v_b) - (f(a) - f(b))|: a lower bound on the two strokes' errors together for any model whose f(a) - f(b)
is the adjusted model's (every model here differs between matched deliveries by 0.01-0.02 of smash).
"""
import csv
import json
import subprocess
import sys

BIN, DATA, OUT, SPLIT = sys.argv[1:5]
MPH_PER_MPS = 1 / 0.44704
SESSIONS = {
    "validation": [("first", "validation-8i-5i.csv"), ("third", "report-2025-03-13-pw-driver-5w-7i.json"),
                   ("third", "report-2025-07-11-driver-4i-5h-pw.json"),
                   ("third", "report-2025-10-30-5w-driver-6i-9i.json"), ("third", "report-2026-02-14-driver-7i.json")],
    "heldout": [("second", "heldout-7i-pw-driver.csv"), ("third", "report-2025-06-13-driver-7i-9i.json"),
                ("third", "report-2025-08-05-5w-driver-7i-pw.json"), ("third", "report-2026-02-07-driver-7i.json")],
}[SPLIT]
PRESETS = {f"{n} Iron": f"iron{n}" for n in range(4, 10)}
API = {f"{n}Iron": f"{n} Iron" for n in range(4, 10)}
TOL = {"spin loft": 2.0, "height": 3.0, "offset": 10.0, "face to path": 5.0}


def strokes(player, name):
    """(player, session, club, delivery, measured ball speed mph) of every usable stroke."""
    path = f"{DATA}/{name}"
    out = []
    if name.endswith(".json"):
        for g in json.load(open(path))["StrokeGroups"]:
            for s in g["Strokes"]:
                m = s.get("Measurement") or {}
                keys = ["ClubSpeed", "BallSpeed", "AttackAngle", "ClubPath", "FaceAngle", "DynamicLoft",
                        "ImpactOffset", "ImpactHeight"]
                club = API.get(g["Club"])
                if club is None or any(m.get(k) is None for k in keys):
                    continue
                d = {"club_speed_mph": m["ClubSpeed"] * MPH_PER_MPS, "attack_angle_deg": m["AttackAngle"],
                     "club_path_deg": m["ClubPath"], "face_angle_deg": m["FaceAngle"],
                     "dynamic_loft_deg": m["DynamicLoft"], "impact_h_mm": m["ImpactOffset"] * 1e3,
                     "impact_v_mm": m["ImpactHeight"] * 1e3}
                if m.get("DynamicLie") is not None:
                    d["dynamic_lie_deg"] = m["DynamicLie"]
                out.append((player, name[:17], club, d, m["BallSpeed"] * MPH_PER_MPS))
    else:
        lines = open(path, encoding="utf-8-sig").read().splitlines()
        rows = list(csv.reader(lines[1:]))
        head = rows[0]
        cols = [("club_speed_mph", "Club Speed"), ("attack_angle_deg", "Attack Angle"), ("club_path_deg", "Club Path"),
                ("face_angle_deg", "Face Angle"), ("dynamic_loft_deg", "Dyn. Loft"), ("impact_h_mm", "Impact Offset"),
                ("impact_v_mm", "Impact Height")]
        for r in rows[2:]:
            d = dict(zip(head, r))
            if d["Club"] not in PRESETS or any(not d[c] for _, c in cols) or not d["Ball Speed"]:
                continue
            delivery = {k: float(d[c]) for k, c in cols}
            if d.get("Dynamic Lie"):
                delivery["dynamic_lie_deg"] = float(d["Dynamic Lie"])
            out.append((player, name[:17], d["Club"], delivery, float(d["Ball Speed"])))
    return out


shots = [s for player, name in SESSIONS for s in strokes(player, name)]
for club in sorted({s[2] for s in shots}):
    group = [s for s in shots if s[2] == club]
    p = subprocess.run([BIN, "predict", "--club", PRESETS[club], "--model", "adjusted"], check=True, text=True,
                       capture_output=True, input="".join(json.dumps(s[3]) + "\n" for s in group))
    for s, line in zip(group, p.stdout.splitlines()):
        s[3]["predicted_mph"] = json.loads(line)["ball_speed_mph"]


def feature(s):
    d = s[3]
    return (d["dynamic_loft_deg"] - d["attack_angle_deg"], d["impact_v_mm"], d["impact_h_mm"],
            d["face_angle_deg"] - d["club_path_deg"])


players = sorted({s[0] for s in shots})
first, third = players[0], "third"
pairs = [(a, b) for a in shots if a[0] == first for b in shots if b[0] == third
         and all(abs(x - y) < t for x, y, t in zip(feature(a), feature(b), TOL.values()))]
smash = lambda s: s[4] / s[3]["club_speed_mph"]
predicted = lambda s: s[3]["predicted_mph"] / s[3]["club_speed_mph"]
mean = lambda xs: sum(xs) / len(xs)
matched = ["| players | pairs (strokes) | clubs | club speed (mph) | measured smash | adjusted smash "
           "| the two strokes' errors together, at least (mph): mean / smallest |", "|---|---|---|---|---|---|---|"]
if pairs:
    bound = [abs((a[4] - b[4]) - (a[3]["predicted_mph"] - b[3]["predicted_mph"])) for a, b in pairs]
    clubs = sorted({(a[2], b[2]) for a, b in pairs})
    matched.append(
        f"| {first} - {third} | {len(pairs)} ({len({id(a) for a, _ in pairs})} + {len({id(b) for _, b in pairs})}) "
        f"| {', '.join(f'{x} - {y}' for x, y in clubs)} "
        f"| {mean([a[3]['club_speed_mph'] for a, _ in pairs]):.1f} - {mean([b[3]['club_speed_mph'] for _, b in pairs]):.1f} "
        f"| {mean([smash(a) for a, _ in pairs]):.3f} - {mean([smash(b) for _, b in pairs]):.3f} "
        f"| {mean([predicted(a) for a, _ in pairs]):.3f} - {mean([predicted(b) for _, b in pairs]):.3f} "
        f"| {mean(bound):.2f} / {min(bound):.2f} |")
json.dump(matched, open(f"{OUT}/matched-{SPLIT}.json", "w"))

# The adjusted model's ball-speed error against TrackMan's impact height, per player and club: a least-squares
# line e = e0 + slope * h gives the slope.
height = ["| player | club | session(s) | shots | impact height (mm): median | error MAE / bias (mph) "
          "| slope against height (mph per mm) |", "|---|---|---|---|---|---|---|"]
for player in players:
    for club in sorted({s[2] for s in shots if s[0] == player}, key=lambda c: int(c.split()[0])):
        g = [s for s in shots if s[0] == player and s[2] == club]
        h = [s[3]["impact_v_mm"] for s in g]
        e = [s[3]["predicted_mph"] - s[4] for s in g]
        hm, em = mean(h), mean(e)
        sxx = sum((x - hm) ** 2 for x in h)
        slope = sum((x - hm) * (y - em) for x, y in zip(h, e)) / sxx
        sessions = ", ".join(sorted({s[1][7:17] if s[1].startswith("report") else s[1][:10] for s in g}))
        height.append(f"| {player} | {club} | {sessions} | {len(g)} | {sorted(h)[len(h) // 2]:.1f} "
                      f"| {mean([abs(x) for x in e]):.2f} / {em:+.2f} | {slope:+.2f} |")
json.dump(height, open(f"{OUT}/height-errors-{SPLIT}.json", "w"))
