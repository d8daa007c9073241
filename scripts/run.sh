#!/usr/bin/env bash
# The main job. Until the grasp benchmark lands (issue "Grasp objects, scripted grasp trials and
# the headless grasp benchmark"), it runs what exists: the servo datasheet check, the paper's
# bending test and the Menagerie smoke rollout of the default gripper.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
.venv/bin/gripper servo
.venv/bin/gripper bend
.venv/bin/gripper check
