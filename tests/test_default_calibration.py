"""The calibrated default: converged references, the committed calibration and its staleness,
paper 000's flexible multibody model."""

import json
import math

import numpy as np
import pytest

from gripper.calibration.calfile import Calibration, CalibrationMismatch, apply_calibration, design_hash
from gripper.calibration.pipeline import default_settings, settings_hash, stale_reasons
from gripper.core.params import DEFAULT_CALIBRATION_FILE, GripperParams, HingeSprings
from gripper.references.convergence import linear_compliance, richardson
from gripper.references.finger_mesh import MeshResolution

COMMITTED = Calibration.load(DEFAULT_CALIBRATION_FILE)


def test_default_springs_are_the_committed_calibration():
    s = GripperParams().springs
    n = GripperParams().finger.n_hinges
    k, c, rest = s.per_hinge(n)
    assert k == COMMITTED.stiffness and c == COMMITTED.damping and rest == COMMITTED.rest_angle_deg
    assert COMMITTED.source == "continuum"
    # The fitted springs stand on the converged body: the run used the stiffness correction.
    conv = COMMITTED.settings["convergence"]
    assert COMMITTED.settings["run"]["modulus_factor"] == pytest.approx(conv["stiffness_correction"])


def test_committed_calibration_is_fresh():
    assert stale_reasons(COMMITTED, GripperParams()) == []


def test_a_design_change_makes_the_committed_calibration_stale():
    p = GripperParams()
    thinner = p.replace(finger=p.finger.replace(bridge_thickness=0.0025))
    reasons = stale_reasons(COMMITTED, thinner)
    assert reasons and "design" in reasons[0]
    with pytest.raises(CalibrationMismatch):
        apply_calibration(thinner, COMMITTED)


def test_a_reference_settings_change_makes_it_stale(monkeypatch):
    import gripper.calibration.pipeline as pipeline
    from gripper.references.continuum import ReferenceConfig

    monkeypatch.setattr(pipeline, "ReferenceConfig", lambda: ReferenceConfig(n_levels=4))
    assert any("settings" in r for r in stale_reasons(COMMITTED, GripperParams()))


def test_committed_fit_meets_the_accuracy_lines():
    m = COMMITTED.metrics
    assert m["tip_rms_frac"] <= 0.03
    for h in m["held_out"]:
        assert h["tip_error_frac"] <= 0.05
    # the fitted finger at rest against the reference at rest, at every level: the same bound
    for level in m["settled"]["levels"]:
        assert level["tip_error_frac"] <= 0.03, level


def test_committed_reference_static_points_are_at_rest():
    """The committed reference record carries its static points relaxed to rest, each accepted
    on its own residual (the bending angle's move over the last half second)."""
    from gripper.references.relaxation import REST_TOL_DEG

    rec = json.loads((DEFAULT_CALIBRATION_FILE.parent / "reference.json").read_text())
    moved = rec["rest_moved_deg"]
    assert len(moved) == len(rec["static"]) == len(rec["rest_tip_xz_m"])
    assert max(moved) < REST_TOL_DEG


def test_paper_springs_stay_available():
    per_deg = HingeSprings.paper()
    assert per_deg.stiffness == (pytest.approx(1.9e-3 * 180 / math.pi),)
    assert HingeSprings.paper("per_radian").stiffness == (1.9e-3,)
    with pytest.raises(ValueError, match="per_degree or per_radian"):
        HingeSprings.paper("per_minute")


def test_richardson_recovers_a_known_order():
    h = (1 / 2, 1 / 3, 1 / 4)
    r = richardson(h, tuple(3.0 + 2.0 * x ** 1.5 for x in h))
    assert r.order == pytest.approx(1.5, rel=1e-6)
    assert r.extrapolated == pytest.approx(3.0, rel=1e-9)
    with pytest.raises(ValueError, match="oscillatory"):
        richardson(h, (1.0, 2.0, 1.5))
    flat = richardson(h, (2.0, 2.0 + 1e-9, 2.0 + 2e-9))  # converged already: the finest stands
    assert flat.extrapolated == pytest.approx(2.0) and math.isinf(flat.order)


def test_linear_solve_is_the_flex_at_small_load():
    """The convergence study's linear solve of the reference's discretisation agrees with
    MuJoCo's own relaxation of that mesh (coarse Kuhn mesh, for speed): at 0.01 N the flex's
    geometric nonlinearity is about 1 %."""
    from gripper.references.continuum_checks import static_bend

    mesh = MeshResolution(split="kuhn6")
    lin = linear_compliance(None, mesh)["compliance_deg_per_N"]
    flex = static_bend(None, mesh, tension=0.01)["bending_angle_deg"] / 0.01
    assert flex == pytest.approx(lin, rel=0.02)


