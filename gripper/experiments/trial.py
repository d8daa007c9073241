"""One grasp trial on the gripper with one object.

Within a chunk of ``protocol.chunk_steps`` steps every command is a function of time, so each
phase is stepped with ``mujoco.rollout`` chunk by chunk on the trial's own ``MjData``; between
chunks the runner checks stability (MuJoCo warnings, non-finite state), slip and damage, and the
drive's grip controller (:meth:`gripper.drives.drive.Drive.grip_controller`) reads the drive and sets the next
chunk's goals, so a chunk is also its control period. Cable tension is the tendon-limit force
sensor, recorded at every step by the rollout; per-finger contact force is the sum of the
normal forces of all contacts between that finger's elements and the object, read from the
contact list at the end of every chunk (so peaks are sampled every ``chunk_steps`` steps, 40 ms
by default at the 2 ms step).

Example:
    >>> from gripper.experiments.trial import run_trial
    >>> rec = run_trial("block", seed=0, index=0)          # doctest: +SKIP
    >>> rec["success"], rec["peak_total_force_N"]          # doctest: +SKIP
"""

from __future__ import annotations

import math
import time
import zlib
from typing import Any

import mujoco
import numpy as np

from gripper.core.arguments import check_instance, check_int
from gripper.core.hashing import stable_hash
from gripper.core.params import GripperParams
from gripper.core.provenance import versions
from gripper.core.ranges import INDEX_MAX, SEED_MAX
from gripper.drives import Drive, drive_for
from gripper.drives.cable.sensing import ServoSensing
from gripper.experiments.approach import ApproachPlan, fingertip_palm_z, plan_approach
from gripper.experiments.protocol import GraspProtocol, TrialNoise, is_held
from gripper.experiments.record import TrialRecord
from gripper.model.builders import WRIST
from gripper.objects.grasp_object import GraspObject
from gripper.objects.library import get_object
from gripper.objects.scene_objects import Placement
from gripper.sim.damage import damage_measure
from gripper.sim.depth import DepthCamera, NoObjectSeen, estimate_object, palm_depth_points
from gripper.sim.probes import ObjectProbe, PeakRecorder
from gripper.sim.scene import build_grasp_scene, trial_params
from gripper.sim.stability import SimulationUnstable
from gripper.sim.stepping import ChunkStepper, run_phase


def sample_placement(obj: GraspObject, noise: TrialNoise, seed: int, index: int) -> Placement:
    """The perturbation of trial ``index`` of a run with base ``seed``: deterministic, and the
    same whichever process runs it (the generator is seeded by seed, index and object name)."""
    rng = np.random.default_rng([seed, index, zlib.crc32(obj.name.encode())])
    x, y = rng.uniform(-noise.xy, noise.xy, size=2)
    yaw = rng.uniform(-math.pi, math.pi)
    ms = rng.uniform(1 - noise.mass_frac, 1 + noise.mass_frac)
    fs = rng.uniform(1 - noise.friction_frac, 1 + noise.friction_frac)
    return Placement(x=float(x), y=float(y), yaw=float(yaw) if noise.yaw and not obj.yaw_symmetric else 0.0,
                     mass_scale=float(ms), friction_scale=float(fs))


def grasp_height(p: GripperParams, obj: GraspObject, proto: GraspProtocol) -> float:
    """Palm-face height above the floor at which the fingers close [m], by the catalogue rule
    (``protocol.approach = "catalogue"``: from the object's size)."""
    return max(drive_for(p).finger_length + proto.tip_clearance, obj.height + proto.palm_clearance)


