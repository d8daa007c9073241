"""Before a run: does this design simulate at all?

A parameter set whose every field is in range can still make a model MuJoCo cannot step: a
Young's modulus of 1e300 Pa gives hinge springs whose time constant is far below the step, and
the closed cuts' static match diverges. :func:`check_design` finds that in about a second, before
any file is written, and names the fields that differ most from the defaults, since one of
them is the likely cause.

Example:
    >>> from gripper.core.params import GripperParams
    >>> from gripper.sim.preflight import check_design
    >>> check_design(GripperParams())  # doctest: +SKIP
"""

from __future__ import annotations

import dataclasses
import math
import warnings

import mujoco
import numpy as np

from gripper.core.params import GripperParams
from gripper.sim.scene import grasp_scene_spec
from gripper.sim.stability import SimulationUnstable, check_stable

PREFLIGHT_S = 0.3  # s of the scene with every cable at its strongest command: the stiffest state


def _departures(p: GripperParams, n: int = 3) -> list[str]:
    """The ``n`` numeric fields furthest (in orders of magnitude) from the defaults."""
    base = GripperParams()
    out: list[tuple[float, str]] = []
    for f in dataclasses.fields(p):
        sub, ref = getattr(p, f.name), getattr(base, f.name)
        if not dataclasses.is_dataclass(sub):
            continue
        for g in dataclasses.fields(sub):
            v, d = getattr(sub, g.name), getattr(ref, g.name)
            if isinstance(v, bool) or not isinstance(v, int | float) or v == d:
                continue
            far = abs(math.log10(abs(v) / abs(d))) if v and d else math.inf
            out.append((far, f"{f.name}.{g.name} = {v:g} (default {d:g})"))
    return [text for _, text in sorted(out, reverse=True)[:n]]


def check_design(p: GripperParams, flag: str = "--params") -> None:
    """Build the grasp scene of design ``p`` (its closed cuts matched as every trial matches
    them) and step it for :data:`PREFLIGHT_S` with every actuator at the top of its range.

    Raises:
        ValueError: one line naming ``flag``, what went wrong and the fields furthest from the
            defaults.
    """
    log = mujoco.MjLogConfig.get()
    console = log.logto_console
    log.logto_console = False  # the one line below says it; no console copy of each warning
    log.set()
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # a design this far out also warns while it builds
            model = grasp_scene_spec(p).compile()
        data = mujoco.MjData(model)
        data.ctrl[:] = model.actuator_ctrlrange[:, 1]
        for _ in range(int(round(PREFLIGHT_S / model.opt.timestep))):
            mujoco.mj_step(model, data)
        check_stable(model, data, "preflight")
        if not np.all(np.isfinite(data.qpos)):
            raise SimulationUnstable("non-finite state")
    except (RuntimeError, ValueError, FloatingPointError, OverflowError) as e:
        first = str(e).splitlines()[0] if str(e) else type(e).__name__
        far = _departures(p)
        hint = f"; furthest from the defaults: {', '.join(far)}" if far else ""
        raise ValueError(f"{flag}: this design does not simulate stably ({first}){hint}") from None
    finally:
        log.logto_console = console
        log.set()
