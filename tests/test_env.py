"""Gymnasium environment: API checks, determinism, vector env equality, docs, bad input."""

import pickle
import re
import warnings
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest
from conftest import needs_gl
from gymnasium.utils.env_checker import check_env

import gripper  # noqa: F401  (registers the environment)
from gripper.envs.grasp_env import SoftGripperGraspEnv

ENV_ID = "gripper:SoftGripperGrasp-v12"

# Warnings check_env may raise, each with its reason:
ALLOWED_WARNINGS = (
    # the observation holds unbounded physical quantities (velocities, forces), as in
    # Gymnasium's own MuJoCo environments, whose spaces are also (-inf, inf)
    "A Box observation space minimum value is -infinity",
    "A Box observation space maximum value is infinity",
)


def test_check_env_passes_with_allow_listed_warnings_only():
    env = gym.make(ENV_ID, objects="block")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(env.unwrapped)
    unexpected = [str(w.message) for w in caught if not any(a in str(w.message) for a in ALLOWED_WARNINGS)]
    assert unexpected == []


def _rollout(env, seed, n=200):
    obs, _ = env.reset(seed=seed)
    rng = np.random.default_rng(seed)
    out = [obs]
    env.action_space.seed(seed)
    for _ in range(n):
        obs, _, term, trunc, _ = env.step(rng.uniform(-1, 1, env.action_space.shape))
        out.append(obs)
        if term or trunc:
            obs, _ = env.reset()
            out.append(obs)
    return np.array(out)


def test_same_seed_same_episode():
    a = _rollout(gym.make(ENV_ID, objects="block,cylinder"), seed=3)
    b = _rollout(gym.make(ENV_ID, objects="block,cylinder"), seed=3)
    assert np.array_equal(a, b)
    c = _rollout(gym.make(ENV_ID, objects="block,cylinder"), seed=4, n=20)
    assert not np.array_equal(a[:21], c)


def test_reset_state_identical_after_a_step():
    """As Gymnasium's check_mujoco_reset_state: reset(seed) after stepping gives the same state."""
    env = gym.make(ENV_ID, objects="block")
    obs1, _ = env.reset(seed=11)
    d1 = env.unwrapped._ep.data
    q1, v1 = d1.qpos.copy(), d1.qvel.copy()
    env.step(env.action_space.sample())
    obs2, _ = env.reset(seed=11)
    d2 = env.unwrapped._ep.data
    assert np.array_equal(obs1, obs2)
    assert np.array_equal(q1, d2.qpos) and np.array_equal(v1, d2.qvel)


@pytest.mark.parametrize("nthread", [None, 0])
def test_native_vector_env_equals_single_envs(nthread):
    n = 3
    venv = gym.make_vec(ENV_ID, num_envs=n, vectorization_mode="vector_entry_point", nthread=nthread,
                        objects="block,cylinder", max_episode_steps=40)
    singles = [gym.make(ENV_ID, objects="block,cylinder", max_episode_steps=40) for _ in range(n)]
    vobs, _ = venv.reset(seed=20)
    sobs = [e.reset(seed=20 + i)[0] for i, e in enumerate(singles)]
    assert np.array_equal(vobs, np.stack(sobs))
    rng = np.random.default_rng(0)
    pending = [False] * n
    ends = 0
    for _ in range(90):
        act = rng.uniform(-1, 1, (n,) + singles[0].action_space.shape)
        vobs, vrew, vterm, vtrunc, _ = venv.step(act)
        for i, e in enumerate(singles):
            if pending[i]:  # NEXT_STEP autoreset: this step resets the slot
                o, _ = e.reset()
                r, te, tr = 0.0, False, False
            else:
                o, r, te, tr, _ = e.step(act[i])
            pending[i] = te or tr
            ends += pending[i]
            assert np.array_equal(vobs[i], o)
            assert vrew[i] == r and vterm[i] == te and vtrunc[i] == tr
    assert ends >= n  # every slot went through at least one truncation and autoreset


