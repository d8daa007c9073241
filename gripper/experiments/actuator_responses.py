"""The response a design study measures on one of paper 001's actuators: its bending angle
against pressure (the paper's Figs. 12-16), from the finite-element model
(:mod:`gripper.references.actuator_fe`).

Example:
    >>> from gripper.experiments.actuator_responses import inflation_response
    >>> from gripper.references.pneumatic_params import PneumaticActuator
    >>> metrics, curves = inflation_response(PneumaticActuator(), {"pressure_max": 50e3})  # doctest: +SKIP
"""

from __future__ import annotations

import numpy as np

from gripper.references.actuator_bending import STUDY_REFINEMENT  # the mesh; its convergence: docs/pneumatic.md
from gripper.references.actuator_fe import inflate
from gripper.references.actuator_mesh import MeshSize
from gripper.references.pneumatic_params import PneumaticActuator

INFLATION_STEPS = 10  # pressures recorded between 0 and pressure_max (the paper's 25 kPa apart)


def inflation_response(actuator: PneumaticActuator, opts: dict) -> tuple[dict, dict]:
    """Metrics (the bending angle at ``pressure_max`` and at half of it [deg]) and the curve
    (pressure [kPa], bending angle [deg]) of one sweep from 0 to ``opts["pressure_max"]`` [Pa]
    (default: the actuator's, 250 kPa) in ``opts["steps"]`` equal steps, on the mesh of
    ``opts["refinement"]`` (default ``STUDY_REFINEMENT``).

    Raises:
        RuntimeError: the sweep stopped before ``pressure_max`` (a limit point, or Newton's
            method failed): a study records the point as failed, never a partial curve.
    """
    p_max = float(opts.get("pressure_max", actuator.pressure_max))
    steps = int(opts.get("steps", INFLATION_STEPS))
    pressures = np.linspace(0.0, p_max, steps + 1)
    result = inflate(actuator, pressures, MeshSize.at_refinement(int(opts.get("refinement", STUDY_REFINEMENT))))
    if result.failed_at is not None:
        raise RuntimeError(f"the sweep stopped at {result.failed_at / 1e3:.4g} kPa of {p_max / 1e3:g} kPa "
                           "(Newton's method did not converge there: a limit point or an unstable model)")
    half = pressures[steps // 2]
    metrics = {"bending_angle_at_max_deg": result.angle_at(p_max), "bending_angle_at_half_deg": result.angle_at(half)}
    curves = {"pressure_kPa": (result.pressures / 1e3).tolist(), "bending_angle_deg": result.angles_deg.tolist()}
    return metrics, curves
