"""The Yeoh thick-walled tube: Rivlin's exact solution against the linear Lamé limit, and the
FElupe plane-strain solution against the exact one within 1 % over paper 001's 0-250 kPa, with its
mesh convergence."""

from __future__ import annotations

from functools import cache

import numpy as np
import pytest

from gripper.references.yeoh_tube import (
    YeohMaterial,
    fe_tube_inflation,
    inner_radius_for_pressure,
    limit_point,
    tube_pressure,
)

A, B = 5e-3, 8e-3  # m, the test tube: wall 3 mm, its limit point (364 kPa) well above 250 kPa
PRESSURES = (50e3, 100e3, 150e3, 200e3, 250e3)  # Pa, over paper 001's range
MATERIAL = YeohMaterial()


def lame_inner_displacement(p: float, material: YeohMaterial) -> float:
    """Linear elasticity, incompressible (nu = 0.5), plane strain: u = C / r (zero volume change),
    so sigma_tt - sigma_rr = 2 mu (eps_tt - eps_rr) = 4 mu C / r^2, and the radial equilibrium
    p = integral_A^B 4 mu C / r^3 dr = 2 mu C (B^2 - A^2) / (A^2 B^2) gives u(A) = C / A."""
    return p * A * B**2 / (2.0 * material.mu * (B**2 - A**2))


@cache
def fe_errors(n_radial: int, n_hoop: int) -> np.ndarray:
    """The FE inner-radius change's relative error against the exact one at each of PRESSURES."""
    a_fe = fe_tube_inflation(PRESSURES, A, B, MATERIAL, n_radial=n_radial, n_hoop=n_hoop)
    a_exact = np.array([inner_radius_for_pressure(p, A, B, MATERIAL) for p in PRESSURES])
    return (a_fe - A) / (a_exact - A) - 1.0


def test_the_material_is_paper_001s_rtv_230():
    m = YeohMaterial()
    assert (m.C10, m.C20, m.C30) == pytest.approx((0.11596e6, 0.0168e6, -0.000319e6))
    assert m.mu == pytest.approx(2 * 0.11596e6)
    assert m.strain_energy_derivative(3.0) == pytest.approx(m.C10)  # undeformed: W1 = C10
    x = 2.0
    assert m.strain_energy_derivative(3.0 + x) == pytest.approx(m.C10 + 2 * m.C20 * x + 3 * m.C30 * x**2)


def test_the_exact_solution_tends_to_lames_at_small_pressure():
    # the nonlinear correction is first order in p: 0.56 % at 1 kPa, a hundredth of that at 10 Pa
    for p, rtol in ((1e3, 1e-2), (10.0, 1e-4)):
        u = inner_radius_for_pressure(p, A, B, MATERIAL) - A
        assert u == pytest.approx(lame_inner_displacement(p, MATERIAL), rel=rtol)


def test_pressure_and_radius_invert_each_other():
    assert inner_radius_for_pressure(0.0, A, B, MATERIAL) == A
    assert tube_pressure(A, A, B, MATERIAL) == 0.0
    for p in PRESSURES:
        a = inner_radius_for_pressure(p, A, B, MATERIAL)
        assert tube_pressure(a, A, B, MATERIAL) == pytest.approx(p, rel=1e-10)


def test_the_pressure_rises_monotonically_over_0_to_250_kpa():
    a_max, p_max = limit_point(A, B, MATERIAL)
    assert p_max == pytest.approx(364.2e3, rel=1e-3) and a_max / A == pytest.approx(5.26, rel=1e-2)
    radii = np.linspace(A, inner_radius_for_pressure(PRESSURES[-1], A, B, MATERIAL), 200)
    assert np.all(np.diff([tube_pressure(a, A, B, MATERIAL) for a in radii]) > 0)
    with pytest.raises(ValueError, match="limit point"):
        inner_radius_for_pressure(1.01 * p_max, A, B, MATERIAL)


def test_fe_inflation_matches_the_exact_solution_within_1_percent():
    # the acceptance: 8 radial by 16 hoop cells, measured errors -0.13 % to -0.07 %
    errors = fe_errors(8, 16)
    assert np.all(np.abs(errors) < 0.01), errors


def test_fe_error_falls_fourfold_per_halving_of_the_cells():
    # bilinear quads converge in second order: measured ratios 4.0 to 4.2 from 4 x 8 to 16 x 32 cells
    coarse, medium, fine = fe_errors(4, 8), fe_errors(8, 16), fe_errors(16, 32)
    for e1, e2 in ((coarse, medium), (medium, fine)):
        assert np.all((3.5 < e1 / e2) & (e1 / e2 < 5.0)), e1 / e2
    assert np.all(np.abs(fine) < 5e-4), fine
