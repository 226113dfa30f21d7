#!/usr/bin/env bash
# Writes the model registry into the docs: the README's model list (`impactd models`) and docs/club-files.md's
# club-file sections (`impactd models --sections`). tests/cli/registry_docs.rs fails when they drift.
set -euo pipefail
cd "$(dirname "$0")/.."
BIN="${BIN:-target/release/impactd}"
[ -x "$BIN" ] || cargo build --release --quiet
python3 - "$BIN" <<'PY'
import subprocess, sys
sys.path.insert(0, "scripts")
import docs_regions
bin = sys.argv[1]
models = subprocess.run([bin, "models"], check=True, capture_output=True, text=True).stdout
sections = subprocess.run([bin, "models", "--sections"], check=True, capture_output=True, text=True).stdout
presets = subprocess.run([bin, "models", "--presets"], check=True, capture_output=True, text=True).stdout
docs_regions.replace("README.md", {"models": models.rstrip("\n")})
docs_regions.replace("docs/club-files.md", {"sections": sections.rstrip("\n"), "presets": presets.rstrip("\n")})
PY