def run_trial(obj: str | GraspObject, seed: int = 0, index: int = 0, *,
              params: GripperParams | None = None, protocol: GraspProtocol | None = None,
              noise: TrialNoise | None = None, placement: Placement | None = None,
              sensing: ServoSensing | None = None, camera: DepthCamera | None = None,
              frame_sink=None) -> TrialRecord:
    """Run one scripted grasp trial; return its record (:class:`TrialRecord`, SI units).

    ``placement`` overrides the sampled perturbation; ``sensing`` the drive's sensor model (the
    cable drive's :class:`ServoSensing`; a drive ignores another's) and
    ``camera`` the palm camera's (their noise is drawn from generators seeded by seed, index and
    object name). The grasp itself reads no field of the object: under the default
    ``protocol.approach = "sensed"`` the palm camera finds it, and a table where the camera sees
    nothing gives ``status = "no_object"`` (neither success nor failure). ``frame_sink`` (optional, see
    :class:`gripper.render.video.FrameRecorder`) gets ``start(model, probe)`` once and then
    ``add(phase, states, sensordata)`` after every chunk, for recording a video. An unstable simulation does not raise:
    the record gets ``status = "error"`` and the message, and counts neither as success nor
    failure.
    """
    check_instance("obj", obj, (str, GraspObject), optional=False)
    check_int("seed", seed, 0, SEED_MAX)
    check_int("index", index, 0, INDEX_MAX)
    for name, value, cls in (("params", params, GripperParams), ("protocol", protocol, GraspProtocol),
                             ("noise", noise, TrialNoise), ("placement", placement, Placement),
                             ("sensing", sensing, ServoSensing), ("camera", camera, DepthCamera)):
        check_instance(name, value, cls)
    obj = get_object(obj) if isinstance(obj, str) else obj.validate()
    proto = (protocol or GraspProtocol()).validate()
    p = (params or GripperParams()).validate()
    p = trial_params(p, proto.timestep).validate()
    noise = (noise or TrialNoise()).validate()
    sensing = (sensing or ServoSensing()).validate()
    camera = (camera or DepthCamera()).validate()
    place = placement.validate() if placement is not None else sample_placement(obj, noise, seed, index)
    head: dict[str, Any] = {
        "trial_id": f"{obj.name}-{seed}-{index:04d}", "object": obj.name, "seed": seed, "index": index,
        "perturbation": {"x_m": place.x, "y_m": place.y, "yaw_rad": place.yaw,
                         "mass_scale": place.mass_scale, "friction_scale": place.friction_scale},
        "config_hash": stable_hash([p.to_dict(), proto.to_dict(), noise.to_dict(), obj.to_dict(),
                                   sensing.to_dict(), camera.to_dict()]),
        "versions": versions(),
    }
    wall0 = time.perf_counter()
    m = build_grasp_scene(p, obj, place)
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    drive = drive_for(p)
    probe = ObjectProbe(m, obj, p.layout.n_fingers, drive)
    rec = PeakRecorder(probe)
    if frame_sink is not None:
        frame_sink.start(m, probe)
        rec.frame_sink = frame_sink
    try:
        sensor = drive.sensor(m, np.random.default_rng([seed, index, zlib.crc32(obj.name.encode()), 1]), sensing)
        eye = Eye(camera, np.random.default_rng([seed, index, zlib.crc32(obj.name.encode()), 2]))
        outcome = {"status": "ok", **run_protocol(m, d, p, obj, proto, probe, rec, sensor, eye)}
    except NoObjectSeen as e:
        outcome = {"status": "no_object", "success": None, "failed_phase": None, "error": str(e)}
    except SimulationUnstable as e:
        outcome = {"status": "error", "success": None, "failed_phase": None, "error": str(e)}
    outcome.update(drive.trial_outcome(rec.peak_effort))
    return TrialRecord(
        **head, **outcome,
        peak_total_force_N=rec.peak_total, peak_finger_force_N=rec.peak_finger.tolist(),
        warnings=int(sum(w.number for w in d.warning)),
        sim_time_s=float(d.time), wall_time_s=time.perf_counter() - wall0)


class Eye:
    """The palm camera of one trial: its model and its noise generator."""

    def __init__(self, camera: DepthCamera, rng: np.random.Generator):
        self.camera, self.rng = camera, rng

    def look(self, m, d, palm: int):
        """The object estimate in the state of ``d`` (raises :class:`NoObjectSeen`)."""
        return estimate_object(palm_depth_points(m, d, palm, self.camera, self.rng), self.camera)


