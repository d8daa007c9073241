"""Train PPO, SAC or TQC on ``SoftGripperGrasp`` (or its goal-conditioned variant) through the
native vector env: chunked, logged, checkpointed and resumable.

A run folder holds:

- ``config.json``: the :class:`~gripper.rl.config.TrainConfig`, the hyper-parameters in effect
  and the package versions;
- ``progress.csv``: one row per chunk (environment steps, wall time, the chunk's training
  episodes: count, success rate, mean return; the deterministic policy's success over
  ``eval_episodes`` unseen seeds, overall and per object);
- ``checkpoints/``: the model after each chunk (``step_<n>.zip``, with its ``VecNormalize``
  statistics, and for SAC the replay buffer of the latest one);
- ``policy.zip`` (and ``vecnormalize.pkl``): the final policy.

Determinism: each chunk starts from a seeded reset of the environments and re-seeded random
generators (Python, NumPy, PyTorch, the action space), both derived from ``(seed, chunk)``, and
PyTorch runs on one CPU thread. So the same seed gives the same learning curve, and a run
resumed from a checkpoint continues bitwise as the run that never stopped; only ``wall_s``
differs. An episode still running at a chunk's end is cut there (not counted in the chunk's
training statistics).

Example:
    >>> from gripper.rl.config import TrainConfig                              # doctest: +SKIP
    >>> from gripper.rl.training import train                                  # doctest: +SKIP
    >>> train(TrainConfig(steps=131_072), "runs/train/ppo-s0")                 # doctest: +SKIP
"""

from __future__ import annotations

import csv
import json
import time
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from gripper.core.atomic import write_atomic
from gripper.core.user_files import read_user_data
from gripper.rl.config import EVAL_SEED, TrainConfig
from gripper.rl.hyperparams import hyperparams_for

if TYPE_CHECKING:
    from gripper.rl.demo_regulariser import DemoRegulariser

COLUMNS = ["steps", "wall_s", "train_episodes", "train_success", "train_return", "eval_success",
           "eval_return"]
CONFIG_FILE, PROGRESS_FILE, POLICY_FILE, NORM_FILE = "config.json", "progress.csv", "policy.zip", "vecnormalize.pkl"
RUN_FILES = (CONFIG_FILE, PROGRESS_FILE, POLICY_FILE, NORM_FILE)


