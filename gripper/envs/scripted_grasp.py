"""The scripted grasp as a policy of the environment's own observation and velocity actions:
the demonstrator of reinforcement learning's demonstrations (``gripper train --demos``).

It does what the grasp benchmark's protocol does, decided from the observation alone (no
clock), so that a network can imitate it: with ``xy_actions`` it moves the palm over the
object (``object_pos_rel_palm``); it lowers the palm until the fingertips are 8 mm above the
floor; it then reels all cables in at 2 rad/s of spool (the protocol's closing rate) until every
finger's sensed spool tension reaches the protocol's set-point (5 N, as the benchmark's grasp
controller), or to 3.0 rad (the object library's rigid closing angle), and then it lifts the palm
to its home height at the palm's full speed and holds (reeling always to 3.0 rad, where the
servos stall, squeezed the cylinder to its 200 N damage limit on the silicone's pads; the
CHANGELOG has the history). Each phase is read from the
observed set-points (``servo_setpoint``, ``palm_setpoint``), which the environment integrates
from the velocity actions, so the state says where in the grasp the policy is.

Example:
    >>> import gymnasium as gym                                                  # doctest: +SKIP
    >>> envs = gym.make_vec("gripper:SoftGripperGrasp-v12", num_envs=4, action_mode="synergy",
    ...                     vectorization_mode="vector_entry_point")            # doctest: +SKIP
    >>> expert = ScriptedGrasp(envs.unwrapped.config)                          # doctest: +SKIP
    >>> obs, _ = envs.reset(seed=0)                                            # doctest: +SKIP
    >>> obs, *_ = envs.step(expert(obs))                                       # doctest: +SKIP
"""

from __future__ import annotations

import numpy as np

from gripper.drives import drive_for
from gripper.envs.config import HELD, EnvConfig
from gripper.envs.task import observation_divisor, observation_structure
from gripper.objects.library import RIGID_CLOSE as CLOSE_ANGLE  # rad: rigid objects' closing angle

CENTRED = 0.002         # m: the palm counts as over the object within this horizontal distance
# rad: a servo set-point past the reel's slack and the fingers' first curl; with the palm above
# the grasp height it says the grasp is being lifted
LIFTING_ANGLE = 0.5
# m: the palm counts as down at the grasp height within this distance above it: 1.5 steps of the
# palm at full speed, so that DART noise on the demonstrations (σ 0.3 of a step) does not flip the
# phase (0.5 steps, until 0.22.0, let noise 0.1 start 44 % of the lifts before the fingers gripped)
LOW_MARGIN = 0.003
# While the palm is above the grasp height with the servos past LIFTING_ANGLE, the grasp counts as
# being lifted only if every finger's sensed spool tension is at least this fraction of the grip
# set-point (a held object keeps the cables taut; fingers closing in the air do not)
HOLD_TENSION_FRACTION = 0.25
# The observation parts the script reads besides the palm's and the object's
SCRIPT_OBSERVES = ("servo_setpoint", "sensed_spool_tension")


class ScriptedGrasp:
    """``expert(obs batch) -> action batch`` for an environment made with ``config`` (velocity
    servo and palm actions; either action mode; with or without x/y actions).

    Raises:
        ValueError: the environment's actions are position set-points or its gripper's drive
            does not observe a servo set-point and a sensed spool tension (this script reels
            cables: the cable drive's observations).
    """

    def __init__(self, config: EnvConfig):
        if config.servo_control != "velocity" or config.palm_control != "velocity":
            raise ValueError("ScriptedGrasp: needs servo_control and palm_control 'velocity'")
        self.cfg = config
        self.divisor = observation_divisor(config)
        self.struct = observation_structure(config)
        missing = [name for name in SCRIPT_OBSERVES if name not in self.struct]
        if missing:
            raise ValueError(f"ScriptedGrasp: the scripted grasp reels cables; this gripper "
                             f"(actuation.kind = {config.params.actuation.kind!r}) observes no {', '.join(missing)}")
        p = config.params
        drive = drive_for(p)
        self.z_grasp = drive.finger_length + HELD.tip_clearance  # palm-face height at the grasp [m]
        self.z_top = p.lift.home_height
        dt = config.control_period
        self.palm_step = config.palm_speed * dt      # set-point change at an action of 1 [m]
        self.servo_step = drive.command_rate(HELD) * dt     # [rad]
        # the protocol's closing rate (cable speed over spool radius) as a fraction of the slew rate
        self.close_action = drive.open_loop_rate(HELD) / drive.command_rate(HELD)
        self.n_servo = config.n_fingers if config.action_mode == "fingers" else 1

    def _part(self, obs: np.ndarray, name: str) -> np.ndarray:
        i, n, _ = self.struct[name]
        return obs[:, i:i + n] * self.divisor[i:i + n]

    def __call__(self, obs: np.ndarray) -> np.ndarray:
        obs = np.atleast_2d(np.asarray(obs, dtype=np.float64))
        servo_sp = self._part(obs, "servo_setpoint").mean(axis=1)
        palm_sp = self._part(obs, "palm_setpoint")
        rel = self._part(obs, "object_pos_rel_palm")
        tension = self._part(obs, "sensed_spool_tension")
        low = palm_sp[:, 2] <= self.z_grasp + LOW_MARGIN
        # gripped: every finger's sensed tension at the protocol's set-point (the benchmark's
        # controller), or the servos at the closing angle; lifting: the fingers closed and the palm
        # above the grasp height (stateless: the observation alone tells the phase)
        gripped = (tension.min(axis=1) >= HELD.grip_tension) | (servo_sp >= CLOSE_ANGLE - 1e-6)
        taut = tension.min(axis=1) >= HOLD_TENSION_FRACTION * HELD.grip_tension
        closed = gripped | (~low & (servo_sp >= LIFTING_ANGLE) & taut)
        a = np.zeros((len(obs), self.cfg.action_size), dtype=np.float32)
        # servo: close at the protocol's rate once the palm is down; then hold the grip as the
        # benchmark's tension controller does, reeling in again whenever a finger's sensed tension
        # falls below the set-point (holding the set-point still, as until 0.22.0, let DART noise
        # of 0.1 drift the spools back 0.14 rad within 12 steps of the lift and drop the block)
        close = np.clip((CLOSE_ANGLE - servo_sp) / self.servo_step, 0.0, self.close_action)
        slack = tension.min(axis=1) < HELD.grip_tension
        a[:, :self.n_servo] = np.where((low & ~closed) | (closed & slack), close, 0.0)[:, None]
        # palm: to the grasp height (and kept there) until the fingers grip, up to home after
        down = np.clip((self.z_grasp - palm_sp[:, 2]) / self.palm_step, -1.0, 1.0)
        up = np.clip((self.z_top - palm_sp[:, 2]) / self.palm_step, 0.0, 1.0)
        a[:, self.n_servo] = np.where(closed, up, down)
        if self.cfg.xy_actions:  # over the object while the fingers are open
            xy = np.clip(rel[:, :2] / self.palm_step, -1.0, 1.0)
            centred = np.hypot(rel[:, 0], rel[:, 1]) < CENTRED
            a[:, self.n_servo + 1:] = np.where((closed | centred)[:, None], 0.0, xy)
        return a
