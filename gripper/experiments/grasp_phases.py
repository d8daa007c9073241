"""The grasp protocol as a sequence of phases, each readable on its own: settle, approach, close,
lift, hold, shake, release. A phase steps the trial's :class:`Grasp` (the scene, the drive's
controller, the plan and what was measured so far) with :func:`gripper.sim.stepping.run_phase`;
:func:`run_phases` runs them in order and returns the grasp's outcome.

The drive is asked, never named: its command range, its open-loop closing rate, its grip
controller (None: the per-object ramp to the object's closing command) and what it reports.

Example:
    >>> from gripper.experiments.grasp_phases import PHASES
    >>> [phase.name for phase in PHASES]
    ['settle', 'approach', 'close', 'lift', 'hold', 'shake', 'release']
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from gripper.drives import drive_for
from gripper.experiments.approach import ApproachPlan, fingertip_palm_z, plan_approach
from gripper.experiments.protocol import is_held
from gripper.model.builders import WRIST
from gripper.sim.damage import damage_measure
from gripper.sim.stepping import run_phase


@dataclass
class Grasp:
    """One trial's grasp in progress: what every phase reads, and what the phases have found."""

    stepper: Any
    p: Any
    obj: Any
    proto: Any
    probe: Any
    rec: Any
    sensor: Any
    eye: Any
    grip: Any = None  # the drive's grip controller; None: the per-object ramp
    turn: float = 0.0  # the wrist's goal once the plan has it [rad]
    plan: ApproachPlan | None = None
    estimate: Any = None
    start: np.ndarray | None = None  # the object's position after it settled [m]
    z_grasp: float = 0.0  # the lift stage's set-point at the grasp [m]
    hold_command: Any = None  # the drive's command through the lift and the hold
    sensed: dict[str, dict] = field(default_factory=dict)  # the drive's reading at grasp and hold end
    rel_lift: np.ndarray | None = None  # the object relative to the palm after the lift [m]
    phase_ok: dict[str, tuple] = field(default_factory=dict)
    max_slip: float = 0.0
    result: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self):
        m = self.stepper.m
        self.drive = self.probe.drive
        self.travel = float(m.actuator_ctrlrange[self.probe.actuators[0], 1])
        self.close_rate = self.drive.open_loop_rate(self.proto)  # per-object ramp [command unit/s]
        self.drive.check_set_point(self.proto)
        self.grip = self.drive.grip_controller(m, self.sensor, self.proto)
        self.close_command = min(self.obj.close_command * self.proto.close_command_scale, self.travel)
        self.lift_y = m.actuator("lift_y").id
        self.wrist = m.actuator(WRIST).id if self.p.lift.yaw_enabled else None
        self.home = self.p.lift.home_height

    @property
    def d(self):
        return self.stepper.d

    @property
    def planned(self) -> ApproachPlan:
        """The approach's plan (made by :class:`Approach`)."""
        assert self.plan is not None, "the approach phase makes the plan"
        return self.plan

    @property
    def xy(self) -> tuple[float, float]:
        """The palm's place over the object, from the plan [m]."""
        return self.planned.x, self.planned.y

    def ctrl(self, command, z, x=None, y=None, yaw=None):
        """Controls over a chunk's times: the drive's ``command`` (one goal for all fingers, or
        one per finger), the lift stage's ``z``, ``x``, ``y`` and the wrist's ``yaw`` (each a
        value or a function of the phase's time; the wrist holds :attr:`turn` by default)."""
        m, probe = self.stepper.m, self.probe

        def fn(t):
            u = np.zeros((len(t), m.nu))
            if self.wrist is not None:
                u[:, self.wrist] = self.turn if yaw is None else yaw(t)
            s = np.asarray(command(t) if callable(command) else command, dtype=float)
            u[:, probe.actuators] = s[:, None] if s.ndim == 1 else s
            u[:, probe.lift_z] = z(t) if callable(z) else z
            if x is not None:
                u[:, probe.lift_x] = x(t) if callable(x) else x
            if y is not None:
                u[:, self.lift_y] = y(t) if callable(y) else y
            return u
        return fn

    def run(self, name: str, controls, duration: float, on_chunk=None) -> None:
        run_phase(self.stepper, self.probe, self.rec, controls, duration, self.proto.chunk_steps, name, on_chunk)

    def relative(self, d) -> np.ndarray:
        """The object's position relative to the palm [m]."""
        return self.probe.object_pos(d) - d.xpos[self.probe.palm]

    def check_held(self, name: str) -> None:
        """Whether the object is held at the end of phase ``name`` (height, slip since the lift)."""
        assert self.start is not None, "the settle phase records the start"
        h = self.probe.object_pos(self.d)[2] - self.start[2]
        slip = float(np.linalg.norm(self.relative(self.d) - self.rel_lift))
        self.phase_ok[name] = (is_held(h, slip, self.proto), h, slip)

    def watch(self, track_slip: bool = False):
        """A chunk callback: the grip controller's update, and the largest slip since the lift."""
        def fn(d):
            if self.grip is not None:
                self.grip.update(d)
            if track_slip:
                self.max_slip = max(self.max_slip, float(np.linalg.norm(self.relative(d) - self.rel_lift)))
            return False
        return fn


