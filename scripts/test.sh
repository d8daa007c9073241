#!/usr/bin/env bash
# Lint (ruff), the import layers (import-linter), types (mypy), the docs site (mkdocs --strict)
# and the default test suite; --slow adds the slow tests.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
export MUJOCO_GL="${MUJOCO_GL:-egl}"
.venv/bin/ruff check gripper tests scripts docs/hooks
.venv/bin/lint-imports --no-cache >/dev/null || .venv/bin/lint-imports --no-cache
.venv/bin/mypy
NO_MKDOCS_2_WARNING=1 .venv/bin/mkdocs build --strict --quiet --site-dir "${TMPDIR:-/tmp}/gripper-site-$$"
rm -rf "${TMPDIR:-/tmp}/gripper-site-$$"
if [ "${1:-}" = "--slow" ]; then
  .venv/bin/python -m pytest -q -m "slow or not slow"
else
  .venv/bin/python -m pytest -q
fi
