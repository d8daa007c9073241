#!/usr/bin/env bash
# Lint (ruff) and the default test suite; --slow adds the slow tests.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
export MUJOCO_GL="${MUJOCO_GL:-egl}"
.venv/bin/ruff check gripper tests scripts
if [ "${1:-}" = "--slow" ]; then
  .venv/bin/python -m pytest -q -m "slow or not slow"
else
  .venv/bin/python -m pytest -q
fi
