#!/usr/bin/env bash
# Regenerates the tables of research/real-shots.md from `impactd compare --by-club --json` on the real TrackMan
# sessions of tests/data/trackman/ and from `impactd predict --json` lines:
#   region validation   the validation session, shots with an impact location, every model
#   region validation-all  the same session, every shot with club data (unlocated ones at the face centre)
#   region height       ball speed against impact height on the 5-iron: the head alone, with the shaft's share,
#                       on the seed's flexible shaft
#   region reference    the validation session with TrackMan's impact heights moved down by 0-8 mm (adjusted)
#   region slope        smash against impact height on the 8- and 5-iron presets (adjusted) beside the closed-form
#                       effective mass, with the heel-toe inertia doubled and with the sweet spot moved up the face
#   region heldout      the held-out session (7-iron, pitching wedge, driver), every model
#   region tour         TrackMan's tour 7-iron at its launch: the slip model's e_y and e against spin and speed
#   region relation     per club, TrackMan's measured spin over 2.5 v sin(a) / R from its own loft, face and launch
#   region strike-height  the validation session's located shots by TrackMan's impact height: measured and
#                       predicted smash (adjusted), ball speed bias
#   region variants     the validation session's located shots on copies of the 8- and 5-iron presets with the
#                       heel-toe inertia scaled or the CG moved toward the heel (adjusted, through predict)
#   region heel-toe     the same shots 3 to 13 mm up, by TrackMan's impact offset: measured smash, ball speed bias
#                       of the free head (adjusted) and of the head on the seed's shaft (ground --soil none)
#   region spin-relation  the validation session with TrackMan's loft and face read through its spin relation
#   region heldout-relation  the held-out session, the same reading
#   region spin-launch  per club of the validation session (measured spins), the launch the seed's ball needs below
#                       TrackMan's to reach TrackMan's spin off TrackMan's face (closed form)
#   region report-validation  the third player's TrackMan report JSON sessions chosen for validation
#                       (2025-03-13, 2025-07-11, 2025-10-30, 2026-02-14), every model, one table per session
#   region report-heldout  the same player's held-out report sessions (2025-06-13, 2025-08-05, 2026-02-07)
#   region matched, height-errors  research/scripts/matched-deliveries.py on the validation sessions: the first and third
#                       players' irons at matched deliveries, and the adjusted model's ball-speed error per player
#                       and club against impact height; matched-heldout, height-errors-heldout the same on the
#                       held-out sessions (the second and third players)
# Usage: research/scripts/real-shots-docs.sh   (seconds on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/../.."

cargo build --release --quiet
BIN=target/release/impactd
DATA=tests/data/trackman
# The held-out sessions, which only the research reads.
HELDOUT=research/data/trackman
OUT="$(mktemp -d)"
trap 'rm -rf "$OUT"' EXIT
MODELS=standard,adjusted,slip,continuous,maw,arakawa,ground

"$BIN" compare --by-club --located --json --soil none --models "$MODELS" "$DATA/validation-8i-5i.csv" \
    2>/dev/null >"$OUT/validation.json"
"$BIN" compare --by-club --json --soil none --models "$MODELS" "$DATA/validation-8i-5i.csv" \
    2>/dev/null >"$OUT/validation-all.json"
"$BIN" compare --by-club --located --json --soil none --models "$MODELS" "$HELDOUT/heldout-7i-pw-driver.csv" \
    2>/dev/null >"$OUT/heldout.json"
"$BIN" compare --by-club --located --json --soil none --spin-relation --models "$MODELS" \
    "$DATA/validation-8i-5i.csv" 2>/dev/null >"$OUT/spin-relation.json"
"$BIN" compare --by-club --located --json --soil none --spin-relation --models "$MODELS" \
    "$HELDOUT/heldout-7i-pw-driver.csv" 2>/dev/null >"$OUT/heldout-relation.json"

# The third player's report JSON sessions: the split was fixed by date order before any comparison (1st, 3rd, 5th
# and 7th for validation; the 2nd, 4th and 6th held out).
REPORT_VALIDATION="2025-03-13-pw-driver-5w-7i 2025-07-11-driver-4i-5h-pw 2025-10-30-5w-driver-6i-9i
    2026-02-14-driver-7i"
REPORT_HELDOUT="2025-06-13-driver-7i-9i 2025-08-05-5w-driver-7i-pw 2026-02-07-driver-7i"
for s in $REPORT_VALIDATION; do
    "$BIN" compare --by-club --located --json --soil none --models "$MODELS" "$DATA/report-$s.json" \
        2>/dev/null >"$OUT/report-$s.json"
