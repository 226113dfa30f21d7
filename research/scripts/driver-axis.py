#!/usr/bin/env python3
"""Regenerates the tables of research/driver-axis.md: the driver's spin axis against the third player's VALIDATION
report sessions (tests/data/trackman/report-*.json: 2025-03-13, 2025-07-11, 2025-10-30, 2026-02-14; the held-out
sessions are not read), each stroke selected as `impactd compare --by-club --located` selects it (a driver with
club data and an impact location; spin and axis only where `ReducedAccuracy` names neither), each delivery read
one way or another and run through `impactd predict`:

  region geometry   TrackMan's own numbers: its spin axis against the tilt of `n x b` (its face normal n, its
                    ball direction b), per session and per club; the normal turn that the axis needs; launch
                    direction against face, path and impact offset, TrackMan's and the models'
  region adjusted   the adjusted model with one of Table 3.3's adjustments at a time (club files with `[adjusted]`)
  region readings   the spin axis under each reading of TrackMan's face, every impulse-momentum and continuous
                    model but Arakawa
  region readings-other  ball speed, launch and spin under the same readings (standard and adjusted, pooled)
  region identified  the slip model on copies of the driver preset with its vertical-axis inertia scaled and e_z
                    varied: the axis a two-parameter identification on these sessions reaches
  region flight     TrackMan's axis against its own curve: the curve per unit of carry against the sine of the
                    axis and of the tilt of `n x b`
  region floor      a turn of TrackMan's face linear in the delivery, fitted on the strokes to their axis
  region across     the same turn fitted on three sessions and applied to the fourth

The contact-point reading (`compare --by-club`'s) is `examples/face_centre_reading`. Usage, from the repository:
`research/scripts/driver-axis.py` (builds impactd and the example; a few minutes on 2 cores).
"""
import json
import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from docs_regions import replace  # noqa: E402

BIN = "target/release/impactd"
READ = "target/release/examples/face_centre_reading"
DOC = "research/driver-axis.md"
DATA = "tests/data/trackman"
VALIDATION = ["2025-03-13-pw-driver-5w-7i", "2025-07-11-driver-4i-5h-pw", "2025-10-30-5w-driver-6i-9i",
              "2026-02-14-driver-7i"]
MPH = 1 / 0.44704
MODELS = ["standard", "adjusted", "slip", "continuous", "maw"]
# Table 3.1: the ball, and the driver head (mass, CG -> face centre, inertia about the CG, loft).
M_BALL, R_BALL = 0.0459, 0.0213
CG_TO_FACE_M = (0.0408, 0.0114, 0.001)
INERTIA_G_CM2 = ((2843.0, -733.0, 530.2), (-733.0, 5679.0, 0.5), (530.2, 0.5, 4085.0))
LOFT_DEG = 9.8
# The contact lasts about 0.45 ms (research/real-shots.md: 0.4-0.5 ms); under a half-sine force the head has turned
# 0.0908 T times its final rate change by maximum compression (T/2) and, weighted by the force, T/8 on average.
CONTACT_S = 0.45e-3
TMP = tempfile.mkdtemp()


# --- small vector algebra (no numpy: the docs scripts run on a plain python3) ---
def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def norm(a):
    return math.sqrt(dot(a, a))


def scale(a, s):
    return tuple(x * s for x in a)


def add(a, b):
    return tuple(x + y for x, y in zip(a, b))


def matvec(m, v):
    return tuple(dot(row, v) for row in m)


def transpose(m):
    return tuple(tuple(m[j][i] for j in range(3)) for i in range(3))


def matmul(a, b):
    bt = transpose(b)
    return tuple(tuple(dot(row, col) for col in bt) for row in a)


def solve3(m, v):
    """m x = v by Cramer's rule."""
    def det(a):
        return (a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
                + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]))
    d = det(m)
    out = []
    for c in range(3):
        a = [list(r) for r in m]
        for r in range(3):
            a[r][c] = v[r]
        out.append(det(a) / d)
    return tuple(out)


