"""gripper: MuJoCo simulator of a four-finger, cable-driven soft gripper.

Example:
    >>> from gripper import GripperParams, run_trial
    >>> rec = run_trial("block", seed=0, index=0, params=GripperParams())   # doctest: +SKIP
    >>> rec["success"], rec["peak_cable_tension_N"]                         # doctest: +SKIP
"""
from gripper.bench import BenchConfig, run_benchmark, wilson_interval
from gripper.model import build_bending_spec, build_gripper_spec, build_scene_spec
from gripper.objects import GraspObject, Placement, get_object, mesh_object
from gripper.params import GripperParams
from gripper.protocol import GraspProtocol, TrialNoise
from gripper.trial import run_pullout, run_trial

__all__ = ["GripperParams", "build_gripper_spec", "build_scene_spec", "build_bending_spec",
           "GraspObject", "Placement", "get_object", "mesh_object", "GraspProtocol", "TrialNoise",
           "run_trial", "run_pullout", "BenchConfig", "run_benchmark", "wilson_interval"]
__version__ = "0.1.0"
