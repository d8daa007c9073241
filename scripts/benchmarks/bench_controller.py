"""The grasp controller's overhead over the trial runner: medians, side by side.

For each object, runs the same trials (seed 0, indices 0..N-1) under the controller and under
the per-object closing, in one process, alternating, and prints:

- the median wall time per trial of each policy, and per simulated second (the policies close
  for different times, so wall per simulated second is the like-for-like figure);
- the controller's own share: the time spent in its code (sensor reads, state updates, goal
  ramps), timed around each call, as a median fraction of the trial's wall time.

Usage: ``.venv/bin/python scripts/bench_controller.py [--trials 5] [--objects block,balloon]``
"""

from __future__ import annotations

import argparse
import functools
import statistics
import time

from gripper.experiments import controller as ctl
from gripper.experiments.protocol import GraspProtocol
from gripper.experiments.trial import run_trial

SPENT = [0.0]


def timed(fn):
    @functools.wraps(fn)
    def wrapper(*a, **k):
        t0 = time.perf_counter()
        try:
            return fn(*a, **k)
        finally:
            SPENT[0] += time.perf_counter() - t0
    return wrapper


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--trials", type=int, default=5)
    ap.add_argument("--objects", default="block,cylinder,balloon,paper_box,bag")
    args = ap.parse_args()
    for name in ("goals", "update", "start", "settled"):
        setattr(ctl.GripController, name, timed(getattr(ctl.GripController, name)))
    print(f"{'object':<10} {'ctrl s/trial':>12} {'per_obj s/trial':>15} {'ctrl s/sim-s':>12} "
          f"{'per_obj s/sim-s':>15} {'ratio':>6} {'ctrl share':>10}")
    for obj in args.objects.split(","):
        wall = {"controller": [], "per_object": []}
        per_sim = {"controller": [], "per_object": []}
        share = []
        for i in range(args.trials):
            for policy in ("controller", "per_object"):
                SPENT[0] = 0.0
                r = run_trial(obj, seed=0, index=i, protocol=GraspProtocol(policy=policy))
                wall[policy].append(r.wall_time_s)
                per_sim[policy].append(r.wall_time_s / r.sim_time_s)
                if policy == "controller":
                    share.append(SPENT[0] / r.wall_time_s)
        med = {k: statistics.median(v) for k, v in wall.items()}
        ps = {k: statistics.median(v) for k, v in per_sim.items()}
        print(f"{obj:<10} {med['controller']:>12.3f} {med['per_object']:>15.3f} {ps['controller']:>12.4f} "
              f"{ps['per_object']:>15.4f} {ps['controller'] / ps['per_object']:>6.3f} "
              f"{statistics.median(share):>9.2%}")


if __name__ == "__main__":
    main()