def rotate(v, axis_angle):
    """Rodrigues: v turned by the rotation vector `axis_angle` (rad)."""
    th = norm(axis_angle)
    if th < 1e-15:
        return v
    k = scale(axis_angle, 1 / th)
    return add(add(scale(v, math.cos(th)), scale(cross(k, v), math.sin(th))), scale(k, dot(k, v) * (1 - math.cos(th))))


def lstsq(columns, y):
    """Least squares of y on the columns (normal equations), the coefficients and the residuals."""
    n = len(columns)
    a = [[dot(columns[i], columns[j]) for j in range(n)] for i in range(n)]
    b = [dot(columns[i], y) for i in range(n)]
    for i in range(n):  # Gauss-Jordan
        p = a[i][i]
        for j in range(n):
            a[i][j] /= p
        b[i] /= p
        for k in range(n):
            if k != i:
                f = a[k][i]
                for j in range(n):
                    a[k][j] -= f * a[i][j]
                b[k] -= f * b[i]
    resid = [yy - sum(b[i] * columns[i][r] for i in range(n)) for r, yy in enumerate(y)]
    return b, resid


def mean(v):
    return sum(v) / len(v)


def sd(v):
    m = mean(v)
    return math.sqrt(sum((x - m) ** 2 for x in v) / len(v))


# --- TrackMan's geometry ---
def unit(elevation_deg, azimuth_deg):
    e, a = math.radians(elevation_deg), math.radians(azimuth_deg)
    return (math.cos(e) * math.cos(a), math.sin(e), math.cos(e) * math.sin(a))


def angles(n):
    """Elevation and azimuth (deg) of a direction."""
    return math.degrees(math.asin(max(-1.0, min(1.0, n[1] / norm(n))))), math.degrees(math.atan2(n[2], n[0]))


def axis_deg(w, u):
    """TrackMan's spin axis of the spin w for a ball along u (ARCHITECTURE.md section 2)."""
    a = cross(u, (0.0, 1.0, 0.0))
    a = scale(a, 1 / norm(a))
    up = cross(a, u)
    return math.degrees(math.atan2(-dot(w, up), dot(w, a)))


def tilt(n, b):
    """The spin axis of a rigid ball that left a face of normal n along b: its spin is along b x n."""
    return axis_deg(cross(b, n), b)


def strokes(session, club="Driver"):
    with open(f"{DATA}/report-{session}.json", encoding="utf-8") as f:
        report = json.load(f)
    for g in report["StrokeGroups"]:
        for st in g["Strokes"]:
            if (st.get("Club") or g.get("Club")) != club:
                continue
            m = st.get("Measurement") or {}
            if not all(k in m for k in ["ClubSpeed", "BallSpeed", "AttackAngle", "ClubPath", "FaceAngle", "DynamicLoft"]):
                continue
            if "ImpactHeight" not in m:
                continue
            ra = m.get("ReducedAccuracy") or []
            m["spin_measured"] = not ("SpinRate" in ra or "SpinAxis" in ra)
            m["axis_measured"] = m["spin_measured"] and "SpinAxis" in m
            yield m


def delivery(m, face_deg=None, loft_deg=None):
    """TrackMan's row as a delivery whose loft and face are the contact point's (before the face-centre reading)."""
    d = {"club_speed_mph": m["ClubSpeed"] * MPH, "attack_angle_deg": m["AttackAngle"], "club_path_deg": m["ClubPath"],
         "face_angle_deg": m["FaceAngle"] if face_deg is None else face_deg,
         "dynamic_loft_deg": m["DynamicLoft"] if loft_deg is None else loft_deg,
         "impact_h_mm": m["ImpactOffset"] * 1e3, "impact_v_mm": m["ImpactHeight"] * 1e3}
    if m.get("DynamicLie") is not None:
        d["dynamic_lie_deg"] = m["DynamicLie"]
    return d


def face_centre(lines, club="driver"):
    text = "".join(json.dumps(d) + "\n" for d in lines)
    out = subprocess.run([READ, club], input=text, capture_output=True, text=True, check=True).stdout
    return [json.loads(x) for x in out.splitlines()]


