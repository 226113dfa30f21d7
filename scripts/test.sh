#!/usr/bin/env bash
# The README's test command: everything the tests need, then every test.
#
# Some integration tests check impactd against independent clients: Python packages from PyPI (see
# scripts/test-requirements.txt) in a virtual environment under target/pyenv, created once and refreshed when
# the requirements change; Debian's headless Chromium with its WebDriver for the web page; and Vicon's own
# DataStream SDK client, built from its source against Debian's boost once and cached under target/vicon-sdk
# (scripts/vicon-sdk-client.sh). Debian packages are installed with apt when missing and this user may install
# packages. Extra arguments go to `cargo test`.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
venv="$root/target/pyenv"
req="$root/scripts/test-requirements.txt"

# Debian's Chromium and ChromeDriver, for the browser tests; cmake and boost for Vicon's SDK client; Debian's
# venv module where python3 lacks it.
if [ -f "$root/scripts/test-debian-packages.txt" ]; then
  missing=()
  while read -r pkg; do
    case "$pkg" in ''|'#'*) continue ;; esac
    dpkg -s "$pkg" >/dev/null 2>&1 || missing+=("$pkg")
  done < "$root/scripts/test-debian-packages.txt"
  python3 -c "import venv, ensurepip" >/dev/null 2>&1 || missing+=(python3-venv)
  if [ ${#missing[@]} -gt 0 ]; then
    echo "test.sh: installing ${missing[*]} with apt" >&2
    sudo_=""
    if [ "$(id -u)" -ne 0 ]; then
      if ! command -v sudo >/dev/null 2>&1; then
        echo "test.sh: ${missing[*]} missing and no sudo to install them: as root, run" >&2
        echo "  apt-get install --no-install-recommends ${missing[*]}" >&2
        exit 1
      fi
      sudo_="sudo"
    fi
    $sudo_ apt-get update -qq && DEBIAN_FRONTEND=noninteractive $sudo_ apt-get install -y -qq --no-install-recommends "${missing[@]}"
  fi
fi

if [ ! -x "$venv/bin/python" ] || ! cmp -s "$req" "$venv/.requirements" 2>/dev/null; then
  echo "test.sh: setting up the Python test clients in target/pyenv" >&2
  mkdir -p "$root/target"
  python3 -m venv "$venv"
  "$venv/bin/python" -m pip install --quiet --disable-pip-version-check -r "$req"
  cp "$req" "$venv/.requirements"
fi

export IMPACTD_PYTHON="$venv/bin/python"

# The integration tests wait on sockets, child processes and swings paced in real time more than they compute:
# twice as many test threads per binary as cores overlap those waits (a caller's RUST_TEST_THREADS wins).
export RUST_TEST_THREADS="${RUST_TEST_THREADS:-$((2 * $(nproc)))}"

# Vicon's SDK client (C++) builds while cargo builds the tests; its output goes to target/vicon-sdk-client.log.
# Without a target of your own (`--test NAME`, `--lib`, ...), the tests are every library's, binary's and
# integration test's, then the doc tests: the examples are not linked (clippy --all-targets checks they compile).
cargo_args=()
picks_targets=false
for a in "$@"; do
  [ "$a" = "--" ] && break
  case "$a" in
    --lib|--bin|--bin=*|--bins|--test|--test=*|--tests|--example|--example=*|--examples|--bench|--bench=*|--benches|--all-targets|--doc)
      picks_targets=true ;;
  esac
  cargo_args+=("$a")
done
targets=()
$picks_targets || targets=(--lib --bins --tests)
mkdir -p "$root/target"
vicon_log="$root/target/vicon-sdk-client.log"
bash "$root/scripts/vicon-sdk-client.sh" >"$root/target/vicon-sdk-client.path" 2>"$vicon_log" &
vicon=$!
cargo test --release --no-run "${targets[@]}" "${cargo_args[@]}"
if ! wait "$vicon"; then
  cat "$vicon_log" >&2
  echo "test.sh: building Vicon's SDK client failed (above)" >&2
  exit 1
fi
IMPACTD_VICON_SDK_CLIENT="$(cat "$root/target/vicon-sdk-client.path")"
export IMPACTD_VICON_SDK_CLIENT
if $picks_targets; then
  exec cargo test --release "$@"
fi
# Two lanes side by side: the test binaries that mostly wait (daemons and clients on loopback, pages in
# Chromium, swings paced in real time) beside those that compute. Every test binary of the workspace that is not
# named as waiting runs in the second lane, so a new one is never left out. The waiting lane's output is printed
# when it ends.
waiting=(daemon web inputs sim_drain)
mapfile -t all_tests < <(cargo metadata --no-deps --format-version 1 | "$IMPACTD_PYTHON" -c '
import json, sys
for p in json.load(sys.stdin)["packages"]:
    for t in p["targets"]:
        if "test" in t["kind"]:
            print(t["name"])')
lane1=() lane2=(--workspace --lib --bins)
for t in "${all_tests[@]}"; do
  if [[ " ${waiting[*]} " == *" $t "* ]]; then lane1+=(--test "$t"); else lane2+=(--test "$t"); fi
done
lane1_log="$root/target/test-waiting-lane.log"
( cargo test --release -p impactd "${lane1[@]}" "$@" >"$lane1_log" 2>&1 ) &
lane1_pid=$!
status=0
cargo test --release "${lane2[@]}" "$@" || status=$?
lane1_status=0
wait "$lane1_pid" || lane1_status=$?
echo "test.sh: the waiting lane (${waiting[*]}):" >&2
cat "$lane1_log"
[ "$lane1_status" -eq 0 ] || status=$lane1_status
if [ "$status" -ne 0 ] && [[ " ${cargo_args[*]} " != *" --no-fail-fast "* ]]; then
  exit "$status"
fi
cargo test --release --doc "$@" || status=$?
exit "$status"
