#!/usr/bin/env bash
# Load test: N rigs at RATE Hz for DURATION seconds into one recording daemon on loopback.
# Checks that no sample is dropped, every shot is predicted, and the daemon's resident memory stays flat and
# under 64 MiB. Usage: scripts/load-test.sh [DURATION_S=600] [RIGS=10] [RATE=720]
set -euo pipefail
duration=${1:-600}
rigs=${2:-10}
rate=${3:-720}
cd "$(dirname "$0")/.."
cargo build --release --quiet
bin=target/release/impactd
work=$(mktemp -d)
port=$(python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])')
endpoint="tcp/127.0.0.1:$port"
for i in $(seq 1 "$rigs"); do printf '[[rig]]\nname = "rig%d"\n\n' "$i"; done > "$work/impactd.toml"

"$bin" run -c "$work/impactd.toml" --record "$work/load.mcap" -m peer -l "$endpoint" --no-multicast-scouting 2> "$work/daemon.log" &
daemon=$!
sleep 1
"$bin" sim --rigs "$rigs" --shots 0 --rate "$rate" --interval 2 -m peer -e "$endpoint" --no-multicast-scouting 2> "$work/sim.log" &
sim=$!

echo "t_s rss_kib" > "$work/rss.txt"
start=$(date +%s)
while [ $(( $(date +%s) - start )) -lt "$duration" ]; do
  sleep 10
  rss=$(awk '/VmRSS/ {print $2}' "/proc/$daemon/status")
  echo "$(( $(date +%s) - start )) $rss" | tee -a "$work/rss.txt"
done
kill -INT "$sim"; wait "$sim" || true
sleep 2
kill -INT "$daemon"; wait "$daemon" || true

sent=$(grep -o 'sent [0-9]* samples, [0-9]* shots' "$work/sim.log" | tail -1)
echo "rig: $sent"
"$bin" info "$work/load.mcap" > "$work/info.txt"
cat "$work/info.txt"
python3 - "$work" "$sent" "$rigs" <<'PY'
import re, sys
work, sent, rigs = sys.argv[1], sys.argv[2], int(sys.argv[3])
samples_sent, shots_sent = map(int, re.findall(r"\d+", sent))
info = open(f"{work}/info.txt").read()
recorded = sum(int(n) for n in re.findall(r"/mocap/rig\d+/clubhead\s+\S+\s+(\d+)", info))
predicted = sum(int(n) for n in re.findall(r"rig\d+: (\d+) predicted", info))
rss = [int(l.split()[1]) for l in open(f"{work}/rss.txt").read().splitlines()[1:]]
third = max(1, len(rss) // 3)
early, late = max(rss[:third]), max(rss[-third:])
ok = recorded == samples_sent and predicted == shots_sent and max(rss) < 64 * 1024 and late <= early * 1.10 + 1024
print(f"samples sent {samples_sent}, recorded {recorded}; shots {shots_sent}, predicted {predicted}")
print(f"resident memory: max {max(rss)/1024:.1f} MiB, first third max {early/1024:.1f} MiB, last third max {late/1024:.1f} MiB")
print("PASS" if ok else "FAIL")
sys.exit(0 if ok else 1)
PY
