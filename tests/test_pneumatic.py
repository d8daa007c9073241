"""The pneumatic gripper: the regulator against its datasheet, the chain's statics against the
closed form, the committed calibration against paper 001's actuator in finite elements, and the
gripper in a trial and in the environment."""

import json
import math

import mujoco
import numpy as np
import pytest

from gripper.calibration.pneumatic_fit import (
    ChainStatics,
    _finger_params,
    chain_tips,
    stale_reasons,
)
from gripper.core.params import PNEUMATIC_CALIBRATION_FILE, GripperParams
from gripper.datasheets.regulator import RESPONSE_FRACTION, regulator_datasheet
from gripper.model.builders import build_gripper_spec
from gripper.references.actuator_bending import ActuatorRecord
from gripper.references.pneumatic_params import PneumaticActuator

COMMITTED = json.loads(PNEUMATIC_CALIBRATION_FILE.read_text())
RECORD = ActuatorRecord.from_json_dict(json.loads((PNEUMATIC_CALIBRATION_FILE.parent / "reference.json").read_text()))


def pneumatic(**changes) -> GripperParams:
    p = GripperParams()
    return p.replace(actuation=p.actuation.replace(kind="pneumatic"), **changes)


def test_regulator_reproduces_its_datasheet():
    """A set-point step on the built gripper's chamber actuator: the pressure reaches 90 % of the
    step in the datasheet's response time (within 5 %), settles on the set-point within the
    datasheet's linearity, and a set-point past the range is held at the range's end."""
    p = pneumatic()
    ds = regulator_datasheet(p.pneumatic.regulator)
    m = build_gripper_spec(p.replace(sim=p.sim.replace(timestep=1e-4))).compile()
    d = mujoco.MjData(m)
    act = m.actuator("f0_chamber").id
    step = 200e3
    d.ctrl[act] = step
    times, pressure = [], []
    while d.time < 5 * ds.response_time:
        mujoco.mj_step(m, d)
        times.append(d.time)
        pressure.append(d.act[m.actuator_actadr[act]])
    t90 = times[int(np.argmax(np.array(pressure) >= RESPONSE_FRACTION * step))]
    assert t90 == pytest.approx(ds.response_time, rel=0.05)
    assert abs(pressure[-1] - step) <= ds.linearity * ds.pressure_max
    assert m.actuator_ctrlrange[act, 1] == min(p.pneumatic.pressure_max, ds.pressure_max)
    assert ds.output(2 * ds.pressure_max) == ds.pressure_max and ds.output(0.5 * ds.pressure_min) == 0.0


def test_chain_statics_match_the_closed_form():
    """No gravity and a pressure below the knee: every inner hinge turns g p / k and the root
    g p / k_root (the chamber tendon gives each hinge the same moment)."""
    p = _finger_params(pneumatic(), PneumaticActuator(), RECORD)
    st = ChainStatics(p)
    pf = p.pneumatic
    pressure = 0.2 * pf.knee_curvature * pf.bending_stiffness / pf.moment_per_pascal  # inner hinges at 20 % of the knee
    q, _ = st.rest(pressure, np.zeros(3))
    g = pf.moment_per_pascal * pressure
    assert q[0] == pytest.approx(g / pf.root_stiffness, rel=1e-6)
    assert np.allclose(q[1:], g / pf.hinge_stiffness, rtol=1e-6)


def test_committed_pneumatic_calibration_meets_its_lines():
    """Fresh, and the committed values put the chain's tip at rest within 3 % of the length of the
    finite-element actuator's over the fitted pressures and 5 % at the held-out one, recomputed
    here from the committed reference record."""
    assert stale_reasons(COMMITTED) == []
    fitted = COMMITTED["fitted"]
    pf = GripperParams().pneumatic
    assert {k: getattr(pf, k) for k in fitted} == fitted  # the defaults are the committed fit
    p = _finger_params(pneumatic(), PneumaticActuator(), RECORD)
    tips, sag = chain_tips(ChainStatics(p), fitted, RECORD)
    err = np.linalg.norm(tips - RECORD.tip, axis=1) / RECORD.length
    held = np.isin(RECORD.pressures / 1e3, [h["pressure_kPa"] for h in COMMITTED["metrics"]["held_out"]])
    assert held.sum() == 1
    assert math.sqrt(np.mean(err[~held] ** 2)) <= 0.03
    assert err[held].max() <= 0.05
    assert np.linalg.norm(sag - RECORD.sag_tip) / RECORD.length <= 0.03
    assert COMMITTED["metrics"]["fit_wall_time_s"] < 60


def test_a_changed_actuator_makes_the_pneumatic_calibration_stale():
    changed = dict(COMMITTED, design_hash="0" * 16)
    assert any("design hash" in r for r in stale_reasons(changed))


