"""Where a grasp trial's time goes: MuJoCo's own timers, per object and per phase.

Runs trial 0 of seed 0 of each object (the default protocol) in this process, reads
``MjData.timer`` before and after every phase, and prints per phase the wall time and the
shares of ``mj_step`` spent in collision (broad and narrow phase), making constraints, the
constraint solver and the rest of the position stage (kinematics, inertia, flex). One
process, no workers: the figures are single-core.

Usage: ``.venv/bin/python scripts/profile_trials.py [--objects paper_box,bag] [--index 0]``
"""

from __future__ import annotations

import argparse
import time

import mujoco
import numpy as np

from gripper.experiments import trial as trial_mod
from gripper.sim import stepping

T = mujoco.mjtTimer
COLUMNS = {"broad": T.mjTIMER_COL_BROAD, "narrow": T.mjTIMER_COL_NARROW, "make": T.mjTIMER_POS_MAKE,
           "solver": T.mjTIMER_CONSTRAINT, "position": T.mjTIMER_POSITION, "step": T.mjTIMER_STEP}


def timers(d: mujoco.MjData) -> np.ndarray:
    return np.array([d.timer[k].duration for k in COLUMNS.values()])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--objects", default="block,balloon,paper_box,bag")
    ap.add_argument("--index", type=int, default=0)
    args = ap.parse_args()
    rows: list[tuple] = []
    real = stepping.run_phase

    def run_phase(stepper, probe, rec, ctrl_fn, duration, chunk, what, on_chunk=None):
        t0, w0 = timers(stepper.d), time.perf_counter()
        try:
            return real(stepper, probe, rec, ctrl_fn, duration, chunk, what, on_chunk)
        finally:
            rows.append((what, time.perf_counter() - w0, timers(stepper.d) - t0))

    trial_mod.run_phase = run_phase
    print(f"{'object':<10} {'phase':<9} {'wall s':>7} {'step s':>7} {'broad':>6} {'narrow':>6} {'make':>6} "
          f"{'solver':>6} {'other pos':>9} {'rest':>6}")
    for obj in args.objects.split(","):
        rows.clear()
        rec = trial_mod.run_trial(obj, seed=0, index=args.index)
        for what, wall, t in [*rows, ("trial", rec.wall_time_s, sum(r[2] for r in rows))]:
            broad, narrow, make, solver, position, step = t
            other = position - broad - narrow - make
            rest = step - position - solver

            def pct(x, step=step):
                return f"{100 * x / step:5.1f}%" if step > 0 else "    -"
            print(f"{obj:<10} {what:<9} {wall:>7.2f} {step:>7.2f} {pct(broad):>6} {pct(narrow):>6} {pct(make):>6} "
                  f"{pct(solver):>6} {pct(other):>9} {pct(rest):>6}")


if __name__ == "__main__":
    main()
