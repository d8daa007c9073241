"""Paper 001's actuator as the pneumatic finger's calibration reference: the finite-element model
(:mod:`gripper.references.actuator_fe`) inflated from 0 to 250 kPa, and laid sideways under its
own weight, read as the hinge-chain finger is read: the neutral layer's line and its tip point.

The frame of a record (the *neutral frame*, the pneumatic finger's own): x along the actuator from
the clamped end, z across it towards the neutral layer's side (the side inflation bends it to,
the finger's grasping face), origin on the neutral layer's mid-plane at the clamp. In the mesh's
frame (:mod:`gripper.references.actuator_mesh`) that is x_f = z, z_f = -y.

Two load cases, both on the studies' mesh (``STUDY_REFINEMENT``; its convergence is in
``docs/pneumatic.md``):

- **inflation**: hanging from the clamp (gravity along +x), pressure 0-250 kPa in 25 kPa steps:
  what the finger does in the gripper;
- **sag**: no pressure, gravity along +z (the actuator lying on its back, clamped, bending
  towards its neutral layer under its own weight): the bending stiffness on its own, which the
  inflation cannot separate from the pressure's moment (both scale the bend alike).

Example (about four minutes; the tip (x, z) at 250 kPa):
    >>> from gripper.references.actuator_bending import run_actuator_reference
    >>> rec = run_actuator_reference()        # doctest: +SKIP
    >>> rec.tip[-1]                           # doctest: +SKIP
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Any

import numpy as np

from gripper.references.actuator_fe import GRAVITY, inflate
from gripper.references.actuator_mesh import MeshSize
from gripper.references.pneumatic_params import KPA, PneumaticActuator

STUDY_REFINEMENT = 1  # the studies' mesh (MeshSize.at_refinement; gripper.experiments.actuator_responses uses it too)
REFERENCE_PRESSURES = np.arange(0.0, 250.0 + 1e-9, 25.0) * KPA  # Pa, the paper's 25 kPa steps


@dataclass(frozen=True)
class ActuatorRecord:
    """The reference's readings in the neutral frame (module docstring), SI units.

    Attributes:
        pressures: inflation pressures [Pa], shape (n,).
        tip: the neutral layer's tip point (x, z) at each pressure [m], shape (n, 2).
        angles_deg: the tip's bending angle at each pressure [deg] (paper 001's, as the studies).
        line: the neutral layer's mid-plane line (x, z) at each pressure [m], shape (n, k, 2).
        sag_tip: the tip point lying sideways under gravity ``gravity``, no pressure [m].
        gravity: gravitational acceleration of both load cases [m/s²].
        length: the actuator's length [m].
        mass: the actuator's mass [kg] (every layer, from the mesh's volumes and densities).
        refinement: the mesh (``MeshSize.at_refinement``).
        wall_time_s: wall-clock time of both solves [s].
    """

    pressures: np.ndarray
    tip: np.ndarray
    angles_deg: np.ndarray
    line: np.ndarray
    sag_tip: np.ndarray
    gravity: float
    length: float
    mass: float
    refinement: int
    wall_time_s: float = 0.0

    def to_json_dict(self) -> dict:
        return {k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in self.__dict__.items()}

    @classmethod
    def from_json_dict(cls, data: dict) -> ActuatorRecord:
        arrays = ("pressures", "tip", "angles_deg", "line", "sag_tip")
        values: dict[str, Any] = {k: (np.asarray(v, dtype=float) if k in arrays else v) for k, v in data.items()}
        return cls(**values)


def _neutral_line(points: np.ndarray, thickness: float) -> tuple[np.ndarray, np.ndarray]:
    """Indices of the mid-plane (x = 0) nodes on the neutral layer's two faces (y = -t/2, +t/2) at
    every station along the actuator, sorted by z: shape (stations, 2)."""
    x, y, z = points.T
    on = np.isclose(x, 0.0)
    lo = np.flatnonzero(on & np.isclose(y, -0.5 * thickness))
    hi = np.flatnonzero(on & np.isclose(y, 0.5 * thickness))
    lo, hi = lo[np.argsort(z[lo])], hi[np.argsort(z[hi])]
    if len(lo) != len(hi) or not np.allclose(z[lo], z[hi]):
        raise RuntimeError("actuator reference: the neutral layer's faces have different stations")
    return np.column_stack([lo, hi]), z[lo]


def _to_neutral_frame(deformed: np.ndarray, pairs: np.ndarray) -> np.ndarray:
    """The neutral line (x_f, z_f) = (z, -y) of the mid-points of each face pair [m]."""
    mid = 0.5 * (deformed[pairs[:, 0]] + deformed[pairs[:, 1]])
    return np.column_stack([mid[:, 2], -mid[:, 1]])


def actuator_mass(actuator: PneumaticActuator, refinement: int = STUDY_REFINEMENT) -> float:
    """The actuator's mass [kg]: the mesh's cell volumes times their layers' densities (the fibre
    layer's share of fibre, the neutral layer's fabric), as the finite-element model weighs it."""
    import felupe as fem

    from gripper.references.actuator_fe import fibre_volume_fraction
    from gripper.references.actuator_mesh import FIBRE, NEUTRAL, actuator_mesh

    m = actuator_mesh(actuator, MeshSize.at_refinement(refinement))
    vol = fem.RegionHexahedron(fem.Mesh(m.points, m.cells, "hexahedron")).dV.sum(axis=0)
    rho = np.full(len(vol), actuator.silicone_density)
    phi = fibre_volume_fraction(actuator)
    rho[m.material == FIBRE] += 2 * phi * (actuator.fibre_density - actuator.silicone_density)
    rho[m.material == NEUTRAL] = actuator.fabric_density
    return float(2.0 * (vol * rho).sum())  # the mesh is half the actuator


def run_actuator_reference(actuator: PneumaticActuator | None = None, refinement: int = STUDY_REFINEMENT,
                           pressures: np.ndarray | None = None) -> ActuatorRecord:
    """Both load cases of the module docstring on the mesh of ``refinement``.

    Raises:
        RuntimeError: a load case did not converge (a limit point, or Newton's method failed):
            nothing unconverged becomes a reference.
    """
    from gripper.references.actuator_mesh import actuator_mesh

    a = (actuator or PneumaticActuator()).validate()
    ps = REFERENCE_PRESSURES if pressures is None else np.asarray(pressures, dtype=float)
    size = MeshSize.at_refinement(refinement)
    t0 = time.perf_counter()
    hang = inflate(a, ps, size, keep_shapes=True)
    if hang.failed_at is not None:
        raise RuntimeError(f"actuator reference: the inflation stopped at {hang.failed_at / KPA:.4g} kPa")
    sag = inflate(a, [0.0], size, keep_shapes=True, gravity=(0.0, -GRAVITY, 0.0))
    if sag.failed_at is not None:
        raise RuntimeError("actuator reference: the sideways sag did not converge")
    points = actuator_mesh(a, size).quadratic()[0]
    pairs, _ = _neutral_line(points, a.neutral_thickness)
    lines = np.array([_to_neutral_frame(s, pairs) for s in hang.shapes])
    sag_line = _to_neutral_frame(sag.shapes[0], pairs)
    return ActuatorRecord(pressures=hang.pressures, tip=lines[:, -1], angles_deg=hang.angles_deg, line=lines,
                          sag_tip=sag_line[-1], gravity=GRAVITY, length=a.length, mass=actuator_mass(a, refinement),
                          refinement=refinement, wall_time_s=time.perf_counter() - t0)


__all__ = ["REFERENCE_PRESSURES", "STUDY_REFINEMENT", "ActuatorRecord", "actuator_mass", "run_actuator_reference"]