done
for s in $REPORT_HELDOUT; do
    "$BIN" compare --by-club --located --json --soil none --models "$MODELS" "$HELDOUT/report-$s.json" \
        2>/dev/null >"$OUT/report-$s.json"
done
echo "$REPORT_VALIDATION" >"$OUT/report-validation.list"
python3 research/scripts/matched-deliveries.py "$BIN" "$DATA" "$OUT" validation
python3 research/scripts/matched-deliveries.py "$BIN" "$HELDOUT" "$OUT" heldout
echo "$REPORT_HELDOUT" >"$OUT/report-heldout.list"

# The 5-iron preset without the shaft's share: the head alone, as Table 3.1's 7-iron is.
sed '/^shaft_heel_toe_inertia_g_cm2/d' clubs/presets/iron5.toml >"$OUT/iron5-head.toml"
for v in -4 0 4 8 12 16; do
    echo "{\"club_speed_mph\":95,\"attack_angle_deg\":-7.5,\"dynamic_loft_deg\":13,\"impact_v_mm\":$v}"
done >"$OUT/height.jsonl"
"$BIN" predict --club "$OUT/iron5-head.toml" --model adjusted -i "$OUT/height.jsonl" >"$OUT/height-head.jsonl"
"$BIN" predict --club iron5 --model adjusted -i "$OUT/height.jsonl" >"$OUT/height-share.jsonl"
"$BIN" predict --club iron5 --model ground --soil none -i "$OUT/height.jsonl" >"$OUT/height-shaft.jsonl"

# TrackMan's impact heights moved down by s mm: the file with its Impact Height column edited, nothing else.
for s in 0 2 4 6 8; do
    python3 - "$DATA/validation-8i-5i.csv" "$s" >"$OUT/shift-$s.csv" <<'PY'
import csv, sys
path, s = sys.argv[1], float(sys.argv[2])
lines = open(path, encoding="utf-8-sig").read().splitlines()
rows = list(csv.reader(lines[1:]))
col = rows[0].index("Impact Height")
w = csv.writer(sys.stdout, quoting=csv.QUOTE_ALL, lineterminator="\n")
sys.stdout.write(lines[0] + "\n")
for i, r in enumerate(rows):
    if i >= 2 and r[col] != "":
        r[col] = repr(float(r[col]) - s)
    w.writerow(r)
PY
    "$BIN" compare --by-club --located --json --models adjusted,continuous "$OUT/shift-$s.csv" 2>/dev/null \
        >"$OUT/shift-$s.json"
done

# Smash against impact height on the 8- and 5-iron presets: the adjusted model, the closed-form effective mass of
# a normal impact (the preset's head mass, tensor and shaft share), and the same head with its heel-toe inertia
# (head and share) doubled, or with its CG moved up the face so that the sweet spot sits at the face centre or
# 6 mm above it (club files beside the presets, nothing else changed).
python3 - "$BIN" "$OUT" <<'PY'
import json, math, re, subprocess, sys
bin, out = sys.argv[1], sys.argv[2]
heights = [-4, 0, 4, 8, 12, 16]
M_BALL = 0.0459  # Table 3.1


def numbers(text, key):
    return [float(x) for x in re.findall(r"-?[0-9.]+", re.search(rf"^{key} = (.*)$", text, re.M).group(1))]


def variant(text, loft, inertia_scale=1.0, sweet_spot_mm=None):
    if sweet_spot_mm is not None:
        c = numbers(text, "cg_to_face_center_m")
        L = math.radians(loft)
        depth = c[0] * math.cos(L) + c[1] * math.sin(L)
        e = -sweet_spot_mm * 1e-3  # the face centre sits e up the face from the CG's projection
        c = [depth * math.cos(L) - e * math.sin(L), depth * math.sin(L) + e * math.cos(L), c[2]]
        text = re.sub(r"^cg_to_face_center_m = .*$", f"cg_to_face_center_m = [{c[0]:.6f}, {c[1]:.6f}, {c[2]}]", text,
                      flags=re.M)
    if inertia_scale != 1.0:
        i = numbers(text, "inertia_g_cm2")
        i[8] *= inertia_scale
        rows = ", ".join("[" + ", ".join(f"{x:.1f}" for x in i[3 * r:3 * r + 3]) + "]" for r in range(3))
        text = re.sub(r"^inertia_g_cm2 = .*$", f"inertia_g_cm2 = [{rows}]", text, flags=re.M)
        share = numbers(text, "shaft_heel_toe_inertia_g_cm2")[0]
        text = re.sub(r"^shaft_heel_toe_inertia_g_cm2 = .*$", f"shaft_heel_toe_inertia_g_cm2 = {share * inertia_scale:.1f}",
                      text, flags=re.M)
    return text


