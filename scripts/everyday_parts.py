"""Grasp the everyday parts (a 22 mm die, an AA cell and a 130 mm pen lying on the table; built as
meshes by gripper.objects.everyday_parts) with a design, and print each part's successes.

    .venv/bin/python scripts/everyday_parts.py --trials 10 --seed 1
    .venv/bin/python scripts/everyday_parts.py --params my_design.toml --parts pen

Each trial is the benchmark's (sensed approach, the wrist, the grasp controller at its default
set-point, ±10 mm placement noise, a random yaw), seeded by the seed and its index.
"""

from __future__ import annotations

import argparse
import collections
import sys
import tempfile
import time


def main(argv=None) -> int:
    from gripper.core.params import GripperParams
    from gripper.experiments.trial import run_trial
    from gripper.objects.everyday_parts import PARTS, everyday_part

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--params", help="a parameter file (defaults: the default design)")
    ap.add_argument("--parts", default=",".join(PARTS), help=f"comma-separated, of {', '.join(PARTS)}")
    ap.add_argument("--trials", type=int, default=10)
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args(argv)
    p = GripperParams.load(args.params) if args.params else GripperParams()
    print("| part | held | grasp, pose (count) | failed phase (count) | wall |")
    print("|---|---|---|---|---|")
    with tempfile.TemporaryDirectory(prefix="gripper-parts-") as tmp:
        for name in args.parts.split(","):
            obj = everyday_part(name, tmp)
            t0 = time.perf_counter()
            recs = [run_trial(obj, args.seed, i, params=p) for i in range(args.trials)]
            ok = [r for r in recs if r["status"] == "ok"]
            held = sum(bool(r["success"]) for r in ok)
            poses = collections.Counter(f"{r['grasp']}, {r['pose']}" for r in ok)
            failed = collections.Counter(r["failed_phase"] for r in ok if not r["success"])
            errors = len(recs) - len(ok)
            print(f"| {name} | {held}/{len(ok)}{f' ({errors} not ended)' if errors else ''} | "
                  f"{', '.join(f'{k} ({v})' for k, v in poses.items())} | "
                  f"{', '.join(f'{k} ({v})' for k, v in failed.items()) or '-'} | {time.perf_counter() - t0:.0f} s |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
