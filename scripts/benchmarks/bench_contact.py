"""Cost of the pads (issue 44): per-trial wall time with ``contact.model = "pads"`` against
0.16.0's ``"solver"`` contact, side by side in one run, for each default object and gripper.

Usage: .venv/bin/python scripts/benchmarks/bench_contact.py [--trials 5] [--objects ...]
       [--actuation cable|pneumatic] [--seed 1]

Each (object, model) pair warms up once (the per-process caches: closure match, reach), then runs
``--trials`` trials alternating the two models, so both see the same machine load. Prints medians
and the ratio pads / solver; the issue's bound is 1.3.
"""

from __future__ import annotations

import argparse
import statistics
import time

from gripper import GripperParams, run_trial

OBJECTS = "balloon,block,cylinder,paper_box,bag"


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--trials", type=int, default=5)
    ap.add_argument("--objects", default=OBJECTS)
    ap.add_argument("--actuation", default="cable", choices=("cable", "pneumatic"))
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()
    base = GripperParams()
    base = base.replace(actuation=base.actuation.replace(kind=a.actuation))
    params = {m: base.replace(contact=base.contact.replace(model=m)) for m in ("solver", "pads")}
    print(f"{a.actuation} gripper, seed {a.seed}, {a.trials} trials per object and model; wall s per trial")
    print(f"{'object':<10} {'solver':>8} {'pads':>8} {'ratio':>6}")
    for obj in a.objects.split(","):
        times: dict[str, list[float]] = {m: [] for m in params}
        for p in params.values():
            run_trial(obj, seed=a.seed, index=0, params=p)  # warm the per-process caches
        for i in range(1, a.trials + 1):
            for m, p in params.items():
                t0 = time.perf_counter()
                run_trial(obj, seed=a.seed, index=i, params=p)
                times[m].append(time.perf_counter() - t0)
        s, q = statistics.median(times["solver"]), statistics.median(times["pads"])
        print(f"{obj:<10} {s:8.3f} {q:8.3f} {q / s:6.2f}", flush=True)


if __name__ == "__main__":
    main()
