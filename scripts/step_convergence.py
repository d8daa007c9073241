"""Do grasp forces converge with the time step? Peak squeeze (a trial's peak total contact
force) and holding force (``gripper pullout``) at 0.5, 1 and 2 ms, the control period held at
40 ms (80, 40 and 20 steps per chunk), medians over trials with placement noise.

Usage: .venv/bin/python scripts/step_convergence.py [--trials 10] [--objects block,cylinder,balloon]
       [--actuation cable|pneumatic] [--contact pads|solver] [--pullout-trials 3]

Prints, per object, the medians at each step and their spread over the three steps (max/min - 1);
the issue's bound is 5 %.
"""

from __future__ import annotations

import argparse
import statistics

from gripper import GripperParams, run_trial
from gripper.experiments.protocol import GraspProtocol
from gripper.experiments.pullout import run_pullout
from gripper.experiments.trial import TrialNoise, sample_placement
from gripper.objects.library import get_object

CONTROL_PERIOD = 0.04  # s
STEPS = (0.0005, 0.001, 0.002)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--trials", type=int, default=10)
    ap.add_argument("--pullout-trials", type=int, default=3)
    ap.add_argument("--objects", default="block,cylinder,balloon")
    ap.add_argument("--actuation", default="cable", choices=("cable", "pneumatic"))
    ap.add_argument("--contact", default="pads", choices=("pads", "solver"))
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()
    p = GripperParams()
    p = p.replace(actuation=p.actuation.replace(kind=a.actuation), contact=p.contact.replace(model=a.contact))
    print(f"{a.actuation} gripper, contact {a.contact}, seed {a.seed}, {a.trials} trials, "
          f"control period {CONTROL_PERIOD * 1e3:g} ms")
    print(f"{'object':<10} {'quantity':<16} " + " ".join(f"{dt * 1e3:>8g}ms" for dt in STEPS) + "   spread")
    for obj in a.objects.split(","):
        squeeze, holding, held = {}, {}, {}
        for dt in STEPS:
            proto = GraspProtocol(timestep=dt, chunk_steps=round(CONTROL_PERIOD / dt))
            recs = [run_trial(obj, seed=a.seed, index=i, params=p, protocol=proto) for i in range(a.trials)]
            ok = [r for r in recs if r.status == "ok"]
            squeeze[dt] = statistics.median(r.peak_total_force_N for r in ok)
            held[dt] = sum(bool(r.success) for r in recs)
            places = [sample_placement(get_object(obj), TrialNoise(), a.seed, i) for i in range(a.pullout_trials)]
            pulls = [run_pullout(obj, params=p, protocol=proto, placement=pl) for pl in places]
            holding[dt] = statistics.median(r["holding_force_N"] for r in pulls)
        for name, vals in (("peak squeeze N", squeeze), ("holding force N", holding)):
            v = [vals[dt] for dt in STEPS]
            print(f"{obj:<10} {name:<16} " + " ".join(f"{x:>10.2f}" for x in v)
                  + f"   {max(v) / min(v) - 1:6.1%}", flush=True)
        print(f"{obj:<10} {'held':<16} " + " ".join(f"{held[dt]:>7d}/{a.trials}" for dt in STEPS), flush=True)


if __name__ == "__main__":
    main()
