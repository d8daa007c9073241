"""The semi-analytical bending model of paper 001's actuator: its cross-section against closed
forms, its small-pressure limit against linear beam bending, and its moment balance."""

from __future__ import annotations

import math

import numpy as np
import pytest

from gripper.references.bending_moment_model import (
    CrossSection,
    bending_curve_deg,
    curvature_at,
    elastic_moment,
)
from gripper.references.pneumatic_params import PneumaticActuator

A = PneumaticActuator().validate()
SECTION = CrossSection(A)


def test_the_duct_is_a_half_disc_with_rounded_edges_above_the_bottom_wall():
    """The grid's duct against polar quadrature of the duct's wall r_d(θ) (a half disc of radius
    a whose two edges the 1 mm fillets round): area 2∫½r_d² dθ, first moment about the neutral
    axis y_c·area + 2∫⅓r_d³ sin θ dθ."""
    from gripper.references.actuator_mesh import Geometry

    g = Geometry(A)
    theta = np.linspace(0.0, math.pi / 2, 200001)
    r = g.duct_radius_at(theta)
    area = 2 * np.trapezoid(0.5 * r ** 2, theta)
    moment = g.y_centre * area + 2 * np.trapezoid(r ** 3 / 3 * np.sin(theta), theta)
    # each 1 mm fillet fills ~0.29 mm² of the corner between flat side and arc: ~1 % of the half disc
    assert 0.98 * 0.5 * math.pi * g.a ** 2 < area < 0.995 * 0.5 * math.pi * g.a ** 2
    assert SECTION.duct_area == pytest.approx(area, rel=2e-3)
    assert SECTION.duct_first_moment == pytest.approx(moment, rel=2e-3)


def test_small_pressures_bend_as_a_linear_beam():
    """At 1 kPa the stretches are within 0.2 % of 1: Yeoh's plane-strain modulus is 4μ = 8 C10,
    and κ = P Q / (4 μ I) (Q the duct's first moment, I the silicone's second moment)."""
    pressure = 1e3
    linear = pressure * SECTION.duct_first_moment / (4 * A.yeoh_shear_modulus * SECTION.second_moment)
    assert curvature_at(pressure, SECTION) == pytest.approx(linear, rel=2e-3)


def test_the_moments_balance_at_every_pressure():
    for pressure in (50e3, 150e3, 250e3):
        k = curvature_at(pressure, SECTION)
        assert elastic_moment(k, SECTION) == pytest.approx(pressure * SECTION.duct_first_moment, rel=1e-9)


def test_bending_grows_with_pressure_and_falls_with_the_walls():
    """Paper 001's trends (its Figs. 12 and 13): thicker cladding or main body, less bending."""
    curve = bending_curve_deg(A, np.linspace(0, 250e3, 6))
    assert curve[0] == 0 and np.all(np.diff(curve) > 0)
    at_250 = {t: bending_curve_deg(A.replace(cladding_thickness=t), [250e3])[0] for t in (0.0, 0.001, 0.0025)}
    assert at_250[0.0] > at_250[0.001] > at_250[0.0025]
    body = {t: bending_curve_deg(A.replace(main_body_thickness=t), [250e3])[0] for t in (0.0005, 0.002, 0.003)}
    assert body[0.0005] > body[0.002] > body[0.003]


def test_the_grid_is_fine_enough():
    """Halving the quadrature cell moves the angle at 250 kPa by less than 0.1 %."""
    fine = CrossSection(A, cell=0.5 * SECTION.cell)
    assert curvature_at(250e3, fine) == pytest.approx(curvature_at(250e3, SECTION), rel=1e-3)
