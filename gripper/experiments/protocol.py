"""The scripted grasp protocol and the per-trial perturbations (frozen dataclasses, SI units).

Phases, in order: settle, approach from above, close (servos ramped to the object's closing
command at the contraction speed), lift, hold, horizontal shake, optional release.

Example:
    >>> from gripper.experiments.protocol import GraspProtocol
    >>> GraspProtocol().replace(hold_s=1.0).lift_height
    0.1
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any

from gripper.core.params import check_between


def _check(name: str, value: Any, lo: float, hi: float) -> None:
    check_between(name, value, lo, hi, closed=True)


@dataclass(frozen=True)
class GraspProtocol:
    """Scripted grasp, every phase configurable.

    Attributes:
        settle_s: time for the object to settle on the floor before anything moves [s].
        approach_speed: palm descent speed [m/s].
        tip_clearance: fingertip height above the floor at the grasp height [m]; the palm also
            stays ``palm_clearance`` above the object's top, whichever is higher.
        palm_clearance: gap kept between the palm face and the object's top [m].
        close_speed: cable contraction speed while closing [m/s] (spool surface speed).
        close_command_scale: multiplier on the object's closing command [-] (1 = default;
            > 1 closes harder, as in the damage check).
        close_hold_s: time at the closing command before lifting [s].
        lift_height: lift after closing [m] (0.10 by the benchmark definition).
        lift_speed: [m/s].
        lift_settle_s: pause after the lift, before "end of lift" is taken [s].
        hold_s: static hold [s].
        shake_amplitude: horizontal shake amplitude along x [m].
        shake_frequency: [Hz].
        shake_s: shake duration [s].
        release: open the fingers at the end.
        release_s: release duration [s].
        success_height: minimum object rise above its start at the end [m].
        max_slip: maximum object displacement relative to the palm since the end of lift [m].
        chunk_steps: steps per rollout chunk, between checks of slip, damage and stability, and
            the sampling of contact forces (flex strain is read at every step from the
            chunk's states). 20 steps (40 ms at the 2 ms step):
            the fastest commanded motion, the 2 Hz shake, is sampled 12 times a period. Each
            chunk costs about 40 µs in the rollout call and 30 µs of Python checks; at 10 steps
            that was 15 % over plain ``mj_step`` on a short cylinder trial, at 20 about half
            (scripts/bench_trial.py). Force peaks are samples: read per step they were up to
            7.3 N higher on 100 rigid trials (README, "Grasp benchmark").
        timestep: simulation step of grasp trials [s]; replaces ``params.sim.timestep``. 2 ms,
            with the ``discrete`` integrator: with the closed cuts the squeezed teeth
            (:mod:`gripper.model.closure`), block and cylinder trials 0-3 and balloon, paper box and
            bag trials 0-1 give the same outcome at 1 and 2 ms (cylinder trial 0 fails at both,
            in another phase). The peak total force grows
            with the step, to first order: block trial 0 61.0 / 62.3 / 65.8 / 68.9 N and
            cylinder trial 1 64.8 / 67.1 / 70.9 / 76.6 N at 0.5 / 1 / 2 / 3 ms (read every
            12 ms; version 0.5.1), so 2 ms is 8-9 % above 0.5 ms at a quarter of the cost;
            3 ms 13-18 %.
            (With the old rigid stop, whose overrun grows as the step squared, the cylinder
            was held at 2 ms and dropped in the hold at 1 ms.)
    """

    settle_s: float = 0.3
    approach_speed: float = 0.10
    tip_clearance: float = 0.008
    palm_clearance: float = 0.010
    close_speed: float = 0.04
    close_command_scale: float = 1.0
    close_hold_s: float = 0.4
    lift_height: float = 0.10
    lift_speed: float = 0.10
    lift_settle_s: float = 0.2
    hold_s: float = 2.0
    shake_amplitude: float = 0.010
    shake_frequency: float = 2.0
    shake_s: float = 2.0
    release: bool = False
    release_s: float = 0.5
    success_height: float = 0.08
    max_slip: float = 0.020
    chunk_steps: int = 20
    timestep: float = 0.002

    def replace(self, **changes: Any) -> GraspProtocol:
        return dataclasses.replace(self, **changes).validate()

    def validate(self) -> GraspProtocol:
        for name, lo, hi in (("settle_s", 0, 10), ("approach_speed", 1e-3, 1), ("tip_clearance", 0, 0.1),
                             ("palm_clearance", 0, 0.1), ("close_speed", 1e-3, 1),
                             ("close_command_scale", 0.05, 10), ("close_hold_s", 0, 10),
                             ("lift_height", 0, 0.2), ("lift_speed", 1e-3, 1), ("lift_settle_s", 0, 10),
                             ("hold_s", 0, 60), ("shake_amplitude", 0, 0.05), ("shake_frequency", 0, 20),
                             ("shake_s", 0, 60), ("release_s", 0, 10), ("success_height", 0, 0.2),
                             ("max_slip", 0, 1), ("timestep", 1e-4, 0.004)):
            _check(f"protocol.{name}", getattr(self, name), lo, hi)
        if not isinstance(self.chunk_steps, int) or not 1 <= self.chunk_steps <= 1000:
            raise ValueError(f"protocol.chunk_steps: must be an integer in [1, 1000], got {self.chunk_steps!r}")
        return self

    def to_dict(self) -> dict[str, Any]:
        return dataclasses.asdict(self)


@dataclass(frozen=True)
class TrialNoise:
    """Perturbations sampled per trial.

    Attributes:
        xy: object offset uniform in [-xy, xy] in x and y [m].
        yaw: sample yaw uniform in [-π, π) for objects that are not yaw-symmetric.
        mass_frac: mass multiplier uniform in [1-mass_frac, 1+mass_frac] (0: off; 0.2 typical).
        friction_frac: friction multiplier, likewise.
    """

    xy: float = 0.010
    yaw: bool = True
    mass_frac: float = 0.0
    friction_frac: float = 0.0

    def validate(self) -> TrialNoise:
        _check("noise.xy", self.xy, 0.0, 0.02)
        _check("noise.mass_frac", self.mass_frac, 0.0, 0.5)
        _check("noise.friction_frac", self.friction_frac, 0.0, 0.5)
        return self

    def to_dict(self) -> dict[str, Any]:
        return dataclasses.asdict(self)