def test_sync_and_async_vector_envs_and_pickle():
    for mode in ("sync", "async"):
        venv = gym.make_vec(ENV_ID, num_envs=2, vectorization_mode=mode, objects="block")
        obs, _ = venv.reset(seed=0)
        obs2, *_ = venv.step(venv.action_space.sample())
        assert obs2.shape == (2, 107)
        venv.close()
    env = gym.make(ENV_ID, objects="block")
    env.reset(seed=1)
    env.step(env.action_space.sample())
    clone = pickle.loads(pickle.dumps(env))
    a = env.action_space.sample()
    assert np.array_equal(env.step(a)[0], clone.step(a)[0])


def _doc_table(doc: str, heading: str) -> list[list[str]]:
    section = doc.split(f"## {heading}")[1].split("## ")[0]
    rows = [r.strip() for r in section.splitlines() if r.strip().startswith("|")]
    return [[c.strip() for c in r.strip("|").split("|")] for r in rows[2:]]


ENV_PAGE = (Path(__file__).parents[1] / "docs" / "environment.md").read_text()


def test_docs_tables_match_spaces():
    """docs/environment.md's action and observation tables are the environment's spaces."""
    env = SoftGripperGraspEnv(objects="block")
    rows = _doc_table(ENV_PAGE, "Observation space")
    struct = env.observation_structure
    assert [r[0] for r in rows] == list(struct)
    for name, idx, size, unit in rows:
        start, n, u = struct[name]
        assert idx == f"{start}-{start + n - 1}" and int(size) == n and unit == u
    assert f"({env.observation_space.shape[0]},)" in ENV_PAGE
    assert f"({env.observation_space.shape[0]},)" in (SoftGripperGraspEnv.__doc__ or "")
    actions = _doc_table(ENV_PAGE, "Action space")
    for mode, extra in (("fingers", 0), ("synergy", 0), ("fingers", 2)):
        e = SoftGripperGraspEnv(objects="block", action_mode=mode, xy_actions=bool(extra))
        listed = 0
        for r in actions:
            if r[0] in (mode, "either, xy_actions" if extra else mode):
                a, _, b = r[1].partition("-")
                listed += int(b or a) - int(a) + 1 if r[0] != "either, xy_actions" else 2
        assert listed == e.action_space.shape[0]


@pytest.mark.parametrize("kwargs, field", [
    ({"objects": "teapot"}, "unknown object"),
    ({"render_mode": "video"}, "render_mode"),
    ({"action_mode": "claw"}, "action_mode"),
    ({"pose_noise": -0.1}, "pose_noise"),
    ({"camera": "drone"}, "camera"),
    ({"palm_control": "torque"}, "palm_control"),
    ({"palm_speed": 0.0}, "palm_speed"),
    ({"servo_control": "pwm"}, "servo_control"),
])
def test_bad_constructor_arguments(kwargs, field):
    with pytest.raises(ValueError, match=re.escape(field)):
        SoftGripperGraspEnv(**kwargs)


def test_bad_actions():
    env = SoftGripperGraspEnv(objects="block")
    env.reset(seed=0)
    with pytest.raises(ValueError, match="action: expected shape"):
        env.step(np.zeros(3))
    with pytest.raises(ValueError, match="action: contains NaN"):
        env.step(np.full(5, np.nan))


@needs_gl
def test_rgb_and_depth_rendering():
    env = SoftGripperGraspEnv(objects="block", render_mode="rgb_array", width=160, height=120)
    env.reset(seed=0)
    img = env.render()
    assert img.shape == (120, 160, 3) and img.std() > 5
    env = SoftGripperGraspEnv(objects="block", render_mode="depth_array", width=160, height=120)
    env.reset(seed=0)
    depth = env.render()
    assert depth.shape == (120, 160) and 0.1 < float(np.median(depth)) < 2.0  # metres, camera 0.5 m away


