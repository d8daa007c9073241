"""Compile-time constants of interpolated flexes made independent of the process's history.

MuJoCo 4.0.0 compiles an interpolated flex (``dof="trilinear"``, the balloon) to stiffness
matrices and node masses that differ in their last bits depending on what the process compiled
before (a balloon compiled first in a fresh interpreter and one compiled after another scene
differ by about 1e-15 relative in 3906 of 4608 ``flex_stiffness`` entries and in 20 of the 27
node masses; the rigid parts, the card box and the bag compile bit-identically). A grasp on a
4 g membrane is chaotic enough to turn those bits into a different trial: the same seed gave a
different balloon record depending on which worker ran it and what it had run before, once a
burst (strain 1.27 where the other runs read 0.17).

So every balloon model gets the constants of one canonical compile: the object alone, at the
origin, unit mass scale, in a fresh interpreter (whose allocation history is always the same).
They are computed once per process and object description (a child process, about 1.5 s) and
written over the trial model's own (masses and inertias scaled by the trial's mass scale),
after which :func:`mujoco.mj_setConst` recomputes the derived constants. The values are the
same physics to 1e-15; what changes is that they are the same numbers in every process.

Example:
    >>> from gripper.objects.library import get_object
    >>> consts = canonical_flex_constants(get_object("balloon"))   # doctest: +SKIP
    >>> consts["flex_stiffness"].shape                             # doctest: +SKIP
    (4608,)
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Any

import mujoco
import numpy as np

from gripper.objects.grasp_object import GraspObject
from gripper.objects.scene_objects import OBJECT_BODY, Placement, add_object

_CACHE: dict[str, dict[str, np.ndarray]] = {}


def needs_canonical_constants(obj: GraspObject) -> bool:
    """Whether ``obj`` compiles to history-dependent constants (the interpolated balloon flex)."""
    return obj.object_kind.history_dependent


def _compile_alone(obj: GraspObject) -> dict[str, np.ndarray]:
    spec = mujoco.MjSpec()
    add_object(spec, obj, Placement())
    m = spec.compile()
    bodies = [b for b in range(1, m.nbody) if m.body(b).name.startswith(OBJECT_BODY)]
    return {"flex_stiffness": m.flex_stiffness.copy(),
            "names": np.array([m.body(b).name for b in bodies]),
            "mass": m.body_mass[bodies].copy(), "inertia": m.body_inertia[bodies].copy()}


def canonical_flex_constants(obj: GraspObject) -> dict[str, np.ndarray]:
    """The canonical compile's ``flex_stiffness`` and node-body ``names``, ``mass`` [kg] and
    ``inertia`` [kg·m²] of ``obj`` at unit mass scale (cached per process)."""
    key = json.dumps(obj.to_dict(), sort_keys=True, default=str)
    if key not in _CACHE:
        # a fixed string-hash seed: the child's start-up (and so its allocations) never varies
        env = {**os.environ, "PYTHONHASHSEED": "0"}
        with tempfile.TemporaryDirectory() as tmp:
            path = Path(tmp) / "consts.npz"
            done = subprocess.run([sys.executable, "-m", "gripper.sim.canonical", key, str(path)],
                                  capture_output=True, text=True, timeout=300, env=env)
            if done.returncode != 0:
                tail = (done.stderr.strip().splitlines() or ["no output"])[-1]
                raise RuntimeError(f"canonical compile of {obj.name} failed in a child process "
                                   f"({sys.executable} -m gripper.sim.canonical): {tail}")
            with np.load(path) as z:
                _CACHE[key] = {k: z[k].copy() for k in z.files}
    return _CACHE[key]


def apply_canonical_constants(m: mujoco.MjModel, obj: GraspObject, place: Placement) -> None:
    """Overwrite ``m``'s flex constants of ``obj`` with the canonical ones (see the module)."""
    if not needs_canonical_constants(obj):
        return
    c = canonical_flex_constants(obj)
    if m.flex_stiffness.shape != c["flex_stiffness"].shape:
        raise RuntimeError("canonical flex constants do not fit the model (several flexes?)")
    m.flex_stiffness[:] = c["flex_stiffness"]
    for name, mass, inertia in zip(c["names"], c["mass"], c["inertia"], strict=True):
        b = m.body(str(name)).id
        m.body_mass[b] = mass * place.mass_scale
        m.body_inertia[b] = inertia * place.mass_scale
    mujoco.mj_setConst(m, mujoco.MjData(m))


def _main(argv: list[str]) -> None:
    """Child process: compile the object described by argv[0] (JSON) alone, save to argv[1]."""
    fields: dict[str, Any] = {k: tuple(v) if isinstance(v, list) else v for k, v in json.loads(argv[0]).items()}
    obj = GraspObject(**fields)
    arrays: dict[str, Any] = _compile_alone(obj.validate())
    np.savez(argv[1], **arrays)


if __name__ == "__main__":
    _main(sys.argv[1:])