def m_eff(text, loft, v_mm):
    """1 / (1/m + (r x n) . I^-1 (r x n)), club frame, r from the CG to the contact point."""
    m = numbers(text, "mass_kg")[0] + 0.0101  # the adjusted model's added mass (the seed's Table 3.3 7-iron)
    c = numbers(text, "cg_to_face_center_m")
    i = [x * 1e-7 for x in numbers(text, "inertia_g_cm2")]
    i[8] += numbers(text, "shaft_heel_toe_inertia_g_cm2")[0] * 1e-7
    L = math.radians(loft)
    n, u = (math.cos(L), math.sin(L), 0.0), (-math.sin(L), math.cos(L), 0.0)
    r = [c[k] + v_mm * 1e-3 * u[k] for k in range(3)]
    k = (r[1] * n[2] - r[2] * n[1], r[2] * n[0] - r[0] * n[2], r[0] * n[1] - r[1] * n[0])
    A = [i[0:3], i[3:6], i[6:9]]
    det = lambda M: (M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0])
                     + M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]))
    x = []
    for col in range(3):
        B = [row[:] for row in A]
        for rr in range(3):
            B[rr][col] = k[rr]
        x.append(det(B) / det(A))
    return 1.0 / (1.0 / m + sum(k[q] * x[q] for q in range(3)))


rows = []
for preset, club_mph, attack, loft_dyn in [("iron8", 90, -7.5, 21.5), ("iron5", 95, -7.5, 13.0)]:
    text = open(f"clubs/presets/{preset}.toml").read()
    loft = numbers(text, "loft_deg")[0]
    lines = "".join(json.dumps({"club_speed_mph": club_mph, "attack_angle_deg": attack, "dynamic_loft_deg": loft_dyn,
                                "impact_v_mm": v}) + "\n" for v in heights)

    def smash(club_text):
        path = f"{out}/slope.toml"
        open(path, "w").write(club_text)
        p = subprocess.run([bin, "predict", "--club", path, "--model", "adjusted"], input=lines, capture_output=True,
                           text=True, check=True)
        return [json.loads(l)["ball_speed_mph"] / club_mph for l in p.stdout.splitlines()]

    c = numbers(text, "cg_to_face_center_m")
    L = math.radians(loft)
    sweet = -(-c[0] * math.sin(L) + c[1] * math.cos(L)) * 1e3  # the CG's projection on the face, mm up from the centre
    preset_smash = smash(text)
    # Closed form: the normal impact's (1 + e) m_eff / (m_eff + m_ball), scaled to the model's smash at the sweet spot.
    p = subprocess.run([bin, "predict", "--club", f"clubs/presets/{preset}.toml", "--model", "adjusted"],
                       input=json.dumps({"club_speed_mph": club_mph, "attack_angle_deg": attack,
                                         "dynamic_loft_deg": loft_dyn, "impact_v_mm": sweet}) + "\n",
                       capture_output=True, text=True, check=True)
    s0 = json.loads(p.stdout)["ball_speed_mph"] / club_mph
    f = lambda v: (lambda me: me / (me + M_BALL))(m_eff(text, loft, v))
    closed = [s0 * f(v) / f(sweet) for v in heights]
    # The heel-toe inertia (head and share) at which the closed form keeps 98 % of the sweet spot's smash 13 mm up
    # the face (TrackMan's 5-iron: 1.410 below 3 mm, 1.416 from 9 to 13 mm), by bisection.
    lo, hi = 0.0, 50000.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        t = re.sub(r"^shaft_heel_toe_inertia_g_cm2 = .*$", "shaft_heel_toe_inertia_g_cm2 = 0.0", variant(text, loft),
                   flags=re.M)
        i = numbers(t, "inertia_g_cm2")
        i[8] = mid
        rows_i = ", ".join("[" + ", ".join(f"{x:.6f}" for x in i[3 * r:3 * r + 3]) + "]" for r in range(3))
        t = re.sub(r"^inertia_g_cm2 = .*$", f"inertia_g_cm2 = [{rows_i}]", t, flags=re.M)
        g = lambda v: (lambda me: me / (me + M_BALL))(m_eff(t, loft, v))
        lo, hi = (lo, mid) if g(13.0) / g(sweet) >= 0.98 else (mid, hi)
    i = numbers(text, "inertia_g_cm2")
    rows.append({"club": preset, "sweet_mm": sweet, "heights": heights, "needed_g_cm2": hi,
                 "heel_toe_g_cm2": i[8] + numbers(text, "shaft_heel_toe_inertia_g_cm2")[0], "vertical_g_cm2": i[4],
                 "series": [["adjusted, the preset", preset_smash],
                            ["closed form, the preset's m and I", closed],
                            ["adjusted, heel-toe inertia x 2", smash(variant(text, loft, inertia_scale=2.0))],
                            ["adjusted, sweet spot at the face centre", smash(variant(text, loft, sweet_spot_mm=0.0))],
                            ["adjusted, sweet spot 6 mm above it", smash(variant(text, loft, sweet_spot_mm=6.0))]]})
