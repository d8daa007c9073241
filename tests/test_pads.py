"""The pads' contact law: the force-indentation a rigid part meets on a finger element follows
Hertz's closed form for the silicone (paper 000 Table 2; paper 001's Yeoh fit), whatever the part
weighs and whatever the step; the rounded surfaces keep the elements' outer size."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial import ConvexHull

from gripper.core.params import GripperParams
from gripper.core.rounding import ARC_POINTS, inset_polygon, rounded_prism, rounded_sweep
from gripper.drives import drive_for
from gripper.drives.cable.geometry import element_profile
from gripper.drives.pneumatic.chamber import segment_section
from gripper.experiments.pad_press import press_pad
from gripper.parts.pads import KNOT_FORCE_RATIO, hertz_law, pad_spring

FORCES = [0.1, 0.3, 1.0, 2.0, 5.0]  # N: the acceptance range, 0.1-5 N


def _params(kind: str) -> GripperParams:
    p = GripperParams()
    return p.replace(actuation=p.actuation.replace(kind=kind)) if kind == "pneumatic" else p


def test_hertz_law_from_the_datasheet_modulus():
    # E* = E / (1 - nu^2) with paper 000 Table 2's 0.44 MPa and 0.48: 0.572 MPa; a 5 mm sphere
    # under 2 N sinks 1.1 mm (docs/limitations.md's figure, by hand)
    law = hertz_law(drive_for(GripperParams()))
    assert law.effective_modulus == pytest.approx(0.44e6 / (1 - 0.48 ** 2), rel=1e-12)
    five_mm = type(law)(law.effective_modulus, 0.005)
    assert five_mm.indentation(2.0) == pytest.approx(1.1e-3, rel=0.02)
    # the pneumatic finger's: E = 6 C10 of paper 001's Yeoh fit, incompressible
    pn = hertz_law(drive_for(_params("pneumatic")))
    assert pn.effective_modulus == pytest.approx(6 * 0.11596e6 / 0.75, rel=1e-12)


@pytest.mark.parametrize("kind", ["cable", "pneumatic"])
def test_piecewise_spring_follows_hertz(kind):
    # a chord of x^1.5 from 1 to r (r = 3^(2/3), a force ratio of KNOT_FORCE_RATIO) over the curve,
    # at its worst: the interpolant's bound, from the closed form alone
    r = KNOT_FORCE_RATIO ** (2.0 / 3.0)
    t = np.linspace(1.0, r, 100001)
    bound = np.max((1.0 + (r ** 1.5 - 1.0) * (t - 1.0) / (r - 1.0)) / t ** 1.5)
    assert 1.04 < bound < 1.06
    p = _params(kind)
    drive = drive_for(p)
    law, spring = hertz_law(drive), pad_spring(drive)
    top = min(p.contact.fit_force_max, float(law.force(drive.pad_depth)))  # where the pad bottoms out
    assert top > 5.0  # the acceptance range, 0.1-5 N, is inside
    delta = law.indentation(np.geomspace(0.1, top, 2000))
    ratio = spring.force(delta) / law.force(delta)
    assert ratio.min() >= 1.0 - 1e-9
    assert ratio.max() <= bound + 1e-9


@pytest.mark.parametrize("kind", ["cable", "pneumatic"])
@pytest.mark.parametrize("part_mass", [0.01, 1.0])
def test_pad_force_indentation_is_hertz_whatever_the_part_weighs(kind, part_mass):
    p = _params(kind)
    press = press_pad(p, FORCES, part_mass=part_mass)
    ref = hertz_law(drive_for(p)).indentation(FORCES)
    np.testing.assert_allclose(press.indentation, ref, rtol=0.15)  # the 15 %


@pytest.mark.parametrize("kind", ["cable", "pneumatic"])
def test_part_mass_moves_the_law_by_under_5_percent(kind):
    p = _params(kind)
    light = press_pad(p, FORCES, part_mass=0.01).indentation
    heavy = press_pad(p, FORCES, part_mass=1.0).indentation
    # 5 % of the indentation, or 2 µm where it is a tenth of a millimetre (the settle's reading)
    np.testing.assert_allclose(heavy, light, rtol=0.05, atol=2e-6)


def test_pad_law_does_not_move_with_the_step():
    p = GripperParams()
    fine = press_pad(p, FORCES, timestep=5e-4).indentation
    coarse = press_pad(p, FORCES, timestep=2e-3).indentation
    np.testing.assert_allclose(coarse, fine, rtol=0.05, atol=2e-6)


def test_solver_contact_depends_on_the_part_mass():
    """0.16.0's contact (MuJoCo's default softness) is what the pads replace: its
    force-indentation moves with the part's mass, by far more than the 5 % the pads keep to."""
    p = GripperParams()
    p = p.replace(contact=p.contact.replace(model="solver"))
    light = press_pad(p, [1.0], part_mass=0.01).indentation[0]
    heavy = press_pad(p, [1.0], part_mass=1.0).indentation[0]
    assert abs(heavy / light - 1.0) > 0.2


def test_rounded_shapes_keep_the_outer_size():
    g = GripperParams().finger
    prof = element_profile(g, "middle")
    pts = rounded_prism(prof, g.width, 0.0015)
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    np.testing.assert_allclose([lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]],
                               [0.0, -0.5 * g.width, 0.0, g.pitch, 0.5 * g.width, g.height], atol=1e-12)
    # every hull vertex lies within the unrounded prism, and the corners are cut: the hull is smaller
    sharp = rounded_prism(prof, g.width, 0.0)
    assert ConvexHull(pts).volume < ConvexHull(sharp).volume
    pf = _params("pneumatic").pneumatic
    sec = segment_section(pf)
    sweep = rounded_sweep(sec, pf.pitch, 0.002)
    # the rounding's facets fall short of its radius by r (1 - cos(45° / ARC_POINTS)) at most
    facet = 0.002 * (1.0 - np.cos(np.radians(45.0 / ARC_POINTS)))
    np.testing.assert_allclose(sweep[:, 1:].min(axis=0), sec.min(axis=0), atol=facet)
    np.testing.assert_allclose(sweep[:, 1:].max(axis=0), sec.max(axis=0), atol=facet)


def test_inset_polygon_refuses_a_radius_that_does_not_fit():
    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    with pytest.raises(ValueError, match="does not fit"):
        inset_polygon(square, 0.6)