def run_protocol(m, d, p, obj, proto, probe, rec, sensor=None, eye: Eye | None = None) -> dict:
    """Run the grasp protocol on a built scene; ``sensor`` reads the drive (default: the drive's
    sensor with its default sensing and a fixed generator), ``eye`` is the palm camera (default:
    :class:`DepthCamera` with a fixed generator).

    Raises:
        NoObjectSeen: the sensed approach saw nothing on the table.
    """
    stepper = ChunkStepper(m, d)
    if sensor is None:
        sensor = drive_for(p).sensor(m, np.random.default_rng(0))
    if eye is None:
        eye = Eye(DepthCamera(), np.random.default_rng(0))
    try:
        return _protocol_phases(stepper, p, obj, proto, probe, rec, sensor, eye)
    finally:
        stepper.close()


def _protocol_phases(stepper, p, obj, proto, probe, rec, sensor, eye) -> dict:
    m, d = stepper.m, stepper.d
    drive: Drive = probe.drive
    ch = proto.chunk_steps
    home = p.lift.home_height
    travel = float(m.actuator_ctrlrange[probe.servo[0], 1])
    close_rate = drive.open_loop_rate(proto)  # per-object ramp [command unit/s]
    drive.check_set_point(proto)
    grip = drive.grip_controller(m, sensor, proto)  # None: the per-object ramp
    if grip is not None:
        servo_cmd = grip.goals
    close_cmd = min(obj.close_command * proto.close_command_scale, travel)
    lift_y = m.actuator("lift_y").id
    wrist = m.actuator(WRIST).id if p.lift.yaw_enabled else None
    turn = [0.0]  # the wrist's goal once the plan has it [rad]

    def ctrl(servo, z, x=None, y=None, yaw=None):
        def fn(t):
            u = np.zeros((len(t), m.nu))
            if wrist is not None:
                u[:, wrist] = turn[0] if yaw is None else yaw(t)
            s = np.asarray(servo(t) if callable(servo) else servo, dtype=float)
            u[:, probe.servo] = s[:, None] if s.ndim == 1 else s  # one goal for all, or one per finger
            u[:, probe.lift_z] = z(t) if callable(z) else z
            if x is not None:
                u[:, probe.lift_x] = x(t) if callable(x) else x
            if y is not None:
                u[:, lift_y] = y(t) if callable(y) else y
            return u
        return fn

    run_phase(stepper, probe, rec, ctrl(0.0, 0.0), proto.settle_s, ch, "settle")
    start = probe.object_pos(d)
    estimate = None
    if proto.approach == "sensed":
        estimate = eye.look(m, d, probe.palm)  # raises NoObjectSeen
        plan = plan_approach(estimate, p, proto)
    elif proto.grasp == "fingertip":  # the catalogue's size, the fingertip grasp (for ablations)
        plan = ApproachPlan(grasp="fingertip", x=0.0, y=0.0,
                            palm_z=drive.finger_length + drive.fingertip_clearance(proto),
                            support_z=0.0, floor_z=obj.height + proto.palm_clearance)
    else:
        plan = ApproachPlan(grasp="envelope", x=0.0, y=0.0, palm_z=grasp_height(p, obj, proto), support_z=0.0)
    z_grasp = plan.palm_z - home  # lift_z set-point [m]
    t_app = abs(z_grasp) / proto.approach_speed
    t_lat = max(math.hypot(plan.x, plan.y) / proto.approach_speed, 1e-9)
    t_turn = max(abs(plan.yaw) / proto.wrist_speed, 1e-9)

    def lateral(target):
        return lambda t: target * np.minimum(1.0, t / t_lat)

    run_phase(stepper, probe, rec, ctrl(0.0, lambda t: z_grasp * np.minimum(1.0, t / t_app),
                                        lateral(plan.x), lateral(plan.y),
                                        lambda t: plan.yaw * np.minimum(1.0, t / t_turn)),
              max(t_app, t_lat, t_turn), ch, "approach")
    turn[0] = plan.yaw
    xc, yc = plan.x, plan.y
    sensed: dict[str, dict] = {}
    z_close: Any = z_grasp
    if grip is None:
        t_close = close_cmd / close_rate

        def ramp(t):
            return close_cmd * np.minimum(1.0, t / t_close)

        if plan.grasp == "fingertip":  # the palm follows the fingers' reach down the ramp
            def z_close(t):
                return fingertip_palm_z(plan, p, proto, ramp(t)) - home
        run_phase(stepper, probe, rec, ctrl(ramp, z_close, xc, yc), t_close + proto.close_hold_s, ch, "close")
        hold_cmd = close_cmd
        if plan.grasp == "fingertip":
            z_grasp = float(fingertip_palm_z(plan, p, proto, close_cmd) - home)
    else:
        grip.start(d)

        def closed(dd):
            grip.update(dd)
            return not math.isnan(grip.grip_time) and dd.time - grip.t0 >= grip.grip_time + proto.close_hold_s

        if plan.grasp == "fingertip":
            # the palm descends as the fingers curl, keeping their lowest point at the clearance
            def z_close(t):
                return fingertip_palm_z(plan, p, proto, grip.goals(t).min(axis=1)) - home
        run_phase(stepper, probe, rec, ctrl(servo_cmd, z_close, xc, yc), travel / close_rate + proto.close_hold_s,
                  ch, "close", closed)
        hold_cmd = servo_cmd
        if plan.grasp == "fingertip":
            z_grasp = float(fingertip_palm_z(plan, p, proto, grip.goal.min()) - home)
    sensed["grasp"] = sensor.read(d.sensordata).to_dict()
    t_lift = proto.lift_height / proto.lift_speed
    z_top = z_grasp + proto.lift_height
    on_grip = grip.update if grip is not None else None

    def chained(*fns):
        def fn(dd):
            for f in fns:
                if f is not None:
                    f(dd)
            return False
        return fn

    lift = ctrl(hold_cmd, lambda t: z_grasp + proto.lift_height * np.minimum(1.0, t / t_lift), xc, yc)
    run_phase(stepper, probe, rec, lift, t_lift + proto.lift_settle_s, ch, "lift", on_grip)

    def rel(dd):
        return probe.object_pos(dd) - dd.xpos[probe.palm]

    rel_lift = rel(d)
    phase_ok = {}

    def check(name):
        h = probe.object_pos(d)[2] - start[2]
        slip = float(np.linalg.norm(rel(d) - rel_lift))
        phase_ok[name] = (is_held(h, slip, proto), h, slip)

    check("lift")
    max_slip = [0.0]

    def track(dd):
        max_slip[0] = max(max_slip[0], float(np.linalg.norm(rel(dd) - rel_lift)))
        return False

    run_phase(stepper, probe, rec, ctrl(hold_cmd, z_top, xc, yc), proto.hold_s, ch, "hold", chained(on_grip, track))
    check("hold")
    sensed["hold"] = sensor.read(d.sensordata).to_dict()
    w = 2 * math.pi * proto.shake_frequency
    run_phase(stepper, probe, rec, ctrl(hold_cmd, z_top, lambda t: xc + proto.shake_amplitude * np.sin(w * t), yc),
              proto.shake_s, ch, "shake", chained(on_grip, track))
    check("shake")
    lift_height = float(probe.object_pos(d)[2] - start[2])
    slip = float(np.linalg.norm(rel(d) - rel_lift))
    damage = damage_measure(m, d, obj, probe, peak_strain=rec.peak_strain, peak_force=rec.peak_total)
    if proto.release:
        if grip is None:
            opening = ctrl(lambda t: close_cmd * np.maximum(0.0, 1 - t / proto.release_s), z_top, xc, yc)
        else:
            grip.release()
            opening = ctrl(servo_cmd, z_top, xc, yc)
        run_phase(stepper, probe, rec, opening, proto.release_s, ch, "release", on_grip)
    damaged = obj.is_damaged(damage)
    failed = next((name for name in ("lift", "hold", "shake") if not phase_ok[name][0]), None)
    if failed is None and damaged:
        failed = "damage"
    out = {
        "success": failed is None, "failed_phase": failed, "lift_height_m": lift_height, "slip_m": slip,
        "max_slip_m": max_slip[0], "damaged": damaged, "damage_measure": damage,
        "damage_limit": obj.damage_limit,
        "close_command_rad": close_cmd if grip is None else drive.close_command(grip),
        "policy": proto.policy, "servo_at_grasp": sensed["grasp"], "servo_at_hold_end": sensed["hold"],
        "grasp": plan.grasp, "palm_xy_m": [xc, yc], "wrist_yaw_rad": plan.yaw, "pose": plan.pose,
        "depth_estimate": estimate.to_dict() if estimate is not None else None,
    }
    if grip is not None:
        out.update(drive.controller_outcome(grip))
    return out
