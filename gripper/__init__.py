"""gripper: MuJoCo simulator of a four-finger, cable-driven soft gripper.

Example:
    >>> from gripper import GripperParams, run_trial
    >>> rec = run_trial("block", seed=0, index=0, params=GripperParams())   # doctest: +SKIP
    >>> rec["success"], rec["peak_cable_tension_N"]                         # doctest: +SKIP

Video, pictures and design studies:

    >>> from gripper import record_trial_video, load_study, run_study               # doctest: +SKIP
    >>> record_trial_video("balloon", "balloon.mp4", camera="track")               # doctest: +SKIP
    >>> run_study(load_study("models/studies/one_at_a_time.toml"), "runs/oat")      # doctest: +SKIP

Calibration of the hinge springs against the flex reference finger or bench data:

    >>> from gripper import calibrate, apply_calibration                             # doctest: +SKIP
    >>> cal, fit, record = calibrate("runs/calibration")                             # doctest: +SKIP
    >>> p = apply_calibration(GripperParams(), "runs/calibration/calibration.json")  # doctest: +SKIP

Damage models checked with a platen crush (the balloon bursts when flattened):

    >>> from gripper import crush_test
    >>> crush_test("balloon", depth=0.040)["damaged"]                    # doctest: +SKIP
    True

The Gymnasium environment ``SoftGripperGrasp-v1`` is registered on import:

    >>> import gymnasium as gym
    >>> env = gym.make("gripper:SoftGripperGrasp-v1", objects="block")   # doctest: +SKIP
"""
from gripper.render import choose_gl_backend

choose_gl_backend()  # before anything imports mujoco: headless EGL unless MUJOCO_GL is set

from gripper.bench import BenchConfig, run_benchmark, wilson_interval
from gripper.calibration.calfile import Calibration, apply_calibration, design_hash
from gripper.calibration.fit import FitConfig, fit_hinges
from gripper.calibration.pipeline import calibrate
from gripper.calibration.reference import ReferenceConfig, run_reference
from gripper.crush import crush_test
from gripper.env import SoftGripperGraspEnv
from gripper.figures import bending_figure, success_plot
from gripper.model import build_bending_spec, build_gripper_spec, build_scene_spec
from gripper.objects import GraspObject, Placement, get_object, mesh_object
from gripper.params import GripperParams
from gripper.protocol import GraspProtocol, TrialNoise
from gripper.study import load_study, run_study
from gripper.trial import run_pullout, run_trial
from gripper.video import record_trial_video

__all__ = ["GripperParams", "build_gripper_spec", "build_scene_spec", "build_bending_spec",
           "GraspObject", "Placement", "get_object", "mesh_object", "GraspProtocol", "TrialNoise",
           "run_trial", "run_pullout", "BenchConfig", "run_benchmark", "wilson_interval",
           "SoftGripperGraspEnv", "record_trial_video", "bending_figure", "success_plot", "load_study",
           "run_study", "Calibration", "apply_calibration", "design_hash", "FitConfig", "fit_hinges",
           "calibrate", "ReferenceConfig", "run_reference", "crush_test"]
__version__ = "0.6.0"


def _register_envs() -> None:
    import gymnasium

    if "SoftGripperGrasp-v1" not in gymnasium.registry:
        gymnasium.register(
            id="SoftGripperGrasp-v1", entry_point="gripper.env:SoftGripperGraspEnv",
            vector_entry_point="gripper.vector_env:SoftGripperGraspVectorEnv",
            max_episode_steps=300)


_register_envs()
