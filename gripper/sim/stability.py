"""Detect an unstable simulation: MuJoCo warnings or a non-finite state.

Example:
    >>> import mujoco
    >>> m = mujoco.MjModel.from_xml_string("<mujoco/>")
    >>> check_stable(m, mujoco.MjData(m), "empty")
"""

from __future__ import annotations

import mujoco
import numpy as np


class SimulationUnstable(RuntimeError):
    """The simulation diverged or MuJoCo raised a warning; its results must not be used."""


def warning_counts(data: mujoco.MjData) -> dict[str, int]:
    """Non-zero MuJoCo warning counters by name (e.g. ``{"mjWARN_BADQACC": 3}``)."""
    out = {}
    for i, w in enumerate(data.warning):
        if w.number:
            out[mujoco.mjtWarning(i).name] = int(w.number)
    return out


def check_stable(model: mujoco.MjModel, data: mujoco.MjData, what: str) -> None:
    """Raise :class:`SimulationUnstable` on any MuJoCo warning or non-finite qpos/qvel/act.

    Raises:
        SimulationUnstable: naming ``what``, the time and the warnings seen.
    """
    finite = (np.isfinite(data.qpos).all() and np.isfinite(data.qvel).all()
              and np.isfinite(data.act).all())
    if finite and not data.warning.number.any():  # fast path: one vector read, no per-warning loop
        return
    warns = warning_counts(data)
    if warns or not finite:
        detail = ", ".join(f"{k}×{v}" for k, v in warns.items()) or "non-finite state"
        raise SimulationUnstable(f"{what}: unstable at t = {data.time:.4f} s ({detail})")
