"""The goal-conditioned variant SoftGripperGraspGoal: Gymnasium's checker, the dict observation
and compute_reward that hindsight experience replay relies on, and the vector env's slots."""

import pickle

import gymnasium as gym
import numpy as np
import pytest

from gripper.envs.goal_env import GOAL_TOLERANCE, LIFT_TARGET
from gripper.envs.registration import GOAL_ENV_ID

ID = f"gripper:{GOAL_ENV_ID}"


def test_gymnasium_env_checker_passes_with_allow_listed_warnings_only():
    import warnings

    from gymnasium.utils.env_checker import check_env
    from test_env import ALLOWED_WARNINGS

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(gym.make(ID, objects="block", action_mode="synergy").unwrapped)
    assert [str(w.message) for w in caught if not any(a in str(w.message) for a in ALLOWED_WARNINGS)] == []


def test_goal_is_a_lift_target_and_the_reward_is_recomputable():
    """The desired goal lies straight above the start, LIFT_TARGET higher; the step's reward is
    compute_reward of the step's own goals (what HER recomputes for relabelled goals), and
    is_success is the goal met within GOAL_TOLERANCE."""
    env = gym.make(ID, objects="block,cylinder", action_mode="synergy")
    obs, _ = env.reset(seed=3)
    scale = 0.1  # the object position's observation scale
    a, g = obs["achieved_goal"] * scale, obs["desired_goal"] * scale
    assert np.allclose(a[:2], g[:2]) and LIFT_TARGET[0] <= g[2] - a[2] <= LIFT_TARGET[1]
    for _ in range(5):
        obs, reward, _, _, info = env.step(np.array([0.0, 1.0], dtype=np.float32))
        assert reward == env.unwrapped.compute_reward(obs["achieved_goal"], obs["desired_goal"], info) == -1.0
        assert info["is_success"] is False and info["grasp_held"] is False


def test_compute_reward_is_vectorised_sparse_and_dense():
    env = gym.make(ID, objects="block")
    u = env.unwrapped
    desired = np.zeros((4, 3))
    achieved = np.zeros((4, 3))
    achieved[:, 2] = np.array([0.0, 0.019, 0.021, 0.1]) / 0.1  # metres, scaled by 0.1 m
    assert u.compute_reward(achieved, desired, [{}] * 4).tolist() == [0.0, 0.0, -1.0, -1.0]
    assert GOAL_TOLERANCE == 0.02
    dense = gym.make(ID, objects="block", reward_type="dense").unwrapped
    np.testing.assert_allclose(dense.compute_reward(achieved, desired, None), [0.0, -0.019, -0.021, -0.1])
    # HER's batch: (batch, 1, 3) shapes reduce over the last axis only
    assert u.compute_reward(achieved[:, None], desired[:, None], None).shape == (4, 1)


def test_vector_slots_are_the_single_envs_and_pickling_keeps_the_goal():
    n = 3
    venv = gym.make_vec(ID, num_envs=n, vectorization_mode="vector_entry_point", objects="block,cylinder",
                        action_mode="synergy", nthread=1)
    vo, _ = venv.reset(seed=10)
    act = np.tile(np.array([[0.5, -1.0]], dtype=np.float32), (n, 1))
    for _ in range(3):
        vo, vr, *_ = venv.step(act)
    assert np.all(vr == venv.compute_reward(vo["achieved_goal"], vo["desired_goal"], None))
    for i in range(n):
        env = gym.make(ID, objects="block,cylinder", action_mode="synergy")
        so, _ = env.reset(seed=10 + i)
        for _ in range(3):
            so, *_ = env.step(act[i])
        for k in so:
            np.testing.assert_array_equal(so[k], vo[k][i])
    clone = pickle.loads(pickle.dumps(env.unwrapped))
    np.testing.assert_array_equal(clone._goal, env.unwrapped._goal)
    venv.close()


def test_sb3_env_checker_passes():
    pytest.importorskip("stable_baselines3")
    from stable_baselines3.common.env_checker import check_env

    check_env(gym.make(ID, objects="block", action_mode="synergy").unwrapped, warn=False)


def test_off_the_shelf_her_trains_through_sb3s_own_vec_env():
    """A user's client: SB3's make_vec_env (DummyVecEnv over gym.make's wrappers), SAC with
    HerReplayBuffer, which reaches compute_reward through env_method and relabels goals."""
    pytest.importorskip("stable_baselines3")
    from stable_baselines3 import SAC, HerReplayBuffer
    from stable_baselines3.common.env_util import make_vec_env

    venv = make_vec_env(ID, n_envs=2, seed=0, env_kwargs={"objects": "block", "action_mode": "synergy",
                                                          "max_episode_steps": 20})
    model = SAC("MultiInputPolicy", venv, replay_buffer_class=HerReplayBuffer, learning_starts=60, batch_size=16,
                seed=0, device="cpu", policy_kwargs={"net_arch": [16]})
    model.learn(100)
    batch = model.replay_buffer.sample(16)
    assert batch.rewards.shape == (16, 1) and set(np.unique(batch.rewards)) <= {-1.0, 0.0}
