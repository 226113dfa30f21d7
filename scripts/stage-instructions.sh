#!/usr/bin/env bash
# Instructions per operation of `impactd bench` stages, two builds side by side, counted by callgrind (repeatable
# on a busy machine, unlike wall time): each stage is run by examples/stage_loop N times and 0 times, and the
# difference over N is one operation. Rewrites docs/performance.md's region `instructions`.
# Usage: scripts/stage-instructions.sh BASELINE_STAGE_LOOP LABEL   (the other build is this tree's; needs valgrind)
set -euo pipefail
cd "$(dirname "$0")/.."

BASE="$1"
LABEL="$2"
cargo build --release --quiet --example stage_loop
NEW=target/release/examples/stage_loop
STAGES=(continuous/driver continuous/iron7 maw/driver maw/iron7
    arakawa/driver arakawa/iron7 ground/iron7 ground/firm/iron7_fat
    standard/iron7 adjusted/driver extrapolate/poly/driver extrapolate/arc/iron7 club_data/iron7
    flight/trajectory pipeline/sample/iron7)

# A stage's name in a build from before each model was published under its registry name (the registry's
# FORMER_NAMES: maw was continuous/maw, ...).
former() {
    case "$1" in
    continuous/*) echo "continuous/two_layer/${1#continuous/}" ;;
    maw/* | arakawa/*) echo "continuous/$1" ;;
    standard/* | adjusted/* | slip/*) echo "impulse/$1" ;;
    *) echo "$1" ;;
    esac
}

count() { # BIN STAGE N -> instructions (under the stage's former name when the build does not know it)
    local stage="$2"
    "$1" "$stage" 0 >/dev/null 2>&1 || stage="$(former "$2")"
    valgrind --tool=callgrind --callgrind-out-file=/dev/null "$1" "$stage" "$3" 2>&1 | sed -n 's/.*Collected : //p'
}

OUT="$(mktemp)"
trap 'rm -f "$OUT"' EXIT
for stage in "${STAGES[@]}"; do
    n=20
    [[ "$stage" == standard/* || "$stage" == adjusted/* || "$stage" == slip/* || "$stage" == pipeline/* || "$stage" == club_data/* ]] && n=2000
    [[ "$stage" == extrapolate/* || "$stage" == flight/* ]] && n=200
    row="$stage $n"
    for bin in "$BASE" "$NEW"; do
        row="$row $(count "$bin" "$stage" 0) $(count "$bin" "$stage" "$n")"
    done
    echo "$row" >>"$OUT"
    echo "$row" >&2
done
python3 - "$OUT" "$LABEL" <<'PY'
import sys

sys.path.insert(0, "scripts")
from docs_regions import replace  # noqa: E402

label = sys.argv[2]
lines = [f"| stage | {label} | this build | speed-up |", "|---|---|---|---|"]


def m(x):
    return f"{x / 1e6:.2f} M" if x >= 1e6 else f"{x / 1e3:.1f} k" if x >= 1e3 else f"{x:.0f}"


with open(sys.argv[1]) as f:
    for line in f:
        stage, n, b0, b1, n0, n1 = line.split()
        n = int(n)
        base, new = (int(b1) - int(b0)) / n, (int(n1) - int(n0)) / n
        lines.append(f"| {stage} | {m(base)} | {m(new)} | {base / new:.2f}x |")
lines += ["", f"Instructions per operation (callgrind, `examples/stage_loop STAGE N` less `STAGE 0`, over N), "
          f"`scripts/stage-instructions.sh`."]
replace("docs/performance.md", {"instructions": lines})
PY
