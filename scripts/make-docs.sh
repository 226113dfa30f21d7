#!/usr/bin/env bash
# Regenerates the numeric tables and figures of docs/ (the manual) and research/ (the findings) from the commands'
# JSON output, and ARCHITECTURE.md's equation index:
#   impactd eval extrapolation --json   -> docs/estimation.md, regions extrapolation-*
#   impactd bench --json --baseline     -> docs/performance.md, region bench (scripts/docs-bench.sh)
#   impactd predict --club iron7        -> research/offcentre-iron.md, region offcentre (research/scripts/offcentre-iron.py)
#   impactd predict [--flight]          -> research/models-notes.md, regions gear-driver, gear-iron (research/scripts/gear-effect.py)
#   impactd map                         -> docs/map-iron7-ball-speed.svg, docs/map-driver-offline.svg
#   examples/ground_face (JSON lines)   -> docs/ground.md and research/ground-findings.md (scripts/ground-table.py)
#   impactd predict --model ground      -> research/ground-sensitivity.md (research/scripts/ground-sensitivity.py)
#   examples/ground_parts (JSON lines)  -> research/ground-parts.md (research/scripts/ground-parts.py)
#   scripts/club-data-docs.sh           -> docs/club-data.md, region club-data
#   research/scripts/real-shots-docs.sh -> research/real-shots.md (compare --by-club on the real TrackMan sessions)
#   research/scripts/driver-axis.py     -> research/driver-axis.md (the driver's spin axis, validation report sessions)
#   research/scripts/wedge-spin-docs.sh -> research/wedge-spin.md (the spin decomposition, the slip model's obliquity law)
#   scripts/docs-identify.sh            -> docs/identify.md (compare, fit time, live latency) and
#                                          research/identify-results.md (recovery, bounds, cross-validation)
#   scripts/flight-docs.py              -> docs/flight.md (coefficients) and research/flight-fit.md (the fit's tables)
#   scripts/docs-hostile.sh            -> docs/hostile-peers.md (the honest rig's latency beside each hostile probe)
#   scripts/equation-index.py           -> ARCHITECTURE.md, region equations (where each seed equation is cited)
#   impactd models [--sections]         -> README.md region models, docs/club-files.md region sections
# Each table sits between `<!-- generated: NAME -->` and `<!-- end -->`; the text around it is left alone.
# Usage: scripts/make-docs.sh   (SHOTS=N for another number of swings per evaluation; default 200000; about 30 minutes in all on 2 cores, most of it docs-identify.sh)
set -euo pipefail
cd "$(dirname "$0")/.."

python3 scripts/equation-index.py

SHOTS="${SHOTS:-200000}"
cargo build --release --quiet
BIN=target/release/impactd
BIN="$BIN" bash scripts/registry-docs.sh
OUT="$(mktemp -d)"
trap 'rm -rf "$OUT"' EXIT

for club in driver iron7; do
    for rate in 240 720 1000; do
        echo "eval extrapolation: $club, arc paths, $rate Hz, $SHOTS swings" >&2
        "$BIN" eval extrapolation --club "$club" --rate "$rate" --shots "$SHOTS" --seed 1 --json \
            2>/dev/null >"$OUT/arc-$club-$rate.json"
    done
    echo "eval extrapolation: $club, double-pendulum paths, 720 Hz, $SHOTS swings" >&2
    "$BIN" eval extrapolation --club "$club" --rate 720 --shots "$SHOTS" --seed 1 --path double-pendulum --json \
        2>/dev/null >"$OUT/pendulum-$club.json"
done
echo "bench" >&2
scripts/docs-bench.sh
echo "ground model over the face: docs/ground.md, research/ground-findings.md, research/ground-sensitivity.md, research/ground-parts.md" >&2
cargo run --release --quiet --example ground_face >"$OUT/ground-face.jsonl"
python3 scripts/ground-table.py docs/ground.md research/ground-findings.md <"$OUT/ground-face.jsonl"
python3 research/scripts/ground-sensitivity.py "$BIN" >research/ground-sensitivity.md
cargo run --release --quiet --example ground_parts | python3 research/scripts/ground-parts.py research/ground-parts.md

