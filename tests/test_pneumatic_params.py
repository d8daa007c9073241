"""Paper 001's actuator parameters: the paper's numbers, their consistency, one-line refusals."""

from __future__ import annotations

import math

import pytest

from gripper.references.pneumatic_params import PneumaticActuator


def test_the_defaults_are_the_papers_recommended_design():
    a = PneumaticActuator().validate()
    # Table 1
    assert (a.cladding_thickness, a.main_body_thickness, a.neutral_thickness) == (0.001, 0.002, 0.0002)
    assert (a.fibre_diameter, a.twist_angle_deg) == (0.0005, 4.0)
    # §3 Step 2, the Yeoh constants in Pa
    assert (a.yeoh_c10, a.yeoh_c20, a.yeoh_c30) == pytest.approx((115960.0, 16800.0, -319.0))
    # Fig. 17's segments and gaps span exactly the 140 mm length the paper gives separately
    assert a.neutral_span == pytest.approx(a.length, abs=1e-12)


def test_the_helix_pitch_follows_from_the_twist_angle():
    a = PneumaticActuator(twist_angle_deg=10.0).validate()
    turns = a.length / a.fibre_pitch
    # one turn advances P tan(α) along the axis (P the winding's perimeter): the thread's length
    # per turn is P / cos(α), the unrolled helix's hypotenuse
    assert turns * a.winding_perimeter / math.cos(math.radians(10.0)) == pytest.approx(
        math.hypot(a.length, turns * a.winding_perimeter))
    # the perimeter: half-round r + d/2, the two sides down past the neutral layer, the corners, the bottom
    d = a.fibre_diameter
    assert a.winding_perimeter == pytest.approx(
        math.pi * (a.outer_radius + d / 2) + 2 * (a.main_body_thickness + a.neutral_thickness) + math.pi * d / 2
        + 2 * a.outer_radius)


@pytest.mark.parametrize("changes,word", [
    ({"cladding_thickness": -0.001}, "actuator.cladding_thickness"),
    ({"twist_angle_deg": 0.2}, "overlap"),
    ({"segment_gaps": (0.005,)}, "actuator.segment_gaps"),
    ({"segment_lengths": (0.1, 0.1, 0.1), "segment_gaps": (0.0, 0.0)}, "more than the length"),
    ({"yeoh_c10": 0.0}, "actuator.yeoh_c10"),
])
def test_bad_values_are_refused_in_one_line(changes, word):
    with pytest.raises(ValueError, match=word) as e:
        PneumaticActuator(**changes).validate()
    assert "\n" not in str(e.value)