def test_segment_count_keeps_the_calibrated_bend():
    """Springs are stored per length: a finger of 12 segments bends like the default's 8 (its
    tip at 250 kPa within 1 % of the length)."""
    p8 = _finger_params(pneumatic(), PneumaticActuator(), RECORD)
    p12 = p8.replace(pneumatic=p8.pneumatic.replace(n_segments=12))
    g = np.array([RECORD.gravity, 0.0, 0.0])
    _, tip8 = ChainStatics(p8).rest(250e3, g)
    _, tip12 = ChainStatics(p12).rest(250e3, g)
    assert np.linalg.norm(tip12 - tip8) / RECORD.length < 0.01


def test_pneumatic_trial_grasps_the_block():
    from gripper.experiments.trial import run_trial

    r = run_trial("block", seed=1, index=0, params=pneumatic())
    assert r["status"] == "ok" and r["success"] and r["warnings"] == 0
    assert r["drive"]["kind"] == "pneumatic" and r["drive"]["grip_pressure_Pa"] == 250e3
    assert r["drive"]["peak_pressure_Pa"] == pytest.approx(250e3, rel=0.01)
    assert "close_command_Pa" not in r["drive"] and r["grasp_time_s"] is not None
    assert not any("cable" in key for key in (*r, *r["drive"]))


def test_pneumatic_set_points_are_checked():
    from gripper.drives import drive_for
    from gripper.experiments.protocol import GraspProtocol

    drive = drive_for(pneumatic())
    with pytest.raises(ValueError, match=r"^protocol.grip_pressure: must be in \(0, 250000\] Pa"):
        drive.check_set_point(GraspProtocol(grip_pressure=300e3))
    with pytest.raises(ValueError, match="^protocol.policy: the pneumatic gripper"):
        drive.check_set_point(GraspProtocol(policy="per_object"))


def test_environment_with_the_pneumatic_gripper():
    import gymnasium as gym
    from gymnasium.utils.env_checker import check_env

    import gripper  # noqa: F401  (registers the environment)
    from gripper.envs.grasp_env import ENV_ID

    env = gym.make(ENV_ID, actuation="pneumatic")
    check_env(env.unwrapped, skip_render_check=True)
    struct = env.unwrapped.observation_structure
    assert "chamber_pressure" in struct and "cable_tension" not in struct

    def episode():
        e = gym.make(ENV_ID, actuation="pneumatic")
        obs, _ = e.reset(seed=7)
        e.action_space.seed(7)
        out = [obs]
        for _ in range(25):
            out.append(e.step(e.action_space.sample())[0])
        return np.array(out)

    a, b = episode(), episode()
    assert np.array_equal(a, b)
    i, n, _ = struct["pressure_setpoint"]
    assert a[-1, i:i + n].max() > 0  # the set-points moved


def test_docs_show_the_committed_report():
    from gripper.calibration.pneumatic_fit import DOCS_REPORT

    if not DOCS_REPORT.parent.is_dir():
        pytest.skip("an installed package: no docs folder")
    assert DOCS_REPORT.read_bytes() == (PNEUMATIC_CALIBRATION_FILE.parent / "report.png").read_bytes()


def test_a_pneumatic_study_refuses_the_cable_responses(tmp_path):
    from gripper.studies.study_file import load_study

    study = tmp_path / "s.toml"
    study.write_text('[study]\nname = "x"\ndesign = "one_at_a_time"\n[fixed]\n"actuation.kind" = "pneumatic"\n'
                     '[vary]\n"pneumatic.n_segments" = [4]\n[responses]\nbending = { r_max = 0.45 }\n')
    with pytest.raises(ValueError, match="responses.bending: the pneumatic gripper's drive has no such response"):
        load_study(study)
    shipped = load_study("pneumatic_segments")
    assert shipped.base.actuation.kind == "pneumatic"


def test_random_commands_keep_the_pneumatic_gripper_stable():
    """Menagerie's smoke check at the model's own step: every actuator (chambers and stages) at a
    new random command every 0.1 s for 2 s, with no MuJoCo warning (explicit springs diverged at
    1 ms; the builder gives the pneumatic gripper the discrete integrator)."""
    from gripper.experiments.smoke import random_control_rollout

    for seed in (0, 1):
        assert random_control_rollout(pneumatic(), duration=2.0, seed=seed)["steps"] == 2000


def test_cable_only_commands_refuse_the_pneumatic_gripper():
    import subprocess
    import sys

    done = subprocess.run([sys.executable, "-m", "gripper.cli.main", "bend", "--actuation", "pneumatic"],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 2
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and "gripper bend tests the cable finger" in lines[0]


@pytest.mark.slow
def test_the_committed_reference_is_the_finite_element_model_now():
    """The committed reference record is what the finite-element model gives today (about 1.5
    minutes): tips within 0.1 mm, and the fit from it lands on the committed values within 1 %."""
    from gripper.calibration.pneumatic_fit import fit_pneumatic
    from gripper.references.actuator_bending import run_actuator_reference

    fresh = run_actuator_reference()
    assert np.allclose(fresh.tip, RECORD.tip, atol=1e-4) and np.allclose(fresh.sag_tip, RECORD.sag_tip, atol=1e-4)
    fit = fit_pneumatic(fresh)
    for k, v in COMMITTED["fitted"].items():
        assert fit.values[k] == pytest.approx(v, rel=0.01), k
