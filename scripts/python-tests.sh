#!/usr/bin/env bash
# Builds the Python package into a fresh virtual environment (maturin from
# PyPI, `pip install ./python`) and runs its pytest suite against the tribo
# binary. Skips, saying why, where Python 3.9+ with venv is absent.
set -euo pipefail
cd "$(dirname "$0")/.."

export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$HOME/.cache/tribo-target}"
PYTHON="${PYTHON:-python3}"

if ! command -v "$PYTHON" >/dev/null 2>&1; then
  echo "skip: Python tests need python3 (3.9 or newer); none found"
  exit 0
fi
if ! "$PYTHON" -c 'import sys, venv; sys.exit(sys.version_info < (3, 9))' 2>/dev/null; then
  echo "skip: Python tests need python3 >= 3.9 with the venv module; $("$PYTHON" --version 2>&1) has not"
  exit 0
fi

VENV="$CARGO_TARGET_DIR/python-venv"
rm -rf "$VENV"
# System site packages: polars, pyarrow and DuckDB are reused where installed.
"$PYTHON" -m venv --system-site-packages "$VENV"
PIP=("$VENV/bin/python" -m pip --disable-pip-version-check --quiet)

start=$(date +%s)
"${PIP[@]}" install ./python
echo "python: wheel built and installed in $(( $(date +%s) - start )) s"
"${PIP[@]}" install pytest polars pyarrow duckdb
# The peers the roughness parameters and spectra are checked against
# (python/tests/test_peer_roughness.py skips, saying so, without them).
"${PIP[@]}" install surfalize SurfaceTopography \
  || echo "note: surfalize/SurfaceTopography not installed; the peer roughness tests will skip"

# The CLI whose tables the package must reproduce (TRIBO_BIN to use another).
if [ -z "${TRIBO_BIN:-}" ]; then
  cargo build --quiet --bin tribo
  export TRIBO_BIN="$CARGO_TARGET_DIR/debug/tribo"
fi
"$VENV/bin/python" -X importtime -c 'import tribo' 2> "$VENV/importtime.txt"
echo "python: import tribo $(awk -F'|' '/ tribo$/ {gsub(/ /, "", $2); print $2}' "$VENV/importtime.txt") us (cumulative)"
# The installed package, not python/tribo: pytest run from the root.
"$VENV/bin/pytest" -q python/tests