def predict(lines, model, club="driver"):
    text = "".join(json.dumps(d) + "\n" for d in lines)
    out = subprocess.run([BIN, "predict", "--club", club, "--model", model], input=text, capture_output=True, text=True,
                         check=True).stdout
    return [json.loads(x) for x in out.splitlines()]


def errors(ms, preds):
    e = {"speed": [], "launch": [], "spin": [], "axis": [], "direction": []}
    for m, q in zip(ms, preds):
        e["speed"].append(q["ball_speed_mph"] - m["BallSpeed"] * MPH)
        e["launch"].append(q["launch_angle_deg"] - m["LaunchAngle"])
        e["direction"].append(q["launch_direction_deg"] - m["LaunchDirection"])
        if m["spin_measured"]:
            e["spin"].append(q["total_spin_rpm"] - m["SpinRate"])
        if m["axis_measured"]:
            e["axis"].append(q["spin_axis_deg"] - m["SpinAxis"])
    return e


def mae_bias(v, digits=2):
    return f"{mean([abs(x) for x in v]):.{digits}f} / {mean(v):+.{digits}f}"


SESSIONS = {s: list(strokes(s)) for s in VALIDATION}


# --- region geometry ---
def geometry():
    rows = ["| session | drivers with a measured axis | TrackMan's axis, mean (deg) | tilt of n x b, mean (deg) | "
            "axis / tilt (least squares) | MAE of the tilt as the axis (deg) |", "|---|---|---|---|---|---|"]
    every = []
    for s, ms in SESSIONS.items():
        g = [(m["SpinAxis"], tilt(unit(m["DynamicLoft"], m["FaceAngle"]), unit(m["LaunchAngle"], m["LaunchDirection"])), m)
             for m in ms if m["axis_measured"]]
        every += g
        k = sum(a * t for a, t, _ in g) / sum(t * t for _, t, _ in g)
        rows.append(f"| {s[:10]} | {len(g)} | {mean([a for a, _, _ in g]):+.2f} | {mean([t for _, t, _ in g]):+.2f} | "
                    f"{k:.3f} | {mean([abs(a - t) for a, t, _ in g]):.2f} |")
    k = sum(a * t for a, t, _ in every) / sum(t * t for _, t, _ in every)
    rows.append(f"| all four | {len(every)} | {mean([a for a, _, _ in every]):+.2f} | {mean([t for _, t, _ in every]):+.2f} | "
                f"{k:.3f} | {mean([abs(a - t) for a, t, _ in every]):.2f} |")
    rows += ["", "| club (the same sessions) | strokes with a measured axis | axis / tilt (least squares) | "
             "MAE of the tilt as the axis (deg) |", "|---|---|---|---|"]
    for club in ["7Iron", "4Iron", "6Iron", "9Iron", "PitchingWedge"]:
        g = [(m["SpinAxis"], tilt(unit(m["DynamicLoft"], m["FaceAngle"]), unit(m["LaunchAngle"], m["LaunchDirection"])))
             for s in VALIDATION for m in strokes(s, club) if m["axis_measured"]]
        if g:
            k = sum(a * t for a, t in g) / sum(t * t for _, t in g)
            rows.append(f"| {club} | {len(g)} | {k:.3f} | {mean([abs(a - t) for a, t in g]):.2f} |")
    # The turn of TrackMan's face (about the vertical, open +) that makes n x b tilt as TrackMan's axis, by bisection.
    turns, h_mm, gap = [], [], []
    for _, _, m in every:
        b = unit(m["LaunchAngle"], m["LaunchDirection"])
        turns.append(needed_turn(m))
        h_mm.append(m["ImpactOffset"] * 1e3)
        gap.append(math.degrees(math.acos(dot(unit(m["DynamicLoft"], m["FaceAngle"]), b))))
    (c_h, c0), resid = lstsq([h_mm, [1.0] * len(h_mm)], turns)
    notes = {"turn_per_mm": c_h, "turn_0": c0, "turn_resid_sd": sd(resid), "turn_sd": sd(turns), "gap_mean": mean(gap),
             "gap_min": min(gap), "gap_max": max(gap), "n": len(turns)}
    # Launch direction against face, path and impact location: TrackMan's, and the models' (contact-point reading).
    lines = [(m, delivery(m)) for ms in SESSIONS.values() for m in ms]
    read = face_centre([d for _, d in lines])
    rel = ["| launch direction of | LD - path per (face - path) | per mm of impact offset (toe +) | per mm of impact "
           "height | residual SD (deg) |", "|---|---|---|---|---|"]
    for who in ["TrackMan", "standard", "adjusted", "continuous"]:
        ld = ([m["LaunchDirection"] for m, _ in lines] if who == "TrackMan"
              else [q["launch_direction_deg"] for q in predict(read, who)])
        cols = [[m["FaceAngle"] - m["ClubPath"] for m, _ in lines], [m["ImpactOffset"] * 1e3 for m, _ in lines],
                [m["ImpactHeight"] * 1e3 for m, _ in lines], [1.0] * len(lines)]
        c, r = lstsq(cols, [x - m["ClubPath"] for x, (m, _) in zip(ld, lines)])
        rel.append(f"| {who} | {c[0]:.3f} | {c[1]:+.4f} | {c[2]:+.4f} | {sd(r):.3f} |")
    notes["ld_shots"] = len(lines)
    return rows, rel, notes


