#!/usr/bin/env bash
# Regenerates the comparison table of research/maw-arakawa.md from the binary's own JSON output: the same deliveries through
# every model (`impactd predict --json lines, --trace for the models resolved in time`) and the time per shot from
# `impactd bench --json`. Usage: research/scripts/docs-models.sh [path/to/impactd] > table.md
set -euo pipefail
BIN=${1:-target/release/impactd}
python3 - "$BIN" <<'PY'
import json, subprocess, sys
bin_ = sys.argv[1]
clubs = {"driver": (13.0, -1.3), "iron7": (25.0, -4.3)}
models = ["continuous", "maw", "arakawa", "adjusted"]
timed = {"continuous", "maw", "arakawa"}
ns = {}
for f in ("continuous/", "maw/", "arakawa/", "adjusted/"):
    bench = json.loads(subprocess.run([bin_, "bench", "--json", "--filter", f], check=True, capture_output=True,
                                      text=True).stdout)
    ns.update({s["name"]: s["ns_per_op"] for s in bench["stages"]})
def per_shot(model, club):
    return ns.get(f"{model}/{club}")
print("| club | mph | impact (h, v mm) | model | ball mph | launch deg | direction deg | backspin rpm | sidespin rpm | contact us | peak kN | reversal | time per shot |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
for club, (loft, attack) in clubs.items():
    for mps in (35.0, 45.0, 55.0):
        for h, v in ((0.0, 0.0), (15.0, 5.0)):
            d = {"club_speed_mph": mps / 0.44704, "attack_angle_deg": attack, "dynamic_loft_deg": loft,
                 "impact_h_mm": h, "impact_v_mm": v}
            for m in models:
                args = [bin_, "predict", "--club", club, "--model", m] + (["--trace"] if m in timed else [])
                out = subprocess.run(args, input=json.dumps(d) + "\n", capture_output=True, text=True)
                line = out.stdout.strip().splitlines()
                if not line:
                    print(f"| {club} | {mps/0.44704:.0f} | {h:.0f}, {v:.0f} | {m} | failed: {out.stderr.strip()[:60]} |||||||||")
                    continue
                r = json.loads(line[0])
                contact = peak = rev = "-"
                if m in timed:
                    ft = [p["tangential_force_n"] for p in r["trace"]]
                    size = max(abs(x) for x in ft) or 1.0
                    rev = "yes" if max(ft) > 0.01 * size and min(ft) < -0.01 * size else "no"
                    contact = f"{r['contact_time_us']:.0f}"
                    peak = f"{r['peak_normal_force_n'] / 1e3:.1f}"
                t = per_shot(m, club)
                ts = "-" if t is None else (f"{t / 1e3:.0f} us" if t >= 1e3 else f"{t:.0f} ns")
                print(f"| {club} | {mps/0.44704:.0f} | {h:.0f}, {v:.0f} | {m} | {r['ball_speed_mph']:.1f} | {r['launch_angle_deg']:.1f} | "
                      f"{r['launch_direction_deg']:.1f} | {r['backspin_rpm']:.0f} | {r['sidespin_rpm']:.0f} | {contact} | {peak} | {rev} | {ts} |")
PY
