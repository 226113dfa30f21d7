#!/usr/bin/env bash
# Regenerates the numbers of docs/identify.md and research/identify-results.md from the commands' JSON output:
#   impactd synth                                  -> the synthetic datasets (known parameters, the issue's noise)
#   impactd compare --json                         -> docs/identify.md, region compare-iron7 (Tables 3.2-3.7's layout)
#   impactd fit --json (under /usr/bin/time -v)    -> docs/identify.md, region fit-time; research/identify-results.md,
#                                                     regions recovery-*, cv, crb, adjusted-seeds, valley
#   tests/daemon/live_comparison.rs (IMPACTD_LIVE_LATENCY_JSON) -> docs/identify.md, region live-latency
#   research/scripts/identify-likelihood.sh        -> research/identify-results.md, region likelihood (eq. 3.13
#                                                     against the likelihood over seeds)
# Each table sits between `<!-- generated: NAME -->` and `<!-- end -->`; the text around it is left alone.
# Usage: scripts/docs-identify.sh   (about 10 minutes on 2 cores at load 8, most of it the two-layer fit with its
# 5-fold cross-validation; IDENTIFY_OUT=DIR keeps the JSON there and reuses what is already in it)
set -euo pipefail
cd "$(dirname "$0")/.."

cargo build --release --quiet
BIN=target/release/impactd
if [ -n "${IDENTIFY_OUT:-}" ]; then
    OUT="$IDENTIFY_OUT"
    mkdir -p "$OUT"
else
    OUT="$(mktemp -d)"
    trap 'rm -rf "$OUT"' EXIT
fi

# The truths (SI): adjusted and slip on the driver as in tests/cli/identify.rs, the two-layer model on the 7-iron as
# in research/tests/identifiability.rs (Table 3.5's 7-iron moved by 10-40 % per parameter).
ADJUSTED=(delta_mass=0.0073 ball_cg_shift_x=0.00031 ball_cg_shift_y=-0.00042 ball_cg_shift_z=0.00017)
SLIP=(e_y=0.045 e_z=-0.03)
CONTINUOUS=(k_v=8.5e9 d=0.007 mu=0.42 k_ball=45 c_ball=0.009 t_cover=0.0022 v_tr=0.65)

sets() { for s in "$@"; do printf -- '--set\n%s\n' "$s"; done; }

# once NAME COMMAND...: runs COMMAND into $OUT/NAME unless it is there already.
once() {
    local name="$1"
    shift
    if [ ! -s "$OUT/$name" ]; then
        echo "$name" >&2
        "$@" >"$OUT/$name.part"
        mv "$OUT/$name.part" "$OUT/$name"
    fi
}

# timed NAME COMMAND...: `once` under /usr/bin/time -v, with the load before and after in NAME.time.
timed() {
    local name="$1"
    shift
    if [ ! -s "$OUT/$name" ]; then
        uptime >"$OUT/$name.time"
        once "$name" /usr/bin/time -v -a -o "$OUT/$name.time" "$@"
        uptime >>"$OUT/$name.time"
    fi
}

mapfile -t A < <(sets "${ADJUSTED[@]}")
mapfile -t S < <(sets "${SLIP[@]}")
mapfile -t C < <(sets "${CONTINUOUS[@]}")
once adjusted.jsonl "$BIN" synth --model adjusted --club driver "${A[@]}" --shots 500 --seed 11
once slip.jsonl "$BIN" synth --model slip --club driver "${S[@]}" --shots 500 --seed 12
once iron7.jsonl "$BIN" synth --model continuous --club iron7 "${C[@]}" --shots 550 --seed 17
timed fit-adjusted.json "$BIN" fit --model adjusted --club driver "$OUT/adjusted.jsonl" --json
timed fit-slip.json "$BIN" fit --model slip --club driver "$OUT/slip.jsonl" --json
timed fit-continuous.json "$BIN" fit --model continuous --club iron7 "$OUT/iron7.jsonl" --json \
    -o "$OUT/fitted-continuous.toml"
