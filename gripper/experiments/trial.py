"""One grasp trial on the gripper with one object.

Within a chunk of ``protocol.chunk_steps`` steps every command is a function of time, so each
phase is stepped with ``mujoco.rollout`` chunk by chunk on the trial's own ``MjData``; between
chunks the runner checks stability (MuJoCo warnings, non-finite state), slip and damage, and the
drive's grip controller (:meth:`gripper.drives.drive.Drive.grip_controller`) reads the drive and sets the next
chunk's goals, so a chunk is also its control period. The drive's effort (``Drive.effort_sensors``)
is recorded at every step by the rollout; per-finger contact force is the sum of the
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
from gripper.drives import drive_for
from gripper.experiments.approach import check_fits_opening
from gripper.experiments.grasp_phases import grasp_height, run_phases
from gripper.experiments.protocol import GraspProtocol, TrialNoise
from gripper.experiments.record import TrialRecord
from gripper.objects.grasp_object import GraspObject
from gripper.objects.library import get_object
from gripper.objects.scene_objects import Placement
from gripper.sim.depth import DepthCamera, NoObjectSeen, estimate_object, palm_depth_points
from gripper.sim.probes import ObjectProbe, PeakRecorder
from gripper.sim.scene import build_grasp_scene, trial_params
from gripper.sim.stability import SimulationUnstable
from gripper.sim.stepping import ChunkStepper


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


def run_trial(obj: str | GraspObject, seed: int = 0, index: int = 0, *,
              params: GripperParams | None = None, protocol: GraspProtocol | None = None,
              noise: TrialNoise | None = None, placement: Placement | None = None,
              sensing: Any = None, camera: DepthCamera | None = None,
              frame_sink=None) -> TrialRecord:
    """Run one scripted grasp trial; return its record (:class:`TrialRecord`, SI units).

    ``placement`` overrides the sampled perturbation; ``sensing`` the drive's sensor model (the
    drive's own settings, ``Drive.sensing_class``: the cable drive's ``ServoSensing``, the
    pneumatic drive's ``PressureSensing``) and
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
                             ("camera", camera, DepthCamera)):
        check_instance(name, value, cls)
    obj = get_object(obj) if isinstance(obj, str) else obj.validate()
    proto = (protocol or GraspProtocol()).validate()
    p = (params or GripperParams()).validate()
    p = trial_params(p, proto.timestep).validate()
    check_fits_opening(obj, p)
    noise = (noise or TrialNoise()).validate()
    drive = drive_for(p)
    sensing = drive.trial_sensing(sensing)
    camera = (camera or DepthCamera()).validate()
    place = placement.validate() if placement is not None else sample_placement(obj, noise, seed, index)
    head: dict[str, Any] = {
        "trial_id": f"{obj.name}-{seed}-{index:04d}", "object": obj.name, "seed": seed, "index": index,
        "perturbation": {"x_m": place.x, "y_m": place.y, "yaw_rad": place.yaw,
                         "mass_scale": place.mass_scale, "friction_scale": place.friction_scale},
        "config_hash": stable_hash([p.to_dict(), proto.to_dict(), noise.to_dict(), obj.to_dict(),
                                   sensing.to_dict() if sensing is not None else None, camera.to_dict()]),
        "versions": versions(),
    }
    wall0 = time.perf_counter()
    m = build_grasp_scene(p, obj, place)
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
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
    outcome["drive"] = {**drive.trial_outcome(rec.peak_effort), **outcome.get("drive", {})}
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
        return run_phases(stepper, p, obj, proto, probe, rec, sensor, eye)
    finally:
        stepper.close()


__all__ = ["Eye", "grasp_height", "run_protocol", "run_trial", "sample_placement"]
