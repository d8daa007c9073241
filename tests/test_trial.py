"""One grasp trial on the rigid block: success, determinism, error handling, pull-out."""

import dataclasses

import mujoco
import numpy as np
import pytest

import gripper.experiments.trial as trial_mod
import gripper.sim.probes as probes_mod
import gripper.sim.scene as scene_mod
import gripper.sim.stepping as stepping_mod
from gripper.core.params import GripperParams
from gripper.drives import drive_for
from gripper.experiments.protocol import GraspProtocol, TrialNoise
from gripper.experiments.pullout import run_pullout
from gripper.experiments.trial import run_trial, sample_placement
from gripper.objects.library import get_object

VOLATILE = ("wall_time_s",)


def _stable(rec):
    return {k: v for k, v in rec.items() if k not in VOLATILE}


PER_OBJECT = GraspProtocol(policy="per_object")


def test_block_trial_succeeds_without_warnings():
    rec = run_trial("block", seed=0, index=0, protocol=PER_OBJECT)
    assert rec["status"] == "ok" and rec["warnings"] == 0
    assert rec["success"], rec
    assert rec["lift_height_m"] >= GraspProtocol().success_height
    assert rec["slip_m"] < GraspProtocol().max_slip
    # the servo stalls on a rigid part: cable tension at the stall torque / spool radius
    assert rec["drive"]["peak_cable_tension_N"] == pytest.approx(1.0787 / 0.020, rel=0.05)
    assert len(rec["peak_finger_force_N"]) == 4 and rec["peak_total_force_N"] > 0


def test_same_seed_same_record():
    a = run_trial("block", seed=3, index=1)
    b = run_trial("block", seed=3, index=1)
    assert _stable(a) == _stable(b)


def test_placement_noise_in_range_and_yaw_only_when_asymmetric():
    noise = TrialNoise(xy=0.01)
    for i in range(20):
        pl = sample_placement(get_object("block"), noise, 0, i)
        assert abs(pl.x) <= 0.01 and abs(pl.y) <= 0.01
        assert sample_placement(get_object("cylinder"), noise, 0, i).yaw == 0.0
    assert len({sample_placement(get_object("block"), noise, 0, i).yaw for i in range(5)}) == 5


def test_negative_noise_is_refused():
    with pytest.raises(ValueError, match="noise.xy"):
        TrialNoise(xy=-0.001).validate()


def _tamper_with_chunk(monkeypatch, n, tamper):
    """Call ``tamper(stepper)`` right after the ``n``-th rollout chunk of every trial."""
    calls = {"n": 0}
    real = stepping_mod.ChunkStepper.step

    def step(self, u):
        sens = real(self, u)
        calls["n"] += 1
        if calls["n"] == n:
            tamper(self)
        return sens

    monkeypatch.setattr(stepping_mod.ChunkStepper, "step", step)


def test_unstable_trial_is_an_error_not_a_failure(monkeypatch):
    """A state that turns non-finite mid-trial (here injected into the 30th chunk's result) is
    recorded as an error, neither a success nor a failure."""
    def nan(stepper):
        stepper.last_states[-1, 1] = float("nan")  # first qpos entry of the chunk's last state

    _tamper_with_chunk(monkeypatch, 30, nan)
    rec = run_trial("block", seed=0, index=0)
    assert rec["status"] == "error" and rec["success"] is None
    assert "non-finite" in rec["error"], rec["error"]


def test_warning_makes_the_trial_an_error(monkeypatch):
    """A MuJoCo warning raised during a chunk turns the trial into an error naming it."""
    def warn(stepper):
        stepper.d.warning[int(mujoco.mjtWarning.mjWARN_BADQACC)].number += 1

    _tamper_with_chunk(monkeypatch, 30, warn)
    rec = run_trial("block", seed=0, index=0)
    assert rec["status"] == "error" and "mjWARN_BADQACC" in rec["error"], rec["error"]