# Eq. 3.13 at the truth: the fitted club file with the true [continuous] values.
python3 - "$OUT/fitted-continuous.toml" "$OUT/truth-continuous.toml" <<'PY'
import sys, tomllib
SI = {"k_v_n_per_m3": 8.5e9, "d_s_per_m": 0.007, "mu": 0.42, "k_ball_nm_per_rad": 45.0,
      "c_ball_nms_per_rad": 0.009, "cover_thickness_m": 0.0022, "v_tr_mps": 0.65}
text = open(sys.argv[1]).read()
head, section = text.split("[continuous]")
lines = [f"{l.split('=')[0].strip()} = {SI[l.split('=')[0].strip()]!r}" if l.split("=")[0].strip() in SI else l
         for l in section.splitlines()]
open(sys.argv[2], "w").write(head + "[continuous]" + "\n".join(lines) + "\n")
tomllib.loads(open(sys.argv[2]).read())
PY
once compare-truth.json "$BIN" compare "$OUT/iron7.jsonl" --club "$OUT/truth-continuous.toml" --models continuous --json
once compare-fitted.json "$BIN" compare "$OUT/iron7.jsonl" --club "$OUT/fitted-continuous.toml" --models continuous \
    --json
# The adjusted fit over seeds 11-14 (no cross-validation).
for seed in 11 12 13 14; do
    once "adjusted-$seed.jsonl" "$BIN" synth --model adjusted --club driver "${A[@]}" --shots 500 --seed "$seed"
    once "fit-adjusted-$seed.json" "$BIN" fit --model adjusted --club driver "$OUT/adjusted-$seed.jsonl" --folds 0 --json
done
once compare-iron7.json "$BIN" compare "$OUT/iron7.jsonl" --club iron7 --models standard,adjusted,slip,continuous --json
if [ ! -s "$OUT/live.json" ]; then
    echo "live latency (tests/daemon/live_comparison.rs)" >&2
    IMPACTD_LIVE_LATENCY_JSON="$OUT/live.json" cargo test --release --quiet --test daemon live_comparison:: >&2
fi

python3 - "$OUT" "${ADJUSTED[*]}" "${SLIP[*]}" "${CONTINUOUS[*]}" <<'PY'
import json, math, os, re, sys

out = sys.argv[1]
truths = {m: dict(kv.split("=") for kv in sys.argv[i].split()) for i, m in
          [(2, "adjusted"), (3, "slip"), (4, "continuous")]}
NOISE = [0.5, 0.2, 0.3, 150.0, 150.0]  # synth's default: the issue's launch-monitor noise
LABELS = ["Speed (mph)", "Launch (deg)", "Azimuth (deg)", "Backspin (rpm)", "Sidespin (rpm)"]


def load(name):
    with open(os.path.join(out, name)) as f:
        return json.load(f)


def g(x):
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "n/a"
    a = abs(x)
    if a == 0:
        return "0"
    if a >= 1e5 or a < 1e-3:
        return f"{x:.3g}"
    return f"{x:.4g}"


def timing(name):
    t = {}
    with open(os.path.join(out, name)) as f:
        lines = f.read().splitlines()
    loads = [l.split("load average:")[1].split(",")[0].strip() for l in lines if "load average:" in l]
    for l in lines:
        if ": " in l and "load average" not in l:
            k, v = l.strip().split(": ", 1)
            t[k.strip()] = v.strip()
    cpu = float(t["User time (seconds)"]) + float(t["System time (seconds)"])
    wall = t["Elapsed (wall clock) time (h:mm:ss or m:ss)"]
    parts = [float(p) for p in wall.split(":")]
    wall_s = sum(p * 60 ** i for i, p in enumerate(reversed(parts)))
    return cpu, wall_s, loads


