"""Contact-force samples against what the fingers' statics and the part's inertia allow (issue 44
item 4), over benchmark run folders.

The bound of one trial: every finger at its blocked-tip force for the trial's peak drive (the
cable finger's hinge chain at the peak cable tension, interpolated over a grid of tensions; the
pneumatic finger's at the peak pressure), plus the part's weight and the shake's peak inertia
(±10 mm at 2 Hz: 1.6 m/s²). The blocked tip is the finger's statics in one configuration, not a
proven upper bound for every wrap; a sample above it flags a force the drive cannot explain.

Usage: .venv/bin/python scripts/studies/force_bound.py runs/c1 runs/c2 runs/p1 runs/p2
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

import numpy as np

from gripper.calibration.contact_check import blocked_tip_force_chain
from gripper.core.params import GripperParams
from gripper.experiments.blocked_tip import blocked_tip_force
from gripper.experiments.record import upgrade_record
from gripper.objects.library import get_object

TENSIONS = (0.5, 1.0, 2.0, 5.0, 10.0, 15.0, 20.0, 25.0, 30.0)  # N
SHAKE_ACCEL = (2.0 * math.pi * 2.0) ** 2 * 0.010  # m/s²: the benchmark's shake


def main() -> None:
    cable = GripperParams()
    pneumatic = cable.replace(actuation=cable.actuation.replace(kind="pneumatic"))
    tips = blocked_tip_force_chain(cable, TENSIONS)
    tip_250 = float(blocked_tip_force(pneumatic, [pneumatic.pneumatic.command_max])[0])
    print(f"cable blocked tip [N] at {TENSIONS} N: {np.round(tips, 2).tolist()}; pneumatic at "
          f"{pneumatic.pneumatic.command_max / 1e3:g} kPa: {tip_250:.2f} N")
    print(f"{'run':<10} {'object':<10} {'trials':>6} {'max F N':>8} {'bound N':>8} {'above':>6}")
    for folder in sys.argv[1:]:
        recs = [upgrade_record(json.loads(line))
                for line in (Path(folder) / "trials.jsonl").read_text().splitlines() if line]
        for name in dict.fromkeys(r["object"] for r in recs):
            rs = [r for r in recs if r["object"] == name and r["status"] == "ok"]
            weight = get_object(name).mass * (cable.sim.gravity + SHAKE_ACCEL)
            above, worst, bounds = 0, 0.0, []
            for r in rs:
                if r["drive"]["kind"] == "pneumatic":
                    finger = tip_250 * r["drive"]["peak_pressure_Pa"] / pneumatic.pneumatic.command_max
                else:
                    finger = float(np.interp(r["drive"]["peak_cable_tension_N"], TENSIONS, tips))
                bound = 4 * finger + weight
                bounds.append(bound)
                worst = max(worst, r["peak_total_force_N"])
                above += r["peak_total_force_N"] > bound
            print(f"{folder:<10} {name:<10} {len(rs):>6} {worst:8.2f} {min(bounds):8.2f} {above:>6}", flush=True)


if __name__ == "__main__":
    main()
