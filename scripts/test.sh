#!/usr/bin/env bash
# Lint (ruff), the import layers (import-linter), types (mypy), the docs site (mkdocs --strict)
# and the default test suite; --slow adds the slow tests. mypy runs beside the test suite (it is
# single-threaded and mostly waits on its numpy stubs), and its verdict is read at the end.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
.venv/bin/ruff check gripper tests scripts docs/hooks
.venv/bin/lint-imports --no-cache >/dev/null || .venv/bin/lint-imports --no-cache
site="$(mktemp -d)"
mypy_log="$(mktemp)"
docs_log="$(mktemp)"
trap 'rm -rf "$site" "$mypy_log" "$docs_log"' EXIT
# not --quiet: it hides the warnings that --strict counts; the log is shown only on failure
if ! NO_MKDOCS_2_WARNING=1 .venv/bin/mkdocs build --strict --site-dir "$site" >"$docs_log" 2>&1; then
  cat "$docs_log" >&2
  echo "mkdocs: the docs site does not build (above)" >&2
  exit 1
fi
.venv/bin/mypy >"$mypy_log" 2>&1 &
mypy_pid=$!
if [ "${1:-}" = "--slow" ]; then
  .venv/bin/python -m pytest -q -m "slow or not slow"
else
  .venv/bin/python -m pytest -q
fi
if ! wait "$mypy_pid"; then
  cat "$mypy_log" >&2
  echo "mypy: type errors (above)" >&2
  exit 1
fi
