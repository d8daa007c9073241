"""A semi-analytical model of the fibre-reinforced bending actuator, in the manner of Polygerinos
et al. (IEEE T-RO 31(3), 2015, "Modeling of soft fiber-reinforced bending actuators", §III):
a moment balance on one cross-section, independent of any finite-element solution, to check the
finite-element model of :mod:`gripper.references.pneumatic_params`' actuator against.

Assumptions, each the paper's or Polygerinos's:

- the actuator bends into a circular arc of curvature κ, bending angle θ = κ·L;
- the fabric neutral layer does not stretch (6500 MPa against the silicone's 0.23 MPa shear
  modulus): its mid-plane is the neutral axis, and a fibre at height y from it stretches
  axially by λ = 1 + κ·y;
- the fibre winding (4° from the hoop direction) holds the hoop stretch at 1, the silicone is
  incompressible, so each point deforms in plane strain with stretches (λ, 1, 1/λ) and carries
  the Yeoh nominal axial stress s = 2 W1(I1) (λ − λ⁻³), I1 = λ² + 1 + λ⁻² (radial stress
  neglected, a thin-wall approximation);
- the pressure's moment on a cross-section is P times the first moment of the duct's area
  about the neutral axis (the fluid column's cut face; exact for any shape of the rest), and
  the cross-section keeps its reference shape (the fibres stop it from ballooning).

Then P · A_duct · ȳ_duct = ∫ s(λ(y)) y dA over the silicone (main body and cladding, the
reference cross-section, integrated on a fine grid) fixes κ at each pressure.

The cross-section is the finite-element model's (:class:`gripper.references.actuator_mesh.Geometry`,
y up from the neutral layer's mid-plane): the neutral layer's two halves around y = 0; above it
the main body, a rectangle of the body's width and its wall thickness, then a half-round of outer
radius a + t (a the duct radius) with the half-round duct inside (its edges rounded), its flat
side on the rectangle; the fibre layer (d thick) and the cladding around body and neutral layer.
The fibre layer counts as silicone; the fibre itself is left out of the axial balance (it runs
nearly in the hoop direction).

Example:
    >>> from gripper.references.bending_moment_model import bending_angle_deg
    >>> from gripper.references.pneumatic_params import PneumaticActuator
    >>> round(bending_angle_deg(PneumaticActuator(), 50e3), 1) > 0
    True
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from scipy.optimize import brentq

from gripper.references.actuator_mesh import Geometry
from gripper.references.pneumatic_params import PneumaticActuator

GRID = 0.02e-3  # m: the cross-section's quadrature cell (0.02 mm; halving it moves θ < 0.1 %)


@dataclass(frozen=True)
class CrossSection:
    """The actuator's reference cross-section on a grid: the silicone's cells (their heights y
    above the neutral axis and areas) and the duct's area and centroid height."""

    actuator: PneumaticActuator
    cell: float = GRID

    @cached_property
    def _grid(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        g = Geometry(self.actuator)
        half_width = g.r_out
        xs = np.arange(-half_width + 0.5 * self.cell, half_width, self.cell)
        ys = np.arange(g.y_bottom + 0.5 * self.cell, g.y_centre + g.r_out, self.cell)
        x, y = np.meshgrid(xs, ys)
        rho = np.hypot(x, y - g.y_centre)
        upper = y >= g.y_centre
        duct = upper & (rho < g.duct_radius_at(np.arctan2(y - g.y_centre, np.abs(x))))
        neutral = (np.abs(y) < 0.5 * self.actuator.neutral_thickness) & (np.abs(x) < g.r_body)
        outline = np.where(upper, rho < g.r_out, np.abs(x) < g.r_out)
        silicone = outline & ~duct & ~neutral  # body, fibre layer (its matrix) and cladding
        return y, silicone, duct

    @property
    def silicone_heights(self) -> np.ndarray:
        y, silicone, _ = self._grid
        return y[silicone]

    @property
    def cell_area(self) -> float:
        return self.cell ** 2

    @property
    def duct_area(self) -> float:
        _, _, duct = self._grid
        return float(duct.sum()) * self.cell_area

    @property
    def duct_first_moment(self) -> float:
        """∫ y dA over the duct [m³]: the pressure's lever."""
        y, _, duct = self._grid
        return float(y[duct].sum()) * self.cell_area

    @property
    def second_moment(self) -> float:
        """∫ y² dA over the silicone [m⁴] (the small-strain bending stiffness / 4μ)."""
        y = self.silicone_heights
        return float((y ** 2).sum() * self.cell_area)


def nominal_axial_stress(stretch: np.ndarray, actuator: PneumaticActuator) -> np.ndarray:
    """Yeoh nominal stress [Pa] along the axis under plane strain (hoop stretch 1)."""
    i1 = stretch ** 2 + 1.0 + stretch ** -2
    w1 = actuator.yeoh_c10 + 2 * actuator.yeoh_c20 * (i1 - 3) + 3 * actuator.yeoh_c30 * (i1 - 3) ** 2
    return 2 * w1 * (stretch - stretch ** -3)


def elastic_moment(curvature: float, section: CrossSection) -> float:
    """The silicone's resisting moment [N·m] at ``curvature`` [1/m]."""
    y = section.silicone_heights
    stretch = 1.0 + curvature * y
    return float((nominal_axial_stress(stretch, section.actuator) * y).sum() * section.cell_area)


def curvature_at(pressure: float, section: CrossSection) -> float:
    """The curvature [1/m] at which the silicone's moment balances the pressure's."""
    if pressure <= 0:
        return 0.0
    moment = pressure * section.duct_first_moment
    y_max = float(np.abs(section.silicone_heights).max())
    hi = 0.9 / y_max  # λ stays in (0.1, 1.9): far past any bend this actuator reaches
    return brentq(lambda k: elastic_moment(k, section) - moment, 0.0, hi, xtol=1e-12, rtol=1e-12)


def bending_angle_deg(actuator: PneumaticActuator, pressure: float, section: CrossSection | None = None) -> float:
    """The bending angle [deg] of the whole length at ``pressure`` [Pa]: κ L."""
    section = section or CrossSection(actuator.validate())
    return math.degrees(curvature_at(pressure, section) * actuator.length)


def bending_curve_deg(actuator: PneumaticActuator, pressures) -> np.ndarray:
    """:func:`bending_angle_deg` at each pressure, sharing one cross-section."""
    section = CrossSection(actuator.validate())
    return np.array([bending_angle_deg(actuator, float(p), section) for p in pressures])
