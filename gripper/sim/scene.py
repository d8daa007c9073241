"""The grasp scene: the gripper with one object, compiled as every trial steps it."""

from __future__ import annotations

import mujoco

from gripper.core.params import GripperParams
from gripper.model.builders import build_scene_spec
from gripper.model.closure import tune_closure_limits
from gripper.objects.library import (
    GraspObject,
    Placement,
    add_object,
)
from gripper.sim.canonical import apply_canonical_constants


def grasp_scene_spec(p: GripperParams, *, with_object: bool = False) -> mujoco.MjSpec:
    """The gripper scene as grasp trials step it: ``discrete`` integrator (see objects), with the
    closed cuts matched to their design under that integrator (:mod:`gripper.model.closure`)."""
    spec = build_scene_spec(p, with_object=with_object)
    spec.option.integrator = mujoco.mjtIntegrator.mjINT_DISCRETE
    tune_closure_limits(spec, p, spec.compile())
    return spec


def build_grasp_scene(p: GripperParams, obj: GraspObject, place: Placement) -> mujoco.MjModel:
    """Compile the gripper scene with ``obj`` at ``place`` (:func:`grasp_scene_spec`)."""
    spec = grasp_scene_spec(p)
    add_object(spec, obj, place)
    m = spec.compile()
    apply_canonical_constants(m, obj, place)  # same numbers in every process (gripper.sim.canonical)
    return m
