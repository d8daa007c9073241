"""Wall time per grasp trial, per object, side by side with the deformables' meshes as found.

Every trial runs twice in one run, interleaved (trial i as found, then trial i as shipped, in a
pool of ``--workers`` processes, so both see the same machine load):

- ``found``: the model as issue 24 found it (version 0.9.0): paper box and bag meshes of
  5 x 5 x 6 points;
- ``shipped``: the objects as they are now (``GraspObject.mesh_points`` from the object files).

The rigid objects, the balloon and the paper box (kept at 5 x 5 x 6: docs/performance.md, "Mesh
resolution") are the same model in both columns, so their ratio reads the run's noise. Both
columns run today's code, so what it saves outside the model (the closed cuts' match, now
computed once per design) is in neither ratio. Prints, per object, the median wall time per
trial [s] of each, the ratio shipped / found, each column's ratio to the rigid block's median,
the median cost per simulated second (a held bag costs more than a dropped one; this one reads
the model's cost whatever the outcome) and the trials held.

Usage: ``.venv/bin/python scripts/bench_deformable.py [--trials 10] [--seed 0] [--workers 2]``
"""

from __future__ import annotations

import argparse
import dataclasses
import statistics
from concurrent.futures import ProcessPoolExecutor

OBJECTS = ("block", "cylinder", "balloon", "paper_box", "bag")
# The meshes as issue 24 found them (0.9.0: gripper/objects/library.py, PAPER_BOX_COUNT, BAG_COUNT).
FOUND_POINTS = {"paper_box": (5, 5, 6), "bag": (5, 5, 6), "balloon": (5, 5, 5)}


def one(job: tuple[str, str, int, int]) -> tuple[str, str, float, float, bool]:
    variant, name, seed, index = job
    from gripper.experiments.trial import run_trial
    from gripper.objects.library import get_object

    obj = get_object(name)
    if variant == "found" and name in FOUND_POINTS:
        obj = dataclasses.replace(obj, mesh_points=FOUND_POINTS[name])
    rec = run_trial(obj, seed=seed, index=index)
    if rec.status != "ok":
        raise RuntimeError(f"{name} trial {index} ({variant}) went unstable: {rec.error}")
    return variant, name, rec.wall_time_s, rec.wall_time_s / rec.sim_time_s, bool(rec.success)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--trials", type=int, default=10)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--objects", default=",".join(OBJECTS))
    args = ap.parse_args()
    names = args.objects.split(",")
    if "block" not in names:
        names.insert(0, "block")
    jobs = [(v, n, args.seed, i) for i in range(args.trials) for n in names for v in ("found", "shipped")]
    with ProcessPoolExecutor(args.workers) as pool:
        results = list(pool.map(one, jobs))
    wall: dict[tuple[str, str], list[float]] = {}
    per_s: dict[tuple[str, str], list[float]] = {}
    held: dict[tuple[str, str], int] = {}
    for variant, name, w, ws, ok in results:
        wall.setdefault((variant, name), []).append(w)
        per_s.setdefault((variant, name), []).append(ws)
        held[(variant, name)] = held.get((variant, name), 0) + ok
    med = {k: statistics.median(v) for k, v in wall.items()}
    med_s = {k: statistics.median(v) for k, v in per_s.items()}
    print(f"{args.trials} trials per object, seed {args.seed}, {args.workers} worker processes; medians")
    print(f"{'object':<10} {'found s':>8} {'shipped s':>9} {'shipped/found':>13} {'found/block':>11} "
          f"{'shipped/block':>13} {'s per sim s, found':>18} {'shipped':>8} {'held found':>10} {'shipped':>8}")
    for n in names:
        f, s = med[("found", n)], med[("shipped", n)]
        print(f"{n:<10} {f:>8.2f} {s:>9.2f} {s / f:>13.2f} {f / med[('found', 'block')]:>11.1f} "
              f"{s / med[('shipped', 'block')]:>13.1f} {med_s[('found', n)]:>18.3f} {med_s[('shipped', n)]:>8.3f} "
              f"{held[('found', n)]:>10} {held[('shipped', n)]:>8}")


if __name__ == "__main__":
    main()
