"""Check a servo model against its datasheet with the finger detached.

The servo is built exactly as in the gripper (:func:`gripper.drives.cable.servo.add_servo`) on a bare reel,
with no cable: the no-load speed, the stall torque (reel against a hard stop) and the 60° step
time are measured in simulation.

Example:
    >>> from gripper.drives.cable.datasheet_check import measure_servo
    >>> from gripper.core.params import GripperParams
    >>> m = measure_servo(GripperParams())
    >>> abs(m.no_load_speed / m.datasheet.no_load_speed - 1) < 0.03
    True
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco
import numpy as np

from gripper.core.params import DEG, GripperParams
from gripper.datasheets.servo import ServoDatasheet
from gripper.drives.cable.finger import REEL_MASS
from gripper.drives.cable.servo import add_servo

STEP_TOLERANCE_DEG = 1.0  # a 60° move counts as done within 1° (hobby-servo dead band ≈ 1°)


@dataclass(frozen=True)
class ServoMeasurement:
    """Measured figures (output shaft, SI) beside the datasheet they should match."""

    datasheet: ServoDatasheet
    no_load_speed: float  # rad/s
    stall_torque: float  # N·m
    step_60deg_time: float  # s
    max_cable_tension: float  # N, measured stall torque / spool radius

    def rows(self) -> list[tuple[str, float, float]]:
        ds = self.datasheet
        return [("no-load speed [rad/s]", self.no_load_speed, ds.no_load_speed),
                ("stall torque [N·m]", self.stall_torque, ds.stall_torque),
                ("60° step time [s]", self.step_60deg_time, ds.step_60deg_time)]


def _servo_model(p: GripperParams, *, locked: bool) -> mujoco.MjModel:
    spec = mujoco.MjSpec()
    spec.option.timestep = 1e-4
    spec.option.integrator = mujoco.mjtIntegrator.mjINT_IMPLICITFAST
    spec.option.gravity = [0, 0, 0]
    reel = spec.worldbody.add_body(name="reel")
    reel.add_geom(type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[0.003, 0, 0], mass=REEL_MASS,
                  contype=0, conaffinity=0)
    travel = p.servo.datasheet.travel * p.servo.spool_radius
    stop = 1e-4 if locked else travel + 0.01
    reel.add_joint(name="reel", type=mujoco.mjtJoint.mjJNT_SLIDE, axis=[1, 0, 0],
                   limited=mujoco.mjtLimited.mjLIMITED_TRUE, range=[-0.01, stop],
                   solref_limit=[2e-4, 1.0], solimp_limit=[0.999, 0.999, 0.001, 0.5, 2])
    add_servo(spec, p, "servo", "reel")
    model = spec.compile()
    model.actuator_dynprm[0, 7] = 1e6  # no effective slew limit: datasheets are at full speed
    return model


def measure_servo(p: GripperParams) -> ServoMeasurement:
    """Simulate the detached servo and return the measured datasheet figures."""
    p = p.validate()
    ds = p.servo.datasheet

    free = _servo_model(p, locked=False)
    d = mujoco.MjData(free)
    d.ctrl[0] = ds.travel
    speed = 0.0
    while d.time < 0.5 and d.actuator_length[0] < 0.9 * ds.travel:
        mujoco.mj_step(free, d)
        speed = max(speed, float(d.actuator_velocity[0]))

    locked = _servo_model(p, locked=True)
    d = mujoco.MjData(locked)
    d.ctrl[0] = 0.5 * ds.travel
    for _ in range(2000):
        mujoco.mj_step(locked, d)
    stall = abs(float(d.actuator_force[0]))

    d = mujoco.MjData(free)
    target = math.pi / 3
    d.ctrl[0] = target
    t_done = math.nan
    while d.time < 10 * ds.step_60deg_time:
        mujoco.mj_step(free, d)
        if abs(d.actuator_length[0] - target) < STEP_TOLERANCE_DEG * DEG:
            t_done = float(d.time)
            break
    if not np.isfinite(t_done):
        raise RuntimeError("servo never reached the 60° target")
    return ServoMeasurement(ds, speed, stall, t_done, stall / p.servo.spool_radius)