def recovery(model):
    r = load(f"fit-{model}.json")
    lines = ["| parameter | start | truth | fitted | error | CRB | eq. 3.13 SD | error / SD |", "|---|---|---|---|---|---|---|---|"]
    for p in r["params"]:
        factor = {"g": 1e3, "mm": 1e3, "ms/m": 1e3, "mN m s/rad": 1e3}.get(p["unit"], 1.0)
        truth = float(truths[model][p["name"]]) * factor
        err = p["fitted"] - truth
        sd = p.get("scatter")
        ratio = g(abs(err) / sd) if sd else "n/a"
        unit = f" {p['unit']}" if p["unit"] else ""
        lines.append(f"| {p['name']}{' (' + p['unit'] + ')' if p['unit'] else ''} | {g(p['start'])} | {g(truth)} | "
                     f"{g(p['fitted'])} | {g(err)} | {g(p.get('std_error'))} | {g(sd)} | {ratio} |")
    lines += ["", f"`impactd fit --model {model} --club {r['club']}` on {r['shots']} shots, seed {r['seed']}: "
                  f"eq. 3.13 {r['cost_before']:.5f} -> {r['cost']:.5f}. CRB: the Cramér-Rao bound with every "
                  f"parameter unknown; eq. 3.13 SD: the scatter of the fit's own estimate (identify::fisher)."]
    return lines


def cv_table():
    lines = ["| field | noise MAE | " + " | ".join(f"{m} before | {m} after" for m in ("adjusted", "slip", "continuous")) + " |",
             "|---|---|" + "---|---|" * 3]
    cvs = {m: load(f"fit-{m}.json")["cv"] for m in ("adjusted", "slip", "continuous")}
    for i, label in enumerate(LABELS):
        row = [label, g(NOISE[i] * math.sqrt(2 / math.pi))]
        for m in ("adjusted", "slip", "continuous"):
            row += [g(cvs[m]["before"][i]["mae"]), g(cvs[m]["after"][i]["mae"])]
        lines.append("| " + " | ".join(row) + " |")
    row = ["eq. 3.13", ""]
    for m in ("adjusted", "slip", "continuous"):
        row += [f"{cvs[m]['cost_before']:.4f}", f"{cvs[m]['cost_after']:.4f}"]
    lines.append("| " + " | ".join(row) + " |")
    return lines + ["", "5-fold cross-validated MAE on held-out shots (each fold fitted without them; a two-layer fold's "
                        "local search starts from the fit on all shots, `fit --fold-global` searches each globally); "
                        "the noise's own MAE is σ sqrt(2/π)."]


def dur(s):
    return f"{s:.1f} s" if s < 60 else f"{s / 60:.1f} min"


def time_table():
    lines = ["| model | shots | impacts (fit) | impacts (cross-validation) | wall | CPU | CPU / 2 cores | load before, after |",
             "|---|---|---|---|---|---|---|---|"]
    for m in ("adjusted", "slip", "continuous"):
        r = load(f"fit-{m}.json")
        cpu, wall, loads = timing(f"fit-{m}.json.time")
        lines.append(f"| {m} | {r['shots']} | {r.get('simulations', 0):,} | {r.get('cv_simulations', 0):,} | "
                     f"{dur(wall)} | {dur(cpu)} | {dur(cpu / 2)} | {', '.join(loads)} |")
    return lines + ["", "The whole `impactd fit` command (the fit on all shots and its 5-fold cross-validation) under "
                        "`/usr/bin/time -v`. The machine is shared, so the wall time depends on the load; CPU / 2 "
                        "cores is the wall time on the same two cores with nothing else running."]


def compare_table():
    r = load("compare-iron7.json")
    tables = r["tables"]
    head = "| field | measured mean | " + " | ".join(f"{t['model']} MAE | % | STD | %" for t in tables) + " |"
    lines = [head, "|---|---|" + "---|---|---|---|" * len(tables)]
    for i, label in enumerate(LABELS):
        row = [label, g(tables[0]["fields"][i]["measured_mean"])]
        for t in tables:
            f = t["fields"][i]
            row += [g(f["mae"]), f"{f['mae_pct']:.1f}", g(f["std"]), f"{f['std_pct']:.1f}"]
        lines.append("| " + " | ".join(row) + " |")
    lines.append("| eq. 3.13 cost | | " + " | ".join(f"{t['cost']:.4f} | | |" for t in tables) + " |")
    lines.append("| time per shot (us) | | " + " | ".join(f"{t['time_per_shot_us']:.1f} | | |" for t in tables) + " |")
    return lines + ["", f"`impactd compare iron7.jsonl --club iron7 --models standard,adjusted,slip,continuous --json`: "
                        f"{tables[0]['shots']} synthetic 7-iron shots made by the two-layer model with the truth above, "
                        f"predicted with each model's Table 3.2-3.5 parameters."]


