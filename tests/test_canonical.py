"""Balloon models are the same numbers in every process (see gripper.sim.canonical)."""

import json
import subprocess
import sys

import numpy as np
import pytest

import gripper.sim.canonical as canonical
from gripper.core.params import GripperParams
from gripper.experiments.trial import run_trial
from gripper.objects.library import get_object
from gripper.objects.scene_objects import Placement
from gripper.sim.scene import build_grasp_scene

CHILD = """
import sys, numpy as np
from gripper.objects.scene_objects import Placement
from gripper.objects.library import get_object
from gripper.core.params import GripperParams
from gripper.experiments.trial import build_grasp_scene
m = build_grasp_scene(GripperParams(), get_object("balloon"), Placement(x=0.004, y=-0.003))
np.savez(sys.argv[1], flex_stiffness=m.flex_stiffness, body_mass=m.body_mass, dof_M0=m.dof_M0)
"""


def test_balloon_model_does_not_depend_on_what_the_process_compiled_before(tmp_path):
    """MuJoCo 4.0.0 compiles the interpolated balloon flex with last-bit differences that depend
    on the process's earlier compiles, and a balloon grasp amplifies them into a different trial.
    A fresh interpreter and this one (after other scenes) must give bit-identical constants."""
    balloon = get_object("balloon")
    build_grasp_scene(GripperParams(), balloon, Placement(x=-0.009, y=0.002))  # some history
    build_grasp_scene(GripperParams(), get_object("paper_box"), Placement())
    here = build_grasp_scene(GripperParams(), balloon, Placement(x=0.004, y=-0.003))
    path = tmp_path / "fresh.npz"
    subprocess.run([sys.executable, "-c", CHILD, str(path)], check=True, timeout=300)
    with np.load(path) as fresh:
        for name in fresh.files:
            assert np.array_equal(getattr(here, name), fresh[name]), name


def test_mass_scale_still_scales_the_balloon():
    base = build_grasp_scene(GripperParams(), get_object("balloon"), Placement())
    heavy = build_grasp_scene(GripperParams(), get_object("balloon"), Placement(mass_scale=1.2))
    nodes = [b for b in range(base.nbody) if base.body(b).name.startswith("object")]
    assert np.allclose(heavy.body_mass[nodes], 1.2 * base.body_mass[nodes], rtol=1e-12)
    assert abs(heavy.body_mass[nodes].sum() - 1.2 * get_object("balloon").mass) < 1e-9


def test_failed_canonical_compile_is_one_clear_error(monkeypatch):

    def failing(*a, **k):
        return subprocess.CompletedProcess(a, 1, "", "Traceback ...\nImportError: no gripper here\n")

    monkeypatch.setattr(canonical, "_CACHE", {})
    monkeypatch.setattr(canonical.subprocess, "run", failing)
    with pytest.raises(RuntimeError, match="canonical compile of balloon failed.*no gripper here"):
        canonical.canonical_flex_constants(get_object("balloon"))


TRIAL_CHILD = """
import json, sys
from gripper.experiments.trial import run_trial
rec = run_trial("balloon", seed=0, index=20)
json.dump({k: v for k, v in rec.items() if k != "wall_time_s"}, open(sys.argv[1], "w"))
"""


def test_balloon_trial_is_the_same_in_a_fresh_process(tmp_path):
    """The whole record of a balloon trial, here after other scenes, equals the record of the
    same trial in a fresh interpreter (before the canonical constants it did not)."""
    run_trial("balloon", seed=0, index=0)
    here = {k: v for k, v in run_trial("balloon", seed=0, index=20).items() if k != "wall_time_s"}
    path = tmp_path / "fresh.json"
    subprocess.run([sys.executable, "-c", TRIAL_CHILD, str(path)], check=True, timeout=300)
    assert json.loads(json.dumps(here)) == json.loads(path.read_text())
