"""gripper: MuJoCo simulator of a four-finger, cable-driven soft gripper.

Example:
    >>> from gripper import GripperParams, run_trial
    >>> rec = run_trial("block", seed=0, index=0, params=GripperParams())   # doctest: +SKIP
    >>> rec["success"], rec["drive"]["peak_cable_tension_N"]                # doctest: +SKIP

Video, pictures and design studies:

    >>> from gripper import record_trial_video, load_study, run_study               # doctest: +SKIP
    >>> record_trial_video("balloon", "balloon.mp4", camera="track")               # doctest: +SKIP
    >>> run_study(load_study("one_at_a_time"), "runs/oat")                          # doctest: +SKIP

Calibration of the hinge springs against the flex reference finger or bench data:

    >>> from gripper import calibrate, apply_calibration                             # doctest: +SKIP
    >>> cal, fit, record = calibrate("runs/calibration")                             # doctest: +SKIP
    >>> p = apply_calibration(GripperParams(), "runs/calibration/calibration.json")  # doctest: +SKIP

Damage models checked with a platen crush (the balloon bursts when flattened):

    >>> from gripper import crush_test
    >>> crush_test("balloon", depth=0.040)["damaged"]                    # doctest: +SKIP
    >>> run_trial("bag", camera=DepthCamera(dropout=0.1)).depth_estimate  # doctest: +SKIP
    True

The Gymnasium environment ``SoftGripperGrasp-v12`` is registered on import:

    >>> import gymnasium as gym
    >>> env = gym.make("gripper:SoftGripperGrasp-v12", objects="block")   # doctest: +SKIP
"""

import importlib
from typing import TYPE_CHECKING, Any

from gripper.core.after_import import after_import
from gripper.render.backend import defer_gl_backend

defer_gl_backend()  # no OpenGL library until something renders (gripper.render.backend)


def _no_mujoco_log_file(mujoco) -> None:
    """MuJoCo appends its warnings to ``MUJOCO_LOG.TXT`` in the current folder by default; the
    package counts every warning in its records instead (gripper.sim.stability), so the file
    would only be litter in the user's folder. The console copy stays."""
    log = mujoco.MjLogConfig.get()
    log.logto_file = False
    log.set()


after_import("mujoco", _no_mujoco_log_file)  # when MuJoCo is first imported: not imported here

# The public API, imported on first use (``import gripper`` stays quick): name -> module.
_EXPORTS = {
    "GripperParams": "gripper.core.params",
    "PneumaticFinger": "gripper.core.params",
    "regulator_datasheet": "gripper.datasheets.regulator",
    "PressureSensing": "gripper.drives.pneumatic.sensing",
    "calibrate_pneumatic": "gripper.calibration.pneumatic_fit",
    "fit_pneumatic": "gripper.calibration.pneumatic_fit",
    "run_actuator_reference": "gripper.references.actuator_bending",
    "Drive": "gripper.drives.drive",
    "drive_for": "gripper.drives.drive",
    "register_drive": "gripper.drives.drive",
    "build_gripper_spec": "gripper.model.builders",
    "build_scene_spec": "gripper.model.builders",
    "build_bending_spec": "gripper.drives.cable.finger",
    "GraspObject": "gripper.objects.grasp_object",
    "Placement": "gripper.objects.scene_objects",
    "get_object": "gripper.objects.library",
    "mesh_object": "gripper.objects.library",
    "GraspProtocol": "gripper.experiments.protocol",
    "TrialNoise": "gripper.experiments.protocol",
    "run_trial": "gripper.experiments.trial",
    "run_pullout": "gripper.experiments.pullout",
    "crush_test": "gripper.experiments.crush",
    "BenchConfig": "gripper.bench.benchmark",
    "run_benchmark": "gripper.bench.benchmark",
    "wilson_interval": "gripper.bench.benchmark",
    "SoftGripperGraspEnv": "gripper.envs.grasp_env",
    "record_trial_video": "gripper.render.video",
    "bending_figure": "gripper.render.figures",
    "success_plot": "gripper.render.figures",
    "load_study": "gripper.studies.study_file",
    "run_study": "gripper.studies.study",
    "Envelope": "gripper.studies.envelope",
    "load_envelope": "gripper.studies.envelope",
    "run_envelope": "gripper.studies.envelope",
    "ServoSensing": "gripper.drives.cable.sensing",
    "DepthCamera": "gripper.sim.depth",
    "estimate_object": "gripper.sim.depth",
    "Calibration": "gripper.calibration.calfile",
    "apply_calibration": "gripper.calibration.calfile",
    "design_hash": "gripper.calibration.calfile",
    "FitConfig": "gripper.calibration.fit",
    "fit_hinges": "gripper.calibration.fit",
    "calibrate": "gripper.calibration.pipeline",
    "ReferenceConfig": "gripper.references.continuum",
    "run_reference": "gripper.references.continuum",
}
__all__ = [*_EXPORTS, "__version__"]

if TYPE_CHECKING:  # static checkers and IDEs see the real names
    from gripper.bench.benchmark import BenchConfig, run_benchmark, wilson_interval
    from gripper.calibration.calfile import Calibration, apply_calibration, design_hash
    from gripper.calibration.fit import FitConfig, fit_hinges
    from gripper.calibration.pipeline import calibrate
    from gripper.calibration.pneumatic_fit import calibrate_pneumatic, fit_pneumatic
    from gripper.core.params import GripperParams, PneumaticFinger
    from gripper.datasheets.regulator import regulator_datasheet
    from gripper.drives.cable.finger import build_bending_spec
    from gripper.drives.cable.sensing import ServoSensing
    from gripper.drives.drive import Drive, drive_for, register_drive
    from gripper.drives.pneumatic.sensing import PressureSensing
    from gripper.envs.grasp_env import SoftGripperGraspEnv
    from gripper.experiments.crush import crush_test
    from gripper.experiments.protocol import GraspProtocol, TrialNoise
    from gripper.experiments.pullout import run_pullout
    from gripper.experiments.trial import run_trial
    from gripper.model.builders import build_gripper_spec, build_scene_spec
    from gripper.objects.grasp_object import GraspObject
    from gripper.objects.library import get_object, mesh_object
    from gripper.objects.scene_objects import Placement
    from gripper.references.actuator_bending import run_actuator_reference
    from gripper.references.continuum import ReferenceConfig, run_reference
    from gripper.render.figures import bending_figure, success_plot
    from gripper.render.video import record_trial_video
    from gripper.studies.envelope import Envelope, load_envelope, run_envelope
    from gripper.studies.study import run_study
    from gripper.studies.study_file import load_study


def __getattr__(name: str) -> Any:
    if name == "__version__":
        from gripper.core.provenance import package_version

        return package_version()
    if name in _EXPORTS:
        value = getattr(importlib.import_module(_EXPORTS[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'gripper' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))


from gripper.envs.registration import register_envs  # noqa: E402

register_envs()
