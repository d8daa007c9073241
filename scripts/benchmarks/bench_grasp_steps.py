"""Steps per second while grasping: the scripted grasp (with the demonstrations' DART noise 0.2)
on block and cylinder, whole 300-step episodes (descend, close, lift, hold), in one env and in
the native vector env (one ``mujoco.rollout`` call per control step for all slots) on 1 and 2
MuJoCo threads, and with MuJoCo's solver tolerance loosened, each with its success so the
trade-off shows. Medians of --repeats; ratios against the vector env on one thread.

The solver rows change the model's options in place (``opt.tolerance``, ``opt.iterations``): a
measurement of what MuJoCo's knobs would buy, not a setting the environment offers.

Run: .venv/bin/python scripts/benchmarks/bench_grasp_steps.py [--num-envs 8] [--repeats 3]
"""

import argparse
import statistics
import time

import gymnasium as gym
import numpy as np

from gripper.envs.registration import ENV_ID
from gripper.envs.scripted_grasp import ScriptedGrasp

KW = {"objects": "block,cylinder", "action_mode": "synergy"}
NOISE = 0.2


def run(n_envs: int, nthread: int, seed: int, opt: dict | None = None) -> tuple[float, float]:
    """(environment steps per second, success rate) of ``n_envs`` scripted grasps."""
    venv = gym.make_vec(f"gripper:{ENV_ID}", num_envs=n_envs, vectorization_mode="vector_entry_point",
                        nthread=nthread, **KW)
    for scenes in venv._scenes:  # type: ignore[attr-defined]
        for scene in scenes._rigid.values():
            for k, v in (opt or {}).items():
                setattr(scene.model.opt, k, v)
    expert = ScriptedGrasp(venv.config)  # type: ignore[attr-defined]
    rng = np.random.default_rng(seed)
    obs, _ = venv.reset(seed=seed)
    held = np.zeros(n_envs, dtype=bool)
    t0 = time.perf_counter()
    for _ in range(300):
        a = expert(obs)
        obs, _, term, trunc, info = venv.step(np.clip(a + NOISE * rng.standard_normal(a.shape), -1, 1))
        held |= np.asarray(info["is_success"], dtype=bool)
    rate = 300 * n_envs / (time.perf_counter() - t0)
    venv.close()
    return rate, float(held.mean())


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--num-envs", type=int, default=8)
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args()
    n = args.num_envs
    variants = {
        "one env": (1, 1, None),
        f"vector, {n} envs, 1 thread": (n, 1, None),
        f"vector, {n} envs, 2 threads": (n, 2, None),
        f"vector, {n} envs, 1 thread, tolerance 1e-6": (n, 1, {"tolerance": 1e-6}),
        f"vector, {n} envs, 1 thread, tolerance 1e-5": (n, 1, {"tolerance": 1e-5}),
        f"vector, {n} envs, 1 thread, 10 iterations": (n, 1, {"iterations": 10}),
    }
    rates: dict[str, list[float]] = {k: [] for k in variants}
    wins: dict[str, list[float]] = {k: [] for k in variants}
    for r in range(args.repeats):
        for name, (envs, threads, opt) in variants.items():
            rate, success = run(envs, threads, seed=100 * r, opt=opt)
            rates[name].append(rate)
            wins[name].append(success)
    base = statistics.median(rates[f"vector, {n} envs, 1 thread"])
    print("| variant | steps/s (median) | vs vector, 1 thread | success |")
    print("|---|---|---|---|")
    for name in variants:
        med = statistics.median(rates[name])
        print(f"| {name} | {med:,.0f} | {med / base:.2f}x | {np.mean(wins[name]):.0%} |")


if __name__ == "__main__":
    main()
