"""Forces a designer can read (issue 44 item 6): the blocked-tip force and the holding force
(``gripper pullout``: block and cylinder) against the grip set-point, for both grippers. Prints
Markdown tables and writes the holding-force plots.

Usage: .venv/bin/python scripts/studies/set_point_forces.py [--out-dir docs]

Blocked tip: the cable finger's hinge chain against a stop at its tip, pulled with the set-point's
tension (``gripper.calibration.contact_check.blocked_tip_force_chain``); the pneumatic finger's
against the same stop at the set-point's pressure (``gripper.experiments.blocked_tip``).
"""

from __future__ import annotations

import argparse
from pathlib import Path

from gripper.calibration.contact_check import blocked_tip_force_chain
from gripper.core.params import GripperParams
from gripper.experiments.blocked_tip import blocked_tip_force_pneumatic
from gripper.experiments.protocol import GraspProtocol
from gripper.experiments.pullout import run_pullout
from gripper.render.figures import holding_force_plot

OBJECTS = ("block", "cylinder")
TENSIONS = (2.0, 5.0, 10.0)  # N per cable: 5 N is the controller's default
PRESSURES = (100e3, 175e3, 250e3)  # Pa: 250 kPa is the default


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--out-dir", default="docs")
    a = ap.parse_args()
    out = Path(a.out_dir)
    cable = GripperParams()
    pneumatic = cable.replace(actuation=cable.actuation.replace(kind="pneumatic"))
    print("| gripper | set-point | blocked-tip force per finger | holding force, block | holding force, cylinder |")
    print("|---|---|---|---|---|")
    tips = blocked_tip_force_chain(cable, TENSIONS)
    results = []
    for t, tip in zip(TENSIONS, tips, strict=True):
        hold = [run_pullout(o, params=cable, protocol=GraspProtocol(grip_tension=t)) for o in OBJECTS]
        results += hold
        print(f"| cable | {t:g} N | {tip:.2f} N | {hold[0]['holding_force_N']:.2f} N "
              f"| {hold[1]['holding_force_N']:.2f} N |", flush=True)
    holding_force_plot(results, out / "holding_force.png")
    tips = blocked_tip_force_pneumatic(pneumatic, PRESSURES)
    results = []
    for pr, tip in zip(PRESSURES, tips, strict=True):
        hold = [run_pullout(o, params=pneumatic, protocol=GraspProtocol(grip_pressure=pr)) for o in OBJECTS]
        results += hold
        print(f"| pneumatic | {pr / 1e3:g} kPa | {tip:.2f} N | {hold[0]['holding_force_N']:.2f} N "
              f"| {hold[1]['holding_force_N']:.2f} N |", flush=True)
    holding_force_plot(results, out / "holding_force_pneumatic.png")
    print(f"wrote {out / 'holding_force.png'}, {out / 'holding_force_pneumatic.png'}")


if __name__ == "__main__":
    main()
