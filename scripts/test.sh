#!/usr/bin/env bash
# Lint (ruff), the import layers (import-linter), types (mypy) and the default test suite, which
# builds the docs site exactly as the README's command does (tests/test_docs.py; mkdocs.yml sets
# strict, so a broken link fails it); --slow adds the slow tests. mypy runs beside the test suite (it is
# single-threaded and mostly waits on its numpy stubs), and its verdict is read at the end.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
.venv/bin/ruff check gripper tests scripts docs/hooks
.venv/bin/lint-imports --no-cache >/dev/null || .venv/bin/lint-imports --no-cache
mypy_log="$(mktemp)"
trap 'rm -f "$mypy_log"' EXIT
.venv/bin/mypy >"$mypy_log" 2>&1 &
mypy_pid=$!
if [ "${1:-}" = "--slow" ]; then
  .venv/bin/python -m pytest -q --durations=15 -m "slow or not slow"
else
  .venv/bin/python -m pytest -q --durations=15
fi
if ! wait "$mypy_pid"; then
  cat "$mypy_log" >&2
  echo "mypy: type errors (above)" >&2
  exit 1
fi
