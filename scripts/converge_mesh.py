"""Mesh convergence of a deformable object's grasp outcome and damage measure.

Runs the grasp benchmark on one built-in deformable object (balloon, paper_box or bag) at several
mesh resolutions (``GraspObject.mesh_points``), everything else equal: the same name, so the same
sampled placements and sensor noise, the same seed, the same trials. Each resolution runs into
its own folder (``OUT/<nx>x<ny>x<nz>``, resumable, through an object file ``object.json`` that
is the built-in's with ``mesh_points`` replaced), then one table compares them: trials held,
damaged, the largest, 90th-percentile and median damage measure, the median peak total force and
the median wall time per trial, and, against the finest resolution, the share of trials with the
same outcome.

Usage::

    .venv/bin/python scripts/converge_mesh.py --object paper_box --points 4x4x5,5x5x6,6x6x7 \\
        --trials 50 --seed 1 --out runs/converge/paper_box_s1
"""

from __future__ import annotations

import argparse
import json
import statistics
import tomllib
from pathlib import Path

from gripper.bench.benchmark import BenchConfig, read_trials, run_benchmark
from gripper.core.resources import OBJECTS_DIR


def points(text: str) -> tuple[int, int, int]:
    parts = tuple(int(p) for p in text.lower().split("x"))
    if len(parts) != 3:
        raise argparse.ArgumentTypeError(f"--points: expected NXxNYxNZ, got {text!r}")
    return parts  # type: ignore[return-value]


def object_file(name: str, pts: tuple[int, int, int], folder: Path) -> Path:
    data = tomllib.loads((OBJECTS_DIR / f"{name}.toml").read_text())
    data["object"]["mesh_points"] = list(pts)
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / "object.json"
    path.write_text(json.dumps(data, indent=1))
    return path


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--object", required=True, choices=("balloon", "paper_box", "bag"))
    ap.add_argument("--points", required=True, help="comma-separated NXxNYxNZ, coarse to fine")
    ap.add_argument("--trials", type=int, default=20)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    res = [points(p) for p in args.points.split(",")]
    out = Path(args.out)
    runs = {}
    for pts in res:
        tag = "x".join(map(str, pts))
        folder = out / tag
        spec = str(object_file(args.object, pts, folder))
        run_benchmark(BenchConfig(objects=(spec,), trials=args.trials, seed=args.seed), folder,
                      workers=args.workers, progress=False)
        runs[tag] = {r.index: r for r in read_trials(folder / "trials.jsonl")}
    finest = list(runs)[-1]
    print(f"{args.object}, seed {args.seed}, {args.trials} trials; outcome agreement against {finest}")
    print(f"{'points':>8} {'held':>5} {'damaged':>7} {'max dmg':>10} {'p90 dmg':>10} {'median dmg':>10} "
          f"{'F med N':>8} {'wall med s':>10} {'same outcome':>12}")
    for tag, recs in runs.items():
        ok = [r for r in recs.values() if r.status == "ok"]
        dmg = sorted(r.damage_measure or 0.0 for r in ok)
        p90 = dmg[min(len(dmg) - 1, int(0.9 * len(dmg)))]
        same = sum(bool(recs[i].success) == bool(runs[finest][i].success) for i in recs if i in runs[finest])
        print(f"{tag:>8} {sum(bool(r.success) for r in ok):>5} {sum(bool(r.damaged) for r in ok):>7} "
              f"{dmg[-1]:>10.4g} {p90:>10.4g} {statistics.median(dmg):>10.4g} "
              f"{statistics.median(r.peak_total_force_N for r in ok):>8.2f} "
              f"{statistics.median(r.wall_time_s for r in recs.values()):>10.2f} "
              f"{same:>7}/{len(recs)}")
        errors = len(recs) - len(ok)
        if errors:
            print(f"{'':>8} {errors} trial(s) went unstable (status error)")


if __name__ == "__main__":
    main()