json.dump(rows, open(f"{out}/slope.json", "w"))

# The validation session's located shots (the deliveries `compare --by-club` gives an iron: TrackMan's loft and
# face are the face centre's on a planar face) on copies of the 8- and 5-iron presets: the heel-toe inertia (head
# and share) scaled, or the CG moved toward the heel. Ball speed MAE / bias; the 8-iron's spin on measured shots.
import csv
lines = open("tests/data/trackman/validation-8i-5i.csv", encoding="utf-8-sig").read().splitlines()
table = list(csv.reader(lines[1:]))
head = table[0]
fields = [("club_speed_mph", "Club Speed"), ("attack_angle_deg", "Attack Angle"), ("club_path_deg", "Club Path"),
          ("face_angle_deg", "Face Angle"), ("dynamic_loft_deg", "Dyn. Loft"), ("impact_h_mm", "Impact Offset"),
          ("impact_v_mm", "Impact Height"), ("dynamic_lie_deg", "Dynamic Lie")]


def heelward(text, mm):
    c = numbers(text, "cg_to_face_center_m")
    return re.sub(r"^cg_to_face_center_m = .*$", f"cg_to_face_center_m = [{c[0]}, {c[1]}, {c[2] + mm * 1e-3:.5f}]",
                  text, flags=re.M)


variants = []
for label, change in [("the presets", lambda t, L: t),
                      ("heel-toe inertia x 1.5", lambda t, L: variant(t, L, inertia_scale=1.5)),
                      ("heel-toe inertia x 2", lambda t, L: variant(t, L, inertia_scale=2.0)),
                      ("heel-toe inertia x 3", lambda t, L: variant(t, L, inertia_scale=3.0)),
                      ("sweet spot 4 mm toward the heel", lambda t, L: heelward(t, 4.0 - 1.12)),
                      ("sweet spot 7 mm toward the heel", lambda t, L: heelward(t, 7.0 - 1.12))]:
    cells = {}
    for club, preset in [("8 Iron", "iron8"), ("5 Iron", "iron5")]:
        sel = [d for d in (dict(zip(head, r)) for r in table[2:])
               if d["Club"] == club and d["Club Speed"] and d["Impact Height"]]
        text = open(f"clubs/presets/{preset}.toml").read()
        path = f"{out}/variant.toml"
        open(path, "w").write(change(text, numbers(text, "loft_deg")[0]))
        lines_in = "".join(json.dumps({k: float(d[c]) for k, c in fields}) + "\n" for d in sel)
        p = subprocess.run([bin, "predict", "--club", path, "--model", "adjusted"], input=lines_in,
                           capture_output=True, text=True, check=True)
        q = [json.loads(l) for l in p.stdout.splitlines()]
        e = [x["ball_speed_mph"] - float(d["Ball Speed"]) for x, d in zip(q, sel)]
        spin = [abs(x["total_spin_rpm"] - float(d["Spin Rate"])) for x, d in zip(q, sel)
                if d["Spin Rate Type"] == "Measured"]
        cells[club] = (sum(map(abs, e)) / len(e), sum(e) / len(e), sum(spin) / len(spin))
    variants.append({"label": label, "cells": cells})
json.dump(variants, open(f"{out}/variants.json", "w"))
PY

