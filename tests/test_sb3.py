"""Stable-Baselines3 adapter over the native vector env (needs the ``rl`` extra; skipped without it)."""

import gymnasium as gym
import numpy as np
import pytest

pytest.importorskip("stable_baselines3")

import gripper  # noqa: E402,F401  (registers the environment)
from gripper.envs.sb3 import make_sb3_vec_env, split_infos  # noqa: E402

ENV_ID = "gripper:SoftGripperGrasp-v12"


def test_same_step_autoreset_matches_single_envs():
    """Each slot runs a single env's episodes: seed s + i, the final observation in
    ``terminal_observation``, the next episode's first observation in the same step, and no
    step spent on the reset."""
    n, limit = 2, 6
    venv = make_sb3_vec_env(num_envs=n, objects="block,cylinder", max_episode_steps=limit)
    singles = [gym.make(ENV_ID, objects="block,cylinder", max_episode_steps=limit) for _ in range(n)]
    venv.seed(11)
    obs = venv.reset()
    assert np.array_equal(obs, np.stack([e.reset(seed=11 + i)[0] for i, e in enumerate(singles)]))
    assert all(info["object"] in ("block", "cylinder") for info in venv.reset_infos)
    rng = np.random.default_rng(0)
    ends = 0
    for _ in range(2 * limit + 2):
        act = rng.uniform(-1, 1, (n,) + singles[0].action_space.shape).astype(np.float32)
        obs, rew, done, infos = venv.step(act)
        assert rew.dtype == np.float32 and done.dtype == bool and len(infos) == n
        for i, e in enumerate(singles):
            o, r, te, tr, info = e.step(act[i])
            assert rew[i] == np.float32(r) and done[i] == (te or tr)
            if te or tr:
                ends += 1
                assert np.array_equal(infos[i]["terminal_observation"], o)
                assert infos[i]["TimeLimit.truncated"] == (tr and not te)
                assert infos[i]["is_success"] == info["is_success"]
                o, _ = e.reset()
            assert np.array_equal(obs[i], o)
    assert ends >= n
    venv.close()


def test_split_infos_keeps_each_envs_own_keys():
    info = {"a": np.array([1.0, 2.0]), "_a": np.array([True, False]),
            "d": {"x": np.array([3, 4]), "_x": np.array([True, True])}, "_d": np.array([False, True])}
    assert split_infos(info, 2) == [{"a": 1.0}, {"d": {"x": 4}}]


@pytest.mark.slow
def test_ppo_trains_on_the_adapter_reproducibly():
    """A short PPO run through the adapter: it learns without error, and the same seed gives
    the same policy (bitwise)."""
    import torch
    from stable_baselines3 import PPO

    torch.set_num_threads(1)

    def train():
        venv = make_sb3_vec_env(num_envs=2, objects="block", max_episode_steps=32)
        model = PPO("MlpPolicy", venv, n_steps=32, batch_size=32, n_epochs=2, seed=3, device="cpu")
        model.learn(128)
        params = torch.nn.utils.parameters_to_vector(model.policy.parameters()).detach().numpy().copy()
        venv.close()
        return params

    a, b = train(), train()
    assert np.isfinite(a).all() and np.array_equal(a, b)
