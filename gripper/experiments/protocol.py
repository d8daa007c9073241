"""The experiments' protocols: the scripted grasp, its per-trial perturbations, the bending test,
the pull-out and the crush test (frozen dataclasses and constants, SI units).

Grasp phases, in order: settle, approach from above, close (the grasp controller closes each
finger at the contraction speed until its cable tension reaches the grip set-point, or, with
``policy = "per_object"``, the servos ramp to the object's closing command), lift, hold,
horizontal shake, optional release.
This module needs only the standard library, so the command line shows these defaults in its
help without importing MuJoCo.

Example:
    >>> from gripper.experiments.protocol import GraspProtocol
    >>> GraspProtocol().replace(hold_s=1.0).lift_height
    0.1
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any

from gripper.core.fields import Validated, param
from gripper.core.params import PAPER_001_PRESSURE_MAX
from gripper.core.timesteps import PAPER_BENDING_TIMESTEP, TRIAL_TIMESTEP, check_step_budget

# Grasp policies: the object-agnostic controller, or each object's own closing command.
POLICIES = ("controller", "per_object")
# How the approach finds the object: the palm camera (gripper.sim.depth, gripper.experiments.approach),
# or the object's catalogue size centred under the palm (the rule of gripper 0.11 and before).
APPROACHES = ("sensed", "catalogue")
# Which grasp: chosen from the depth estimate, or forced (gripper.experiments.approach).
GRASP_CHOICES = ("auto", "envelope", "fingertip")
# How the wrist turns the palm (gripper.experiments.approach): to the sensed footprint, or not at all
# (the palm at zero yaw, as in 0.20.0 and before).
WRIST_RULES = ("footprint", "fixed")
# The controller's default grip set-point [N of cable tension per finger] (docs/controller.md:
# 5 N chosen on seed 0 and verified on seed 1 in 0.10.0; 7.5 N since 0.21.0, the gripping-range
# study's set-point: at 5 N neither the 0.20.0 design nor the chosen one held 0.5 kg at a 60 mm box,
# docs/envelope.md).
GRIP_TENSION = 7.5
# The documented set-point range [N]: from where the light rigid parts are still held every time
# to where the balloon is still whole (tests/test_controller.py checks both ends).
GRIP_TENSION_RANGE = (3.0, 10.0)


@dataclass(frozen=True)
class GraspProtocol(Validated):
    """Scripted grasp, every phase configurable (fields: unit, range and reason in their
    metadata, listed in ``docs/benchmark.md``).

    ``tip_clearance`` and ``palm_clearance`` set the grasp height: the fingertips stay
    ``tip_clearance`` above the floor and the palm ``palm_clearance`` above the object's top,
    whichever is higher. Success needs the object ``success_height`` above its start at the end
    and at most ``max_slip`` of motion relative to the palm since the end of the lift. The trial
    is stepped in chunks of ``chunk_steps`` steps; between chunks it checks slip, damage and
    stability and samples the contact forces (flex strain is read at every step from the chunk's
    states). ``timestep`` replaces ``params.sim.timestep`` for the trial.
    """

    SECTION = "protocol"

    settle_s: float = param(0.3, "s", ge=0, le=10, source="the object settles on the floor first")
    approach_speed: float = param(0.10, "m/s", ge=1e-3, le=1, source="assumed")
    tip_clearance: float = param(0.008, "m", ge=0, le=0.1, source="assumed: fingertips above the floor")
    palm_clearance: float = param(0.010, "m", ge=0, le=0.1, source="assumed: palm above the object's top")
    approach: str = param("sensed", "-", choices=APPROACHES,
                          source="sensed: from the palm camera's depth estimate; catalogue: from the object's "
                          "size, centred under the palm (0.11.0's rule, for comparison; the envelope grasp "
                          "unless grasp = fingertip)")
    centre: bool = param(True, "-", source="sensed: centre the palm over the estimated footprint's centroid")
    grasp: str = param("auto", "-", choices=GRASP_CHOICES,
                       source="auto: the fingertip grasp where the tips reach the support beside the "
                       "object, else the envelope (gripper.experiments.approach)")
    wrist: str = param("footprint", "-", choices=WRIST_RULES,
                       source="footprint: the wrist turns a finger pair across the sensed footprint's width, "
                       "or straddles a part longer than the opening (gripper.experiments.approach); fixed: "
                       "no turn (0.20.0's grasp)")
    fingertip_margin: float = param(
        0.010, "m", ge=0, le=0.1,
        source="the fingertip grasp only for a footprint this far inside the open tips: a part nearly as wide as the "
        "opening meets the tips at its bottom edge, the fingers barely curled (0.21.0's gripping-range study: a 90 mm "
        "box inside a 99.7 mm opening held 0 of 3 by the fingertips, 3 of 3 by the envelope; docs/controller.md)")
    wrist_speed: float = param(1.5, "rad/s", ge=0.01, le=20,
                               source="assumed: a small rotary stage, a quarter turn in about a second")
    fingertip_clearance: float = param(0.0, "m", ge=0, le=0.05,
                                       source="fingertip grasp: the fingers' lowest point above the sensed support; "
                                       "0, the tips run on it (2 mm lost 5 of 16 zipper bags, docs/controller.md)")
    pneumatic_fingertip_clearance: float = param(
        0.003, "m", ge=0, le=0.05,
        source="the pneumatic gripper's fingertip grasp (fingertip_clearance is the cable gripper's): at 0 its "
        "stiff 19 mm tips, pressed to the table by the chamber, pinched the zipper bag's film against it (seed 21: "
        "8 of 10 films past yield, 0 at 3 mm; docs/contact.md)")
    close_speed: float = param(0.04, "m/s", ge=1e-3, le=1, source="cable contraction speed (spool surface)")
    policy: str = param("controller", "-", choices=POLICIES,
                        source="controller: the object-agnostic grip (gripper.drives.cable.controller); "
                        "per_object: each object's own closing command, for comparison")
    grip_tension: float = param(GRIP_TENSION, "N", gt=0, le=54,
                                source="controller's grip set-point: cable tension per finger "
                                "(docs/controller.md; at most the servo's stall tension, 54 N)")
    grip_pressure: float = param(PAPER_001_PRESSURE_MAX, "Pa", gt=0, le=1e6,
                                 source="pneumatic gripper's grip set-point: chamber pressure, the calibration's "
                                 "highest (paper 001 §2.3: 0-250 kPa; gripper.drives.pneumatic.controller)")
    pressure_rate: float = param(250e3, "Pa/s", ge=1e3, le=1e8,
                                 source="pneumatic gripper: the set-point's ramp, full pressure in 1 s (assumed: "
                                 "about the cable fingers' closing time)")
    close_command_scale: float = param(1.0, "-", ge=0.05, le=10,
                                       source="per_object: multiplier on the object's closing command "
                                       "(>1 squeezes harder)")
    close_hold_s: float = param(0.4, "s", ge=0, le=10, source="at the closing command before lifting")
    lift_height: float = param(0.10, "m", ge=0, le=0.2, source="the benchmark's definition of a grasp")
    lift_speed: float = param(0.10, "m/s", ge=1e-3, le=1, source="assumed")
    lift_settle_s: float = param(0.2, "s", ge=0, le=10, source="pause before the end of the lift is taken")
    hold_s: float = param(2.0, "s", ge=0, le=60, source="the benchmark's static hold")
    shake_amplitude: float = param(0.010, "m", ge=0, le=0.05, source="horizontal shake along x")
    shake_frequency: float = param(2.0, "Hz", ge=0, le=20, source="the benchmark's shake")
    shake_s: float = param(2.0, "s", ge=0, le=60, source="the benchmark's shake")
    release: bool = param(False, "-", source="open the fingers at the end")
    release_s: float = param(0.5, "s", ge=0, le=10, source="assumed")
    success_height: float = param(0.08, "m", ge=0, le=0.2, source="the benchmark's definition: lifted 8 cm")
    max_slip: float = param(0.020, "m", ge=0, le=1, source="the benchmark's definition: no slip")
    chunk_steps: int = param(20, "-", ge=1, le=1000, integer=True,
                             source="40 ms at the 2 ms step: the 2 Hz shake sampled 12 times a period "
                             "(docs/performance.md)")
    timestep: float = param(TRIAL_TIMESTEP, "s", ge=1e-4, le=0.004, source="gripper.core.timesteps")

    def to_dict(self) -> dict[str, Any]:
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}


@dataclass(frozen=True)
class TrialNoise(Validated):
    """Perturbations sampled per trial: the object's x/y offset, uniform in [-xy, xy]; its yaw,
    uniform in [-π, π), for objects that are not yaw-symmetric; multipliers of its mass and
    friction, uniform in [1 - frac, 1 + frac] (0: off; 0.2 is typical)."""

    SECTION = "noise"

    xy: float = param(0.010, "m", ge=0, le=0.02, source="assumed: a placement error of ±10 mm")
    yaw: bool = param(True, "-", source="sample yaw")
    mass_frac: float = param(0.0, "-", ge=0, le=0.5, source="off by default")
    friction_frac: float = param(0.0, "-", ge=0, le=0.5, source="off by default")

    def to_dict(self) -> dict[str, Any]:
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}


@dataclass(frozen=True)
class BendingConfig(Validated):
    """Settings of paper 000's bending test (:func:`gripper.experiments.bending.run_bending_test`).

    ``mode`` is ``dynamic`` (one ramp of the cable shortening rate to ``r_max`` over
    ``duration``) or ``quasi_static`` (each of ``n_points`` set-points held until at rest). At
    rest means every joint slower than ``settle_tol``, or every hinge moving less than
    ``settle_band_deg`` over a 25 ms chunk: with the calibrated (soft) springs, hinges meeting a
    rigid stop under the position servo keep a limit cycle of a few thousandths of a degree
    (0.3°/s peak speed at r = 0.307 on 30° cuts, never below 1e-3 rad/s in 10 s).
    """

    SECTION = "bend"

    r_max: float = param(0.45, "-", gt=0, lt=1,
                         source="the five default cuts close at r ≈ 0.44 (bending ≈ 206°), inside the "
                         "hobby servo's travel (r <= 0.65)")
    duration: float = param(2.0, "s", gt=0, le=600, source="paper 000 §IV: 2 s; at most ten minutes")
    timestep: float = param(PAPER_BENDING_TIMESTEP, "s", ge=1e-5, le=0.01, source="paper 000 §IV: 5e-4 s")
    mode: str = param("dynamic", "-", choices=("dynamic", "quasi_static"), source="one ramp, or held set-points")
    n_points: int = param(101, "-", ge=2, le=100_000, integer=True, source="recorded samples or set-points")
    settle_tol: float = param(1.0e-3, "rad/s", gt=0, source="quasi-static: joint speed counted as at rest")
    settle_time_max: float = param(3.0, "s", gt=0, source="quasi-static: longest wait at one set-point")
    settle_band_deg: float = param(0.01, "deg", gt=0,
                                   source="quasi-static: hinge angle change over a chunk counted as at rest")

    def check(self) -> None:
        check_step_budget(self.duration, self.timestep, "bend.duration")


def is_held(height: float, slip: float, protocol: GraspProtocol) -> bool:
    """The held-grasp rule, the one definition the benchmark, the envelope and the environment
    use: the object ``height`` [m] above its start, at least ``protocol.success_height``, and
    ``slip`` [m] relative to the palm below ``protocol.max_slip``."""
    return height >= protocol.success_height and slip < protocol.max_slip


# Pull-out test (gripper.experiments.pullout): load ramp rate [N/s], the largest load tried [N]
# and the slip that ends it [m]. 20 N/s keeps the test quasi-static (the grasp's slowest mode,
# the object swinging in the fingers, is ≈ 5 Hz) and reaches the 100 N cap in 5 s.
PULL_RATE = 20.0
PULL_MAX = 100.0
PULL_SLIP = 0.005

# Crush test (gripper.experiments.crush): plate speed [m/s], hold at depth [s] and the command
# line's press depth below the object's top [m]. Assumed: a slow press, as a platen test is run;
# 20 mm of travel takes 1 s.
CRUSH_SPEED = 0.02
CRUSH_HOLD_S = 0.2
CRUSH_DEPTH = 0.020