# The validation session's located shots, as `compare --by-club` gives them (irons: TrackMan's loft and face
# are the face centre's), through the adjusted model: smash and ball speed against TrackMan's impact height.
python3 - "$BIN" "$DATA/validation-8i-5i.csv" "$OUT" <<'PY'
import csv, json, subprocess, sys
bin, path, out = sys.argv[1], sys.argv[2], sys.argv[3]
lines = open(path, encoding="utf-8-sig").read().splitlines()
rows = list(csv.reader(lines[1:]))
head, result = rows[0], []
for club, preset in [("8 Iron", "iron8"), ("5 Iron", "iron5")]:
    sel = [d for d in (dict(zip(head, r)) for r in rows[2:]) if d["Club"] == club and d["Club Speed"] and d["Impact Height"]]
    fields = [("club_speed_mph", "Club Speed"), ("attack_angle_deg", "Attack Angle"), ("club_path_deg", "Club Path"),
              ("face_angle_deg", "Face Angle"), ("dynamic_loft_deg", "Dyn. Loft"), ("impact_h_mm", "Impact Offset"),
              ("impact_v_mm", "Impact Height"), ("dynamic_lie_deg", "Dynamic Lie")]
    text = "".join(json.dumps({k: float(d[c]) for k, c in fields}) + "\n" for d in sel)
    p = subprocess.run([bin, "predict", "--club", preset, "--model", "adjusted"], input=text, capture_output=True,
                       text=True, check=True)
    g = subprocess.run([bin, "predict", "--club", preset, "--model", "ground", "--soil", "none"], input=text,
                       capture_output=True, text=True, check=True)
    for d, q, qg in zip(sel, (json.loads(l) for l in p.stdout.splitlines()), (json.loads(l) for l in g.stdout.splitlines())):
        result.append({"club": club, "v": float(d["Impact Height"]), "h": float(d["Impact Offset"]),
                       "club_speed": float(d["Club Speed"]), "ball_speed": float(d["Ball Speed"]),
                       "predicted": q["ball_speed_mph"], "on_shaft": qg["ball_speed_mph"]})
json.dump(result, open(f"{out}/strike-height.json", "w"))
PY

# The tour 7-iron (90 mph, attack -4.3 deg) at the dynamic loft that launches it at TrackMan's 16.3 deg
# (bisection on `predict`), the seed's head with the shaft's share, the slip model's e_y and e varied.
python3 - "$BIN" "$OUT" <<'PY'
import json, subprocess, sys
bin, out = sys.argv[1], sys.argv[2]
# The preset's top-level fields and the shaft's share, then its own [slip] section or the one tried here.
top, _, own_slip = open("clubs/presets/iron7.toml").read().partition("\n[slip]")
preset = top + "\nshaft_heel_toe_inertia_g_cm2 = 594.0\n"
rows = []
for model, e_y, cor in [("standard", None, 0.83), ("slip", 0.0183, 0.83), ("slip", 0.10, 0.83), ("slip", 0.20, 0.83),
                        ("slip", 0.20, 0.78), ("slip", 0.30, 0.78)]:
    club = f"{out}/tour.toml"
    open(club, "w").write(preset + (f"[slip]\ne_y = {e_y}\ne_z = 0.0\n" if e_y is not None else "[slip]" + own_slip))
    def run(dl):
        line = json.dumps({"club_speed_mph": 90, "attack_angle_deg": -4.3, "dynamic_loft_deg": dl}) + "\n"
        p = subprocess.run([bin, "predict", "--club", club, "--model", model, "--cor", str(cor)], input=line,
                           capture_output=True, text=True, check=True)
        return json.loads(p.stdout)
    lo, hi = 10.0, 40.0
    for _ in range(30):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if run(mid)["launch_angle_deg"] < 16.3 else (lo, mid)
    q = run(0.5 * (lo + hi))
    rows.append({"model": model, "e_y": e_y, "cor": cor, "loft": 0.5 * (lo + hi), "speed": q["ball_speed_mph"],
                 "spin": q["total_spin_rpm"], "launch": q["launch_angle_deg"]})
json.dump(rows, open(f"{out}/tour.json", "w"))
PY

python3 - "$OUT" <<'PY'
import json, sys
sys.path.insert(0, "scripts")
import docs_regions

out = sys.argv[1]


def club_table(path):
    r = json.load(open(f"{out}/{path}"))
    rows = []
    if r["unlocated_left_out"]:
        rows.append(f"{r['unlocated_left_out']} shots without an impact location left out.\n")
    rows += ["| club | model | shots | ball speed MAE / bias (mph) | launch MAE / bias (deg) | spin MAE / bias (rpm) | spin axis MAE / bias (deg) |",
             "|---|---|---|---|---|---|---|"]
    for c in r["clubs"]:
        for m in c["models"]:
            def pair(e, d):
                if e["n"] == 0:
                    return "n/a"
                return f"{e['mae']:.{d}f} / {e['bias']:+.{d}f}"
            model = m["model"] + (f" ({m['failed']} failed)" if m["failed"] else "")
            rows.append(f"| {c['label']} | {model} | {c['shots']} ({c['spin_shots']} spin) | {pair(m['ball_speed_mph'], 2)} | "
                        f"{pair(m['launch_angle_deg'], 2)} | {pair(m['spin_rpm'], 0)} | {pair(m['spin_axis_deg'], 2)} |")
    return rows


