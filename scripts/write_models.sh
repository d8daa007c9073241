#!/usr/bin/env bash
# Regenerate models/soft_gripper (the MJCF the trials run) from the default parameters.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
.venv/bin/gripper write-models
