#!/usr/bin/env bash
# Rewrites docs/performance.md's region `bench` from `impactd bench --json --baseline FILE`: each stage's median
# per operation, the saved run's and their ratio, the stages slower by more than 20 %, the date, the machine and
# the load average before and after (all from the JSON). Without a baseline file the table has the medians alone.
# README.md's region `readme-bench` gets the short table users read, from the same run.
# Usage: scripts/docs-bench.sh [BASELINE.json]   (default docs/bench-baseline.json when it exists)
set -euo pipefail
cd "$(dirname "$0")/.."

BASELINE="${1:-docs/bench-baseline.json}"
cargo build --release --quiet
BIN=target/release/impactd
OUT="$(mktemp)"
trap 'rm -f "$OUT"' EXIT
if [[ -f "$BASELINE" ]]; then
    "$BIN" bench --json --baseline "$BASELINE" >"$OUT"
else
    "$BIN" bench --json >"$OUT"
fi
python3 - "$OUT" <<'PY'
import json, sys

sys.path.insert(0, "scripts")
from docs_regions import replace  # noqa: E402

with open(sys.argv[1]) as f:
    run = json.load(f)


def t(ns):
    return f"{ns:.0f} ns" if ns < 1e3 else f"{ns / 1e3:.3g} us" if ns < 1e6 else f"{ns / 1e6:.3g} ms"


base = run.get("baseline")
if base:
    lines = ["| stage | median per op | baseline | ratio |", "|---|---|---|---|"]
    for s in run["stages"]:
        if "ratio" in s:
            lines.append(f"| {s['name']} | {t(s['ns_per_op'])} | {t(s['baseline_ns_per_op'])} | {s['ratio']:.2f} |")
        else:
            lines.append(f"| {s['name']} | {t(s['ns_per_op'])} | | |")
    slower = run.get("slower", [])
    lines += ["", f"Against `{base}`: " + (
        "slower by more than 20 %: " + ", ".join(slower) + "." if slower else "no stage slower by more than 20 %.")]
else:
    lines = ["| stage | median per op |", "|---|---|"]
    lines += [f"| {s['name']} | {t(s['ns_per_op'])} |" for s in run["stages"]]
load = [x for x in run.get("load", []) if x is not None]
at_load = f", load {load[0]:.1f} before and {load[-1]:.1f} after" if load else ""
lines += ["", f"`impactd bench --json`, {run['date']}, {run['machine']}{at_load}."]
replace("docs/performance.md", {"bench": lines})

ns = {s["name"]: s["ns_per_op"] for s in run["stages"]}


def pair(a, b):
    return f"{t(ns[a])} / {t(ns[b])}" if a in ns and b in ns else "not run"


readme = [f"`impactd bench` medians of {run['date']}, {run['machine']}{at_load} (all stages:",
          "[docs/performance.md](docs/performance.md)):", "",
          "| stage | time |", "|---|---|",
          f"| impulse models, driver / iron7 | {pair('adjusted/driver', 'adjusted/iron7')} |",
          f"| continuous two-layer, driver / iron7 | {pair('continuous/driver', 'continuous/iron7')} |",
          f"| maw, driver / iron7 | {pair('maw/driver', 'maw/iron7')} |",
          f"| arakawa, driver / iron7 | {pair('arakawa/driver', 'arakawa/iron7')} |",
          f"| ground: thin / fat 7-iron | {pair('ground/iron7', 'ground/firm/iron7_fat')} |",
          f"| arc extrapolation, driver / iron7 | {pair('extrapolate/arc/driver', 'extrapolate/arc/iron7')} |",
          f"| flight | {t(ns['flight/trajectory']) if 'flight/trajectory' in ns else 'not run'} |",
          f"| pipeline per sample, driver / iron7 | {pair('pipeline/sample/driver', 'pipeline/sample/iron7')} |"]
replace("README.md", {"readme-bench": readme})
PY
