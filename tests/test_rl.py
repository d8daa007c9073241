"""Training entry point (gripper.rl): config validation without the rl extra; with it, a short
PPO and SAC run, the same seed giving the same learning curve, and resume from a checkpoint."""

import json
import re

import numpy as np
import pytest

from gripper.cli.main import main
from gripper.rl.config import TrainConfig
from gripper.rl.hyperparams import PPO_HYPERPARAMS, hyperparams_for


@pytest.mark.parametrize("kwargs, field", [
    ({"algo": "dqn"}, "algo"),
    ({"objects": ()}, "objects"),
    ({"objects": ("teapot",)}, "unknown object"),
    ({"steps": 0}, "steps"),
    ({"n_envs": 2.5}, "n_envs"),
    ({"hyperparams": {"n_stepz": 3}}, "hyperparams.n_stepz"),
    ({"hyperparams": {"learning_rate": -1.0}}, "hyperparams.learning_rate"),
    ({"hyperparams": {"net_arch": []}}, "hyperparams.net_arch"),
    ({"reward_weights": {"grip": 1.0}}, "reward_weights"),
])
def test_bad_train_config_names_the_field(kwargs, field):
    with pytest.raises(ValueError, match=re.escape(field)):
        TrainConfig(**kwargs).validate()


def test_hyperparams_overrides_and_json_round_trip():
    assert hyperparams_for("ppo", {"n_epochs": 4})["n_epochs"] == 4
    assert hyperparams_for("ppo")["n_steps"] == PPO_HYPERPARAMS["n_steps"]
    cfg = TrainConfig(algo="sac", objects=("block",), hyperparams={"batch_size": 64}).validate()
    assert TrainConfig.from_json(json.loads(json.dumps(cfg.to_json()))) == cfg
    assert cfg.differences(TrainConfig(algo="sac", objects=("block",))) == ["hyperparams"]


def test_train_cli_bad_input_exits_2(capsys, tmp_path):
    assert main(["train", "--algo", "ppo", "--steps", "-5", "--out", str(tmp_path / "r")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "steps" in err
    assert main(["train", "--set", "gamma", "--out", str(tmp_path / "r")]) == 2
    assert "--set" in capsys.readouterr().err
    assert not (tmp_path / "r").exists()


def _tiny(algo: str, steps: int) -> TrainConfig:
    hp = ({"n_steps": 32, "batch_size": 32, "n_epochs": 2} if algo == "ppo"
          else {"learning_starts": 64, "buffer_size": 2000, "batch_size": 32})
    return TrainConfig(algo=algo, objects=("block", "cylinder"), steps=steps, n_envs=2, chunk_steps=128,
                       eval_episodes=2, max_episode_steps=24, hyperparams=hp).validate()


def _params(path):
    import torch
    from stable_baselines3 import PPO, SAC

    model = (PPO if "ppo" in str(path) else SAC).load(str(path), device="cpu")
    return torch.nn.utils.parameters_to_vector(model.policy.parameters()).detach().numpy()


def _curve(rows):
    return [{k: v for k, v in r.items() if k != "wall_s"} for r in rows]


@pytest.mark.slow
@pytest.mark.parametrize("algo", ["ppo", "sac"])
def test_same_seed_same_curve_and_resume_is_bitwise(algo, tmp_path):
    """Three chunks straight through, again, and two chunks then a resume for the third:
    the same progress rows (but wall time) and the same final network, bitwise."""
    pytest.importorskip("stable_baselines3")
    from gripper.rl.training import load_policy, train

    a = train(_tiny(algo, 384), tmp_path / f"{algo}_a")
    b = train(_tiny(algo, 384), tmp_path / f"{algo}_b")
    train(_tiny(algo, 256), tmp_path / f"{algo}_c")
    c = train(_tiny(algo, 384), tmp_path / f"{algo}_c", resume=True)
    assert [r["steps"] for r in a] == [128, 256, 384]
    assert _curve(a) == _curve(b) == _curve(c)
    pa = _params(tmp_path / f"{algo}_a" / "policy.zip")
    assert np.isfinite(pa).all()
    assert np.array_equal(pa, _params(tmp_path / f"{algo}_b" / "policy.zip"))
    assert np.array_equal(pa, _params(tmp_path / f"{algo}_c" / "policy.zip"))
    with pytest.raises(ValueError, match="already holds a run"):
        train(_tiny(algo, 384), tmp_path / f"{algo}_a")
    with pytest.raises(ValueError, match="other hyperparams"):
        train(_tiny(algo, 384).replace(hyperparams={}), tmp_path / f"{algo}_a", resume=True)
    cfg, act = load_policy(tmp_path / f"{algo}_a")
    assert cfg == _tiny(algo, 384)
    obs = np.zeros((3, 107))
    assert act(obs).shape == (3, 2) and np.all(np.abs(act(obs)) <= 1.0)
