"""Yeoh thick-walled tube inflation: Rivlin's exact solution and a FElupe plane-strain check

The verification case of the pneumatic actuator model (paper 001's RTV 230 silicone, Yeoh
hyperelastic, 0-250 kPa): an incompressible tube of undeformed inner and outer radii ``A``,
``B`` in plane strain, inflated by an internal pressure ``p``, traction-free outside. The exact
pressure-radius relation is a 1D integral (:func:`tube_pressure`); :func:`fe_tube_inflation`
solves the same problem with large-deformation finite elements (FElupe), so the two can be
compared over the pressure range. SI units throughout: lengths in m, pressures and moduli in Pa.

Example (a tube of 5 mm inner, 8 mm outer radius at 50 and 100 kPa):
    >>> from gripper.references.yeoh_tube import YeohMaterial, fe_tube_inflation, inner_radius_for_pressure
    >>> round(inner_radius_for_pressure(100e3, 5e-3, 8e-3, YeohMaterial()) * 1e3, 3)   # mm
    8.364
    >>> (fe_tube_inflation([50e3, 100e3], 5e-3, 8e-3, YeohMaterial()) * 1e3).round(3)  # mm
    array([6.211, 8.361])
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.integrate import quad
from scipy.optimize import brentq, minimize_scalar

from gripper.core.params import RTV230_YEOH

QUAD_RTOL = 1e-12  # -, relative tolerance of the pressure integral (far below the 1 % checked)
MAX_HOOP_STRETCH = 10.0  # -, the search bound of the limit point's inner hoop stretch a / A
# -, bulk modulus over shear modulus of the FE solid: the closed form is incompressible; the
# radius change's compressibility error falls as 1/bulk_ratio, measured 0.17 % at 5000
# (250 kPa, A = 5 mm, B = 8 mm), so 5e5 leaves 0.002 %; the mixed form does not lock at this value
BULK_RATIO = 5e5
# -, Newton tolerance on the residual forces relative to the reaction forces: at BULK_RATIO their
# round-off floor is about 2e-8 (measured on 32 x 64 cells), above felupe's default 1.5e-8; Newton converges
# quadratically, and the radii change by 1e-14 m when tightened to 1.5e-8 (measured)
NEWTON_TOL = 1e-6


@dataclass(frozen=True)
class YeohMaterial:
    """Yeoh strain energy W = C10 (I1-3) + C20 (I1-3)^2 + C30 (I1-3)^3 [Pa]."""

    # RTV 230 silicone (gripper.core.params.RTV230_YEOH: paper 001 §2.3 Step 2)
    C10: float = RTV230_YEOH[0]
    C20: float = RTV230_YEOH[1]
    C30: float = RTV230_YEOH[2]

    def strain_energy_derivative(self, I1: float) -> float:
        """dW/dI1 [Pa] at the first invariant ``I1`` of the right Cauchy-Green tensor."""
        x = I1 - 3.0
        return self.C10 + 2.0 * self.C20 * x + 3.0 * self.C30 * x**2

    @property
    def mu(self) -> float:
        """Small-strain shear modulus [Pa]: 2 C10."""
        return 2.0 * self.C10


def tube_pressure(a: float, A: float, B: float, material: YeohMaterial) -> float:
    """The internal pressure [Pa] that expands an incompressible Yeoh tube (undeformed inner,
    outer radii ``A``, ``B``) to the deformed inner radius ``a``, in plane strain (no axial
    stretch), traction-free outside.

    Rivlin's exact solution for an incompressible isotropic tube (Rivlin 1949; Ogden,
    Non-linear Elastic Deformations, 1984, ch. 5): incompressibility maps the radius R to
    r = sqrt(R^2 + a^2 - A^2); the principal stretches are r/R (hoop), R/r (radial) and 1
    (axial), so I1 = lam^2 + lam^-2 + 1 with lam = r/R; the radial equilibrium
    d(sigma_rr)/dr = (sigma_tt - sigma_rr)/r with sigma_tt - sigma_rr = 2 W1 (lam^2 - lam^-2),
    sigma_rr(a) = -p and sigma_rr(b) = 0, gives p = integral_a^b (sigma_tt - sigma_rr)/r dr.
    """
    c = a**2 - A**2  # m^2, the area (per pi) that incompressibility shifts outwards
    b = np.sqrt(B**2 + c)

    def integrand(r: float) -> float:
        lam2 = r**2 / (r**2 - c)  # hoop stretch squared (r/R)^2
        I1 = lam2 + 1.0 / lam2 + 1.0
        return 2.0 * material.strain_energy_derivative(I1) * (lam2 - 1.0 / lam2) / r

    p, _ = quad(integrand, a, b, epsabs=0.0, epsrel=QUAD_RTOL, limit=200)
    return float(p)


def limit_point(A: float, B: float, material: YeohMaterial) -> tuple[float, float]:
    """The inner radius [m] and pressure [Pa] of the tube's limit point, the maximum of
    :func:`tube_pressure` over A < a < ``MAX_HOOP_STRETCH`` A (that bound if p keeps rising).

    With the paper's constants dW/dI1 turns negative at I1 - 3 = 38 and p(a) peaks before: at
    a / A = 5.26, 364 kPa for A = 5 mm, B = 8 mm (4.5 as B / A -> 1), so p(a) rises
    monotonically over 0-250 kPa for that tube (checked in the tests)."""
    res = minimize_scalar(lambda a: -tube_pressure(a, A, B, material), bounds=(A, MAX_HOOP_STRETCH * A),
                          method="bounded", options={"xatol": 1e-9 * A})
    return float(res.x), float(-res.fun)


def inner_radius_for_pressure(p: float, A: float, B: float, material: YeohMaterial) -> float:
    """The deformed inner radius [m] of the tube at internal pressure ``p`` [Pa]: the root of
    :func:`tube_pressure` on the rising branch A <= a <= the limit point (brentq), where it is
    unique. Raises ValueError for a pressure above the limit point's: the tube bursts."""
    if p == 0.0:
        return A
    a_max, p_max = limit_point(A, B, material)
    if not 0.0 < p < p_max:
        raise ValueError(f"pressure {p:g} Pa outside (0, {p_max:g}) Pa, the limit point of this tube")
    return float(brentq(lambda a: tube_pressure(a, A, B, material) - p, A, a_max, xtol=1e-15, rtol=1e-13))


