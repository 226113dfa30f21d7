#!/usr/bin/env bash
# Makes the example recordings: three shots each of a driver and a 7-iron, through `impactd demo` (the daemon and
# a synthetic 720 Hz rig on loopback zenoh). Replay one with `impactd replay recordings/driver.mcap`.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
for club in driver iron7; do
  target/release/impactd demo --club "$club" --shots 3 --seed 7 --record "recordings/$club.mcap" --overwrite > /dev/null
done
ls -l recordings/*.mcap