def test_convergence_record_of_the_default(tmp_path):
    """The committed convergence study: an observed order near the notch singularity's
    (2·lambda ≈ 1.0 for a 315° corner), the corrected default within 2 % of the extrapolated."""
    conv = json.loads((DEFAULT_CALIBRATION_FILE.parent / "convergence.json").read_text())
    assert 0.7 < conv["richardson"]["order"] < 1.6
    assert conv["scales"][0] == 1 and len(conv["scales"]) >= 4
    f0 = conv["richardson"]["extrapolated"]
    corrected = linear_compliance(None, MeshResolution())["compliance_deg_per_N"]
    corrected /= COMMITTED.settings["run"]["modulus_factor"]
    assert corrected == pytest.approx(f0, rel=0.02)


@pytest.mark.slow
def test_corrected_flex_has_the_extrapolated_compliance():
    """MuJoCo's reference itself, run with the committed correction, bends at 0.01 N within
    2 % of the extrapolated compliance."""
    from dataclasses import replace

    from gripper.references.continuum_checks import static_bend

    factor = COMMITTED.settings["run"]["modulus_factor"]
    f0 = COMMITTED.settings["convergence"]["extrapolated_compliance_deg_per_N"]
    p = GripperParams()
    p = p.replace(material=replace(p.material, youngs_modulus=p.material.youngs_modulus * factor))
    # A small load: at 0.01 N the corrected finger bends 17° and its geometric nonlinearity adds
    # 3 % (measured 1703 deg/N); at 0.0025 N it bends about 4°.
    flex = static_bend(p, tension=0.0025, rest_tol_deg=0.005)["bending_angle_deg"] / 0.0025
    assert flex == pytest.approx(f0, rel=0.02)


@pytest.mark.slow
def test_quadratic_elements_agree_with_the_extrapolated_reference():
    """Independent discretisation (scikit-fem P2 tetrahedra on a gmsh mesh graded towards the
    apexes): its own Richardson extrapolation within 3 % of the reference's."""
    pytest.importorskip("gmsh")
    from gripper.calibration.quadratic_check import quadratic_compliance

    sizes = (3.0, 2.0, 1.5)  # mm
    t = GripperParams().finger.bridge_thickness
    # Apex cells a fixed fraction of the bridge (0.2 t at the coarsest), computed exactly as for
    # docs/calibration.md: the extrapolation is sensitive to the finest mesh (a last-digit change
    # of its apex size, remeshed by gmsh, moved it by 1.2 %).
    f = tuple(quadratic_compliance(size=s * 1e-3, bridge_size=0.2 * t * s / 3.0)["compliance_deg_per_N"]
              for s in sizes)
    p2 = richardson(tuple(s / sizes[0] for s in sizes), f).extrapolated
    f0 = COMMITTED.settings["convergence"]["extrapolated_compliance_deg_per_N"]
    assert p2 == pytest.approx(f0, rel=0.03)


# -- paper 000's flexible multibody model -----------------------------------------------------

def test_fmbs_linear_solve_is_the_hinge_chain_closed_form():
    """With its elements made 1000x stiffer, the flexible multibody model's linear solve under a
    small knot load is a chain of rigid elements on torsion springs: it bends by n·T·lever/K,
    the lever being the cable's height above the hinge axis (straight cable, equal moment at
    every hinge). With the silicone's own modulus the elements change it by their small share
    (either way: B1's own bending is subtracted from the bending angle)."""
    from gripper.references.fmbs import FmbsConfig

    p = GripperParams()
    g = p.finger
    lever = g.hole_height - g.hinge_z
    for reading in ("per_degree", "per_radian"):
        f = FmbsConfig(reading=reading)
        chain = math.degrees(g.n_hinges * lever / f.hinge_stiffness)
        stiff = p.replace(material=p.material.replace(youngs_modulus=1000 * p.material.youngs_modulus))
        rigid = linear_compliance(stiff, MeshResolution(), fmbs=f)["compliance_deg_per_N"]
        assert rigid == pytest.approx(chain, rel=2e-3)
        soft = linear_compliance(p, MeshResolution(), fmbs=f)["compliance_deg_per_N"]
        assert soft == pytest.approx(chain, rel=0.05)


