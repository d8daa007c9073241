"""The servo in the MJCF: a MuJoCo ``dcmotor`` on the reel's slide joint, from the servo's
datasheet (:mod:`gripper.datasheets.servo`) and the design's spool (``GripperParams.servo``).

Example:
    >>> import mujoco
    >>> from gripper.core.params import GripperParams
    >>> from gripper.drives.cable.servo import set_dcmotor
    >>> spec = mujoco.MjSpec()
    >>> set_dcmotor(spec.default.actuator, GripperParams())
"""

from __future__ import annotations

import mujoco

from gripper.core.params import DEG, GripperParams


def servo_gains(p: GripperParams) -> tuple[float, float]:
    """The servo's position-loop gains (kp [N·m/rad], kd [N·m·s/rad]): its datasheet's PD at the
    design's saturation error and damping ratio (the one place they are computed)."""
    s = p.servo
    return s.datasheet.pd_gains(saturation_error=s.saturation_error_deg * DEG, damping_ratio=s.damping_ratio)


def set_dcmotor(act, p: GripperParams) -> None:
    """The servo as a MuJoCo ``dcmotor`` (on an actuator or the ``servo`` default class).

    Gear 1/spool radius makes the actuator length the spool angle [rad] and its force the output
    torque [N·m] (cable tension = torque / spool radius). ``nominal`` = (supply voltage, stall
    torque, no-load speed) from the datasheet; input ``pos`` with the on-board PD in torque
    space, the drive voltage clamped to the supply (``Vmax``) and the set-point slewed at the
    contraction speed (``slewmax``); the reflected rotor inertia is the actuator armature.
    """
    ds = p.servo.datasheet
    kp, kd = servo_gains(p)
    act.set_to_dcmotor(motorconst=[0, 0], resistance=0,
                       nominal=[ds.voltage, ds.stall_torque, ds.no_load_speed],
                       controller=[kp, 0.0, kd, p.servo.slew_rate, 0.0, ds.voltage],
                       ctrlspec=int(mujoco.mjtCtrlInput.mjINPUT_POS))
    act.gear = [1.0 / p.servo.spool_radius, 0, 0, 0, 0, 0]
    act.armature = ds.rotor_inertia
    act.ctrllimited = mujoco.mjtLimited.mjLIMITED_TRUE
    act.ctrlrange = [0.0, ds.travel]


def add_servo(spec: mujoco.MjSpec, p: GripperParams, name: str, reel_joint: str,
              servo_class: mujoco.MjsDefault | None = None) -> None:
    """The servo on the reel's slide joint: of class ``servo`` (:func:`add_defaults`) if given,
    else with its dcmotor set here (:func:`set_dcmotor`)."""
    if servo_class is not None:
        spec.add_actuator(servo_class, name=name, target=reel_joint, trntype=mujoco.mjtTrn.mjTRN_JOINT)
        return
    act = spec.add_actuator(name=name, target=reel_joint, trntype=mujoco.mjtTrn.mjTRN_JOINT)
    set_dcmotor(act, p)