python3 - "$OUT" "$SHOTS" <<'PY'
import json, os, sys

out, shots = sys.argv[1], int(sys.argv[2])

ROWS = [
    ("club_speed_pct", "club speed (%)"),
    ("attack_angle_deg", "attack angle (deg)"),
    ("club_path_deg", "club path (deg)"),
    ("face_angle_deg", "face angle (deg)"),
    ("dynamic_loft_deg", "dynamic loft (deg)"),
    ("impact_h_mm", "impact h (mm)"),
    ("impact_v_mm", "impact v (mm)"),
    ("t_impact_us", "impact time (us)"),
    ("ball_speed_mph", "ball speed (mph)"),
    ("launch_angle_deg", "launch angle (deg)"),
    ("launch_direction_deg", "launch direction (deg)"),
    ("backspin_rpm", "backspin (rpm)"),
    ("sidespin_rpm", "sidespin (rpm)"),
]
CLUB = {"driver": "driver", "iron7": "7-iron"}


def load(name):
    with open(os.path.join(out, name)) as f:
        return json.load(f)


def num(x):
    """Three significant figures, as the hand-written tables had them."""
    if x != x:
        return "n/a"
    if x >= 100:
        return f"{x:.0f}"
    return f"{x:.3g}" if x >= 1 else f"{x:.2g}" if x < 0.1 else f"{x:.2f}"


def table(title, columns):
    """columns: [(header, estimator report)]; one row per error, RMS."""
    lines = ["| " + title + " | " + " | ".join(h for h, _ in columns) + " |",
             "|" + "---|" * (len(columns) + 1)]
    for key, label in ROWS:
        lines.append("| " + label + " | " + " | ".join(num(e["errors"][key]["rms"]) for _, e in columns) + " |")
    refused = sum(sum(e["refused"].values()) for _, e in columns)
    note = f"RMS of {shots} swings per column, seed 1, 0.2 mm and 0.1 deg of noise"
    if refused:
        note += f"; {refused} estimates refused in all"
    return lines + ["", note + "."]


def arc_table(club):
    cols = []
    for rate in (240, 720, 1000):
        r = load(f"arc-{club}-{rate}.json")
        cols += [(f"{rate} Hz {e['name']}", e) for e in r["estimators"]]
    return table(CLUB[club], cols)


def pendulum_table():
    cols = []
    for club in ("driver", "iron7"):
        r = load(f"pendulum-{club}.json")
        cols += [(f"{CLUB[club]} {e['name']}", e) for e in r["estimators"]]
    return table("double pendulum, 720 Hz", cols)


sys.path.insert(0, "scripts")
from docs_regions import replace  # noqa: E402


replace("docs/estimation.md", {
    "extrapolation-arc-driver": arc_table("driver"),
    "extrapolation-arc-iron7": arc_table("iron7"),
    "extrapolation-double-pendulum": pendulum_table(),
})
PY
echo "off-centre iron table" >&2
python3 research/scripts/offcentre-iron.py "$BIN"
echo "off-centre tables of the continuous model" >&2
python3 research/scripts/gear-effect.py "$BIN"
echo "face maps" >&2
"$BIN" map --club iron7 --metric ball-speed --club-speed-mph 85 --attack-angle-deg=-4.5 -o docs/map-iron7-ball-speed.svg 2>/dev/null
"$BIN" map --club driver --metric offline --club-speed-mph 100 --club-path-deg=-2 --face-angle-deg 1 -o docs/map-driver-offline.svg 2>/dev/null
scripts/club-data-docs.sh
echo "flight fit" >&2
python3 scripts/flight-docs.py
research/scripts/real-shots-docs.sh
python3 research/scripts/driver-axis.py
research/scripts/wedge-spin-docs.sh
echo "hostile peers" >&2
scripts/docs-hostile.sh

# docs/identify.md: comparison, recovery, fit time and live latency (about 20 minutes more on 2 shared cores).
scripts/docs-identify.sh