def live_line():
    r = load("live.json")

    def q(v, p):
        v = sorted(v)
        return v[max(1, math.ceil(p * len(v))) - 1]

    rows = [("arrival at the listener -> comparison received on zenoh", r["arrival_ms"]),
            ("the connector's last write -> comparison received on zenoh", r["write_ms"]),
            ("the rig worker's receipt -> publish (`latency_us`)", r["worker_ms"])]
    lines = ["| interval | p50 | p99 | max |", "|---|---|---|---|"]
    lines += [f"| {name} | {q(v, 0.5):.3f} ms | {q(v, 0.99):.3f} ms | {q(v, 1.0):.3f} ms |" for name, v in rows]
    return lines + ["", f"`tests/daemon/live_comparison.rs`, {r['shots']} shots (IMPACTD_LIVE_LATENCY_JSON)."]


def crb_line():
    r = load("fit-adjusted.json")
    x = next(p for p in r["params"] if p["name"] == "ball_cg_shift_x")
    return [f"On the {r['shots']} driver shots above the Cramér-Rao bound of x' is **{x['std_error']:.3f} mm** "
            f"({x['std_error_alone']:.3f} mm were Δm and the tangential shifts known), and eq. 3.13's own estimate "
            f"scatters by **{x['scatter']:.3f} mm**: the 0.05 mm asked is {0.05 / x['std_error']:.2f} of the bound, "
            f"and 0.5 mm is {0.5 / x['scatter']:.1f} standard deviations of the fit."]


def seeds_table():
    t = {k: float(v) * 1e3 for k, v in truths["adjusted"].items()}
    lines = ["| seed | Δm error (g) | Δm SD | x' error (mm) | x' SD | x' error / SD | y' error (mm) | z' error (mm) |",
             "|---|---|---|---|---|---|---|---|"]
    for seed in (11, 12, 13, 14):
        p = {q["name"]: q for q in load(f"fit-adjusted-{seed}.json")["params"]}
        e = {k: p[k]["fitted"] - t[k] for k in t}
        x = p["ball_cg_shift_x"]
        lines.append(f"| {seed} | {e['delta_mass']:+.3f} | {p['delta_mass']['scatter']:.3f} | "
                     f"{e['ball_cg_shift_x']:+.3f} | {x['scatter']:.3f} | {abs(e['ball_cg_shift_x']) / x['scatter']:.1f} | "
                     f"{e['ball_cg_shift_y']:+.4f} | {e['ball_cg_shift_z']:+.4f} |")
    return lines + ["", "`impactd synth` (seed as given) and `impactd fit --model adjusted --folds 0` on 500 driver shots."]


def valley_line():
    at_truth = load("compare-truth.json")["tables"][0]["cost"]
    at_fit = load("compare-fitted.json")["tables"][0]["cost"]
    where = "above" if at_fit > at_truth else "below"
    return [f"On these shots eq. 3.13 is {at_truth:.5f} at the truth and {at_fit:.5f} at the fitted point ({where} "
            f"it)."]


sys.path.insert(0, "scripts")
from docs_regions import replace  # noqa: E402


replace("docs/identify.md", {
    "compare-iron7": compare_table(),
    "fit-time": time_table(),
    "live-latency": live_line(),
})
replace("research/identify-results.md", {
    "recovery-adjusted": recovery("adjusted"),
    "recovery-slip": recovery("slip"),
    "recovery-continuous": recovery("continuous"),
    "crb": crb_line(),
    "cv": cv_table(),
    "adjusted-seeds": seeds_table(),
    "valley": valley_line(),
})
PY
bash research/scripts/identify-likelihood.sh
