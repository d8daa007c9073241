import json

import numpy as np
import pytest

from gripper.cli.main import main
from gripper.core.params import GripperParams
from gripper.drives.cable.closure import (
    realised_secant_stiffness,
    teeth_closure_stiffness,
    teeth_impedance,
    teeth_lock_angle,
    teeth_moment,
)
from gripper.experiments.bending import BendingConfig, run_bending_test


def _closing_design(closure: str = "rigid"):
    """30° cuts close (27.4° per hinge) well inside the servo's travel. The limit checks use the
    rigid stop, the hinge chain's idealisation; the default compliant stop is checked below."""
    p = GripperParams()
    return p.replace(finger=p.finger.replace(cut_angle_deg=30.0),
                     springs=p.springs.replace(closure=closure))


@pytest.fixture(scope="module", params=["dynamic", "quasi_static"])
def closing_run(request):
    p = _closing_design()
    n = 201 if request.param == "dynamic" else 31
    return p, run_bending_test(BendingConfig(mode=request.param, r_max=0.4, n_points=n), p)


def test_straight_at_zero(closing_run):
    _, res = closing_run
    assert abs(res.r[0]) < 1e-9
    assert np.abs(res.joint_angles_deg[0]).max() < 0.1


def test_bending_monotonic_until_cuts_close(closing_run):
    p, res = closing_run
    closed = res.limit_active.all(axis=1)
    first_closed = int(np.argmax(closed)) if closed.any() else len(closed)
    assert first_closed > 5, "cuts should close only late in the sweep"
    bend = res.bending_angle_deg[:first_closed]
    assert np.all(np.diff(bend) > 0)
    assert res.bending_angle_deg[first_closed - 1] > 100.0


def test_hinge_limits_held(closing_run):
    p, res = closing_run
    limit = p.finger.closure_angle_deg
    below_half_stall = res.tension_N < 0.5 * p.servo.max_cable_tension
    assert res.joint_angles_deg[below_half_stall].max() <= limit + 0.5
    assert res.joint_angles_deg.min() >= -p.finger.extension_limit_deg - 0.5
    assert res.limit_active.any(), "the sweep should reach the closed cuts"


def test_cable_never_pushes(closing_run):
    _, res = closing_run
    assert res.tension_N.min() >= 0.0
    assert res.warnings == 0


def test_compliant_closure_is_the_teeth_spring():
    """Past the closure angle the default stop is the squeezed teeth: at rest, the limit's
    moment (its realised secant stiffness times the overrun) carries what the cable's moment
    leaves over after the bridge spring (2 %, the moment-balance tolerance), and that moment
    follows the neo-Hookean teeth within 5 %, up to the 10° this sweep reaches."""
    p = _closing_design("teeth")
    res = run_bending_test(BendingConfig(mode="quasi_static", r_max=0.4, n_points=31), p)
    overrun = np.radians(res.joint_angles_deg - p.finger.closure_angle_deg)
    closed = res.limit_active & (overrun > np.radians(0.5))
    assert closed.sum() > 20 and overrun.max() > np.radians(7.0)
    excess = (res.cable_moment_Nm - res.spring_moment_Nm)[closed]
    realised = realised_secant_stiffness(p, overrun[closed]) * overrun[closed]
    assert np.abs(realised / excess - 1.0).max() < 0.02
    teeth = np.array([teeth_moment(p.finger, p.material, th) for th in overrun[closed]])
    assert np.abs(teeth / excess - 1.0).max() < 0.05


def test_teeth_stiffen_as_they_are_squashed():
    """Neo-Hookean teeth: K_c at small overrun, stiffer as the thin tips are squashed, and the
    limit's impedance curve follows them within 20 % up to its width (five times K_c)."""
    p = GripperParams()
    k0 = teeth_closure_stiffness(p.finger, p.material)
    assert teeth_moment(p.finger, p.material, 1e-4) / 1e-4 == pytest.approx(k0, rel=1e-3)
    width = teeth_impedance(p.finger, p.material)[2]
    theta = np.linspace(0.02, 1.0, 25) * width
    secant = np.array([teeth_moment(p.finger, p.material, th) / th for th in theta])
    assert np.all(np.diff(secant) > 0) and secant[-1] == pytest.approx(5 * k0, rel=0.01)
    assert np.abs(realised_secant_stiffness(p, theta) / secant - 1.0).max() < 0.2


def test_quasi_static_moment_balance():
    # At rest to the balance's 2 %: the slowest hinge relaxes with c / K = 0.42 s (0.15.0's
    # springs), so the default band (0.01° per 25 ms chunk) leaves up to 5 % of the smallest free
    # moment (1e-4 N·m) unbalanced; 0.002° leaves 1 %.
    res = run_bending_test(BendingConfig(mode="quasi_static", r_max=0.4, n_points=17, settle_band_deg=0.002))
    free = ~res.limit_active & (res.spring_moment_Nm > 1e-4)  # calibrated springs: ~2e-3 N·m/rad
    assert free.sum() > 50
    rel = np.abs(res.spring_moment_Nm - res.cable_moment_Nm)[free] / res.spring_moment_Nm[free]
    assert rel.max() < 0.02


def test_default_finger_bends_smoothly():
    res = run_bending_test(BendingConfig(n_points=41))
    assert np.all(np.diff(res.bending_angle_deg) > 0)
    assert res.bending_angle_deg[-1] > 150.0
    g = GripperParams().finger
    assert np.abs(res.tip_xyz_m[0] - [g.length, 0, g.hinge_z]).max() < 1e-4