def test_fmbs_flex_at_rest_is_the_hinge_chain():
    """MuJoCo's flexible multibody finger at rest under a small load: every hinge at T·lever/K
    (its elements some 400x stiffer than the hinges). Before the cable's equivalent forces on
    the rigid zones' nodes were applied to the zones, the proximal hinge rested 11 % short."""
    from gripper.references.continuum import ReferenceConfig
    from gripper.references.fmbs import FmbsConfig, run_fmbs

    p = GripperParams()
    f = FmbsConfig(reading="per_degree")
    T = 0.1
    cfg = ReferenceConfig(tension_max=T, n_levels=1, duration=0.6,
                          mesh=MeshResolution(split="kuhn6"), timestep=1e-3, solver_tolerance=1e-6)
    rec = run_fmbs(p, cfg, f)
    hinge = np.diff(rec.element_angles_deg[-1])
    lever = p.finger.hole_height - p.finger.hinge_z
    expected = math.degrees(T * lever / f.hinge_stiffness)
    assert rec.warnings == 0
    np.testing.assert_allclose(hinge, expected, rtol=0.03)


def test_fmbs_settings_refused_with_one_line():
    from gripper.references.fmbs import FmbsConfig

    with pytest.raises(ValueError, match="fmbs.reading"):
        FmbsConfig(reading="per_turn").validate()
    with pytest.raises(ValueError, match="fmbs.hinge_damping"):
        FmbsConfig(hinge_damping=-1.0).validate()


def test_paper_hinge_damping_freezes_the_finger():
    """Table 2's '10 N·m·s/deg' with its 1.9e-3 N·m/deg spring is a 5263 s relaxation time: the
    flexible multibody finger barely starts to bend in the paper's run (here its first 0.3 s)."""
    from gripper.references.continuum import ReferenceConfig
    from gripper.references.fmbs import FmbsConfig, run_fmbs

    cfg = ReferenceConfig(tension_max=1.0, n_levels=1, duration=0.3,
                          mesh=MeshResolution(split="kuhn6"))
    modal = run_fmbs(None, cfg, FmbsConfig())
    paper = run_fmbs(None, cfg, FmbsConfig(hinge_damping="paper"))
    bend = lambda r: r.element_angles_deg[-1, -1] - r.element_angles_deg[-1, 0]  # noqa: E731
    assert abs(bend(paper)) < 0.2 * abs(bend(modal))


def test_calibrate_refuses_bad_input_and_writes_nothing(tmp_path, capsys):
    from gripper.cli.main import main

    out = tmp_path / "cal"
    assert main(["calibrate", "--data", str(tmp_path / "missing.csv"), "--out", str(out)]) == 2
    assert "missing.csv" in capsys.readouterr().err
    assert not out.exists()
    other = tmp_path / "other.json"
    data = json.loads(DEFAULT_CALIBRATION_FILE.read_text())
    data["design_hash"] = "0" * 16
    other.write_text(json.dumps(data))
    assert main(["bend", "--calibration", str(other)]) == 2
    assert "made for design" in capsys.readouterr().err
    bad = tmp_path / "bad.json"
    bad.write_text("{not json")
    assert main(["bend", "--calibration", str(bad)]) == 2
    assert "not valid JSON" in capsys.readouterr().err
    assert main(["calibrate", "--reference", "beam", "--out", str(out)]) == 2
    assert not out.exists()


def test_settings_hash_is_stable():
    s = default_settings()
    assert settings_hash(s) == settings_hash(json.loads(json.dumps(s)))
    assert design_hash(GripperParams()) == COMMITTED.design_hash


@pytest.mark.slow
def test_rest_points_are_the_equilibria():
    """A level's end-of-hold state relaxed to rest lands where the same finger relaxed from
    straight does (an elastic body has one rest shape per load): coarse mesh, 0.05 N."""
    from gripper.references.continuum import ReferenceConfig, run_reference
    from gripper.references.continuum_checks import static_bend

    mesh = MeshResolution(split="kuhn6")
    cfg = ReferenceConfig(mesh=mesh, tension_max=0.05, n_levels=2, duration=0.4)
    rec = run_reference(None, cfg, at_rest=True)
    fresh = static_bend(None, mesh, tension=0.05, rest_tol_deg=0.005)
    rest = rec.rest_element_angles_deg[-1]
    assert rest[-1] - rest[0] == pytest.approx(fresh["bending_angle_deg"], abs=0.1)
    assert np.allclose(rec.rest_tip_xz_m[-1], fresh["tip_xz_m"], atol=2e-4)
