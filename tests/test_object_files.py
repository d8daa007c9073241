"""Object files, every object spec form through a benchmark and its rerun, declared damage
limits, mesh repair and sizing by the real footprint."""

from __future__ import annotations

import json
import math
import warnings

import numpy as np
import pytest
import trimesh

from gripper.bench.benchmark import BenchConfig, read_trials, run_benchmark
from gripper.core.params import GripperParams
from gripper.core.resources import OBJECTS_DIR
from gripper.experiments.approach import STRADDLE_MARGIN, check_fits_opening, open_radius, straddle_gap
from gripper.experiments.protocol import GraspProtocol
from gripper.experiments.trial import run_trial
from gripper.objects.files import load_object_file
from gripper.objects.library import get_object, mesh_object

SHORT = GraspProtocol(hold_s=0.2, shake_s=0.2)


def _box_stl(path, half=(0.020, 0.020, 0.030)):  # the block's size: the fingers close on it
    trimesh.creation.box(extents=[2 * h for h in half]).export(path)
    return path


def _write(path, text):
    path.write_text(text)
    return path


@pytest.fixture
def user_files(tmp_path):
    stl = _box_stl(tmp_path / "part.stl")
    part = _write(tmp_path / "part.toml", """
[object]
name = "fragile_part"
kind = "mesh"
mesh = "part.stl"
mass = 0.060
friction = 0.7
[damage]
criterion = "contact_force"
limit = 30.0
[reasons]
limit = "a thin-walled print cracks at about 30 N"
""")
    return stl, part


def test_the_built_in_objects_are_object_files():
    for name in ("balloon", "block", "cylinder", "paper_box", "bag", "bag_pack"):
        assert load_object_file(OBJECTS_DIR / f"{name}.toml") == get_object(name)
    assert dict(get_object("block").reasons)["friction"].startswith("silicone on PLA")


def test_every_spec_form_runs_a_benchmark_and_its_rerun(tmp_path, user_files):
    stl, part = user_files
    specs = ("block", str(part), f"mesh:{stl}", f"mesh:{stl}::0.05")
    cfg = BenchConfig(objects=specs, trials=1, protocol=SHORT).validate()
    out = tmp_path / "run"
    first = run_benchmark(cfg, out, workers=1, progress=False)
    assert set(first["objects"]) == {"block", "fragile_part", f"mesh:{stl}", f"mesh:{stl}::0.05"}
    again = run_benchmark(cfg, out, workers=1, progress=False)  # nothing left to run
    assert again["objects"] == first["objects"]
    longer = run_benchmark(BenchConfig(objects=specs, trials=2, protocol=SHORT).validate(), out,
                           workers=1, progress=False)
    recs = read_trials(out / "trials.jsonl")
    keys = [(r.object, r.index) for r in recs]
    assert len(keys) == len(set(keys)) == 8, keys  # no duplicates
    assert keys == [(n, i) for n in cfg.names() for i in range(2)], "trial order kept on extension"
    assert all(longer["objects"][n]["trials"] == 2 for n in cfg.names())
    masses = {r.object: r for r in recs}
    assert masses[f"mesh:{stl}::0.05"]["config_hash"] != masses[f"mesh:{stl}"]["config_hash"]
    for line in (out / "trials.jsonl").read_text().splitlines():  # records round-trip exactly
        rec = json.loads(line)
        assert json.loads(json.dumps(read_trials.__globals__["TrialRecord"].from_dict(rec).to_dict())) == rec


def test_a_declared_force_limit_is_reported_as_damage(user_files):
    _, part = user_files
    rec = run_trial(str(part), 0, 0, protocol=SHORT.replace(policy="per_object"))
    assert rec.status == "ok"
    assert rec.peak_total_force_N > 30.0, "the stalled servos press harder than the part's limit"
    assert rec.damaged and rec.failed_phase == "damage" and not rec.success
    assert rec.damage_limit == 30.0


def test_an_object_without_a_damage_criterion_is_never_damaged(tmp_path):
    f = _write(tmp_path / "tough.toml", """
[object]
name = "tough"
kind = "rigid_box"
size = [0.02, 0.02, 0.03]
density = 1240.0
friction = 0.6
[damage]
criterion = "none"
""")
    obj = load_object_file(f)
    assert obj.mass == pytest.approx(1240.0 * 0.04 * 0.04 * 0.06)
    assert not obj.is_damaged(1e6)


