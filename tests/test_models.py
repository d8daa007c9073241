import mujoco
import pytest

from gripper.menagerie import REPO_MODELS, generate_model_files, readme_with_table
from gripper.params import GripperParams
from gripper.smoke import random_control_rollout


def test_committed_models_match_fresh_generation():
    fresh = generate_model_files()
    for name, text in fresh.items():
        committed = (REPO_MODELS / name).read_text()
        assert committed == text, f"{name} is stale: run scripts/write_models.sh"
    readme = (REPO_MODELS / "README.md").read_text()
    assert readme == readme_with_table(readme), "model README table is stale"


def test_committed_scene_loads():
    m = mujoco.MjModel.from_xml_path(str(REPO_MODELS / "scene.xml"))
    assert m.nu == 7 and m.ntendon == 4
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
