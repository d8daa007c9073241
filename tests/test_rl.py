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


# the variants the resume test covers: PPO, SAC, PPO from demonstrations with its regulariser,
# and TQC with hindsight goals on the goal-conditioned task
VARIANTS = {
    "ppo": {"algo": "ppo"},
    "sac": {"algo": "sac"},
    "ppo_demos": {"algo": "ppo", "demo_episodes": 2, "demo_noise": 0.2,
                  "hyperparams": {"bc_weight": 1.0, "bc_decay": 0.9, "critic_warmup": 1, "log_std_init": -1.6}},
    "tqc_her": {"algo": "tqc", "goal_conditioned": True, "objects": ("block",)},
}


def _tiny(variant: str, steps: int) -> TrainConfig:
    v = dict(VARIANTS[variant])
    hp = ({"n_steps": 32, "batch_size": 32, "n_epochs": 2} if v["algo"] == "ppo"
          else {"learning_starts": 64, "buffer_size": 2000, "batch_size": 32})
    hp.update(v.pop("hyperparams", {}))
    kw = {"objects": ("block", "cylinder"), **v}
    return TrainConfig(steps=steps, n_envs=2, chunk_steps=128, eval_episodes=2, max_episode_steps=24,
                       hyperparams=hp, **kw).validate()


def _params(path):
    import torch

    from gripper.rl.training import load_model

    algo = json.loads((path.parent / "config.json").read_text())["config"]["algo"]
    model = load_model(path, algo)
    return torch.nn.utils.parameters_to_vector(model.policy.parameters()).detach().numpy()


def _curve(rows):
    return [{k: v for k, v in r.items() if k != "wall_s"} for r in rows]


@pytest.mark.slow
@pytest.mark.parametrize("variant", list(VARIANTS))
def test_same_seed_same_curve_and_resume_is_bitwise(variant, tmp_path):
    """Three chunks straight through, again, and two chunks then a resume (on two threads) for
    the third: the same progress rows (but wall time) and the same final network, bitwise; with
    demonstrations (cloned, then regularised towards them) and with hindsight goals too."""
    pytest.importorskip("stable_baselines3")
    if variant == "tqc_her":
        pytest.importorskip("sb3_contrib")
    from gripper.rl.training import load_policy, train

    a = train(_tiny(variant, 384), tmp_path / f"{variant}_a")
    b = train(_tiny(variant, 384), tmp_path / f"{variant}_b")
    train(_tiny(variant, 256), tmp_path / f"{variant}_c")
    # resumed on two MuJoCo threads: each slot is simulated alone, so the curve does not change
    c = train(_tiny(variant, 384), tmp_path / f"{variant}_c", resume=True, nthread=2)
    assert [r["steps"] for r in a] == ([0] if "demo_episodes" in VARIANTS[variant] else []) + [128, 256, 384]
    assert _curve(a) == _curve(b) == _curve(c)
    pa = _params(tmp_path / f"{variant}_a" / "policy.zip")
    assert np.isfinite(pa).all()
    assert np.array_equal(pa, _params(tmp_path / f"{variant}_b" / "policy.zip"))
    assert np.array_equal(pa, _params(tmp_path / f"{variant}_c" / "policy.zip"))
    with pytest.raises(ValueError, match="already holds a run"):
        train(_tiny(variant, 384), tmp_path / f"{variant}_a")
    with pytest.raises(ValueError, match="other hyperparams"):
        train(_tiny(variant, 384).replace(hyperparams={}), tmp_path / f"{variant}_a", resume=True)
    cfg, act = load_policy(tmp_path / f"{variant}_a")
    assert cfg == _tiny(variant, 384)
    if cfg.goal_conditioned:
        obs = {"observation": np.zeros((3, 107)), "achieved_goal": np.zeros((3, 3)), "desired_goal": np.ones((3, 3))}
    else:
        obs = np.zeros((3, 107))
    assert act(obs).shape == (3, 2) and np.all(np.abs(act(obs)) <= 1.0)


def test_demonstration_settings_are_checked():
    with pytest.raises(ValueError, match="bc_weight"):
        TrainConfig(hyperparams={"bc_weight": 1.0}).validate()
    with pytest.raises(ValueError, match="bc_decay"):
        TrainConfig(demo_episodes=4, hyperparams={"bc_decay": 1.5}).validate()
    with pytest.raises(ValueError, match="demo_episodes"):
        TrainConfig(algo="tqc", goal_conditioned=True, demo_episodes=4).validate()