# --- region adjusted ---
def adjusted():
    with open("clubs/presets/driver.toml") as f:
        base = f.read()
    variants = [("standard", None, "standard"), ("adjusted: added mass only (2.54 g)", (0.00254, 0.0, 0.0), "adjusted"),
                ("adjusted: ball CG 0.482 mm down the face only", (0.0, -0.482e-3, 0.0), "adjusted"),
                ("adjusted: ball CG 0.068 mm toward the heel only", (0.0, 0.0, -0.068e-3), "adjusted"),
                ("adjusted (Table 3.3)", None, "adjusted")]
    rows = ["| model | session | ball speed MAE / bias (mph) | launch MAE / bias (deg) | spin MAE / bias (rpm) | "
            "spin axis MAE / bias (deg) |", "|---|---|---|---|---|---|"]
    for label, p, model in variants:
        club = "driver"
        if p is not None:
            club = f"{TMP}/adjusted.toml"
            with open(club, "w") as f:
                f.write(base + f"\n[adjusted]\ndelta_mass_kg = {p[0]}\nball_cg_shift_m = [0.0, {p[1]}, {p[2]}]\n")
        for s, ms in SESSIONS.items():
            e = errors(ms, predict(face_centre([delivery(m) for m in ms], club), model, club))
            rows.append(f"| {label} | {s[:10]} | {mae_bias(e['speed'])} | {mae_bias(e['launch'])} | "
                        f"{mae_bias(e['spin'], 0)} | {mae_bias(e['axis'])} |")
    return rows


# --- the head's turn during contact ---
def world_from_club(face_deg, loft_deg):
    """Ry(-face) Rz(loft - static loft), ARCHITECTURE.md section 2 (the dynamic lie's turn about the normal left out)."""
    f, l = math.radians(face_deg), math.radians(loft_deg - LOFT_DEG)
    ry = ((math.cos(-f), 0.0, math.sin(-f)), (0.0, 1.0, 0.0), (-math.sin(-f), 0.0, math.cos(-f)))
    rz = ((math.cos(l), -math.sin(l), 0.0), (math.sin(l), math.cos(l), 0.0), (0.0, 0.0, 1.0))
    return matmul(ry, rz)


