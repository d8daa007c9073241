"""Menagerie-style smoke test: step the scene under pseudo-random commands.

Example:
    >>> from gripper.experiments.smoke import random_control_rollout
    >>> from gripper.core.params import GripperParams
    >>> random_control_rollout(GripperParams(), duration=0.2)["steps"]
    200
"""

from __future__ import annotations

import math
import time

import mujoco
import numpy as np

from gripper.core.params import GripperParams
from gripper.drives import drive_for
from gripper.model.builders import build_scene_spec
from gripper.sim.stability import check_stable

HOLD_TIME = 0.1  # s between new random commands: fast enough to sweep the range in 2 s
# The open-loop grasp's closing command as a fraction of the drive's range: 2 rad of the cable
# servo's π, past the fingers' first contact on the library block.
OPEN_LOOP_CLOSE = 2.0 / math.pi


def open_loop_grasp_controls(p: GripperParams, m: mujoco.MjModel, sim_time: float = 3.0) -> np.ndarray:
    """A fixed grasp's controls, (steps, nu), for speed measurements (``scripts/benchmarks``):
    descend 0.12 m over 1 s, close every finger's drive to :data:`OPEN_LOOP_CLOSE` of its range
    over the next 0.5 s, lift by 0.1 m at 2.2 s."""
    n = int(round(sim_time / m.opt.timestep))
    t = np.arange(n) * m.opt.timestep
    u = np.zeros((n, m.nu))
    act = drive_for(p).actuator_ids(m)
    close = OPEN_LOOP_CLOSE * m.actuator_ctrlrange[act, 1]
    u[:, act] = np.clip((t - 1.0) * 2.0, 0.0, 1.0)[:, None] * close[None, :]
    u[:, m.actuator("lift_z").id] = -0.12 * np.minimum(1.0, t) + np.where(t > 2.2, 0.1, 0.0)
    return u


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
