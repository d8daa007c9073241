#!/usr/bin/env bash
# Create .venv (if missing) and install the package with its dev extras. Idempotent and quiet:
# pip's output is shown only if the install fails.
set -euo pipefail
cd "$(dirname "$0")/.."
PY="${PYTHON:-python3}"
if [ ! -x .venv/bin/python ]; then "$PY" -m venv .venv; fi
log="$(mktemp)"
trap 'rm -f "$log"' EXIT
if ! { .venv/bin/python -m pip install --quiet --upgrade pip && \
       .venv/bin/python -m pip install --quiet -e ".[dev]"; } >"$log" 2>&1; then
  cat "$log" >&2
  echo "setup: installing the package into .venv failed (pip's output above)" >&2
  exit 1
fi
