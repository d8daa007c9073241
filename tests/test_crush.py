"""Platen crush test: the damage models of the deformable objects respond to a real crush."""

import math

import pytest

from gripper.cli.main import main
from gripper.experiments.crush import crush_test
from gripper.objects.library import get_object


def test_balloon_stiffness_follows_its_overpressure():
    """Pressed 9 mm, an inflated balloon pushes back with about Δp · 2πR · δ (flattened cap).

    Small latex balloons run at Δp = 2-4 kPa (objects.py), so at R = 28 mm the force lies
    between 3.2 N and 6.3 N. With MuJoCo's default contact the plate sank into the balloon and
    read 0.64 N at 15 mm.
    """
    r = get_object("balloon").size[0]
    res = crush_test("balloon", 0.009, speed=0.01, hold_s=0.3)
    lo, hi = (dp * 2 * math.pi * r * 0.009 for dp in (2e3, 4e3))
    assert lo <= res["peak_plate_force_N"] <= hi
    assert not res["damaged"]


def test_balloon_bursts_when_flattened_not_when_pressed_lightly():
    """Flattened to 30 % of its height the membrane stretches past the 25 % burst strain."""
    light = crush_test("balloon", 0.006)
    hard = crush_test("balloon", 0.040)
    assert not light["damaged"] and light["damage_measure"] < 0.1
    assert hard["damaged"] and hard["damage_measure"] > hard["damage_limit"]


def test_paper_box_keeps_a_dent_when_crushed():
    """Pressed 0.1 mm (wall strain 0.17 %, a third of the card's 0.5 % yield strain) the box
    springs back; crushed 15 mm the card yields and keeps a dent deeper than 2 mm."""
    light = crush_test("paper_box", 0.0001)
    hard = crush_test("paper_box", 0.015)
    assert light["peak_plate_force_N"] > 10.0  # the plate did load the box
    assert not light["damaged"] and light["damage_measure"] < 0.05e-3
    assert hard["damaged"] and hard["damage_measure"] > 0.002


def test_crush_bad_input_is_refused(capsys):
    with pytest.raises(ValueError, match="crush.depth"):
        crush_test("balloon", 0.2)
    with pytest.raises(ValueError, match="crush.speed"):
        crush_test("balloon", 0.01, speed=0.0)
    assert main(["crush", "--objects", "teapot"]) == 2
    assert "teapot" in capsys.readouterr().err


def test_the_paper_box_face_stiffens_as_its_mesh_coarsens():
    """Linear-triangle shells lock: a coarser mesh of the same card resists a finger-sized press
    more. This is why the box keeps its 5 x 5 x 6 mesh (docs/performance.md, Mesh resolution)."""
    from gripper.experiments.press import face_press
    from gripper.objects.library import get_object

    shipped = get_object("paper_box").mesh_points
    forces = [face_press(pts, 0.002)["peak_force_N"] for pts in ((4, 4, 5), shipped, (6, 6, 7))]
    assert forces[0] > 1.1 * forces[1] > 1.1 * forces[2] > 0.0
    with pytest.raises(ValueError, match=r"press.depth: must be in \(0, 0.010\] m"):
        face_press(shipped, 0.05)
