"""Environment speed: steps per second of one env, and of the native vector env against
Gymnasium's AsyncVectorEnv with the same number of envs, measured side by side.

Random actions on a rigid object (block), 20 ms control period (frame_skip 10 at 2 ms);
medians of --repeats runs; the ratio is taken per repeat (native and async run back to back).

Run: .venv/bin/python scripts/bench_env.py [--num-envs 16] [--steps 200] [--repeats 3]
"""

import argparse
import statistics
import time

import gymnasium as gym
import numpy as np

import gripper  # noqa: F401

ENV_ID = "gripper:SoftGripperGrasp-v12"


def steps_per_second(env, steps, n_envs, seed=0) -> float:
    env.reset(seed=seed)
    rng = np.random.default_rng(seed)
    acts = rng.uniform(-1, 1, (steps,) + env.action_space.shape).astype(np.float32)
    t0 = time.perf_counter()
    for a in acts:
        out = env.step(a)
        if n_envs == 1 and (out[2] or out[3]):
            env.reset()
    return steps * n_envs / (time.perf_counter() - t0)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--num-envs", type=int, default=16)
    ap.add_argument("--steps", type=int, default=200)
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args()
    kw = dict(objects="block")
    single, native, asyn, ratio = [], [], [], []
    for r in range(args.repeats):
        env = gym.make(ENV_ID, **kw)
        single.append(steps_per_second(env, args.steps * 4, 1, seed=r))
        env.close()
        v = gym.make_vec(ENV_ID, num_envs=args.num_envs, vectorization_mode="vector_entry_point", **kw)
        native.append(steps_per_second(v, args.steps, args.num_envs, seed=r))
        v.close()
        v = gym.make_vec(ENV_ID, num_envs=args.num_envs, vectorization_mode="async", **kw)
        asyn.append(steps_per_second(v, args.steps, args.num_envs, seed=r))
        v.close()
        ratio.append(native[-1] / asyn[-1])
    fmt = lambda xs: ", ".join(f"{x:.0f}" for x in xs)  # noqa: E731
    print(f"single env: median {statistics.median(single):.0f} steps/s (runs {fmt(single)})")
    print(f"native vector, {args.num_envs} envs: median {statistics.median(native):.0f} steps/s (runs {fmt(native)})")
    print(f"AsyncVectorEnv, {args.num_envs} envs: median {statistics.median(asyn):.0f} steps/s (runs {fmt(asyn)})")
    print(f"native / async: median {statistics.median(ratio):.2f}x (runs {', '.join(f'{x:.2f}' for x in ratio)})")


if __name__ == "__main__":
    main()
