"""gripper: MuJoCo simulator of a four-finger, cable-driven soft gripper."""
from gripper.model import build_bending_spec, build_gripper_spec, build_scene_spec
from gripper.params import GripperParams

__all__ = ["GripperParams", "build_gripper_spec", "build_scene_spec", "build_bending_spec"]
__version__ = "0.1.0"
