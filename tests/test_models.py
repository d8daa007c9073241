import mujoco
import pytest

from gripper.core.params import DEG, GripperParams
from gripper.core.resources import MODELS_DIR
from gripper.drives import drive_for
from gripper.drives.cable.closure import teeth_lock_angle
from gripper.experiments.smoke import random_control_rollout
from gripper.model.builders import build_scene_spec
from gripper.parts.pads import pad_spring
from gripper.sim.model_files import generate_model_files, model_dir, readme_with_table, shipped_grippers

REPO_MODELS = MODELS_DIR / "soft_gripper"
GRIPPERS = shipped_grippers()


def test_models_holds_every_gripper_the_trials_run():
    assert sorted(GRIPPERS) == ["pneumatic_gripper", "soft_gripper"]
    assert sorted(p.name for p in MODELS_DIR.iterdir() if p.is_dir()) == sorted(GRIPPERS)


@pytest.mark.parametrize("name", sorted(GRIPPERS))
def test_committed_models_match_fresh_generation(name):
    params = GRIPPERS[name]
    folder = model_dir(params)
    fresh = generate_model_files(params)
    assert sorted(fresh) == sorted(["scene.xml", f"{name}.xml"])
    for file, text in fresh.items():
        committed = (folder / file).read_text()
        assert committed == text, f"{name}/{file} is stale: run scripts/write_models.sh"
    readme = (folder / "README.md").read_text()
    assert readme == readme_with_table(readme, params), f"{name}'s README table is stale"
    # Menagerie's layout: the README shows the model's picture; licence and changelog beside it
    assert f"]({name}.png)" in readme and (folder / f"{name}.png").is_file()
    for file in ("CHANGELOG.md", "LICENSE"):
        assert (folder / file).is_file(), file


@pytest.mark.parametrize("name", sorted(GRIPPERS))
def test_the_committed_scene_is_the_model_the_trials_run(name):
    """``python -m mujoco.viewer --mjcf models/<name>/scene.xml`` shows the trials' model:
    the committed scene and the trial scene (no object) compile to the same numbers, every
    physical and visual array of MjModel (names aside)."""
    import numpy as np

    from gripper.sim.scene import grasp_scene_spec, trial_params

    committed = mujoco.MjModel.from_xml_path(str(model_dir(GRIPPERS[name]) / "scene.xml"))
    trial = grasp_scene_spec(trial_params(GRIPPERS[name])).compile()
    assert committed.opt.timestep == trial.opt.timestep == 0.002
    assert committed.opt.integrator == trial.opt.integrator == mujoco.mjtIntegrator.mjINT_DISCRETE
    compared = 0
    for field in dir(trial):
        value = getattr(trial, field, None)
        if field.startswith(("_", "name", "text", "paths")) or not isinstance(value, np.ndarray) \
                or value.dtype == object:
            continue
        other = getattr(committed, field)
        if field == "site_size":  # a sphere site has one size; the XML leaves the unused two at MuJoCo's 0.005
            sphere = trial.site_type == mujoco.mjtGeom.mjGEOM_SPHERE
            other, value = other.copy(), value.copy()
            other[sphere, 1:] = value[sphere, 1:] = 0
        assert other.shape == value.shape and np.allclose(other, value, rtol=1e-5, atol=1e-9, equal_nan=True), field
        compared += 1
    assert compared > 300
    for k in range(trial.njnt):
        assert committed.joint(k).name == trial.joint(k).name


def test_the_committed_files_use_classes_and_materials():
    """Menagerie's way: the gripper's bodies take the model's class, the servos and hinges share
    theirs, and colours come from named materials, not repeated rgba."""
    text = (REPO_MODELS / "soft_gripper.xml").read_text()
    scene = (REPO_MODELS / "scene.xml").read_text()
    assert '<include file="soft_gripper.xml"/>' in scene and "<body" not in scene
    assert 'childclass="soft_gripper"' in text
    assert text.count('class="servo"') == 1 + 4  # the class and the four servos that take it
    assert text.count("dynprm=") == 1  # the dcmotor's numbers stand once, in the class
    for name in ("silicone", "palm", "cable"):
        assert f'<material name="{name}"' in text
    assert text.count("rgba=") == 2 + 3  # the collision and pad classes, the three materials


def test_committed_scene_loads():
    m = mujoco.MjModel.from_xml_path(str(REPO_MODELS / "scene.xml"))
    # 4 cables (spatial), one stop tendon (fixed) per hinge (4 fingers x 5 hinges) and the pads'
    # knot springs (one fixed tendon per knot past the first, 24 pads)
    knots = len(pad_spring(drive_for(GripperParams())).knots)
    assert m.nu == 8 and m.ntendon == 4 + 20 + 24 * (knots - 1)
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

    from gripper.objects.library import get_object
    from gripper.objects.scene_objects import Placement
    from gripper.sim import scene

    p = GripperParams().replace(sim=GripperParams().sim.replace(timestep=0.002))
    scene._LIMITS.clear()
    first = scene.build_grasp_scene(p, get_object("block"), Placement())
    assert len(scene._LIMITS) == 1
    again = scene.build_grasp_scene(p, get_object("block"), Placement())
    for field in ("jnt_solref", "jnt_solimp", "jnt_range", "jnt_stiffness", "body_mass", "geom_size"):
        assert np.array_equal(getattr(first, field), getattr(again, field)), field


def test_the_open_loop_grasp_closes_every_drive():
    """The speed benchmarks' fixed grasp (gripper.experiments.smoke) drives each gripper's own
    actuators: the cable servos to 2 rad, the chambers to 2/π of their highest pressure."""
    import numpy as np

    from gripper.experiments.smoke import OPEN_LOOP_CLOSE, open_loop_grasp_controls

    for name, p in GRIPPERS.items():
        m = build_scene_spec(p, with_object=False).compile()
        u = open_loop_grasp_controls(p, m, 3.0)
        act = drive_for(p).actuator_ids(m)
        np.testing.assert_allclose(u[-1, act], OPEN_LOOP_CLOSE * m.actuator_ctrlrange[act, 1])
        assert u[:, act].min() == 0.0, name
