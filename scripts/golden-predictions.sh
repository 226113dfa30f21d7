#!/usr/bin/env bash
# Compares two builds' predictions on the golden deliveries: `impactd predict --json` lines (with and without
# `--trace`) of the deliveries in tests/data/im-golden.jsonl and of docs-models.sh's grid (35, 45, 55 m/s, centred
# and 15 mm toe / 5 mm up), per club and model. Prints `identical` or, per differing case, the largest relative
# difference of any number in it; exits 1 if any differ.
# Usage: scripts/golden-predictions.sh BASELINE_IMPACTD [THIS_IMPACTD] [MODEL...]   (default: every model of the
# registry, as `impactd models --names` lists them)
set -euo pipefail
cd "$(dirname "$0")/.."
BASE="$1"
NEW="${2:-target/release/impactd}"
shift $(($# < 2 ? $# : 2))
if [ $# -gt 0 ]; then MODELS=("$@"); else mapfile -t MODELS < <("$NEW" models --names); fi
python3 - "$BASE" "$NEW" ${MODELS[@]} <<'PY'
import json, subprocess, sys

base, new, models = sys.argv[1], sys.argv[2], sys.argv[3:]
clubs = {"driver": (13.0, -1.3), "iron7": (25.0, -4.3)}
lines = {c: [] for c in clubs}
seen = set()
with open("tests/data/im-golden.jsonl") as f:
    for line in f:
        d = json.loads(line)
        key = (d["club"], json.dumps(d["delivery"], sort_keys=True))
        if key not in seen:
            seen.add(key)
            lines[d["club"]].append(json.dumps(d["delivery"]))
for club, (loft, attack) in clubs.items():
    for mps in (35.0, 45.0, 55.0):
        for h, v in ((0.0, 0.0), (15.0, 5.0)):
            lines[club].append(json.dumps({"club_speed_mph": mps / 0.44704, "attack_angle_deg": attack,
                                           "dynamic_loft_deg": loft, "impact_h_mm": h, "impact_v_mm": v}))


def numbers(x, path=""):
    if isinstance(x, dict):
        for k, v in x.items():
            yield from numbers(v, f"{path}.{k}")
    elif isinstance(x, list):
        for i, v in enumerate(x):
            yield from numbers(v, f"{path}[{i}]")
    elif isinstance(x, (int, float)) and not isinstance(x, bool):
        yield path, float(x)


differ = 0
cases = 0
for club, ds in lines.items():
    for model in models:
        for trace in ([], ["--trace"]):
            args = ["predict", "--club", club, "--model", model] + trace
            text = "\n".join(ds) + "\n"
            a = subprocess.run([base] + args, input=text, capture_output=True, text=True)
            b = subprocess.run([new] + args, input=text, capture_output=True, text=True)
            cases += 1
            name = f"{club} {model}{' --trace' if trace else ''}"
            if (a.stdout, a.returncode) == (b.stdout, b.returncode):
                continue
            differ += 1
            worst = (0.0, "")
            for la, lb in zip(a.stdout.splitlines(), b.stdout.splitlines()):
                na, nb = list(numbers(json.loads(la))), list(numbers(json.loads(lb)))
                if [p for p, _ in na] != [p for p, _ in nb]:
                    worst = (float("inf"), "fields differ")
                    break
                for (p, x), (_, y) in zip(na, nb):
                    rel = abs(x - y) / max(abs(x), abs(y), 1e-300) if x != y else 0.0
                    if rel > worst[0]:
                        worst = (rel, f"{p}: {x!r} vs {y!r}")
            print(f"{name}: differs, largest relative {worst[0]:.3g} ({worst[1]})")
print(f"{cases - differ} of {cases} cases identical")
sys.exit(1 if differ else 0)
PY
