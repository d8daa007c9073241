"""Relaxing a reference finger to rest at a cable tension: a static point's own residual, and a
bending record's static points at rest (the continuum body's and the flexible multibody model's).

Example:
    >>> from gripper.references.relaxation import REST_TOL_DEG
    >>> REST_TOL_DEG
    0.02
"""

from __future__ import annotations

import math
import time
from dataclasses import replace

import mujoco
import numpy as np

from gripper.sim.stability import SimulationUnstable, check_stable

# deg: a static point is at rest when its bending angle moves less than this over half a second
# of the relaxation (0.02°: a fiftieth of the fit's 1° angle scale; static_bend's default)
REST_TOL_DEG = 0.02



def relax_to_rest(ref, tension: float, *, ramp_time: float = 0.0, rest_tol_deg: float = 0.02,
                  max_time: float = 20.0, chunk_time: float = 0.5, what: str = "relaxation"
                  ) -> tuple[np.ndarray, np.ndarray, float]:
    """Hold the cable at ``tension`` [N] (ramped over ``ramp_time`` [s] from the data's start)
    until the bending angle moves less than ``rest_tol_deg`` over a ``chunk_time`` chunk: the
    static point's own residual. ``ref`` should be built with a relaxation config (large
    implicit steps, the first mode damped); its data may start anywhere (a snapshot).

    Returns:
        (element angles [rad], tip x, z [m], the bending angle's move over the last chunk [deg]).

    Raises:
        SimulationUnstable: MuJoCo warned, the state became non-finite, or no rest within
            ``max_time`` of simulated time.
    """
    m, d = ref.model, ref.data
    chunk = max(1, int(round(chunk_time / m.opt.timestep)))
    t_start = float(d.time)
    previous = None
    while True:
        for _ in range(chunk):
            ramp = min(1.0, (d.time - t_start) / ramp_time) if ramp_time > 0 else 1.0
            ref.apply_cable(tension * ramp, ref.node_positions())
            mujoco.mj_step(m, d)
        check_stable(m, d, what)
        angles, tip = ref.measure(ref.node_positions())
        bend = math.degrees(angles[-1] - angles[0])
        elapsed = float(d.time) - t_start
        if elapsed > ramp_time and previous is not None and abs(bend - previous) < rest_tol_deg:
            return angles, tip, abs(bend - previous)
        if elapsed >= max_time:
            moved = abs(bend - previous) if previous is not None else float("nan")
            raise SimulationUnstable(f"{what}: not at rest after {max_time} s "
                                     f"(bending still moves {moved:.3f}° per {chunk_time} s)")
        previous = bend


def rest_points(make_ref, record, snapshots: list[np.ndarray], *, rest_tol_deg: float = REST_TOL_DEG
                ) -> dict[str, np.ndarray]:
    """The reference's static points at rest: each level's end-of-hold state (``snapshots``:
    qpos at ``record.static``) relaxed at its tension until its own residual is below
    ``rest_tol_deg`` (:func:`relax_to_rest`). ``make_ref``: builds the reference finger (the
    continuum body or the flexible multibody model) for a :class:`ReferenceConfig`; the
    relaxation uses the record's mesh and correction with 5 ms implicit steps, the first mode
    critically damped.

    Returns:
        ``element_angles_deg`` (k, n), ``tip_xz_m`` (k, 2), ``moved_deg`` (k,): the bending
        angle's move over the last half second, the residual each point was accepted at.
    """
    angles, tips, moved = [], [], []
    for snap, j in zip(snapshots, record.static, strict=True):
        ref = make_ref()
        d = ref.data
        d.qpos[:] = snap
        d.qvel[:] = 0.0
        mujoco.mj_forward(ref.model, d)
        a, tip, mv = relax_to_rest(ref, float(record.tension_N[j]), rest_tol_deg=rest_tol_deg,
                                   what=f"static point at {record.tension_N[j]:.3g} N")
        angles.append(np.degrees(a))
        tips.append(tip)
        moved.append(mv)
    return {"element_angles_deg": np.array(angles), "tip_xz_m": np.array(tips), "moved_deg": np.array(moved)}


def with_rest_points(record, make_ref, snapshots: list[np.ndarray], *, rest_tol_deg: float = REST_TOL_DEG):
    """``record`` with its static points at rest (:func:`rest_points`) and the relaxations'
    wall time added to its own."""
    t0 = time.perf_counter()
    rest = rest_points(make_ref, record, snapshots, rest_tol_deg=rest_tol_deg)
    return replace(record, rest_element_angles_deg=rest["element_angles_deg"], rest_tip_xz_m=rest["tip_xz_m"],
                   rest_moved_deg=rest["moved_deg"], wall_time_s=record.wall_time_s + time.perf_counter() - t0)


__all__ = ["REST_TOL_DEG", "relax_to_rest", "rest_points", "with_rest_points"]
