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
    grippers = (
        ("cable", cable, TENSIONS, blocked_tip_force_chain(cable, TENSIONS),
         lambda t: GraspProtocol(grip_tension=t), lambda t: f"{t:g} N", "holding_force.png"),
        ("pneumatic", pneumatic, PRESSURES, blocked_tip_force_pneumatic(pneumatic, PRESSURES),
         lambda pr: GraspProtocol(grip_pressure=pr), lambda pr: f"{pr / 1e3:g} kPa", "holding_force_pneumatic.png"),
    )
    for name, params, set_points, tips, protocol, shown, plot in grippers:
        results = []
        for sp, tip in zip(set_points, tips, strict=True):
            hold = [run_pullout(o, params=params, protocol=protocol(sp)) for o in OBJECTS]
            results += hold
            cells = " | ".join(f"{h['holding_force_N']:.2f} N" if h["lifted"] else "not lifted" for h in hold)
            print(f"| {name} | {shown(sp)} | {tip:.2f} N | {cells} |", flush=True)
        holding_force_plot(results, out / plot)
    print(f"wrote {out / 'holding_force.png'}, {out / 'holding_force_pneumatic.png'}")


if __name__ == "__main__":
    main()