def quarter_ring(A: float, B: float, n_radial: int, n_hoop: int) -> tuple[Any, np.ndarray, np.ndarray]:
    """A structured quad mesh of the quarter ring A <= r <= B, 0 <= theta <= pi/2 (x, y >= 0),
    with ``n_radial`` by ``n_hoop`` cells, and each point's polar coordinates (r, theta)."""
    import felupe as fem

    rect = fem.mesh.Rectangle(a=(A, 0.0), b=(B, np.pi / 2), n=(n_radial + 1, n_hoop + 1))
    r, theta = rect.points.T  # the polar map (det = r > 0) keeps the cells counter-clockwise
    points = np.column_stack([r * np.cos(theta), r * np.sin(theta)])
    return fem.Mesh(points, rect.cells, cell_type="quad"), r, theta


def fe_tube_inflation(pressures: Sequence[float], A: float, B: float, material: YeohMaterial,
                      n_radial: int = 8, n_hoop: int = 16, bulk_ratio: float = BULK_RATIO) -> np.ndarray:
    """The deformed inner radius [m] at each internal pressure [Pa] of ``pressures`` (the load
    steps, increasing from 0; steps of 50 kPa take Newton 4 to 6 iterations), by FElupe: the
    plane-strain tube of :func:`tube_pressure` as a quarter ring of ``n_radial`` by ``n_hoop``
    quads, symmetric about the x and y axes. The default mesh's error in a - A is -0.13 % to
    -0.07 % over 50-250 kPa for A = 5 mm, B = 8 mm, and falls fourfold per halving of the cells.

    Formulation: FElupe's Yeoh model (isochoric, in I1_bar) with the u/p/J three-field
    (Hu-Washizu) solid of cell-constant pressure and volume ratio, and bulk modulus
    ``bulk_ratio`` mu; the internal pressure is a follower load on the inner arc (per deformed
    length, along the deformed normal). The pure-displacement quads lock volumetrically
    (measured: the radius change 90 % low on 4 radial by 8 hoop cells), so the mixed form is required.
    """
    import felupe as fem  # here: its import takes 0.6 s, and only the FE check needs it

    mesh, r, theta = quarter_ring(A, B, n_radial, n_hoop)
    inner = np.isclose(r, A, rtol=1e-9, atol=0.0)
    region = fem.RegionQuad(mesh)
    field = fem.FieldContainer([fem.FieldPlaneStrain(region, dim=2)])
    umat = fem.Hyperelastic(fem.yeoh, C10=material.C10, C20=material.C20, C30=material.C30)
    solid = fem.SolidBodyNearlyIncompressible(umat, field, bulk=bulk_ratio * material.mu)
    boundaries = {  # symmetry: no normal displacement on the x = 0 and y = 0 edges
        "x0": fem.Boundary(field[0], mask=np.isclose(theta, np.pi / 2), skip=(0, 1)),
        "y0": fem.Boundary(field[0], mask=np.isclose(theta, 0.0), skip=(1, 0)),
    }
    # a positive pressure pushes against the boundary's outward normal: on the inner arc, outwards
    arc = fem.RegionQuadBoundary(mesh, only_surface=True, mask=inner, ensure_3d=True)
    pressure = fem.SolidBodyPressure(fem.FieldContainer([fem.FieldPlaneStrain(arc, dim=2)]))
    step = fem.Step(items=[solid, pressure], ramp={pressure: np.asarray(pressures, dtype=float)},
                    boundaries=boundaries)
    radii: list[float] = []

    def record(context, state) -> None:  # a felupe plugin, called after each converged load step
        deformed = mesh.points[inner] + context.substep.x[0].values[inner]
        radii.append(np.linalg.norm(deformed, axis=1).mean())  # the nodes' radii agree by symmetry

    fem.Job(steps=[step], plugins=[record]).evaluate(verbose=0, tol=NEWTON_TOL)
    return np.array(radii)