def test_pullout_holding_force_exceeds_weight():
    res = run_pullout("block")
    weight = get_object("block").mass * 9.81
    assert not res["held_at_max"]
    assert res["holding_force_N"] > weight


def test_chunking_does_not_change_physics():
    """Rollout chunks carry the solver warm start: where the chunks are cut changes nothing."""
    a = run_trial("block", seed=0, index=3, protocol=PER_OBJECT.replace(chunk_steps=10))
    b = run_trial("block", seed=0, index=3, protocol=PER_OBJECT.replace(chunk_steps=7))
    for key in ("lift_height_m", "slip_m", "max_slip_m"):
        assert a[key] == b[key], key
    assert a["drive"]["peak_cable_tension_N"] == b["drive"]["peak_cable_tension_N"]


@pytest.mark.parametrize("name, hard_scale, card", [("balloon", 2.5, None), ("paper_box", 2.3, 1.2e-4)])
def test_closing_much_harder_damages_deformable_objects(name, hard_scale, card):
    """Damage is physics, not a label: the default closing command leaves the balloon whole and
    the box undented, while the servo driven to its full travel (scale 2.5 or 2.3 of the
    default, stall tension on the cables) bursts the balloon (membrane strain above 0.25) and
    dents the box (permanent dent beyond 2 mm after spring-back). The box is of thinner card
    (0.12 mm), so that the check does not hinge on the default 0.2 mm box, whose dent at stall
    on this trial (2.4 mm) lies near the limit."""
    obj = get_object(name)
    if card is not None:
        obj = dataclasses.replace(obj, thickness=card)
    soft = run_trial(obj, seed=0, index=0, protocol=PER_OBJECT)
    hard = run_trial(obj, seed=0, index=0, protocol=PER_OBJECT.replace(close_command_scale=hard_scale))
    assert soft["status"] == hard["status"] == "ok"
    assert soft["success"] and not soft["damaged"]
    assert soft["damage_measure"] < 0.5 * obj.damage_limit
    assert hard["damaged"] and hard["failed_phase"] == "damage"
    assert hard["damage_measure"] > obj.damage_limit


def _close_on(name, *, at_grasp_height=False, placed_as=None):
    """Trial 3's scene of ``name`` (placed as the object named ``placed_as`` would be); the
    cables reeled in to 2 rad for 300 steps (0.6 s), the palm at its start height or held at the
    catalogue rule's grasp height. Returns the model, the probe, the stepper and a fresh
    ``MjData`` at the chunk's last state (after ``mj_forward``)."""
    import dataclasses

    obj = get_object(name)
    proto = GraspProtocol()
    p = GripperParams().replace(sim=GripperParams().sim.replace(timestep=proto.timestep))
    drawn = dataclasses.replace(obj, name=placed_as) if placed_as else obj
    m = scene_mod.build_grasp_scene(p, obj, sample_placement(drawn, TrialNoise(), 0, 3))
    d = mujoco.MjData(m)
    u = np.zeros((300, m.nu))
    if at_grasp_height:
        z = trial_mod.grasp_height(p, obj, proto) - p.lift.home_height
        d.qpos[m.jnt_qposadr[m.joint("lift_z").id]] = z
        u[:, m.actuator("lift_z").id] = z
    mujoco.mj_forward(m, d)
    probe = probes_mod.ObjectProbe(m, obj, p.layout.n_fingers, drive_for(p))
    stepper = stepping_mod.ChunkStepper(m, d)
    u[:, probe.actuators] = 2.0  # close on the object
    stepper.step(u)
    fresh = mujoco.MjData(m)
    mujoco.mj_setState(m, fresh, stepper.last_states[-1], stepping_mod.STATE_SPEC)
    mujoco.mj_forward(m, fresh)
    return m, probe, stepper, fresh