def speeds(name):
    return [json.loads(l)["ball_speed_mph"] for l in open(f"{out}/{name}")]


heights = [-4, 0, 4, 8, 12, 16]
head, share, shaft = speeds("height-head.jsonl"), speeds("height-share.jsonl"), speeds("height-shaft.jsonl")
height = ["| impact height (mm) | " + " | ".join(str(v) for v in heights) + " |", "|---|" + "---|" * len(heights)]
for label, s in [("adjusted, the head alone (577 g cm2 scaled)", head), ("adjusted, with the shaft's share", share),
                 ("ground --soil none (the head on the seed's shaft)", shaft)]:
    height.append(f"| {label} | " + " | ".join(f"{x:.1f}" for x in s) + " |")

reference = ["| heights moved down (mm) | adjusted 8-iron | adjusted 5-iron | continuous 8-iron | continuous 5-iron | adjusted 8-iron spin MAE / bias (rpm) |",
             "|---|---|---|---|---|---|"]
for s in [0, 2, 4, 6, 8]:
    r = json.load(open(f"{out}/shift-{s}.json"))
    cell = {}
    for c in r["clubs"]:
        for m in c["models"]:
            e = m["ball_speed_mph"]
            cell[(c["label"], m["model"])] = f"{e['mae']:.2f} / {e['bias']:+.2f}"
            cell[(c["label"], m["model"], "spin")] = f"{m['spin_rpm']['mae']:.0f} / {m['spin_rpm']['bias']:+.0f}"
    reference.append(f"| {s} | {cell[('8 Iron', 'adjusted')]} | {cell[('5 Iron', 'adjusted')]} | "
                     f"{cell[('8 Iron', 'continuous')]} | {cell[('5 Iron', 'continuous')]} | "
                     f"{cell[('8 Iron', 'adjusted', 'spin')]} |")

slope = []
for r in json.load(open(f"{out}/slope.json")):
    slope += [f"| {r['club']} (sweet spot {r['sweet_mm']:+.2f} mm) | " + " | ".join(f"{v} mm" for v in r["heights"]) + " |",
              "|---|" + "---|" * len(r["heights"])]
    for label, series in r["series"]:
        slope.append(f"| {label} | " + " | ".join(f"{x:.3f}" for x in series) + " |")
    slope += ["", f"{r['club']}: 98 % of the sweet spot's smash 13 mm above the face centre needs {r['needed_g_cm2']:,.0f} g cm2 "
              f"about the heel-toe axis (the preset: {r['heel_toe_g_cm2']:,.0f} with the shaft's share; about the "
              f"vertical axis the head has {r['vertical_g_cm2']:,.0f}).", ""]
slope.pop()

tour = ["| model | e_y | e | dynamic loft (deg) | ball speed (mph) | spin (rpm) |", "|---|---|---|---|---|---|"]
for t in json.load(open(f"{out}/tour.json")):
    e_y = "rolling" if t["e_y"] is None else f"{t['e_y']:.3g}"
    tour.append(f"| {t['model']} | {e_y} | {t['cor']:.2f} | {t['loft']:.2f} | {t['speed']:.1f} ({(t['speed'] / 120 - 1) * 100:+.1f} %) | "
                f"{t['spin']:.0f} ({(t['spin'] / 7097 - 1) * 100:+.1f} %) |")

import csv, math
relation = ["| session | club | shots | spin / (2.5 v sin a / R): min | mean | max |", "|---|---|---|---|---|---|"]

def unit(e, a):
    """The direction of elevation `e` and azimuth `a` (deg), TrackMan's x forward, y up, z right."""
    e, a = math.radians(float(e)), math.radians(float(a))
    return (math.cos(e) * math.cos(a), math.sin(e), math.cos(e) * math.sin(a))

def ratio(spin_rpm, speed_mps, loft, face, launch, direction):
    """Measured spin over 2.5 v sin(a) / R, `a` between TrackMan's face normal and the ball's direction."""
    n, b = unit(loft, face), unit(launch, direction)
    angle = math.acos(max(-1.0, min(1.0, sum(p * q for p, q in zip(n, b)))))
    return spin_rpm / (2.5 * speed_mps * math.sin(angle) / 0.0213 * 60 / (2 * math.pi))
