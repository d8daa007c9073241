"""The grasp scene: the gripper with one object, compiled as every trial steps it."""

from __future__ import annotations

import math

import mujoco

from gripper.core.hashing import stable_hash
from gripper.core.params import GripperParams
from gripper.core.timesteps import TRIAL_TIMESTEP
from gripper.drives import drive_for
from gripper.model.builders import build_gripper_spec, build_scene_spec
from gripper.objects.grasp_object import GraspObject
from gripper.objects.scene_objects import Placement, add_object
from gripper.parts.defaults import MIN_STEPS, RIGID_STOP_SOLIMP
from gripper.sim.canonical import apply_canonical_constants

# The closed cuts' tuned limits, per design (parameter hash): matching them simulates 2,500
# steps (60 ms, a fifth of a block trial), and every trial of a run has the same design. A few
# designs are kept (a study sweeps many, one after another).
_LIMITS: dict[str, list[tuple[str, list[float], list[float]]]] = {}
_LIMITS_KEPT = 8


def trial_params(p: GripperParams, timestep: float = TRIAL_TIMESTEP) -> GripperParams:
    """``p`` at the trials' step (:data:`gripper.core.timesteps.TRIAL_TIMESTEP` unless given)."""
    return p if p.sim.timestep == timestep else p.replace(sim=p.sim.replace(timestep=timestep))


def _as_trials_run(spec: mujoco.MjSpec, p: GripperParams, key: str) -> mujoco.MjSpec:
    """``spec`` with the ``discrete`` integrator (see objects) and what the drive matches to that
    integrator (the cable finger's closed cuts: :mod:`gripper.drives.cable.closure`; the match is
    computed once per design and process, then reused)."""
    spec.option.integrator = mujoco.mjtIntegrator.mjINT_DISCRETE
    hold_step_floors(spec, p)
    if key not in _LIMITS:
        drive_for(p).tune_for_trials(spec)
        if len(_LIMITS) >= _LIMITS_KEPT:
            _LIMITS.pop(next(iter(_LIMITS)))
        _LIMITS[key] = [(j.name, list(j.solref_limit), list(j.solimp_limit)) for j in spec.joints]
        return spec
    for j, (name, solref, solimp) in zip(spec.joints, _LIMITS[key], strict=True):
        assert j.name == name
        j.solref_limit = solref
        j.solimp_limit = solimp
    return spec


def hold_step_floors(spec: mujoco.MjSpec, p: GripperParams) -> None:
    """The stiffnesses that the builders floor at a few time steps (the cable's stretch at two,
    the rigid stops at ``MIN_STEPS``: MuJoCo's stability floor) floored at the trials' step
    instead, whatever step this scene takes: a finer step then resolves the same model rather
    than a stiffer one. At 0.5 ms the cable was 3.7 times and the rigid stops 16 times stiffer
    than at the trials' 2 ms, and the squeeze moved with the step (docs/contact.md)."""
    step = max(p.sim.timestep, TRIAL_TIMESTEP)
    floors = {"_cable": 2.0 * step, "_stops": MIN_STEPS * step}
    for t in spec.tendons:
        for suffix, floor in floors.items():
            if t.name.endswith(suffix) and t.solref_limit[0] < floor:
                t.solref_limit = [round(floor, 6), float(t.solref_limit[1])]
    rigid = MIN_STEPS * p.sim.timestep
    for j in spec.joints:
        if math.isclose(j.solref_limit[0], rigid) and list(j.solimp_limit) == list(RIGID_STOP_SOLIMP):
            j.solref_limit = [round(MIN_STEPS * step, 6), float(j.solref_limit[1])]


def trial_gripper_spec(p: GripperParams) -> mujoco.MjSpec:
    """The gripper alone as trials step it: the committed ``models/soft_gripper/soft_gripper.xml``
    is this spec for the default design at the trials' step (:mod:`gripper.sim.model_files`)."""
    return _as_trials_run(build_gripper_spec(p), p, stable_hash([p.to_dict(), "gripper"]))


def grasp_scene_spec(p: GripperParams, *, with_object: bool = False) -> mujoco.MjSpec:
    """The gripper scene as grasp trials step it: :func:`trial_gripper_spec` with the floor,
    light and cameras (``with_object``: and the library's block under the palm). The closed
    cuts' match depends on the joints' inverse inertias only, which the floor does not change,
    so the scene's joints are the gripper file's (a test compares the compiled models)."""
    spec = build_scene_spec(p, with_object=with_object)
    return _as_trials_run(spec, p, stable_hash([p.to_dict(), with_object]))


def build_grasp_scene(p: GripperParams, obj: GraspObject, place: Placement) -> mujoco.MjModel:
    """Compile the gripper scene with ``obj`` at ``place`` (:func:`grasp_scene_spec`)."""
    spec = grasp_scene_spec(p)
    add_object(spec, obj, place, rigid_contact=p.contact.model == "pads")
    m = spec.compile()
    apply_canonical_constants(m, obj, place)  # same numbers in every process (gripper.sim.canonical)
    return m
