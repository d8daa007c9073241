"""The pneumatic finger's blocked-tip force against the chain's small-angle statics, by hand.

With the tip held on the grasping side, each hinge j (at distance d_j from the tip, spring k_j)
carries the chamber's moment M = p x moment_per_pascal less the stop's F d_j, and the tip does
not move: sum_j (M - F d_j) d_j / k_j = 0, so F = M sum(d/k) / sum(d^2/k). The simulated chain
turns its hinges by degrees and its pad gives way, so it may differ by the small-angle error.
"""

from __future__ import annotations

import numpy as np
import pytest

from gripper.core.params import GripperParams
from gripper.experiments.blocked_tip import blocked_tip_force_pneumatic


def _small_angle_force(p: GripperParams, pressure: float) -> float:
    pf = p.pneumatic
    x = np.array([0.0] + [(j - 0.5) * pf.pitch for j in range(1, pf.n_segments)])  # hinges: root, then inner
    k = np.array([pf.root_stiffness] + [pf.hinge_stiffness] * (pf.n_segments - 1))
    d = pf.length - x
    return pressure * pf.moment_per_pascal * float(np.sum(d / k) / np.sum(d ** 2 / k))


def test_pneumatic_blocked_tip_force_is_the_chains_statics():
    p = GripperParams()
    p = p.replace(actuation=p.actuation.replace(kind="pneumatic"))
    pressures = [50e3, 250e3]
    f = blocked_tip_force_pneumatic(p, pressures)
    # the small-angle error grows with the bend: 2 % at 50 kPa, 5 % at the 250 kPa set-point
    assert f[0] == pytest.approx(_small_angle_force(p, 50e3), rel=0.02)
    assert f[1] == pytest.approx(_small_angle_force(p, 250e3), rel=0.05)
    # the "a finger that can push about 1 N"
    assert 0.5 < f[1] < 1.5


def test_blocked_tip_refuses_the_cable_gripper_and_bad_pressures():
    with pytest.raises(ValueError, match="pneumatic"):
        blocked_tip_force_pneumatic(GripperParams(), [1e5])
    p = GripperParams()
    p = p.replace(actuation=p.actuation.replace(kind="pneumatic"))
    with pytest.raises(ValueError, match="pressures"):
        blocked_tip_force_pneumatic(p, [0.0])