def test_a_repairable_mesh_runs_and_a_hopeless_one_is_refused(tmp_path):
    box = trimesh.creation.box(extents=[0.04, 0.04, 0.06])
    holed = trimesh.Trimesh(box.vertices, box.faces[1:], process=False)  # one triangle missing
    assert not holed.is_watertight
    holed.export(tmp_path / "holed.stl")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        rec = run_trial(f"mesh:{tmp_path / 'holed.stl'}", 0, 0, protocol=SHORT)
    assert rec.status == "ok" and rec.success
    assert any("not watertight" in str(w.message) for w in caught)
    sheet = trimesh.Trimesh([[0, 0, 0], [0.03, 0, 0], [0, 0.03, 0], [0.03, 0.03, 0.001]],
                            [[0, 1, 2], [1, 3, 2]], process=False)  # an open sheet: no volume to close
    sheet.export(tmp_path / "sheet.stl")
    with pytest.raises(ValueError, match="not watertight"):
        mesh_object(tmp_path / "sheet.stl")


def test_a_round_mesh_is_sized_by_its_footprint_not_its_bounding_box(tmp_path):
    APERTURE_RADIUS = open_radius(GripperParams())  # noqa: N806 (the default design's opening)
    STRADDLE_HALF_WIDTH = straddle_gap(GripperParams()) - STRADDLE_MARGIN  # noqa: N806
    r = 0.85 * APERTURE_RADIUS  # its bounding box's half-diagonal 1.2 times the aperture, its footprint inside
    trimesh.creation.cylinder(radius=r, height=0.05, sections=48).export(tmp_path / "round.stl")
    obj = check_fits_opening(mesh_object(tmp_path / "round.stl"), GripperParams())
    assert np.hypot(obj.size[0], obj.size[1]) > APERTURE_RADIUS
    assert obj.half_width == pytest.approx(r, rel=1e-3)
    half = 0.8 * APERTURE_RADIUS  # a square: its half-diagonal outside, its half-width too wide to straddle
    assert half > STRADDLE_HALF_WIDTH
    _box_stl(tmp_path / "wide.stl", half=(half, half, 0.02))
    with pytest.raises(ValueError, match=rf"{math.hypot(half, half):.3f} m over all yaws and its half-width "
                                         rf"{half:.3f} m; the open fingers of this design leave "
                                         rf"{APERTURE_RADIUS:.3f} m, or straddle"):
        check_fits_opening(mesh_object(tmp_path / "wide.stl"), GripperParams())
    # the pneumatic gripper's fingers stand wider open: it takes the part (issue 58: the opening
    # is the design's in use, not the default cable design's frozen at import)
    pneumatic = GripperParams().replace(actuation=GripperParams().actuation.replace(kind="pneumatic"))
    assert open_radius(pneumatic) > math.hypot(half, half)
    check_fits_opening(mesh_object(tmp_path / "wide.stl"), pneumatic)


# A zipper bag's object table and material, without its contents.
_ZIP = ("[object]\nname='x'\nkind='zipper_bag'\nsize=[0.024,0.0113,0.008]\nmass=0.00253\nfriction=0.6\n"
        "close_command=1.5\n[material]\nyoungs_modulus=2.5e8\nthickness=4.25e-5\n[damage]\nlimit=0.05\n")


