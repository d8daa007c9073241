"""The sensed approach and the fingertip grasp (gripper.experiments.approach, trial)."""

from __future__ import annotations

import dataclasses
import math

import pytest

import gripper.experiments.trial as trial_module
from gripper.core.params import GripperParams
from gripper.experiments.approach import choose_grasp, finger_reach, open_radius
from gripper.experiments.protocol import GraspProtocol, TrialNoise
from gripper.experiments.trial import run_trial
from gripper.objects.grasp_object import GraspObject
from gripper.objects.library import get_object
from gripper.objects.scene_objects import Placement
from gripper.sim.depth import ObjectEstimate

P = GripperParams()


def _box(w, h, mass=0.08, name="box"):
    return GraspObject(name=name, kind="rigid_box", size=(w / 2, w / 2, h / 2), mass=mass, friction=0.6,
                       yaw_symmetric=False, close_command=3.0, damage="none", damage_limit=0.0)


def _estimate(height, radius):
    """A disc's footprint: its rectangle 2r across both ways."""
    return ObjectEstimate(support_z=0.0, top_z=height, x=0.0, y=0.0, length=2 * radius, width=2 * radius, yaw=0.0,
                          radius=radius, pixels=100)


def test_the_grasp_rule_is_geometry():
    proto = GraspProtocol()
    # low and inside the open fingers: the tips go down beside it
    assert choose_grasp(_estimate(0.044, 0.025), P, proto) == "fingertip"
    # taller than the straight fingers (less the palm's clearance): the envelope from above
    assert choose_grasp(_estimate(P.finger.length, 0.025), P, proto) == "envelope"
    # wider than the open fingers' grasping faces at their tips: the tips would land on it
    inside = open_radius(P) - proto.fingertip_margin
    assert choose_grasp(_estimate(0.044, inside + 0.001), P, proto) == "envelope"
    assert choose_grasp(_estimate(0.044, inside - 0.001), P, proto) == "fingertip"
    assert choose_grasp(_estimate(0.044, 0.025), P, proto.replace(grasp="envelope")) == "envelope"


def test_free_closing_reach_is_the_fingers_own():
    angles, low, radial = finger_reach(P.replace(sim=P.sim.replace(timestep=0.002)))
    # straight: splayed by the mount's tilt t, the grasping face's tip corner lowest, L cos t + h sin t
    # below the palm; the grasping face at the palm radius at the mount
    t = math.radians(P.layout.mount_tilt_deg)
    assert low[0] == pytest.approx(P.finger.length * math.cos(t) + P.finger.height * math.sin(t), abs=1.5e-3)
    # (the pads' rounded top edge leaves the face's first vertex below the palm, where the splay
    # has carried it outwards: up to the edge radius more)
    assert radial[0] == pytest.approx(P.layout.palm_radius, abs=1.5e-3 + P.contact.edge_radius)
    assert (low[-1] < low[0] - 0.04) and radial.min() < 0.5 * P.layout.palm_radius


def test_the_grasp_reads_no_field_of_the_object(monkeypatch):
    """Told a wrong size (and closing command), the sensed grasp makes the same trial: the scene
    is built from the real object, and nothing the policy does comes from the description."""
    real = get_object("block")
    wrong = dataclasses.replace(real, size=(0.010, 0.010, 0.012), close_command=0.5)
    build = trial_module.build_grasp_scene
    monkeypatch.setattr(trial_module, "build_grasp_scene", lambda p, obj, place: build(p, real, place))
    place = Placement(x=0.008, y=-0.005, yaw=0.3)
    a = run_trial(real, seed=1, index=0, placement=place).to_dict()
    b = run_trial(wrong, seed=1, index=0, placement=place).to_dict()
    for key in ("success", "lift_height_m", "max_slip_m", "peak_total_force_N", "peak_finger_force_N",
                "grasp", "palm_xy_m", "depth_estimate", "drive", "grasp_time_s"):
        assert a[key] == b[key], key
    assert a["success"]


def test_an_empty_table_is_reported_not_failed():
    rec = run_trial("block", seed=1, index=0, placement=Placement(x=0.3))
    assert rec.status == "no_object"
    assert rec.success is None and rec.failed_phase is None
    assert "no object seen" in rec.error


def test_palm_is_centred_over_the_sensed_object():
    rec = run_trial("cylinder", seed=1, index=0, noise=TrialNoise(xy=0.02))
    px, py = rec.perturbation["x_m"], rec.perturbation["y_m"]
    assert rec.palm_xy_m == pytest.approx([px, py], abs=2e-3)  # within a camera pixel or so


@pytest.mark.parametrize("index", range(3))
def test_fingertip_grasp_holds_a_low_part_the_envelope_cannot(index):
    """The bag's pack alone (36 x 36 x 44 mm, 80 g) was held 0 of 8 times by the envelope grasp
    (docs/controller.md, 0.11.0); the fingertips, closing along the table, hold it."""
    pack = _box(0.036, 0.044, name="pack")
    tip = run_trial(pack, seed=1, index=index)
    assert tip.grasp == "fingertip"
    assert tip.success, tip.failed_phase
    env = run_trial(pack, seed=1, index=index, protocol=GraspProtocol(grasp="envelope"))
    assert not env.success


def test_no_object_trials_are_counted_apart_from_errors():
    from gripper.bench.benchmark import BenchConfig, summarize

    rec = run_trial("block", seed=1, index=0, placement=Placement(x=0.3)).to_dict()
    s = summarize([rec], BenchConfig(objects=("block",), trials=1).validate())["objects"]["block"]
    assert s["no_object"] == 1 and s["errors"] == 0 and s["success_rate"] is None


@pytest.mark.slow
@pytest.mark.parametrize("index", range(3))
def test_the_zipper_bag_is_held_undamaged(index):
    rec = run_trial("bag", seed=1, index=index)
    assert rec.status == "ok" and rec.warnings == 0
    assert rec.grasp == "fingertip" and rec.success and not rec.damaged
