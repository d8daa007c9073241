"""The blocked-tip force (gripper.experiments.blocked_tip), one setup for every drive.

The pneumatic finger against the chain's small-angle statics, by hand: with the tip held on the
grasping side, each hinge j (at distance d_j from the tip, spring k_j) carries the chamber's
moment M = p x moment_per_pascal less the stop's F d_j, and the tip does not move:
sum_j (M - F d_j) d_j / k_j = 0, so F = M sum(d/k) / sum(d^2/k). The simulated chain turns its
hinges by degrees and its pad gives way, so it may differ by the small-angle error.
"""

from __future__ import annotations

import numpy as np
import pytest

from gripper.core.params import GripperParams
from gripper.drives import drive_for
from gripper.experiments.blocked_tip import blocked_tip_force


def _pneumatic() -> GripperParams:
    p = GripperParams()
    return p.replace(actuation=p.actuation.replace(kind="pneumatic"))


def _small_angle_force(p: GripperParams, pressure: float) -> float:
    pf = p.pneumatic
    x = np.array([0.0] + [(j - 0.5) * pf.pitch for j in range(1, pf.n_segments)])  # hinges: root, then inner
    k = np.array([pf.root_stiffness] + [pf.hinge_stiffness] * (pf.n_segments - 1))
    d = pf.length - x
    return pressure * pf.moment_per_pascal * float(np.sum(d / k) / np.sum(d ** 2 / k))


def test_pneumatic_blocked_tip_force_is_the_chains_statics():
    p = _pneumatic()
    f = blocked_tip_force(p, [50e3, 250e3])
    # the small-angle error grows with the bend: 2 % at 50 kPa, 5 % at the 250 kPa set-point
    assert f[0] == pytest.approx(_small_angle_force(p, 50e3), rel=0.02)
    assert f[1] == pytest.approx(_small_angle_force(p, 250e3), rel=0.05)
    # the "a finger that can push about 1 N"
    assert 0.5 < f[1] < 1.5


def test_cable_blocked_tip_force_through_the_drive():
    p = GripperParams()
    drive = drive_for(p)
    # the study's r = 0.15 and 0.3 (cable shortening over finger length): 0.51 and 5.16 N on the
    # default design at issue 58 (the finger curls into an S, its tip sliding back along the stop)
    f = blocked_tip_force(p, [drive.shortening_command(0.15), drive.shortening_command(0.3)])
    assert 0.0 < f[0] < f[1]
    assert f[0] == pytest.approx(0.51, rel=0.1) and f[1] == pytest.approx(5.16, rel=0.1)
    with pytest.raises(ValueError, match="no cable"):
        drive_for(_pneumatic()).shortening_command(0.15)


@pytest.mark.parametrize("kind", ["cable", "pneumatic"])
def test_blocked_tip_refuses_commands_outside_the_drives_range(kind):
    p = GripperParams()
    p = p.replace(actuation=p.actuation.replace(kind=kind))
    with pytest.raises(ValueError, match=f"^blocked_tip_force.commands: .* the {kind} drive"):
        blocked_tip_force(p, [0.0])
    with pytest.raises(ValueError, match="commands"):
        blocked_tip_force(p, [1e9])