class Phase:
    """One step of the protocol: :meth:`run` advances the grasp."""

    name = ""

    def run(self, g: Grasp) -> None:
        raise NotImplementedError


class Settle(Phase):
    """The object settles on the table; the fingers open, the palm at home."""

    name = "settle"

    def run(self, g):
        g.run(self.name, g.ctrl(0.0, 0.0), g.proto.settle_s)
        g.start = g.probe.object_pos(g.d)


class Approach(Phase):
    """The palm camera looks (the sensed approach) or the catalogue's size is used; the palm
    moves over the object, turns the wrist and descends to the grasp height."""

    name = "approach"

    def run(self, g):
        g.plan = self.plan(g)
        z = g.plan.palm_z - g.home
        t_down = abs(z) / g.proto.approach_speed
        t_side = max(math.hypot(g.plan.x, g.plan.y) / g.proto.approach_speed, 1e-9)
        t_turn = max(abs(g.plan.yaw) / g.proto.wrist_speed, 1e-9)

        def lateral(target):
            return lambda t: target * np.minimum(1.0, t / t_side)

        g.run(self.name, g.ctrl(0.0, lambda t: z * np.minimum(1.0, t / t_down), lateral(g.plan.x),
                                lateral(g.plan.y), lambda t: g.plan.yaw * np.minimum(1.0, t / t_turn)),
              max(t_down, t_side, t_turn))
        g.turn = g.plan.yaw
        g.z_grasp = z

    @staticmethod
    def plan(g) -> ApproachPlan:
        proto = g.proto
        if proto.approach == "sensed":
            g.estimate = g.eye.look(g.stepper.m, g.d, g.probe.palm)  # raises NoObjectSeen
            return plan_approach(g.estimate, g.p, proto)
        if proto.grasp == "fingertip":  # the catalogue's size, the fingertip grasp (for ablations)
            return ApproachPlan(grasp="fingertip", x=0.0, y=0.0,
                                palm_z=g.drive.finger_length + g.drive.fingertip_clearance(proto),
                                support_z=0.0, floor_z=g.obj.height + proto.palm_clearance)
        return ApproachPlan(grasp="envelope", x=0.0, y=0.0, palm_z=grasp_height(g.p, g.obj, proto), support_z=0.0)


def grasp_height(p, obj, proto) -> float:
    """Palm-face height above the floor at which the fingers close [m], by the catalogue rule
    (``protocol.approach = "catalogue"``: from the object's size)."""
    return max(drive_for(p).finger_length + proto.tip_clearance, obj.height + proto.palm_clearance)


class Close(Phase):
    """The fingers close: a ramp to the object's closing command, or the drive's grip
    controller until it reports the grip; in a fingertip grasp the palm follows the fingers'
    reach down, keeping their lowest point at the clearance."""

    name = "close"

    def run(self, g):
        (self.ramp if g.grip is None else self.controlled)(g)
        g.sensed["grasp"] = g.sensor.read(g.d.sensordata).to_dict()

    def ramp(self, g):
        t_close = g.close_command / g.close_rate

        def command(t):
            return g.close_command * np.minimum(1.0, t / t_close)

        g.run(self.name, g.ctrl(command, self.palm_z(g, command), *g.xy), t_close + g.proto.close_hold_s)
        g.hold_command = g.close_command
        if g.plan.grasp == "fingertip":
            g.z_grasp = float(fingertip_palm_z(g.plan, g.p, g.proto, g.close_command) - g.home)

    def controlled(self, g):
        grip = g.grip
        grip.start(g.d)

        def closed(d):
            grip.update(d)
            return not math.isnan(grip.grip_time) and d.time - grip.t0 >= grip.grip_time + g.proto.close_hold_s

        g.run(self.name, g.ctrl(grip.goals, self.palm_z(g, lambda t: grip.goals(t).min(axis=1)), *g.xy),
              g.travel / g.close_rate + g.proto.close_hold_s, closed)
        g.hold_command = grip.goals
        if g.plan.grasp == "fingertip":
            g.z_grasp = float(fingertip_palm_z(g.plan, g.p, g.proto, grip.goal.min()) - g.home)

    @staticmethod
    def palm_z(g, command):
        """The lift stage's set-point while closing: held, or following the fingers' reach."""
        if g.plan.grasp != "fingertip":
            return g.z_grasp
        return lambda t: fingertip_palm_z(g.plan, g.p, g.proto, command(t)) - g.home


