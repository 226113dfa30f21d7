#!/usr/bin/env bash
# Rewrites docs/bay-screen.md's regions from measurements: `browser` from the browser test's numbers
# (target/web-page/measured.json, written by `bash scripts/test.sh --test web web_page::`, which this runs), `pages`
# from `cargo bench --bench web_pages -- --json` (sample -> launch latency and the rig worker's CPU time with 0
# and 20 pages open, interleaved blocks, bootstrap intervals) and `instructions` from
# scripts/web-pages-callgrind.sh (the rig worker's instructions per sample under callgrind, 0 and 20 pages) and
# `feed` from `cargo bench --bench web_feed` (criterion's estimates under target/criterion/web_feed/; NO_FEED=1
# keeps the last run's).
# Usage: scripts/docs-web.sh [BENCH.json [CALLGRIND.json]]   (saved runs instead of new ones: the bench with 25
# shots per block and 32 blocks, callgrind with 20 shots, 2 blocks, 2 runs per arm); NO_TEST=1 keeps
# target/web-page/measured.json.
set -euo pipefail
cd "$(dirname "$0")/.."
[ "${NO_TEST:-0}" = 1 ] || bash scripts/test.sh --test web web_page::
OUT="$(mktemp)"
CG="$(mktemp)"
trap 'rm -f "$OUT" "$CG"' EXIT
if [ $# -ge 1 ]; then
    cp "$1" "$OUT"
else
    cargo bench --quiet --bench web_pages -- 25 32 --json | tail -1 >"$OUT"
fi
if [ $# -ge 2 ]; then
    cp "$2" "$CG"
else
    scripts/web-pages-callgrind.sh 20 2 2 >"$CG"
fi
[ "${NO_FEED:-0}" = 1 ] || cargo bench --quiet --bench web_feed -- --warm-up-time 1 --measurement-time 4 >/dev/null
python3 - "$OUT" target/web-page/measured.json "$CG" <<'PY'
import json, os, sys

sys.path.insert(0, "scripts")
from docs_regions import replace  # noqa: E402

bench = json.load(open(sys.argv[1]))
browser = json.load(open(sys.argv[2]))
cg = json.load(open(sys.argv[3]))
us = lambda v: f"{v:.0f} us" if v < 1e4 else f"{v / 1e3:.1f} ms"
rows = {r["pages"]: r for r in bench["rows"]}
pages = [
    "| pages open | blocks | shots | sample -> launch p50 | p99 | max | in the daemon p50 | p99 | rig worker CPU per sample |",
    "|---|---|---|---|---|---|---|---|---|",
]
for n, r in sorted(rows.items()):
    pages.append(
        f"| {n} | {r['blocks']} | {r['shots']} | {us(r['p50_us'])} | {us(r['p99_us'])} | {us(r['max_us'])} | "
        f"{us(r['daemon_p50_us'])} | {us(r['daemon_p99_us'])} | {r['worker_cpu_ns_per_sample'] / 1e3:.1f} us |"
    )


def verdict(r):
    lo, hi = r["ci95"]
    if hi <= 1.10:
        return "within 10 %"
    if lo > 1.10:
        return "NOT within 10 %"
    return "undecided: the interval spans 1.10"


ratio_rows = [
    ("e2e_p99", "sample -> launch p99, all shots of each arm (the issue's number)"),
    ("block_p99_median", "sample -> launch: median over blocks of each block's p99"),
    ("e2e_p50", "sample -> launch p50"),
    ("daemon_p99", "in the daemon (`latency_us`) p99"),
    ("daemon_p50", "in the daemon (`latency_us`) p50"),
    ("worker_cpu", "rig worker thread's CPU time per sample"),
    ("noise_e2e_p99", "no page / no page (alternate A blocks): sample -> launch p99"),
    ("noise_e2e_p50", "no page / no page (alternate A blocks): sample -> launch p50"),
    ("noise_worker_cpu", "no page / no page (alternate A blocks): worker CPU per sample"),
]
pages += ["", "| ratio | measured | 95 % interval | |", "|---|---|---|---|"]
for key, name in ratio_rows:
    r = bench.get(key)
    if r is None:
        continue
    v = verdict(r) if not key.startswith("noise") else "nothing changed: how far it moves"
    pages.append(f"| {name} | {r['ratio']:.3f} | {r['ci95'][0]:.3f} .. {r['ci95'][1]:.3f} | {v} |")
pages += [
    "",
    f"{bench['blocks']} blocks of {bench['shots_per_block']} shots (A B B A ...), {bench['resamples']} bootstrap "
    f"resamples of the blocks; {bench['page_bytes']} bytes sent to the pages; {bench['date']}, {bench['cpus']} CPUs, "
    f"load average {' '.join(bench['loadavg'])} at the end.",
]
arms = {a["pages"]: a for a in cg["arms"]}
instructions = [
    "| pages open | runs | samples per run | rig worker instructions per sample | each run | other threads, instructions per shot |",
    "|---|---|---|---|---|---|",
]
for n, a in sorted(arms.items()):
    each = ", ".join(f"{r['ir_per_sample']:.0f}" for r in a["runs"])
    other = sum(r["other_ir_per_shot"] for r in a["runs"]) / len(a["runs"])
    instructions.append(
        f"| {n} | {len(a['runs'])} | {a['runs'][0]['samples']} | {a['ir_per_sample']:.0f} | {each} | {other / 1e6:.2f} M |"
    )
instructions += [
    "",
    f"Rig worker instructions per sample, 20 pages / none: **{cg['ratio_20_to_0']:.4f}** ({cg['valgrind']}; "
    f"{cg['blocks']} blocks of {cg['shots_per_block']} shots per run).",
]
lat = browser["latency_ms"]
ok = lambda v, lim: "ok" if v <= lim else "OVER"
b = [
    "| what | measured | bound |",
    "|---|---|---|",
    f"| launch published -> numbers drawn, p50 over {browser['shots']} shots | {browser['latency_p50_ms']:.1f} ms | |",
    f"| launch published -> numbers drawn, p99 (max of {browser['shots']}) | {browser['latency_p99_ms']:.1f} ms | <= 100 ms ({ok(browser['latency_p99_ms'], 100)}) |",
    f"| first load: navigation start -> load event | {browser['load_ms']:.1f} ms | <= 300 ms ({ok(browser['load_ms'], 300)}) |",
    f"| first load: navigation start -> first snapshot drawn | {browser['first_draw_ms']:.1f} ms | <= 300 ms ({ok(browser['first_draw_ms'], 300)}) |",
    "",
    f"Each shot (ms): {', '.join(f'{v:.1f}' for v in lat)}. {browser['date']}, load average {browser['loadavg']}.",
]
estimate = lambda name: json.load(open(os.path.join("target/criterion/web_feed", name, "new/estimates.json")))["median"]
feed = ["| on the daemon's zenoh session | median | 95 % interval |", "|---|---|---|"]
for name in ["put a launch, no screen", "put a launch, the screen's feed subscribed",
             "broadcast a page message to 0 pages", "broadcast a page message to 20 pages"]:
    e = estimate(name)
    lo, hi = e["confidence_interval"]["lower_bound"], e["confidence_interval"]["upper_bound"]
    feed.append(f"| {name} | {e['point_estimate']:.0f} ns | {lo:.0f} .. {hi:.0f} ns |")
added = estimate("put a launch, the screen's feed subscribed")["point_estimate"] - estimate("put a launch, no screen")["point_estimate"]
feed += ["", f"The screen's subscriber adds **{added / 1e3:.1f} us** to each launch the rig worker publishes, with or "
         "without pages open (criterion, `cargo bench --bench web_feed`)."]
replace("docs/bay-screen.md", {"browser": b, "pages": pages, "instructions": instructions, "feed": feed})
PY