def test_unstable_simulation_ends_the_episode_and_is_reported():
    env = SoftGripperGraspEnv(objects="block")
    obs0, _ = env.reset(seed=0)
    env._ep.data.qvel[:] = 1e12  # a diverging state, as a blown-up solver would leave
    obs, reward, terminated, truncated, info = env.step(np.zeros(5))
    assert terminated and info["unstable"]
    assert "warning" in info["error"] or "non-finite" in info["error"]
    assert np.isfinite(obs).all() and reward == 0.0


def test_vector_env_with_deformable_and_rigid_objects():
    """Scenes of different sizes (flex balloon, rigid block) are stepped in separate rollout
    groups and still match single environments exactly."""
    n = 3
    venv = gym.make_vec(ENV_ID, num_envs=n, vectorization_mode="vector_entry_point", objects="block,balloon")
    singles = [gym.make(ENV_ID, objects="block,balloon") for _ in range(n)]
    vobs, vinfo = venv.reset(seed=0)
    assert len(set(vinfo["object"])) == 2  # both kinds present with this seed
    for i, e in enumerate(singles):
        assert np.array_equal(e.reset(seed=i)[0], vobs[i])
    rng = np.random.default_rng(1)
    for _ in range(5):
        act = rng.uniform(-1, 1, (n, 5))
        vobs, *_ = venv.step(act)
        for i, e in enumerate(singles):
            assert np.array_equal(e.step(act[i])[0], vobs[i])


def test_vector_env_finds_the_unstable_slot():
    """A warning in the batched rollout is traced back to the slot that raised it (replay)."""
    venv = gym.make_vec(ENV_ID, num_envs=3, vectorization_mode="vector_entry_point", nthread=2, objects="block")
    venv.reset(seed=0)
    venv.unwrapped._eps[1].data.qvel[:] = 1e12  # slot 1 diverges
    _, reward, terminated, _, info = venv.step(np.zeros((3, 5)))
    assert list(terminated) == [False, True, False]
    assert list(info["unstable"]) == [False, True, False] and reward[1] == 0.0


def test_velocity_palm_moves_its_set_point_at_palm_speed_and_stays_in_range():
    """Velocity action: each +-1 step moves the lift set-point palm_speed x 20 ms, 0 holds it,
    and it stops at the range's ends (home 0.25 m; fingertips 4 mm above the floor)."""
    env = SoftGripperGraspEnv(objects="block", action_mode="synergy", scale_observations=False)
    obs, _ = env.reset(seed=0)
    i = env.observation_structure["palm_setpoint"][0] + 2
    z0 = obs[i]
    step = env.config.palm_speed * env.config.control_period
    for k in range(1, 6):
        obs, *_ = env.step(np.array([-1.0, 1.0]))
        assert obs[i] == pytest.approx(z0 + k * step, abs=1e-12)
    obs, *_ = env.step(np.array([-1.0, 0.0]))
    assert obs[i] == pytest.approx(z0 + 5 * step, abs=1e-12)
    for _ in range(60):
        obs, *_ = env.step(np.array([-1.0, 1.0]))
    assert obs[i] == pytest.approx(0.25, abs=1e-12)
    assert abs(obs[env.observation_structure["palm_height"][0]] - 0.25) < 2e-3  # the stage follows
    for _ in range(150):
        obs, *_ = env.step(np.array([-1.0, -1.0]))
    assert obs[i] == pytest.approx(env.config.params.finger.length + 0.004, abs=1e-12)


