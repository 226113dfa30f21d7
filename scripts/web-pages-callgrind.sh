#!/usr/bin/env bash
# The rig worker's instructions per sample with no bay screen open and with twenty, counted by callgrind (which
# counts instructions executed, the same however loaded the machine is), for docs/bay-screen.md.
# Runs `benches/web_pages.rs --pages N` under `valgrind --tool=callgrind --separate-threads=yes` for N = 0 and 20,
# REPEATS times each, finds the thread that runs `impactd::daemon::live::Worker::run`, and divides its instruction
# count by the samples swung; the other threads' instructions (zenoh's, tokio's: the daemon's screens and the
# bench's own rig and page clients) are summed beside it.
# Usage: scripts/web-pages-callgrind.sh [SHOTS_PER_BLOCK BLOCKS REPEATS] > target/web-page/callgrind.json
set -euo pipefail
cd "$(dirname "$0")/.."
shots=${1:-20}
blocks=${2:-2}
repeats=${3:-2}
bench=$(cargo bench --bench web_pages --no-run 2>&1 | sed -n 's/.*Executable .*(\(.*\))$/\1/p' | tail -1)
bench=$(realpath "$bench")
[ -x "$bench" ] || { echo "web-pages-callgrind.sh: no bench executable" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for pages in 0 20; do
    for r in $(seq 1 "$repeats"); do
        dir="$work/p$pages-$r"
        mkdir -p "$dir"
        (cd "$dir" && valgrind --tool=callgrind --separate-threads=yes --callgrind-out-file=cg.%p \
            "$bench" "$shots" "$blocks" --pages "$pages" --json >bench.json 2>valgrind.txt)
        worker=$(grep -l 'impactd::daemon::live::Worker::run' "$dir"/cg.*-* | head -1)
        grep -m1 '^totals:' "$worker" | awk '{print $2}' >"$dir/worker_ir"
        cat "$dir"/cg.*-* | awk '/^totals:/ {s += $2} END {printf "%d\n", s}' >"$dir/all_ir"
    done
done
python3 - "$work" "$shots" "$blocks" "$repeats" <<'PY'
import glob, json, os, statistics, sys

work, shots, blocks, repeats = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
arms = []
for pages in (0, 20):
    runs = []
    for d in sorted(glob.glob(os.path.join(work, f"p{pages}-*"))):
        bench = json.load(open(os.path.join(d, "bench.json")))
        row = bench["rows"][0]
        ir = int(open(os.path.join(d, "worker_ir")).read())
        other = int(open(os.path.join(d, "all_ir")).read()) - ir
        runs.append({"samples": row["samples"], "shots": row["shots"], "worker_ir": ir, "other_threads_ir": other,
                     "ir_per_sample": ir / row["samples"], "other_ir_per_shot": other / max(row["shots"], 1),
                     "page_bytes": bench["page_bytes"]})
    arms.append({"pages": pages, "runs": runs, "ir_per_sample": statistics.mean(r["ir_per_sample"] for r in runs)})
out = {"shots_per_block": shots, "blocks": blocks, "repeats": repeats, "arms": arms,
       "ratio_20_to_0": arms[1]["ir_per_sample"] / arms[0]["ir_per_sample"],
       "valgrind": os.popen("valgrind --version").read().strip()}
print(json.dumps(out))
PY