@pytest.mark.parametrize("name", ["balloon", "bag", "bag_pack"])
def test_flex_strain_is_read_at_every_step(name):
    """The trial's flex strain comes from every step's state (rollout rows), not only from the
    chunk's end: the per-step reading of the last row equals a fresh evaluation of that state,
    and the chunk's maximum is at least its last value."""
    _, probe, stepper, fresh = _close_on(name)
    last = probe.edge_strain_steps(stepper.last_states[-1:])
    assert last == pytest.approx(probe.edge_strain(fresh), abs=1e-9)
    assert probe.edge_strain_steps(stepper.last_states) >= last


def test_bag_pack_does_not_sink_through_the_film():
    """The rigid pack and the film it presses on touch as stiffly as fingers and film: with the
    palm at grasp height and the cables reeled in (0.6 s, 3-5 N per finger), no pack-film
    contact goes deeper than twice the film's collision radius (the film is 50 µm thick; its
    collision shell is 0.7 mm). With MuJoCo's default on the pack's side the pack sank 8-14 mm
    into the film here, and 10-17 mm in full trials."""
    m, probe, _, f = _close_on("bag_pack", at_grasp_height=True, placed_as="bag")  # 0.11.0's bag trial 3
    # The fingers do press on the pack (3-5 N each with the calibrated springs of 0.6.0; 15 N
    # with 0.5.x's stiff springs, see docs/calibration.md on the bag).
    assert (probe.finger_forces(f) > 2.0).all()
    pack = m.geom("object_contents_geom").id
    depth = [-f.contact[i].dist for i in range(f.ncon)
             if pack in f.contact[i].geom and (f.contact[i].flex >= 0).any()]
    assert depth and max(depth) < 2.0 * float(m.flex_radius[probe.flex])


def test_grasp_outcome_does_not_depend_on_the_time_step():
    """The closed cut's compliance is a material property (gripper.drives.cable.closure), so halving the step
    changes the outcome not at all and the squeeze little. With the rigid stop, whose overrun
    grows as the step squared, this cylinder is held at 2 ms and drops out in the hold at 1 ms.
    The envelope grasp is the one this was measured on; the fingertip grasp's peak force is
    25-35 % lower at 2 ms than at 1 ms (docs/limitations.md)."""
    recs = [run_trial("cylinder", seed=0, index=1, protocol=GraspProtocol(timestep=dt, grasp="envelope"))
            for dt in (0.001, 0.002)]
    assert all(r["status"] == "ok" and r["success"] for r in recs)


@pytest.mark.parametrize("obj", ["block", "cylinder"])
def test_grasp_squeeze_converges_in_the_step(obj):
    """Peak total force at 1 and 2 ms, the control period held at 40 ms: within the issue's 5 %.
    With 0.16.0's contact (MuJoCo's default softness on the elements) the cylinder's envelope
    grasp squeezed 11.39 N at 1 ms and 9.90 N at 2 ms (15 %), and the fingertip grasp 25-35 %
    less at 2 ms: the contact's stiffness scaled with the step's effective metric. The pads carry
    the silicone's law in N/m (gripper.parts.pads), so the squeeze is the finger's statics'."""
    recs = [run_trial(obj, seed=1, index=0, protocol=GraspProtocol(timestep=dt, chunk_steps=round(0.04 / dt)))
            for dt in (0.001, 0.002)]
    assert all(r["status"] == "ok" and r["success"] for r in recs)
    assert recs[0]["peak_total_force_N"] == pytest.approx(recs[1]["peak_total_force_N"], rel=0.05)


def test_pullout_of_a_grasp_that_did_not_lift_holds_nothing():
    """A pull down on a part still on the table loads the table: the holding force is 0, not the
    pull's bound (the pneumatic gripper at 100 kPa does not lift the block)."""
    p = GripperParams()
    p = p.replace(actuation=p.actuation.replace(kind="pneumatic"))
    res = run_pullout("block", params=p, protocol=GraspProtocol(grip_pressure=100e3))
    assert res["lifted"] is False and res["holding_force_N"] == 0.0 and not res["held_at_max"]
