"""Design-study speed: wall time per design point for the bending-curve response (median over
the points of a 100-point Latin hypercube), and the whole 100-point study on 2 local workers.

Run: .venv/bin/python scripts/bench_study.py [--points 100] [--workers 2]
"""

import argparse
import json
import statistics
import tempfile
import time
from pathlib import Path

from gripper.studies.study import run_study
from gripper.studies.study_file import load_study

STUDY = """
[study]
name = "bending speed"
design = "latin_hypercube"
points = {points}
seed = 0

[vary]
"finger.cut_angle_deg" = {{ min = 30.0, max = 50.0 }}
"finger.bridge_thickness" = {{ min = 0.002, max = 0.004 }}
"finger.hole_height" = {{ min = 0.010, max = 0.014 }}

[responses]
bending = {{ r_max = 0.40 }}
"""

# Paper 001: about 10 minutes of Abaqus per design point (60 by hand).
PAPER_MINUTES_PER_DESIGN = 10.0


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--points", type=int, default=100)
    ap.add_argument("--workers", type=int, default=2)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        f = Path(tmp) / "s.toml"
        f.write_text(STUDY.format(points=args.points))
        study = load_study(f)
        t0 = time.perf_counter()
        run_study(study, Path(tmp) / "out", workers=args.workers, progress=False)
        total = time.perf_counter() - t0
        recs = [json.loads(x) for x in (Path(tmp) / "out" / "results.jsonl").read_text().splitlines()]
    per = statistics.median(r["wall_time_s"] for r in recs)
    print(f"{len(recs)} design points (bending curve), {args.workers} workers: {total:.1f} s in all "
          f"(including cluster start, table and plots)")
    print(f"per design point: median {per:.3f} s of compute; "
          f"{PAPER_MINUTES_PER_DESIGN * 60 / per:.0f}x faster than paper 001's 10 min per design")


if __name__ == "__main__":
    main()