def test_bend_cli_json(capsys):
    assert main(["bend", "--json", "--points", "11"]) == 0
    out = json.loads(capsys.readouterr().out)
    for key in ("r", "tension_N", "joint_angles_deg", "bending_angle_deg", "tip_xyz_m"):
        assert len(out[key]) == 11
    assert len(out["joint_angles_deg"][0]) == 5 and len(out["tip_xyz_m"][0]) == 3


def test_bad_config():
    with pytest.raises(ValueError, match="bend.r_max"):
        BendingConfig(r_max=1.5).validate()
    with pytest.raises(ValueError, match="bend.r_max"):
        run_bending_test(BendingConfig(r_max=0.9))  # beyond the servo's travel


def test_hinge_limits_held_at_stall(closing_run):
    p, res = closing_run
    assert res.joint_angles_deg.max() <= p.finger.closure_angle_deg + 0.5


@pytest.mark.parametrize("mode", ["dynamic", "quasi_static"])
def test_teeth_lock_held_at_stall(mode):
    """With the default stop (compliant teeth), a hinge's hard limit is the lock, where the
    teeth are squashed flat (closure + 12.4° for the default cut); it must hold within 0.5°, the
    acceptance tolerance, when the servo's stall reaches it. The paper's silicone stops short of
    it (about 9° past closure at stall), so the body here is a softer silicone, E = 66 kPa (0.15x
    paper 000's 0.44 MPa; for scale, Smooth-On's datasheet gives Ecoflex 00-10 a 100 % modulus
    of 8 psi, 55 kPa), which the stall squashes flat."""
    p = GripperParams()
    soft = p.replace(material=p.material.replace(youngs_modulus=0.15 * p.material.youngs_modulus))
    # dynamic: 3 s, as the heavier damping of 0.15.0's springs (c / K up to 0.42 s) reaches the
    # stall later than the 2 s default (94.7 % of it at 2 s)
    res = run_bending_test(BendingConfig(mode=mode, r_max=0.6, n_points=201 if mode == "dynamic" else 41,
                                         **({"duration": 3.0} if mode == "dynamic" else {})), soft)
    lock = soft.finger.closure_angle_deg + np.degrees(teeth_lock_angle(soft.finger))
    assert res.tension_N.max() > 0.95 * soft.servo.max_cable_tension  # at stall
    assert res.joint_angles_deg.max() > lock - 0.5  # the lock is reached ...
    assert res.joint_angles_deg.max() <= lock + 0.5  # ... and held
    assert res.joint_angles_deg.min() >= -soft.finger.extension_limit_deg - 0.5
    assert res.warnings == 0


def test_teeth_stiffness_matches_its_closed_form():
    """E·w·∫ s²/t dz with t linear in z has a closed form: u = t, s = c - u/(2T)."""
    p = GripperParams()
    g = p.finger
    T = np.tan(np.radians(g.cut_angle_deg) / 2)
    P, a, h = g.pitch, g.bridge_thickness, g.hinge_z
    u_top = P - 2 * (g.height - a) * T
    c = a - h + P / (2 * T)
    integral = (c**2 * np.log(P / u_top) - c / T * (P - u_top) + (P**2 - u_top**2) / (8 * T**2)) / (2 * T)
    k = teeth_closure_stiffness(g, p.material)
    assert k == pytest.approx(p.material.youngs_modulus * g.width * integral, rel=1e-6)
    # Far stiffer than the bridge (paper 000: 0.109 N·m/rad), and softer for a softer silicone.
    assert k > 10 * p.springs.stiffness[0]
    softer = p.material.replace(youngs_modulus=0.5 * p.material.youngs_modulus)
    assert teeth_closure_stiffness(g, softer) == pytest.approx(0.5 * k)


@pytest.mark.parametrize("degrees, tol", [
    (2.0, 0.3), (6.0, 0.1), (7.0, 0.3),
    pytest.param(8.0, 0.3, marks=pytest.mark.xfail(
        strict=True, reason="open (0.6.0): within 1° of the squashed teeth's lock (8.9° past closure "
                            "on the 1.9 mm bridge) the matched closed cuts rest 1.4° further than "
                            "their design"))])
def test_closed_cuts_keep_their_design_under_the_trials_integrator(degrees, tol):
    """The grasp trials step at 2 ms with the discrete integrator, which sizes a limit in its own
    effective metric: unmatched, the distal hinge held 6° past closure by its design moment
    rested at 3.3° (1.8x too stiff). Matched (closure.match_discrete_closure), every hinge of
    the four fingers rests within 0.1° of 6°, and within 0.3° at 2° and 7° (the stiffening
    curve is kept up to 2° short of the lock, 8.9° past closure on the default design)."""
    import mujoco

    from gripper.drives.cable.closure import closed_cut_rest_overrun
    from gripper.objects.library import get_object
    from gripper.objects.scene_objects import Placement
    from gripper.sim.scene import build_grasp_scene

    p = GripperParams()
    p = p.replace(sim=p.sim.replace(timestep=0.002))
    m = build_grasp_scene(p, get_object("block"), Placement(x=0.5, y=0.0, yaw=0.0))
    assert m.opt.integrator == mujoco.mjtIntegrator.mjINT_DISCRETE
    ids = np.array([i for i in range(m.njnt) if "_hinge" in m.joint(i).name])
    assert len(ids) == 20
    reached = np.degrees(closed_cut_rest_overrun(m, p, ids, np.radians(degrees)))
    assert np.abs(reached - degrees).max() < tol
