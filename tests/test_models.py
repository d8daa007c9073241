import mujoco
import pytest

from gripper.core.params import DEG, GripperParams
from gripper.experiments.smoke import random_control_rollout
from gripper.model.builders import build_scene_spec
from gripper.model.closure import teeth_lock_angle
from gripper.model.menagerie import REPO_MODELS, generate_model_files, readme_with_table


def test_committed_models_match_fresh_generation():
    fresh = generate_model_files()
    for name, text in fresh.items():
        committed = (REPO_MODELS / name).read_text()
        assert committed == text, f"{name} is stale: run scripts/write_models.sh"
    readme = (REPO_MODELS / "README.md").read_text()
    assert readme == readme_with_table(readme), "model README table is stale"


def test_committed_scene_loads():
    m = mujoco.MjModel.from_xml_path(str(REPO_MODELS / "scene.xml"))
    # 4 cables (spatial) and one stop tendon (fixed) per hinge: 4 fingers x 5 hinges
    assert m.nu == 7 and m.ntendon == 4 + 20
    assert sum(m.tendon(i).name.endswith("_cable") for i in range(m.ntendon)) == 4
    names = [m.sensor(i).name for i in range(m.nsensor)]
    assert "f0_cable_tension" in names and "f3_seg6_pad" in names


@pytest.mark.parametrize(("n_fingers", "n_segments"),
                         [(2, 3), (4, 6), (6, 12), (3, 12), (6, 3), (5, 8)])
def test_scene_steps_without_warnings(n_fingers, n_segments):
    p = GripperParams()
    p = p.replace(finger=p.finger.replace(n_segments=n_segments),
                  layout=p.layout.replace(n_fingers=n_fingers))
    res = random_control_rollout(p, duration=2.0, seed=n_fingers * 100 + n_segments)
    assert res["steps"] == 2000  # raises SimulationUnstable on any warning / NaN


def test_squashed_teeth_lock_holds_whipped_long_fingers():
    """Random stage commands whip 12-element fingers: hinges hit their closed cuts at 100 rad/s.
    Past the teeth's lock angle (tips squashed flat) a rigid stop takes over; without it this
    rollout blew up (MuJoCo BADQACC at 1.25 s)."""
    p = GripperParams()
    p = p.replace(finger=p.finger.replace(n_segments=12), layout=p.layout.replace(n_fingers=6))
    assert random_control_rollout(p, duration=2.0, seed=2)["steps"] == 2000
    m = build_scene_spec(p).compile()
    stop = m.tendon("f0_hinge2_stops").id
    lock = p.finger.closure_angle_deg * DEG + teeth_lock_angle(p.finger)
    assert m.tendon_range[stop] == pytest.approx([-p.finger.extension_limit_deg * DEG, lock])
    assert m.tendon_solref_lim[stop, 0] == pytest.approx(4 * p.sim.timestep)


def test_the_closed_cuts_match_is_reused_bitwise():
    """The second scene of a design takes the first one's tuned limits: the same model."""
    import numpy as np

    from gripper.objects.library import Placement, get_object
    from gripper.sim import scene

    p = GripperParams().replace(sim=GripperParams().sim.replace(timestep=0.002))
    scene._LIMITS.clear()
    first = scene.build_grasp_scene(p, get_object("block"), Placement())
    assert len(scene._LIMITS) == 1
    again = scene.build_grasp_scene(p, get_object("block"), Placement())
    for field in ("jnt_solref", "jnt_solimp", "jnt_range", "jnt_stiffness", "body_mass", "geom_size"):
        assert np.array_equal(getattr(first, field), getattr(again, field)), field
