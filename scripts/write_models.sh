#!/usr/bin/env bash
# Regenerate models/ (each shipped gripper's MJCF as the trials run it: soft_gripper, the cable
# gripper, and pneumatic_gripper) from the default parameters, with each README's picture
# (rendered headless).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
MUJOCO_GL="${MUJOCO_GL:-egl}" .venv/bin/gripper write-models --picture