for name, folder in [("validation-8i-5i.csv", "tests/data/trackman"), ("heldout-7i-pw-driver.csv", "research/data/trackman")]:
    lines = open(f"{folder}/{name}", encoding="utf-8-sig").read().splitlines()
    rows = list(csv.reader(lines[1:]))
    head, by_club = rows[0], {}
    for r in rows[2:]:
        d = dict(zip(head, r))
        if d["Spin Rate Type"] != "Measured" or not d["Dyn. Loft"] or not d["Club Speed"]:
            continue
        by_club.setdefault(d["Club"], []).append(ratio(float(d["Spin Rate"]), float(d["Ball Speed"]) * 0.44704,
                                                       d["Dyn. Loft"], d["Face Angle"], d["Launch Angle"],
                                                       d["Launch Direction"]))
    for club, q in by_club.items():
        relation.append(f"| {name} | {club} | {len(q)} | {min(q):.4f} | {sum(q) / len(q):.4f} | {max(q):.4f} |")
# The third player's report sessions (every club, with a preset or not): TrackMan's JSON in SI units, spin in rpm;
# strokes whose spin rate or axis TrackMan marks ReducedAccuracy left out.
import glob, os
for path in sorted(glob.glob("tests/data/trackman/report-*.json") + glob.glob("research/data/trackman/report-*.json"),
                   key=os.path.basename):
    by_club = {}
    for g in json.load(open(path, encoding="utf-8"))["StrokeGroups"]:
        for st in g["Strokes"]:
            m = st.get("Measurement") or {}
            keys = ["DynamicLoft", "FaceAngle", "LaunchAngle", "LaunchDirection", "BallSpeed", "SpinRate"]
            ra = m.get("ReducedAccuracy") or []
            if not all(k in m for k in keys) or "SpinRate" in ra or "SpinAxis" in ra:
                continue
            by_club.setdefault(st["Club"], []).append(ratio(m["SpinRate"], m["BallSpeed"], m["DynamicLoft"],
                                                            m["FaceAngle"], m["LaunchAngle"], m["LaunchDirection"]))
    for club, q in by_club.items():
        relation.append(f"| {os.path.basename(path)} | {club} | {len(q)} | {min(q):.4f} | {sum(q) / len(q):.4f} | {max(q):.4f} |")

strike = ["| club | TrackMan impact height (mm) | shots | measured smash | predicted smash (adjusted) | ball speed bias (mph) |",
          "|---|---|---|---|---|---|"]
for club in ["8 Iron", "5 Iron"]:
    for lo, hi in [(-99, 3), (3, 9), (9, 13), (13, 99)]:
        g = [x for x in json.load(open(f"{out}/strike-height.json")) if x["club"] == club and lo <= x["v"] < hi]
        if not g:
            continue
        label = f"below {hi}" if lo == -99 else (f"{lo} and above" if hi == 99 else f"{lo} to {hi}")
        mean = lambda f: sum(f(x) for x in g) / len(g)
        strike.append(f"| {club} | {label} | {len(g)} | {mean(lambda x: x['ball_speed'] / x['club_speed']):.3f} | "
                      f"{mean(lambda x: x['predicted'] / x['club_speed']):.3f} | {mean(lambda x: x['predicted'] - x['ball_speed']):+.1f} |")

heel_toe = ["| club | TrackMan impact offset (mm), strikes 3 to 13 mm up | shots | measured smash | ball speed bias, adjusted (mph) | ball speed bias, ground --soil none (mph) |",
            "|---|---|---|---|---|---|"]
for club in ["8 Iron", "5 Iron"]:
    for lo, hi, label in [(-99, -3, "heel, below -3"), (-3, 3, "-3 to 3"), (3, 99, "toe, 3 and above")]:
        g = [x for x in json.load(open(f"{out}/strike-height.json"))
             if x["club"] == club and 3 <= x["v"] < 13 and lo <= x["h"] < hi]
        if not g:
            continue
        mean = lambda f: sum(f(x) for x in g) / len(g)
        heel_toe.append(f"| {club} | {label} | {len(g)} | {mean(lambda x: x['ball_speed'] / x['club_speed']):.3f} | "
                        f"{mean(lambda x: x['predicted'] - x['ball_speed']):+.1f} | {mean(lambda x: x['on_shaft'] - x['ball_speed']):+.1f} |")