def head_turn_rate(centre, ball_velocity):
    """The head's angular velocity change (rad/s, world) from the impulse that gave the ball its velocity: Table
    3.1's driver, the contact at the impact location on the face-centre plane (the bulge's sag left out)."""
    rot = world_from_club(centre["face_angle_deg"], centre["dynamic_loft_deg"])
    L = math.radians(LOFT_DEG)
    u0, t0 = (-math.sin(L), math.cos(L), 0.0), (0.0, 0.0, 1.0)
    r_club = add(add(CG_TO_FACE_M, scale(t0, centre["impact_h_mm"] * 1e-3)), scale(u0, centre["impact_v_mm"] * 1e-3))
    r = matvec(rot, r_club)
    inertia = matmul(matmul(rot, tuple(tuple(x * 1e-7 for x in row) for row in INERTIA_G_CM2)), transpose(rot))
    impulse = scale(ball_velocity, M_BALL)
    return scale(solve3(inertia, cross(r, impulse)), -1.0)


def turned_reading(ms, fraction):
    """Deliveries whose contact normal is TrackMan's turned by `fraction` x T x the head's rate change (sign: +
    forward in the turn, - back), the rate change from the standard model on the contact-point reading."""
    plain = [delivery(m) for m in ms]
    centre = face_centre(plain)
    out = []
    for m, c, q in zip(ms, centre, predict(centre, "standard")):
        turn = scale(head_turn_rate(c, q["ball_velocity_mps"]), fraction * CONTACT_S)
        e, a = angles(rotate(unit(m["DynamicLoft"], m["FaceAngle"]), turn))
        out.append(delivery(m, face_deg=a, loft_deg=e))
    return out


def through_direction(ms, model):
    """TrackMan's face read through its launch direction: the contact-point face angle at which the model's ball
    leaves in TrackMan's direction (secant steps on each shot)."""
    faces = [m["FaceAngle"] for m in ms]
    for _ in range(6):
        q = predict(face_centre([delivery(m, face_deg=f) for m, f in zip(ms, faces)]), model)
        faces = [f + (m["LaunchDirection"] - p["launch_direction_deg"]) / 0.82 for m, f, p in zip(ms, faces, q)]
    return [delivery(m, face_deg=f) for m, f in zip(ms, faces)]


READINGS = [
    ("contact point (compare --by-club)", lambda ms, model: face_centre([delivery(m) for m in ms])),
    ("face centre", lambda ms, model: [delivery(m) for m in ms]),
    ("maximum compression: the first contact's face turned back by the head's turn to it (0.091 T)",
     lambda ms, model: face_centre(turned_reading(ms, -0.0908))),
    ("before impact: the normal turned on by the force-weighted mean of the head's turn (T / 8)",
     lambda ms, model: face_centre(turned_reading(ms, 0.125))),
    ("face through TrackMan's launch direction", lambda ms, model: face_centre(through_direction(ms, model))),
]


def readings():
    rows = ["| reading | session | " + " | ".join(MODELS) + " |", "|---|---|" + "---|" * len(MODELS)]
    pooled = {}
    for label, reading in READINGS:
        per = {}
        for s, ms in SESSIONS.items():
            cells = []
            for model in MODELS:
                e = errors(ms, predict(reading(ms, model), model))
                cells.append(mae_bias(e["axis"]))
                if model in ("standard", "adjusted"):
                    p = pooled.setdefault((label, model), {"speed": [], "launch": [], "spin": [], "axis": []})
                    for k in p:
                        p[k] += e[k]
            per[s] = cells
            rows.append(f"| {label} | {s[:10]} | " + " | ".join(cells) + " |")
    other = ["| reading | model | ball speed MAE / bias (mph) | launch MAE / bias (deg) | spin MAE / bias (rpm) | "
             "spin axis MAE / bias (deg) |", "|---|---|---|---|---|---|"]
    for (label, model), e in pooled.items():
        other.append(f"| {label} | {model} | {mae_bias(e['speed'])} | {mae_bias(e['launch'])} | "
                     f"{mae_bias(e['spin'], 0)} | {mae_bias(e['axis'])} |")
    return rows, other