def chunk_size(cfg: TrainConfig, hp: dict) -> int:
    """Steps per chunk: ``chunk_steps`` rounded up to whole PPO rollouts or whole vector steps."""
    unit = hp["n_steps"] * cfg.n_envs if cfg.algo == "ppo" else cfg.n_envs
    return -(-cfg.chunk_steps // unit) * unit


def chunk_seed(seed: int, chunk: int) -> int:
    """The generators' seed of one chunk (independent streams for each (seed, chunk))."""
    return int(np.random.SeedSequence([seed, chunk]).generate_state(1)[0] % (2**31))


def _versions() -> dict:
    import stable_baselines3
    import torch

    from gripper.core.provenance import versions
    return {**versions(), "stable_baselines3": stable_baselines3.__version__, "torch": torch.__version__}


def algorithm_class(algo: str):
    """The SB3 (or sb3-contrib) class of ``algo``."""
    if algo == "tqc":
        from sb3_contrib import TQC
        return TQC
    from stable_baselines3 import PPO, SAC
    return PPO if algo == "ppo" else SAC


def _build(cfg: TrainConfig, hp: dict, venv):
    from gripper.rl.hyperparams import HER_SAMPLED_GOALS, NOT_SB3, POLICY_KWARGS

    kw = {k: v for k, v in hp.items() if k not in POLICY_KWARGS + NOT_SB3}
    pk = {k: hp[k] for k in POLICY_KWARGS if k in hp}
    policy = "MultiInputPolicy" if cfg.goal_conditioned else "MlpPolicy"
    if cfg.algo == "ppo":
        pk["net_arch"] = {"pi": list(hp["net_arch"]), "vf": list(hp["net_arch"])}
    else:
        pk["net_arch"] = list(hp["net_arch"])
        if cfg.goal_conditioned:
            from stable_baselines3 import HerReplayBuffer
            kw["replay_buffer_class"] = HerReplayBuffer
            kw["replay_buffer_kwargs"] = {"n_sampled_goal": HER_SAMPLED_GOALS, "goal_selection_strategy": "future"}
    return algorithm_class(cfg.algo)(policy, venv, seed=cfg.seed, device="cpu", verbose=0, policy_kwargs=pk, **kw)


def _make_venv(cfg: TrainConfig, hp: dict, nthread: int):
    from stable_baselines3.common.vec_env import VecNormalize

    from gripper.envs.sb3 import make_sb3_vec_env

    venv: Any = make_sb3_vec_env(num_envs=cfg.n_envs, env_id=cfg.env_id(), nthread=nthread,
                                 **cfg.env_kwargs())
    if hp["normalize"]:
        venv = VecNormalize(venv, norm_obs=True, norm_reward=cfg.algo == "ppo", gamma=hp["gamma"])
    return venv


def episode_log(n_envs: int, final_step: bool = False):
    """An SB3 callback that keeps, for each training episode ending in a chunk, whether it
    succeeded (the grasp held at some step; with ``final_step``, the goal met at its last step)
    and its return (``.done``: a list of (success, return))."""
    from stable_baselines3.common.callbacks import BaseCallback

    class EpisodeLog(BaseCallback):
        def __init__(self):
            super().__init__()
            self.ret = np.zeros(n_envs)
            self.held = np.zeros(n_envs, dtype=bool)
            self.done: list[tuple[bool, float]] = []

        def _on_step(self) -> bool:
            infos, dones = self.locals["infos"], self.locals["dones"]
            env = self.training_env
            self.ret += env.get_original_reward() if hasattr(env, "get_original_reward") else self.locals["rewards"]
            now = np.array([bool(i.get("is_success", False)) for i in infos])
            self.held = now if final_step else self.held | now
            for i in np.flatnonzero(dones):
                self.done.append((bool(self.held[i]), float(self.ret[i])))
                self.ret[i], self.held[i] = 0.0, False
            return True

    return EpisodeLog()


def _end_cut_episodes(model) -> None:
    """Close, in a HER replay buffer, the episodes the chunk's end cut (the next chunk starts
    from a reset), as SB3 closes them when it loads a buffer: so that the run that never stopped
    samples from the same buffer as one resumed from this checkpoint."""
    import warnings

    from stable_baselines3 import HerReplayBuffer

    buf = getattr(model, "replay_buffer", None)
    if isinstance(buf, HerReplayBuffer):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", UserWarning)  # "the last trajectory ... will be truncated"
            buf.truncate_last_trajectory()


def load_model(path: str | Path, algo: str):
    """A saved model of ``algo`` for acting (an off-policy one without its replay buffer: HER's
    would need the environment)."""
    custom: dict[str, Any] = {} if algo == "ppo" else {"replay_buffer_class": None, "replay_buffer_kwargs": {},
                                                       "buffer_size": 1}
    return algorithm_class(algo).load(str(path), device="cpu", custom_objects=custom)


def _read_progress(path: Path) -> list[dict]:
    if not path.exists():
        return []
    with open(path, newline="") as f:
        return [{k: (int(v) if k in ("steps", "train_episodes", "demo_steps") else float(v)) for k, v in r.items()}
                for r in csv.DictReader(f)]


def _write_progress(path: Path, rows: list[dict], columns: list[str]) -> None:
    def write(tmp):
        with open(tmp, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=columns)
            w.writeheader()
            for r in rows:
                w.writerow({k: r[k] for k in columns})
    write_atomic(path, write)


def _latest_checkpoint(folder: Path) -> tuple[int, Path] | None:
    found = [(int(p.stem.split("_")[1]), p) for p in folder.glob("step_*.zip")] if folder.is_dir() else []
    return max(found) if found else None


def train(cfg: TrainConfig, out: str | Path, *, resume: bool = False,
          on_progress: Callable[[dict], None] | None = None, nthread: int = 1) -> list[dict]:
    """Train ``cfg`` into the run folder ``out``; return the progress rows.

    ``resume``: continue the run in ``out`` from its latest checkpoint (its config must equal
    ``cfg``). Without it, ``out`` must not hold a run already. ``nthread``: MuJoCo threads of
    the training and evaluation envs (each slot is simulated alone, so the curve is bitwise the
    same for any number; 2 on 2 free cores steps a grasp 1.4 times as fast as 1,
    ``docs/environment.md``, "Cheaper steps").

    Raises:
        ValueError: a bad config, a folder that holds another run (or none to resume), a
            config that differs from the one being resumed (the fields named), or a folder
            another training is writing (its lock, as every run folder's:
            :func:`gripper.bench.execution.folder_lock`).
    """
    from gripper.bench.execution import LOCK_FILE, folder_lock

    out = Path(out)
    made = not out.exists()
    out.mkdir(parents=True, exist_ok=True)
    try:
        with folder_lock(out):
            return _train(cfg, out, resume=resume, on_progress=on_progress, nthread=nthread)
    finally:
        if made and not (out / CONFIG_FILE).exists():  # refused before it began: leave nothing
            (out / LOCK_FILE).unlink(missing_ok=True)
            try:
                out.rmdir()
            except OSError:
                pass


def _train(cfg: TrainConfig, out: Path, *, resume: bool, on_progress: Callable[[dict], None] | None,
           nthread: int) -> list[dict]:
    import torch

    cfg = cfg.validate()
    hp = hyperparams_for(cfg.algo, cfg.hyperparams)
    out = Path(out)
    _claim_run_folder(cfg, hp, out, resume)
    torch.set_num_threads(1)
    chunk = chunk_size(cfg, hp)
    if not isinstance(nthread, int) or isinstance(nthread, bool) or not 1 <= nthread <= 64:
        raise ValueError(f"nthread: must be an integer in [1, 64], got {nthread!r}")
    run = _TrainingRun(cfg, hp, out, resume=resume, nthread=nthread, on_progress=on_progress)
    try:
        run.start_from_demonstrations()
        while run.done_steps < cfg.steps:
            run.train_chunk(chunk)
        run.save_policy(out)
    finally:
        run.close()
    return run.rows


def _claim_run_folder(cfg: TrainConfig, hp: dict, out: Path, resume: bool) -> None:
    """Check that ``out`` holds no other run (with ``resume``: a run of ``cfg``), then make it
    and its checkpoint folder and write the config file.

    Raises:
        ValueError: a folder with another run, or with none to resume.
    """
    cfg_path, prog_path = out / CONFIG_FILE, out / PROGRESS_FILE
    if resume:
        if not cfg_path.exists():
            raise ValueError(f"--resume: {out} holds no run to resume (no {CONFIG_FILE})")
        old = TrainConfig.from_json(_run_config(cfg_path))
        diff = [d for d in old.differences(cfg) if d != "steps"]
        if diff:
            raise ValueError(f"--resume: the run in {out} was made with other {', '.join(diff)}")
    elif cfg_path.exists() or prog_path.exists():
        raise ValueError(f"--out: {out} already holds a run; give --resume to continue it or another folder")
    out.mkdir(parents=True, exist_ok=True)
    (out / "checkpoints").mkdir(exist_ok=True)
    write_atomic(cfg_path, lambda tmp: Path(tmp).write_text(json.dumps(
        {"config": cfg.to_json(), "hyperparams": hp, "versions": _versions()}, indent=2) + "\n"))


def _norm_path(checkpoint: Path) -> Path:
    """The ``VecNormalize`` statistics saved with a checkpoint."""
    return checkpoint.with_name(checkpoint.stem + "_" + NORM_FILE)


def _eval_fields(ev: dict, objects: tuple[str, ...]) -> dict[str, Any]:
    """A progress row's evaluation columns: overall success and return, success per object."""
    return {"eval_success": ev["success"], "eval_return": ev["return"],
            **{f"eval_{o}": ev["by_object"].get(o, float("nan")) for o in sorted(set(objects))}}


class _TrainingRun:
    """One training run in its folder: the model, its training and evaluation envs, and the
    progress rows so far (``done_steps`` environment steps, ``t_wall`` seconds of wall time).

    A new run builds the model; a resumed one loads its latest checkpoint (model, normalisation
    statistics, replay buffer) and keeps the rows up to it.
    """

    def __init__(self, cfg: TrainConfig, hp: dict, out: Path, *, resume: bool, nthread: int,
                 on_progress: Callable[[dict], None] | None):
        from stable_baselines3.common.vec_env import VecNormalize

        self.cfg, self.hp, self.on_progress = cfg, hp, on_progress
        self.ckpt_dir, self.prog_path = out / "checkpoints", out / PROGRESS_FILE
        self.venv = _make_venv(cfg, hp, nthread)
        self.norm = self.venv if isinstance(self.venv, VecNormalize) else None
        self.rows: list[dict] = []
        self.latest = _latest_checkpoint(self.ckpt_dir) if resume else None
        self.model: Any
        if self.latest is not None:
            self.done_steps, path = self.latest
            self.model = self._load_checkpoint(path)
            self.rows = [r for r in _read_progress(self.prog_path) if r["steps"] <= self.done_steps]
        else:
            self.done_steps = 0
            self.model = _build(cfg, hp, self.venv)
        from gripper.rl.evaluation import make_eval_env

        self.eval_env = make_eval_env(cfg.env_kwargs(), cfg.eval_episodes, cfg.env_id(), nthread=nthread)
        self.columns = COLUMNS + [f"eval_{o}" for o in sorted(set(cfg.objects))] + (
            ["demo_steps"] if cfg.demo_episodes else [])
        self.t_wall = self.rows[-1]["wall_s"] if self.rows else 0.0
        self.demo_steps = int(self.rows[0]["demo_steps"]) if self.rows and cfg.demo_episodes else 0
        self.regulariser: DemoRegulariser | None = None

    def _load_checkpoint(self, path: Path):
        """The model of checkpoint ``path``, its normalisation statistics put into the training
        env and (off-policy) its replay buffer loaded."""
        from stable_baselines3.common.vec_env import VecNormalize

        if self.norm is not None:
            stats = VecNormalize.load(str(_norm_path(path)), self.norm.venv)
            self.norm.obs_rms, self.norm.ret_rms = stats.obs_rms, stats.ret_rms
        model: Any = algorithm_class(self.cfg.algo).load(str(path), env=self.venv, device="cpu")
        if self.cfg.algo != "ppo":
            model.load_replay_buffer(str(self.ckpt_dir / "replay_buffer.pkl"))
        return model

    def record(self, row: dict[str, Any]) -> None:
        """Append a progress row, rewrite ``progress.csv`` and report the row."""
        if self.cfg.demo_episodes:
            row["demo_steps"] = self.demo_steps
        self.rows.append(row)
        _write_progress(self.prog_path, self.rows, self.columns)
        if self.on_progress is not None:
            self.on_progress(row)

    def checkpoint(self, steps: int) -> None:
        """Save the model (with its normalisation statistics and, off-policy, the replay
        buffer) as ``checkpoints/step_<steps>.zip``."""
        path = self.ckpt_dir / f"step_{steps}.zip"
        self.model.save(str(path))
        if self.norm is not None:
            self.norm.save(str(_norm_path(path)))
        if self.cfg.algo != "ppo":
            self.model.save_replay_buffer(str(self.ckpt_dir / "replay_buffer.pkl"))

    def evaluate(self) -> dict:
        """The deterministic policy on the evaluation episodes (unseen seeds)."""
        from gripper.rl.evaluation import evaluate_policy

        return evaluate_policy(deterministic_policy(self.model, self.norm), self.cfg.env_kwargs(),
                               self.cfg.eval_episodes, EVAL_SEED, venv=self.eval_env)

    def start_from_demonstrations(self) -> None:
        """Collect the scripted demonstrations where the run uses them: for the PPO regulariser
        (``bc_weight`` or ``critic_warmup``, resumed runs too) and, in a new run, to pretrain."""
        cfg, hp = self.cfg, self.hp
        regularised = cfg.algo == "ppo" and (hp["bc_weight"] > 0 or hp["critic_warmup"] > 0)
        if cfg.demo_episodes and (self.latest is None or regularised):
            # the demonstrations: seeded by the run's seed, so a resumed run collects them again
            # bitwise (its regulariser draws from them)
            from gripper.rl.demonstrations import collect_demonstrations

            t0 = time.perf_counter()
            demo = collect_demonstrations(cfg.env_kwargs(), cfg.demo_episodes, cfg.demo_noise, cfg.seed,
                                          n_envs=cfg.n_envs)
            self.t_wall += time.perf_counter() - t0 if self.latest is None else 0.0
        if regularised:
            from gripper.rl.demo_regulariser import DemoRegulariser

            self.regulariser = DemoRegulariser(self.model, demo, weight=hp["bc_weight"], decay=hp["bc_decay"],
                                               critic_warmup=hp["critic_warmup"],
                                               seed=chunk_seed(cfg.seed, 2**31 + 1))
        if cfg.demo_episodes and self.latest is None:
            self._pretrain(demo)

    def _pretrain(self, demo) -> None:
        """Behaviour cloning from the scripted grasp (gripper.rl.demonstrations), evaluated
        and checkpointed as step 0; the demonstrations' own outcome is the row's training part."""
        from gripper.rl.demonstrations import fill_replay_buffer, pretrain

        cfg = self.cfg
        t0 = time.perf_counter()
        self.demo_steps = demo.steps
        pretrain(self.model, demo, seed=chunk_seed(cfg.seed, 2**31))
        if cfg.algo != "ppo":
            fill_replay_buffer(self.model, demo)
        ev = self.evaluate()
        self.checkpoint(0)
        self.t_wall += time.perf_counter() - t0
        ends = np.flatnonzero(demo.done)
        starts = np.concatenate([[0], ends[:-1] + 1])
        demo_return = float(np.mean([demo.reward[a:b + 1].sum() for a, b in zip(starts, ends, strict=True)]))
        self.record({"steps": 0, "wall_s": round(self.t_wall, 1), "train_episodes": len(ends),
                     "train_success": float(demo.success.mean()),
                     "train_return": demo_return, **_eval_fields(ev, cfg.objects)})

    def train_chunk(self, chunk: int) -> None:
        """Learn ``chunk`` steps from a seeded reset, then evaluate, checkpoint and record."""
        cfg, model, norm = self.cfg, self.model, self.norm
        t0 = time.perf_counter()
        k = self.done_steps // chunk
        s = chunk_seed(cfg.seed, k)
        model.set_random_seed(s)  # Python, NumPy, PyTorch, the action space, the envs' seeds
        model._last_obs = self.venv.reset()
        if norm is not None:
            model._last_original_obs = norm.get_original_obs()
        model._last_episode_starts = np.ones(cfg.n_envs, dtype=bool)
        log = episode_log(cfg.n_envs, final_step=cfg.goal_conditioned)
        model.learn(chunk, reset_num_timesteps=False, callback=log, progress_bar=False)
        self.done_steps = model.num_timesteps
        _end_cut_episodes(model)
        if norm is not None:
            norm.training = False

        ev = self.evaluate()
        if norm is not None:
            norm.training = True
        self.checkpoint(self.done_steps)
        self.t_wall += time.perf_counter() - t0
        row: dict[str, Any] = {
            "steps": self.done_steps, "wall_s": round(self.t_wall, 1), "train_episodes": len(log.done),
            "train_success": float(np.mean([d[0] for d in log.done])) if log.done else float("nan"),
            "train_return": float(np.mean([d[1] for d in log.done])) if log.done else float("nan"),
            **_eval_fields(ev, cfg.objects)}
        self.record(row)

    def save_policy(self, out: Path) -> None:
        """The final policy (and its normalisation statistics) into the run folder."""
        self.model.save(str(out / POLICY_FILE))
        if self.norm is not None:
            self.norm.save(str(out / NORM_FILE))

    def close(self) -> None:
        """Remove the regulariser's hooks and close both envs."""
        if self.regulariser is not None:
            self.regulariser.remove()
        self.eval_env.close()
        self.venv.close()


def _run_config(path: Path) -> dict:
    """The ``config`` table of a run folder's config file, read within the user-file limits."""
    data = read_user_data(path, "run config", (".json",))
    if not isinstance(data, dict) or not isinstance(data.get("config"), dict):
        raise ValueError(f"run config {path}: no 'config' table; not a folder 'gripper train' wrote")
    return data["config"]


def load_policy(run: str | Path) -> tuple[TrainConfig, Callable[[np.ndarray], np.ndarray]]:
    """A run folder's config and its final policy as a deterministic ``act(obs batch)``."""
    run = Path(run)
    if not (run / CONFIG_FILE).exists() or not (run / POLICY_FILE).exists():
        raise ValueError(f"--run: {run} holds no trained policy ({CONFIG_FILE} and {POLICY_FILE})")
    cfg = TrainConfig.from_json(_run_config(run / CONFIG_FILE))
    model = load_model(run / POLICY_FILE, cfg.algo)
    norm = None
    if (run / NORM_FILE).exists():
        import pickle

        with open(run / NORM_FILE, "rb") as f:
            norm = pickle.load(f)
        norm.training = False
    return cfg, deterministic_policy(model, norm)


def deterministic_policy(model, norm) -> Callable[[np.ndarray], np.ndarray]:
    """``act(obs batch)``: the model's mean action on observations normalised by ``norm``
    (a ``VecNormalize`` with frozen statistics, or None)."""
    def act(obs):
        o = norm.normalize_obs(obs) if norm is not None else obs
        return model.predict(o, deterministic=True)[0]
    return act
