"""Menagerie-style smoke test: step the scene under pseudo-random commands.

Example:
    >>> from gripper.experiments.smoke import random_control_rollout
    >>> from gripper.core.params import GripperParams
    >>> random_control_rollout(GripperParams(), duration=0.2)["steps"]
    200
"""

from __future__ import annotations

import time

import mujoco
import numpy as np

from gripper.core.params import GripperParams
from gripper.model.builders import build_scene_spec
from gripper.sim.stability import check_stable

HOLD_TIME = 0.1  # s between new random commands: fast enough to sweep the range in 2 s


def random_control_rollout(p: GripperParams, *, duration: float = 2.0, seed: int = 0) -> dict:
    """Step the scene for ``duration`` [s]; every actuator gets a uniform random command over its
    whole control range, renewed every ``HOLD_TIME``.

    Raises:
        SimulationUnstable: any MuJoCo warning or a non-finite state.
    """
    model = build_scene_spec(p).compile()
    data = mujoco.MjData(model)
    rng = np.random.default_rng(seed)
    lo, hi = model.actuator_ctrlrange.T
    n_steps = int(round(duration / model.opt.timestep))
    hold = max(1, int(round(HOLD_TIME / model.opt.timestep)))
    t0 = time.perf_counter()
    for step in range(n_steps):
        if step % hold == 0:
            data.ctrl[:] = rng.uniform(lo, hi)
        mujoco.mj_step(model, data)
        if step % 100 == 0:
            check_stable(model, data, "random-control rollout")
    check_stable(model, data, "random-control rollout")
    wall = time.perf_counter() - t0
    return {"steps": n_steps, "sim_time_s": data.time, "wall_time_s": wall,
            "realtime_factor": data.time / wall}