# --- region identified ---
def identified():
    with open("clubs/presets/driver.toml") as f:
        base = f.read()
    rows = ["| vertical-axis inertia (g cm2) | e_z | " + " | ".join(s[:10] for s in VALIDATION) +
            " | largest axis MAE (deg) | largest spin MAE (rpm) |", "|---|---|" + "---|" * len(VALIDATION) + "---|---|"]
    for iyy_scale in [1.0, 1.3, 1.6, 2.0]:
        for e_z in [-0.0151, -0.1, -0.2, -0.3, -0.4]:
            club = f"{TMP}/slip.toml"
            iyy = 5679.0 * iyy_scale
            with open(club, "w") as f:
                f.write(base.replace("[-733.0, 5679.0, 0.5]", f"[-733.0, {iyy:.1f}, 0.5]")
                        + f"\n[slip]\ne_y = -0.0103\ne_z = {e_z}\n")
            cells, axes, spins = [], [], []
            for s, ms in SESSIONS.items():
                e = errors(ms, predict(face_centre([delivery(m) for m in ms], club), "slip", club))
                cells.append(mae_bias(e["axis"]))
                axes.append(mean([abs(x) for x in e["axis"]]))
                spins.append(mean([abs(x) for x in e["spin"]]))
            rows.append(f"| {iyy:,.0f} | {e_z:g} | " + " | ".join(cells) + f" | {max(axes):.2f} | {max(spins):.0f} |")
    return rows


# --- region floor ---
def needed_turn(m):
    """The turn of TrackMan's face about the vertical (open +, deg) at which n x b tilts as TrackMan's axis."""
    b = unit(m["LaunchAngle"], m["LaunchDirection"])
    f = lambda d: tilt(unit(m["DynamicLoft"], m["FaceAngle"] + d), b) - m["SpinAxis"]  # noqa: E731
    lo, hi = -10.0, 10.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if f(lo) * f(mid) <= 0 else (mid, hi)
    return lo


def floor():
    """The axis a rigid ball leaving along TrackMan's direction would have if its face were TrackMan's turned by a
    linear function of the delivery, fitted on these very strokes to the axis itself (in sample: what such a
    correction can reach at best on them, not a prediction). The fit minimises the axis MAE by iteratively
    reweighted least squares on the turn, each stroke weighted by the axis' sensitivity to the turn."""
    ms = [(s, m) for s, g in SESSIONS.items() for m in g if m["axis_measured"]]
    turns = [needed_turn(m) for _, m in ms]
    axis_of = lambda m, t: tilt(unit(m["DynamicLoft"], m["FaceAngle"] + t), unit(m["LaunchAngle"],  # noqa: E731
                                                                               m["LaunchDirection"]))
    # d(axis)/d(turn) at the needed turn, deg per deg.
    slope = [(axis_of(m, t + 1e-3) - axis_of(m, t - 1e-3)) / 2e-3 for (_, m), t in zip(ms, turns)]
    features = {
        "impact offset": lambda m: m["ImpactOffset"] * 1e3,
        "impact height": lambda m: m["ImpactHeight"] * 1e3,
        "club speed": lambda m: m["ClubSpeed"],
        "face to path": lambda m: m["FaceAngle"] - m["ClubPath"],
        "attack angle": lambda m: m["AttackAngle"],
        "dynamic loft": lambda m: m["DynamicLoft"],
        "club path": lambda m: m["ClubPath"],
    }
    def fit(names, train):
        """IRLS on the strokes `train`: the coefficients of the turn, linear in the features `names`."""
        cols = [[features[n](m) for _, m in ms] for n in names] + [[1.0] * len(ms)]
        weights = [slope[i] ** 2 for i in train]
        for _ in range(50):
            root = [math.sqrt(w) for w in weights]
            coef, _ = lstsq([[col[i] * r for i, r in zip(train, root)] for col in cols],
                            [turns[i] * r for i, r in zip(train, root)])
            axis_err = [abs(slope[i] * (turns[i] - sum(c * col[i] for c, col in zip(coef, cols)))) for i in train]
            weights = [slope[i] ** 2 / max(e, 1e-3) for i, e in zip(train, axis_err)]
        return [sum(c * col[i] for c, col in zip(coef, cols)) for i in range(len(ms))], len(cols)

    def cells(fitted, which):
        err = {}
        for i, ((s, m), f) in enumerate(zip(ms, fitted)):
            if which(i):
                err.setdefault(s, []).append(abs(axis_of(m, f) - m["SpinAxis"]))
        return [mean(err[s]) for s in VALIDATION if s in err]

    head = ["| the turn of TrackMan's face, linear in | parameters | " + " | ".join(s[:10] for s in VALIDATION)
            + " | largest (deg) |", "|---" * (3 + len(VALIDATION)) + "|"]
    rows, across = list(head), list(head)
    everyone = list(range(len(ms)))
    for label, names in [("a constant", []), ("the impact offset", ["impact offset"]),
                         ("the impact offset and height", ["impact offset", "impact height"]),
                         ("all seven of the delivery", list(features))]:
        fitted, k = fit(names, everyone)
        c = cells(fitted, lambda i: True)
        rows.append(f"| {label} | {k} | " + " | ".join(f"{x:.2f}" for x in c) + f" | {max(c):.2f} |")
        # Fitted on the other three sessions, applied to each one in turn.
        out = []
        for s in VALIDATION:
            fitted, _ = fit(names, [i for i in everyone if ms[i][0] != s])
            out += cells(fitted, lambda i: ms[i][0] == s)
        across.append(f"| {label} | {k} | " + " | ".join(f"{x:.2f}" for x in out) + f" | {max(out):.2f} |")
    return rows, across


