"""How far random exploration reaches in ``SoftGripperGrasp-v8``: white against held noise.

PPO and SAC explore with Gaussian action noise drawn anew every control step (white). The servo
(slew-limited at its no-load speed) and the velocity palm (an integrator) filter that noise, so
the states it visits stay near the middle. gSDE (``use_sde``) holds its noise draw for
``sde_sample_freq`` steps. This script drives the block episode with N(0, 1) actions, clipped,
drawn every ``--hold`` steps, and prints the 5-95 % range of the servo angle and the palm height
over steps 50-150 of each episode (and the servo angle over steps 0-30, the descent), with
the servo action a position set-point (``--servo-control position``, v4's first design) or a
velocity (v4 as shipped).

Run: .venv/bin/python scripts/rl_exploration.py [--episodes 8] [--holds 1,4,16] [--servo-control velocity]
"""

import argparse

import gymnasium as gym
import numpy as np

import gripper  # noqa: F401  (registers the environment)
from gripper.envs.registration import ENV_ID


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--episodes", type=int, default=8)
    ap.add_argument("--holds", default="1,4,16")
    ap.add_argument("--servo-control", choices=("position", "velocity"), default="position")
    args = ap.parse_args()
    env = gym.make(f"gripper:{ENV_ID}", objects="block", action_mode="synergy", servo_control=args.servo_control,
                   scale_observations=False)
    st = env.unwrapped.observation_structure
    i_servo, i_palm = st["servo_angle"][0], st["palm_height"][0]
    print(f"servo_control={args.servo_control}")
    print("| noise drawn every | servo angle in the descent, 5-95 % [rad] | servo angle 5-95 % [rad] "
          "| servo sd | palm height 5-95 % [m] | palm sd [mm] |")
    print("|---|---|---|---|---|---|")
    for hold in (int(h) for h in args.holds.split(",")):
        servo, palm, descent = [], [], []
        for ep in range(args.episodes):
            obs, _ = env.reset(seed=ep)
            rng = np.random.default_rng(ep)
            for k in range(150):
                if k % hold == 0:
                    noise = rng.normal(0.0, 1.0, 2)
                obs, *_ = env.step(np.clip(noise, -1.0, 1.0))
                if k < 30:
                    descent.append(obs[i_servo])
                if k >= 50 and k % 10 == 0:
                    servo.append(obs[i_servo])
                    palm.append(obs[i_palm])
        s, p, e = np.array(servo), np.array(palm), np.array(descent)
        print(f"| {hold} steps | {np.percentile(e, 5):.2f}-{np.percentile(e, 95):.2f} | "
              f"{np.percentile(s, 5):.2f}-{np.percentile(s, 95):.2f} | {s.std():.2f} | "
              f"{np.percentile(p, 5):.3f}-{np.percentile(p, 95):.3f} | {p.std() * 1e3:.1f} |")


if __name__ == "__main__":
    main()