class Lift(Phase):
    """The palm rises by the lift height and waits; then whether the object came with it."""

    name = "lift"

    def run(self, g):
        t_lift = g.proto.lift_height / g.proto.lift_speed
        z = g.z_grasp
        g.run(self.name, g.ctrl(g.hold_command, lambda t: z + g.proto.lift_height * np.minimum(1.0, t / t_lift),
                                *g.xy), t_lift + g.proto.lift_settle_s, g.grip.update if g.grip is not None else None)
        g.rel_lift = g.relative(g.d)
        g.check_held(self.name)


class Hold(Phase):
    """The palm holds still at the top; the object must stay without slipping."""

    name = "hold"

    def run(self, g):
        g.run(self.name, g.ctrl(g.hold_command, g.z_grasp + g.proto.lift_height, *g.xy), g.proto.hold_s,
              g.watch(track_slip=True))
        g.check_held(self.name)
        g.sensed["hold"] = g.sensor.read(g.d.sensordata).to_dict()


class Shake(Phase):
    """The palm shakes sideways; then the object's height, slip and damage are measured."""

    name = "shake"

    def run(self, g):
        proto, (xc, yc) = g.proto, g.xy
        w = 2 * math.pi * proto.shake_frequency
        g.run(self.name, g.ctrl(g.hold_command, g.z_grasp + proto.lift_height,
                                lambda t: xc + proto.shake_amplitude * np.sin(w * t), yc),
              proto.shake_s, g.watch(track_slip=True))
        g.check_held(self.name)
        g.result = {"lift_height_m": float(g.probe.object_pos(g.d)[2] - g.start[2]),
                    "slip_m": float(np.linalg.norm(g.relative(g.d) - g.rel_lift)),
                    "damage_measure": damage_measure(g.stepper.m, g.d, g.obj, g.probe,
                                                     peak_strain=g.rec.peak_strain, peak_force=g.rec.peak_total)}


class Release(Phase):
    """The fingers open (where the protocol releases), the palm at the top."""

    name = "release"

    def run(self, g):
        if not g.proto.release:
            return
        if g.grip is None:
            def command(t):
                return g.close_command * np.maximum(0.0, 1 - t / g.proto.release_s)
        else:
            g.grip.release()
            command = g.grip.goals
        g.run(self.name, g.ctrl(command, g.z_grasp + g.proto.lift_height, *g.xy), g.proto.release_s,
              g.grip.update if g.grip is not None else None)


PHASES: tuple[Phase, ...] = (Settle(), Approach(), Close(), Lift(), Hold(), Shake(), Release())


def run_phases(stepper, p, obj, proto, probe, rec, sensor, eye) -> dict:
    """Run :data:`PHASES` on a built scene; return the grasp's outcome (the trial record's
    fields of the grasp)."""
    g = Grasp(stepper, p, obj, proto, probe, rec, sensor, eye)
    for phase in PHASES:
        phase.run(g)
    return outcome(g)


def outcome(g: Grasp) -> dict[str, Any]:
    """Success (held after the lift, the hold and the shake, and not damaged), where it failed,
    and what the grasp measured."""
    plan = g.planned
    damaged = g.obj.is_damaged(g.result["damage_measure"])
    failed = next((name for name in ("lift", "hold", "shake") if not g.phase_ok[name][0]), None)
    if failed is None and damaged:
        failed = "damage"
    out = {
        "success": failed is None, "failed_phase": failed, "lift_height_m": g.result["lift_height_m"],
        "slip_m": g.result["slip_m"], "max_slip_m": g.max_slip, "damaged": damaged,
        "damage_measure": g.result["damage_measure"], "damage_limit": g.obj.damage_limit,
        "policy": g.proto.policy,
        "drive": {**g.drive.command_outcome(g.grip, g.close_command),
                  "at_grasp": g.sensed["grasp"], "at_hold_end": g.sensed["hold"]},
        "grasp": plan.grasp, "palm_xy_m": [plan.x, plan.y], "wrist_yaw_rad": plan.yaw, "pose": plan.pose,
        "depth_estimate": g.estimate.to_dict() if g.estimate is not None else None,
    }
    if g.grip is not None:
        out.update(g.drive.controller_outcome(g.grip))
    return out
