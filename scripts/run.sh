#!/usr/bin/env bash
# The main job: the grasp benchmark on the five default objects (balloon, block, cylinder,
# paper_box, bag), 10 seeded trials each on 2 local Dask workers, headless. Writes
# runs/bench/{trials.jsonl,summary.csv,summary.json} and prints the summary table; rerunning
# resumes. Extra arguments go to `gripper bench` (e.g. --trials 50 --out runs/b50).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
.venv/bin/gripper bench --trials 10 --workers 2 --out runs/bench "$@"