spin_launch = ["| club | measured spins | TrackMan's ball-to-face angle (deg) | the seed's ball needs (deg) | launch below TrackMan's (deg) | spin at TrackMan's launch (rpm, MAE) |",
               "|---|---|---|---|---|---|"]
lines = open("tests/data/trackman/validation-8i-5i.csv", encoding="utf-8-sig").read().splitlines()
rows = list(csv.reader(lines[1:]))
head, per_club = rows[0], {}
for r in rows[2:]:
    d = dict(zip(head, r))
    if d["Spin Rate Type"] != "Measured" or not d["Dyn. Loft"] or not d["Club Speed"] or not d["Impact Height"]:
        continue
    def unit(e, a):
        e, a = math.radians(float(e)), math.radians(float(a))
        return (math.cos(e) * math.cos(a), math.sin(e), math.cos(e) * math.sin(a))
    n, b = unit(d["Dyn. Loft"], d["Face Angle"]), unit(d["Launch Angle"], d["Launch Direction"])
    a = math.acos(max(-1.0, min(1.0, sum(p * q for p, q in zip(n, b)))))
    w = float(d["Spin Rate"]) * 2 * math.pi / 60
    need = math.asin(min(1.0, w * 0.0213 / (2.5 * float(d["Ball Speed"]) * 0.44704)))
    bound = 2.5 * float(d["Ball Speed"]) * 0.44704 * math.sin(a) / 0.0213 * 60 / (2 * math.pi)
    per_club.setdefault(d["Club"], []).append((math.degrees(a), math.degrees(need), abs(bound - float(d["Spin Rate"]))))
for club, q in per_club.items():
    m = lambda i: sum(x[i] for x in q) / len(q)
    spin_launch.append(f"| {club} | {len(q)} | {m(0):.2f} | {m(1):.2f} | {m(1) - m(0):.2f} | {m(2):.0f} |")

def report_tables(split):
    """One table per report session of the split, with what was left out before the models ran."""
    rows = []
    for session in open(f"{out}/report-{split}.list").read().split():
        r = json.load(open(f"{out}/report-{session}.json"))
        rows.append(f"**{session[:10]}** (`report-{session}.json`)\n")
        notes = []
        sk = r["skipped_rows"]
        if sk["without_club_or_ball"]:
            notes.append(f"{sk['without_club_or_ball']} without club or ball speed")
        if sk["incomplete_club_data"]:
            notes.append(f"{sk['incomplete_club_data']} with club speed but incomplete club data")
        for n in r["no_preset"]:
            notes.append(f"{n['shots']} {n['label']} (no preset)")
        if r["unlocated_left_out"]:
            notes.append(f"{r['unlocated_left_out']} without an impact location")
        for c in r["clubs"]:
            for reason, n in c["refused"].items():
                notes.append(f"{n} {c['label']} refused by the club ({reason})")
        if notes:
            rows.append("Strokes left out: " + "; ".join(notes) + ".\n")
        table = club_table(f"report-{session}.json")
        rows += [t for t in table if t.startswith("|")]
        rows.append("")
    return rows[:-1]


variants = ["| the 8- and 5-iron presets | 8-iron ball speed MAE / bias (mph) | 5-iron ball speed MAE / bias (mph) | 8-iron spin MAE (rpm) |",
            "|---|---|---|---|"]
for v in json.load(open(f"{out}/variants.json")):
    c8, c5 = v["cells"]["8 Iron"], v["cells"]["5 Iron"]
    variants.append(f"| {v['label']} | {c8[0]:.2f} / {c8[1]:+.2f} | {c5[0]:.2f} / {c5[1]:+.2f} | {c8[2]:.0f} |")

docs_regions.replace("research/real-shots.md", {
    "report-validation": report_tables("validation"),
    "report-heldout": report_tables("heldout"),
    "variants": variants,
    "relation": relation,
    "tour": tour,
    "validation": club_table("validation.json"),
    "validation-all": club_table("validation-all.json"),
    "height": height,
    "reference": reference,
    "slope": slope,
    "heldout": club_table("heldout.json"),
    "strike-height": strike,
    "heel-toe": heel_toe,
    "spin-launch": spin_launch,
    "spin-relation": club_table("spin-relation.json"),
    "heldout-relation": club_table("heldout-relation.json"),
    "matched": json.load(open(f"{out}/matched-validation.json")),
    "height-errors": json.load(open(f"{out}/height-errors-validation.json")),
    "matched-heldout": json.load(open(f"{out}/matched-heldout.json")),
    "height-errors-heldout": json.load(open(f"{out}/height-errors-heldout.json")),
})
PY
