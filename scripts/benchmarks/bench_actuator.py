"""Paper 001's actuator model: the wall time of one 0-250 kPa sweep on the studies' mesh, the
median of ``--repeats`` runs, beside the PARDISO solve that redoes its ordering every time
(pypardiso.spsolve, the solver before 0.20.0) on the same sweep, with the machine's load.

    .venv/bin/python scripts/benchmarks/bench_actuator.py [--repeats 3] [--threads 1]

Each sweep runs in this process, one after another; ``--threads`` sets MKL's threads (the
model's default is one, so results do not depend on the thread count).
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--baseline", action="store_true", help="also time pypardiso.spsolve (doubles the run)")
    args = ap.parse_args()
    os.environ["MKL_NUM_THREADS"] = str(args.threads)
    import numpy as np

    import gripper.references.actuator_fe as fe
    from gripper.references.actuator_bending import STUDY_REFINEMENT
    from gripper.references.actuator_mesh import MeshSize
    from gripper.references.pneumatic_params import PneumaticActuator

    pressures = np.linspace(0.0, 250e3, 11)
    size = MeshSize.at_refinement(STUDY_REFINEMENT)

    def sweep() -> tuple[float, float, int]:
        r = fe.inflate(PneumaticActuator(), pressures, size)
        if r.failed_at is not None:
            sys.exit(f"the sweep failed at {r.failed_at:g} Pa")
        return r.wall_time_s, float(r.angles_deg[-1]), r.newton_iterations

    rows = {"PardisoSameSparsity": [sweep() for _ in range(args.repeats)]}
    if args.baseline:
        import pypardiso

        keep = fe.linear_solver
        fe.linear_solver = lambda: pypardiso.spsolve
        rows["pypardiso.spsolve"] = [sweep() for _ in range(args.repeats)]
        fe.linear_solver = keep
    load = os.getloadavg()
    print(f"studies' mesh (refinement {STUDY_REFINEMENT}), {args.threads} MKL thread(s), {os.cpu_count()} cores, "
          f"load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}")
    print("| solver | median sweep [s] | runs [s] | Newton iterations | bend at 250 kPa [deg] |")
    print("|---|---|---|---|---|")
    medians = {}
    for name, runs in rows.items():
        medians[name] = statistics.median(t for t, _, _ in runs)
        print(f"| {name} | {medians[name]:.1f} | {', '.join(f'{t:.1f}' for t, _, _ in runs)} | {runs[0][2]} | "
              f"{runs[0][1]:.3f} |")
    if len(medians) == 2:
        print(f"ratio spsolve / same-sparsity: {medians['pypardiso.spsolve'] / medians['PardisoSameSparsity']:.2f}")


if __name__ == "__main__":
    main()
