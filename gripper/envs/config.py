"""The environment's definition: every argument declared once (:class:`EnvConfig`), the reward's
weights and the task's constants (workspace, palm speed, clearances), with their reasons.

Example:
    >>> from gripper.envs.config import EnvConfig
    >>> EnvConfig(objects=("block",), action_mode="synergy").validate().action_size
    2
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field

import numpy as np

from gripper.core.fields import Validated, param
from gripper.core.params import GripperParams
from gripper.core.timesteps import TRIAL_TIMESTEP
from gripper.experiments.protocol import GraspProtocol
from gripper.objects.library import get_object

# Physics step of the environments [s]: the grasp trials' 2 ms (see GraspProtocol.timestep).
# Palm-face height at the start of an episode, above the object's top plus the finger length [m]:
# 10 mm keeps the straight fingertips clear of the object's top at any sampled offset.
START_CLEARANCE = 0.010
# Lowest palm set-point: fingertips 4 mm above the floor [m] (they must not dig into it).
TIP_FLOOR_CLEARANCE = 0.004
# Horizontal set-point range of the x/y actions [m]: ±20 mm covers the ±10 mm pose noise twice.
XY_ACTION_RANGE = 0.020
# Palm speed at a velocity action of +-1 [m/s] (``palm_control="velocity"``): the scripted grasp's
# approach and lift speed (gripper.envs.scripted_grasp).
PALM_SPEED = 0.10
# Workspace: the object has left it beyond this horizontal distance from the palm axis's home
# [m] (a gripper of 57 mm radius cannot reach it) or below the floor by 20 mm (fell through).
WORKSPACE_RADIUS = 0.15
WORKSPACE_FLOOR = -0.020
IDENTITY_QUAT = np.array([1.0, 0.0, 0.0, 0.0])  # orientation reported for a flex object

# A finger touches the object above this normal force [N] (the contact reward).
CONTACT_FORCE = 0.05
# Two fingers oppose each other when their azimuths (evenly spaced, 2πk/n) are at least this far
# apart [rad]: across the palm for four fingers (180°), every pair for three (120°). A grasp needs
# the object pressed from opposite sides; fingertips resting on its top press from one side only.
OPPOSING_ANGLE = 2.0 * math.pi / 3.0 - 1e-9
# Length scale of the reach reward [m]: 1 - tanh(d / REACH_SCALE) falls from 0.52 at the
# benchmark's grasp pose over the block (d = 26 mm) to 0.06 at the start (d = 88 mm).
REACH_SCALE = 0.05
# The dense reward's weights (v12): a ladder whose every rung pays more than the one below it,
# measured with the reference policies of gripper.envs.reference_policies (docs/environment.md,
# "The reward ladder"). Reach pays only while the fingers are open, so a hand closed in the air
# earns nothing; contact pays only when opposing fingers press, weighted by how close the grasp
# point is, so fingertips on the object's top earn little; lift and success as in v7. A held step
# at the grasp point pays 1 (contact + lift + success).
DEFAULT_REWARD_WEIGHTS = {
    # times 1 - tanh(grasp point to object / REACH_SCALE), times the fingers' openness
    # (1 - the drive's mean set-point over its range)
    "reach": 0.1,
    # times the fraction of fingers pressing on the object (> CONTACT_FORCE) when two opposing
    # ones do (else 0), times the reach factor 1 - tanh(d / REACH_SCALE)
    "contact": 0.2,
    "lift": 0.2,      # object rise above its start / success height, clipped to [0, 1]
    "success": 0.6,   # per control step at which the grasp counts as held
    "damage": 1.25,   # once, when the object is damaged
    "action": 0.00125,  # per unit squared action norm
}

# Observation scales (``scale_observations``, since v7): each part of the observation is
# divided by its characteristic magnitude, so that every entry is of order 1, as a network with
# default initialisation expects (the raw parts span newtons, metres and radians per second,
# four orders of magnitude apart). Part name -> (scale in the part's unit, the reason).
OBSERVATION_SCALES: dict[str, tuple[float, str]] = {
    "hinge_angle": (1.0, "rad: hinge angles are 0-1 rad in a grasp"),
    "hinge_velocity": (10.0, "rad/s: the hinges swing at up to 26 rad/s when a grasp snaps"),
    "cable_shortening": (0.02 * math.pi, "m: the cable reeled in over the servo's travel (20 mm spool, π rad)"),
    "cable_tension": (50.0, "N: a stalled servo pulls the cable with about 51 N (scripted grasp)"),
    "servo_angle": (math.pi, "rad: the servo's travel"),
    "servo_setpoint": (math.pi, "rad: the servo's travel"),
    "chamber_pressure": (1.0, "-: already a fraction of the highest set-point"),
    "pressure_setpoint": (1.0, "-: already a fraction of the highest set-point"),
    "palm_height": (0.1, "m: the palm travels between 0.1 and 0.25 m above the floor"),
    "palm_setpoint": (0.1, "m: as palm_height (x and y within ±0.02 m)"),
    "object_pos_rel_palm": (0.1, "m: the object is within a finger length (0.1 m) of the palm in a grasp"),
    "object_quat": (1.0, "-: a unit quaternion"),
    "pad_force": (1.0, "N: a pad (tooth top) reads 0-0.2 N in the scripted grasps"),
    "finger_object_force": (5.0, "N: a finger presses 1-20 N on the block or the cylinder"),
    "sensed_servo_position": (math.pi, "rad: the servo's travel"),
    "sensed_servo_current": (1.0, "A: a stalled servo draws about 1.3 A (scripted grasp)"),
    "sensed_spool_tension": (50.0, "N: as cable_tension"),
    "sensed_pressure": (1.0, "-: already a fraction of the highest set-point"),
}


# The benchmark's held grasp (lifted, not slipping): the environment's success uses the same rule
# and numbers (gripper.experiments.protocol.is_held).
HELD = GraspProtocol()


@dataclass(frozen=True)
class EnvConfig(Validated):
    """Everything that defines the environment, validated once (SI units). Each scalar argument
    is declared here once with :func:`gripper.core.fields.param`; the environment's keyword
    arguments, its pickling and the docs' argument table (``docs/environment.md``) follow from
    these fields.
    """

    SECTION = "env"

    objects: tuple[str, ...] = ("block", "cylinder")
    pose_noise: float = param(0.010, "m", ge=0, le=0.02,
                              source="x/y offset range ±, the benchmark's placement noise")
    yaw_noise: bool = param(True, "-", source="random yaw for objects that are not symmetric")
    mass_noise: float = param(0.0, "-", ge=0, le=0.9, source="± fraction on the object's mass")
    friction_noise: float = param(0.0, "-", ge=0, le=0.9, source="± fraction on the object's friction")
    action_mode: str = param("fingers", "-", choices=("fingers", "synergy"),
                             source="one closing action per finger, or one for all")
    xy_actions: bool = param(False, "-", source="add palm x/y actions (needs params.lift.xy_enabled)")
    palm_control: str = param("velocity", "-", choices=("velocity", "position"),
                              source="palm actions as velocities (integrated) or set-points")
    palm_speed: float = param(PALM_SPEED, "m/s", gt=0, le=1.0,
                              source="palm speed at a velocity action of ±1: the scripted grasp's")
    servo_control: str = param("velocity", "-", choices=("velocity", "position"),
                               source="finger (drive) actions as velocities (integrated) or set-points")
    frame_skip: int = param(10, "-", ge=1, le=500, integer=True,
                            source="physics steps (2 ms) per control step: a 20 ms control period")
    scale_observations: bool = param(True, "-", source="divide each observation part by its "
                                     "characteristic magnitude (OBSERVATION_SCALES), as networks expect")
    reward_type: str = param("dense", "-", choices=("dense", "sparse"), source="see Rewards")
    reward_weights: dict = field(default_factory=lambda: dict(DEFAULT_REWARD_WEIGHTS))
    terminate_on_success: bool = param(False, "-", source="end the episode once the grasp is held")
    success_hold_s: float = param(1.0, "s", gt=0, le=60,
                                  source="held this long counts as success (the benchmark holds 2 s)")
    params: GripperParams = field(default_factory=GripperParams)

    def check(self) -> None:
        if isinstance(self.objects, str) or not self.objects:
            raise ValueError(f"env.objects: expected a non-empty list of object names, got {self.objects!r}")
        for name in self.objects:
            get_object(name)  # raises with the allowed names
        unknown = set(self.reward_weights) - set(DEFAULT_REWARD_WEIGHTS)
        if unknown:
            raise ValueError(f"env.reward_weights: unknown terms {sorted(unknown)}; allowed: "
                             f"{', '.join(DEFAULT_REWARD_WEIGHTS)}")
        for k, v in self.reward_weights.items():
            if isinstance(v, bool) or not (isinstance(v, int | float) and math.isfinite(v)):
                raise ValueError(f"env.reward_weights.{k}: must be a finite number, got {v!r}")
        if self.xy_actions and not self.params.lift.xy_enabled:
            raise ValueError("env.xy_actions: needs params.lift.xy_enabled = true")
        self.params.validate()

    @property
    def n_fingers(self) -> int:
        return self.params.layout.n_fingers

    @property
    def action_size(self) -> int:
        n = self.n_fingers if self.action_mode == "fingers" else 1
        return n + 1 + (2 if self.xy_actions else 0)

    @property
    def control_period(self) -> float:
        return self.frame_skip * TRIAL_TIMESTEP

    @functools.cached_property
    def weights(self) -> dict:
        """The reward weights in effect (defaults overridden by ``reward_weights``)."""
        return {**DEFAULT_REWARD_WEIGHTS, **self.reward_weights}