def test_critic_warmup_freezes_the_actor_and_the_bc_term_pulls_towards_the_labels():
    """One PPO update under the regulariser: during the warm-up the actor's parameters are
    bitwise unchanged while the critic's move; after it, the behaviour-cloning term moves the
    policy's mean towards the labels."""
    pytest.importorskip("stable_baselines3")
    import torch
    from stable_baselines3 import PPO

    from gripper.envs.sb3 import make_sb3_vec_env
    from gripper.rl.demo_regulariser import CRITIC_PREFIXES, DemoRegulariser
    from gripper.rl.demonstrations import Demonstrations

    torch.set_num_threads(1)
    venv = make_sb3_vec_env(num_envs=2, objects="block", action_mode="synergy", max_episode_steps=16, nthread=1)
    model = PPO("MlpPolicy", venv, n_steps=16, batch_size=16, n_epochs=2, seed=0, device="cpu",
                policy_kwargs={"net_arch": {"pi": [16], "vf": [16]}})
    rng = np.random.default_rng(0)
    obs = rng.normal(size=(64, 107))
    label = np.clip(rng.normal(size=(64, 2)), -1, 1)
    demo = Demonstrations(obs=obs, next_obs=obs, label=label, action=label, reward=np.zeros(64),
                          done=np.zeros(64, dtype=bool), terminated=np.zeros(64, dtype=bool), success=np.zeros(0))

    def split():
        actor = {n: p.detach().clone() for n, p in model.policy.named_parameters() if not n.startswith(CRITIC_PREFIXES)}
        critic = {n: p.detach().clone() for n, p in model.policy.named_parameters() if n.startswith(CRITIC_PREFIXES)}
        return actor, critic

    def mse():
        with torch.no_grad():
            mean = model.policy.get_distribution(torch.as_tensor(obs, dtype=torch.float32)).distribution.mean
        return float(torch.mean((mean - torch.as_tensor(label, dtype=torch.float32)) ** 2))

    reg = DemoRegulariser(model, demo, weight=1.0, decay=1.0, critic_warmup=1, seed=0)
    a0, c0 = split()
    model.learn(32)  # one update (16 steps x 2 envs), in the warm-up
    a1, c1 = split()
    assert all(torch.equal(a0[n], a1[n]) for n in a0)
    assert any(not torch.equal(c0[n], c1[n]) for n in c0)
    reg.remove()
    # after the warm-up, a heavy BC term (PPO's own gradient is clipped to norm 0.5, the BC
    # term's 100x larger) lowers the distance to the labels
    reg = DemoRegulariser(model, demo, weight=100.0, decay=1.0, critic_warmup=0, seed=0)
    before = mse()
    for _ in range(3):
        model.learn(32, reset_num_timesteps=False)
    assert mse() < before
    reg.remove()
    venv.close()


def test_committed_curves_are_of_todays_recipe():
    """The learning curves in docs/rl (scripts/rl_table.py's input) were trained with today's
    hyper-parameters: each run's table is today's defaults with its own overrides, and the
    recommended recipe's runs are ``--recommended``'s. A changed default or recipe makes them
    stale: retrain with the commands in docs/environment.md ("Baselines")."""
    from pathlib import Path

    from gripper.rl.hyperparams import RECOMMENDED

    runs = sorted((Path(__file__).parent.parent / "docs" / "rl").glob("*/config.json"))
    assert runs, "no committed curves"
    for path in runs:
        data = json.loads(path.read_text())
        cfg = TrainConfig.from_json(data["config"])
        assert data["hyperparams"] == hyperparams_for(cfg.algo, cfg.hyperparams), path
        if path.parent.name.startswith("recommended"):
            assert (cfg.algo, cfg.demo_episodes, cfg.demo_noise, cfg.hyperparams) == (
                RECOMMENDED["algo"], RECOMMENDED["demo_episodes"], RECOMMENDED["demo_noise"],
                RECOMMENDED["hyperparams"]), path
        assert (path.parent / "progress.csv").exists()
