"""The pull-out test: the holding force of a grasp, pulling the held object straight down."""

from __future__ import annotations

import math

import mujoco
import numpy as np

from gripper.core.params import GripperParams
from gripper.drives import drive_for
from gripper.experiments.approach import check_fits_opening
from gripper.experiments.protocol import PULL_MAX, PULL_RATE, PULL_SLIP, GraspProtocol
from gripper.experiments.trial import run_protocol
from gripper.objects.grasp_object import GraspObject
from gripper.objects.library import get_object
from gripper.objects.scene_objects import Placement
from gripper.sim.probes import ObjectProbe, PeakRecorder
from gripper.sim.scene import build_grasp_scene, trial_params
from gripper.sim.stability import check_stable


def run_pullout(obj: str | GraspObject, *, params: GripperParams | None = None,
                protocol: GraspProtocol | None = None, placement: Placement | None = None,
                rate: float = PULL_RATE, max_force: float = PULL_MAX, slip: float = PULL_SLIP) -> dict:
    """Holding force [N]: grasp and lift as in a trial, then pull the object straight down.

    The pull is a body force on every body of the object in proportion to its mass (as a
    hanging weight would load it), ramped at ``rate`` until the object has moved ``slip``
    relative to the palm; the force at that moment is the holding force. If ``max_force`` is
    reached first, the result is that bound with ``held_at_max = True``. A grasp that did not lift
    the object to ``protocol.success_height`` holds nothing: 0 N, ``lifted = False``. Under the grasp
    controller the servos keep the goals and the current limit they had at the end of the hold
    (the pull loads the cables more, so no regrip is due).
    """
    obj = get_object(obj) if isinstance(obj, str) else obj.validate()
    proto = (protocol or GraspProtocol()).validate()
    p = (params or GripperParams()).validate()
    p = trial_params(p, proto.timestep).validate()
    check_fits_opening(obj, p)
    for name, v in (("rate", rate), ("max_force", max_force), ("slip", slip)):
        if not (math.isfinite(v) and v > 0):
            raise ValueError(f"pullout.{name}: must be > 0, got {v!r}")
    m = build_grasp_scene(p, obj, (placement or Placement()).validate())
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    probe = ObjectProbe(m, obj, p.layout.n_fingers, drive_for(p))
    rec = PeakRecorder(probe)
    short = proto.replace(hold_s=0.3, shake_s=0.0)
    grasp = run_protocol(m, d, p, obj, short, probe, rec)
    drive = drive_for(p)
    out = {"object": obj.name, "slip_m": slip, "rate_N_per_s": rate, "policy": proto.policy,
           drive.set_point_record: grasp["drive"].get(drive.set_point_record)}
    if grasp["lift_height_m"] < short.success_height:
        # not lifted: a pull down would load the table, not the grasp (until 0.17.0 the pull's
        # upper bound there as held)
        return {**out, "holding_force_N": 0.0, "held_at_max": False, "lifted": False}
    out["lifted"] = True
    masses = m.body_mass[probe.object_bodies]
    share = masses / masses.sum()
    rel0 = probe.object_pos(d) - d.xpos[probe.palm]
    u = d.ctrl.copy()
    dt = m.opt.timestep
    force = 0.0
    while force < max_force:
        force = min(max_force, force + rate * dt)
        d.xfrc_applied[probe.object_bodies, 2] = -force * share
        d.ctrl[:] = u
        mujoco.mj_step(m, d)
        check_stable(m, d, "pull-out")
        if np.linalg.norm(probe.object_pos(d) - d.xpos[probe.palm] - rel0) >= slip:
            return {**out, "holding_force_N": force, "held_at_max": False}
    return {**out, "holding_force_N": max_force, "held_at_max": True}