# --- region flight ---
def correlation(x, y):
    mx, my = mean(x), mean(y)
    return (sum((a - mx) * (b - my) for a, b in zip(x, y))
            / math.sqrt(sum((a - mx) ** 2 for a in x) * sum((b - my) ** 2 for b in y)))


def flight():
    """TrackMan's spin axis against its curve (the landing point's sideways distance from the launch direction's
    line, per unit of carry), both read by TrackMan from one trajectory, and the rigid-ball tilt against the same."""
    rows = ["| club | strokes with a measured axis and curve | curve / carry against sin(TrackMan's axis): "
            "correlation | against sin(tilt of n x b): correlation |", "|---|---|---|---|"]
    for club in ["Driver", "7Iron", "PitchingWedge"]:
        g = [m for s in VALIDATION for m in strokes(s, club) if m["axis_measured"] and "Curve" in m and m.get("Carry")]
        bend = [m["Curve"] / m["Carry"] for m in g]
        axis = [math.sin(math.radians(m["SpinAxis"])) for m in g]
        rigid = [math.sin(math.radians(tilt(unit(m["DynamicLoft"], m["FaceAngle"]),
                                            unit(m["LaunchAngle"], m["LaunchDirection"])))) for m in g]
        rows.append(f"| {club} | {len(g)} | {correlation(bend, axis):.3f} | {correlation(bend, rigid):.3f} |")
    return rows


def main():
    subprocess.run(["cargo", "build", "--release", "--quiet", "--bin", "impactd", "--example", "face_centre_reading"],
                   check=True)
    geo, relation, notes = geometry()
    with open(f"{TMP}/notes.json", "w") as f:
        json.dump(notes, f)
    print(json.dumps(notes, indent=1), file=sys.stderr)
    turn = [f"On the {notes['n']} drivers with a measured axis the ball left {notes['gap_mean']:.2f} deg from "
            f"TrackMan's normal on average ({notes['gap_min']:.2f} to {notes['gap_max']:.2f}); the turn of "
            f"TrackMan's face (open +) at which `n x b` tilts as TrackMan's axis is {notes['turn_per_mm']:+.4f} deg "
            f"per mm of impact offset {notes['turn_0']:+.3f} deg (residual SD {notes['turn_resid_sd']:.3f} deg, "
            f"the turns' own SD {notes['turn_sd']:.3f})."]
    read, other = readings()
    in_sample, across = floor()
    replace(DOC, {"geometry": geo, "turn": turn, "relation": relation, "adjusted": adjusted(), "readings": read,
                  "readings-other": other, "identified": identified(), "floor": in_sample, "across": across,
                  "flight": flight()})


if __name__ == "__main__":
    main()