def test_position_control_keeps_the_v3_actions():
    """palm_control and servo_control "position": the entries are the set-points themselves."""
    env = SoftGripperGraspEnv(objects="block", action_mode="synergy", scale_observations=False, palm_control="position",
                              servo_control="position")
    env.reset(seed=0)
    a, c = env.unwrapped.lift_action(0.2), env.unwrapped.servo_action(1.2)
    for _ in range(3):
        obs, *_ = env.step(np.array([c, a]))
    assert obs[env.observation_structure["palm_setpoint"][0] + 2] == pytest.approx(0.2, abs=1e-12)
    assert obs[env.observation_structure["servo_setpoint"][0]] == pytest.approx(1.2, abs=1e-12)


def test_velocity_servo_moves_its_set_point_at_the_slew_rate():
    env = SoftGripperGraspEnv(objects="block", action_mode="synergy", scale_observations=False)
    obs, _ = env.reset(seed=0)
    i = env.observation_structure["servo_setpoint"][0]
    step = env.config.params.servo.slew_rate * env.config.control_period
    assert obs[i] == 0.0  # the fingers start open
    for k in range(1, 4):
        obs, *_ = env.step(np.array([0.5, 0.0]))
        assert obs[i] == pytest.approx(0.5 * k * step, abs=1e-12)
    for _ in range(10):
        obs, *_ = env.step(np.array([-1.0, 0.0]))
    assert obs[i] == 0.0


def test_a_velocity_grasp_succeeds_and_the_episode_runs_on():
    """The benchmark's grasp, driven through velocity actions (descend to fingertips 8 mm above
    the floor, close to 3 rad, lift at 0.1 m/s), is held; by default success does not end the
    episode (with the dense reward's positive terms, ending it would forfeit the rest of the
    episode's lift reward), and every held step keeps paying the success term."""
    env = SoftGripperGraspEnv(objects="block", action_mode="synergy")
    obs, _ = env.reset(seed=0)
    u, h = env.unwrapped, env.observation_structure["palm_height"][0]
    grasp = env.config.params.finger.length + 0.008
    close = u.command_action(3.0)
    held_at, terminated = None, False
    for k in range(300):
        if obs[h] > grasp + 0.001 and held_at is None and k < 60:
            a = [-1.0, max(-1.0, -(obs[h] - grasp) / 0.002)]
        elif k < 100:
            a = [close, 0.0]
        else:
            a = [close, 1.0]
        obs, r, terminated, truncated, info = env.step(np.array(a))
        assert not terminated
        if info["is_success"] and held_at is None:
            held_at = k
    assert held_at is not None and held_at < 250
    assert info["is_success"] and info["reward_success"] == env.config.weights["success"]


def test_observations_are_the_physical_values_over_their_scales():
    """v7: the returned observation is each part's SI value divided by its stated scale, and the
    scaled and unscaled environments run the same episode (same seed, same actions)."""
    from gripper.envs.config import OBSERVATION_SCALES

    scaled = SoftGripperGraspEnv(objects="block", action_mode="synergy")
    raw = SoftGripperGraspEnv(objects="block", action_mode="synergy", scale_observations=False)
    a, _ = scaled.reset(seed=3)
    b, _ = raw.reset(seed=3)
    for _ in range(5):
        a, ra, *_ = scaled.step(np.array([1.0, -1.0]))
        b, rb, *_ = raw.step(np.array([1.0, -1.0]))
        assert ra == rb
    for name, (i, n, _) in scaled.observation_structure.items():
        np.testing.assert_allclose(a[i:i + n] * OBSERVATION_SCALES[name][0], b[i:i + n], rtol=1e-12, atol=0)
    np.testing.assert_allclose(a * scaled.observation_divisor, b, rtol=1e-12, atol=0)


def test_a_held_step_at_the_grasp_point_pays_one():
    """v12's dense reward: contact (all fingers, at the grasp point), lift and success pay 1 a
    step; reach pays only while the fingers are open, so no step pays more than 1 + reach."""
    from gripper.envs.config import DEFAULT_REWARD_WEIGHTS as w

    assert w["contact"] + w["lift"] + w["success"] == pytest.approx(1.0)
    assert w["reach"] < w["contact"] < w["success"]
