#!/usr/bin/env bash
# Regenerate gripper/data/soft_gripper from the default parameters.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
.venv/bin/gripper write-models
