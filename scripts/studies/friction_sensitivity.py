"""How the grasp results move with the assumed friction coefficients (issue 44 item 5): each
object's coefficient scaled by 0.5, 1 and 1.67 (the envelope's 0.3-1.0 span around the usual 0.6),
trials held and the median holding force (``gripper pullout``).

Usage: .venv/bin/python scripts/studies/friction_sensitivity.py [--trials 10] [--pulls 3]
       [--objects balloon,block,cylinder,paper_box,bag] [--actuation cable|pneumatic] [--seed 1]
"""

from __future__ import annotations

import argparse
import statistics

from gripper import GripperParams, run_trial
from gripper.experiments.protocol import TrialNoise
from gripper.experiments.pullout import run_pullout
from gripper.experiments.trial import sample_placement
from gripper.objects.library import get_object

SCALES = (0.5, 1.0, 1.67)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--trials", type=int, default=10)
    ap.add_argument("--pulls", type=int, default=3)
    ap.add_argument("--objects", default="balloon,block,cylinder,paper_box,bag")
    ap.add_argument("--actuation", default="cable", choices=("cable", "pneumatic"))
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()
    p = GripperParams()
    p = p.replace(actuation=p.actuation.replace(kind=a.actuation))
    print(f"{a.actuation} gripper, seed {a.seed}: held / trials and median holding force [N] per friction scale")
    print(f"{'object':<10} {'mu':>5} " + " ".join(f"{f'x{s:g}':>16}" for s in SCALES))
    for name in a.objects.split(","):
        obj = get_object(name)
        cells = []
        for s in SCALES:
            places = [sample_placement(obj, TrialNoise(), a.seed, i).replace(friction_scale=s) for i in range(a.trials)]
            held = sum(bool(run_trial(obj, seed=a.seed, index=i, params=p, placement=pl).success)
                       for i, pl in enumerate(places))
            pulls = [run_pullout(obj, params=p, placement=pl)["holding_force_N"] for pl in places[:a.pulls]]
            cells.append(f"{held:>3d}/{a.trials:<3d} {statistics.median(pulls):7.2f} N")
        print(f"{name:<10} {obj.friction:5.2f} " + " ".join(f"{c:>16}" for c in cells), flush=True)


if __name__ == "__main__":
    main()