@pytest.mark.parametrize(("text", "message"), [
    ("[object]\nname='x'\nkind='rigid_box'\nsize=[0.02,0.02,0.03]\nmass=0.1\n", "object.friction: missing"),
    ("[object]\nname='x'\nkind='jelly'\n", "object.kind: must be one of"),
    ("[object]\nname='x'\nkind='rigid_box'\nsize=[0.02,0.02]\nmass=0.1\nfriction=1\n", "object.size: must be three"),
    ("[object]\nname='x'\nkind='rigid_box'\nsize=[0.02,0.02,0.03]\nmass=0.1\nfriction=1\n[damage]\ncriterion='dent'\n",
     "damage.criterion: a rigid_box allows contact_force, none"),
    ("[object]\nname='x'\nkind='rigid_box'\nsize=[0.02,0.02,0.03]\nmass=0.1\nfriction=1\ncolour='red'\n",
     "object.colour: unknown key"),
    ("[object]\nname='x'\nkind='rigid_box'\nsize=[0.02,0.02,0.03]\nmass=0.1\nfriction=1\n",
     "damage.criterion: missing: declare how the object is damaged"),
    ("[object]\nname='x'\nkind='rigid_box'\nsize=[0.02,0.02,0.03]\nmass=0.1\nfriction=1\n[damage]\ncriterion='contact_force'\n",
     "damage.limit: missing"),
    ("[object]\nname='x'\nkind='mesh'\nmesh='nowhere.stl'\nfriction=1\n[damage]\ncriterion='none'\n",
     "object.mesh: mesh .*nowhere.stl: cannot read it"),
    ("[object\n", "not valid TOML"),
    ("[object]\nname='x'\nkind='rigid_box'\nsize=[0.02,0.02,0.03]\nmass=0.1\nfriction=1\nmesh_points=[4,4,5]\n"
     "[damage]\ncriterion='none'\n", "object.mesh_points: a rigid_box is rigid: it takes no mesh resolution"),
    ("[object]\nname='x'\nkind='bag'\nsize=[0.02,0.02,0.03]\nmass=0.1\nfriction=1\nclose_command=1.5\n"
     "mesh_points=[4,4,2]\n[damage]\nlimit=0.1\n[material]\nyoungs_modulus=2e8\nthickness=5e-5\n",
     r"object.mesh_points: must be three whole numbers from 3 to 12 \(points along x, y, z\), got \[4, 4, 2\]"),
    ("[object]\nname='x'\nkind='bag'\nsize=[0.02,0.02,0.03]\nmass=0.1\nfriction=1\nclose_command=1.5\n"
     "mesh_points=[4.5,4,5]\n[damage]\nlimit=0.1\n[material]\nyoungs_modulus=2e8\nthickness=5e-5\n",
     "object.mesh_points: must be three whole numbers"),
    (_ZIP, r"contents.count: must be a whole number from 1 to 64, got None"),
    (_ZIP + "[contents]\ncount=9\nsize=[0.0079,0.0079,0.0057]\nmass=0.0001\n",
     r"contents: 9 items of 15.8 x 15.8 x 11.4 mm do not lie in one layer inside 48 x 23 x 16 mm"),
    (_ZIP + "[contents]\ncount=2\nsize=[0.0079,0.0079,0.0057]\nmass=0.002\n",
     r"contents.mass: each item > 0 kg and all 2 lighter than the bag's total 0.00253 kg"),
    ("[object]\nname='x'\nkind='rigid_box'\nsize=[0.02,0.02,0.03]\nmass=0.1\nfriction=1\n[damage]\n"
     "criterion='none'\n[contents]\ncount=1\n", "contents: only a zipper_bag holds loose contents"),
])
def test_a_bad_object_file_names_the_file_and_the_key(tmp_path, text, message):
    f = _write(tmp_path / "bad.toml", text)
    with pytest.raises(ValueError, match=message) as err:
        load_object_file(f)
    assert str(err.value).startswith(f"object file {f}:") and "\n" not in str(err.value)


def test_a_bad_mass_in_the_shortcut_names_the_field(tmp_path):
    stl = _box_stl(tmp_path / "p.stl")
    with pytest.raises(ValueError, match=r"the mass after '::' must be a number in kg, got 'abc'"):
        get_object(f"mesh:{stl}::abc")


def test_a_corrupt_record_line_is_named(tmp_path):
    out = tmp_path / "run"
    cfg = BenchConfig(objects=("block",), trials=1, protocol=SHORT).validate()
    run_benchmark(cfg, out, workers=1, progress=False)
    path = out / "trials.jsonl"
    path.write_text(path.read_text() + "{not json\n")
    with pytest.raises(ValueError, match=r"trials.jsonl: line 2 is not a JSON record"):
        run_benchmark(cfg, out, workers=1, progress=False)


def test_the_environment_takes_an_object_file(user_files):
    import pickle

    import gymnasium as gym

    _, part = user_files
    env = gym.make("gripper:SoftGripperGrasp-v12", objects=f"block,{part}")
    env.reset(seed=1)
    names = set()
    for seed in range(4):
        _, info = env.reset(seed=seed)
        names.add(info["object"])
    _, _, _, _, info = env.step(env.action_space.sample())
    assert names <= {"block", "fragile_part"} and "fragile_part" in names | {info["object"]}
    clone = pickle.loads(pickle.dumps(env.unwrapped))
    assert clone._ep.scene.obj.name == env.unwrapped._ep.scene.obj.name
