"""What an off-policy run's replay buffer saw: how far the object rose above its start in the
stored transitions, and how far the fingers closed. The measured reason when hindsight goals do
not teach the lift: HER relabels with goals the object reached, so a buffer in which the object
never left the floor holds no lifted goal to learn from.

Reads ``checkpoints/replay_buffer.pkl`` of a ``gripper train --goal`` run (SAC or TQC).

Run: .venv/bin/python scripts/replay_coverage.py runs/train/her-s0 [more runs]
"""

import argparse
import pickle
from pathlib import Path

import numpy as np

from gripper.envs.config import OBSERVATION_SCALES, EnvConfig
from gripper.envs.task import observation_structure


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", nargs="+", type=Path)
    args = ap.parse_args()
    scale = OBSERVATION_SCALES["object_pos_rel_palm"][0]
    print("| run | transitions | object rise > 1 cm | > 4 cm (the lowest goal) | highest rise | "
          "servo set-point > 1.2 rad (gripping) | first rise > 4 cm (environment step) |")
    print("|---|---|---|---|---|---|---|")
    for run in args.runs:
        with open(run / "checkpoints" / "replay_buffer.pkl", "rb") as f:
            buf = pickle.load(f)
        n = buf.buffer_size if buf.full else buf.pos
        nxt, now = buf.next_observations, buf.observations  # arrays (step, env, ...)
        envs = np.arange(buf.n_envs)[None, :]
        # the rise above the episode's first position (the desired goal's base; h is not stored)
        start = now["achieved_goal"][buf.ep_start[:n], envs]
        rise2d = (nxt["achieved_goal"][:n, :, 2] - start[..., 2]) * scale
        rise = rise2d.reshape(-1)
        # the buffer's row t holds every env's transition of vector step t (environment steps
        # t * n_envs), in order while it has not wrapped around
        lifted = np.flatnonzero((rise2d > 0.04).any(axis=1))
        first = "none" if not len(lifted) else (f"{int(lifted[0]) * buf.n_envs:,}" if not buf.full else "?")
        i0, k, _ = observation_structure(EnvConfig().validate())["servo_setpoint"]
        servo = nxt["observation"][:n, :, i0:i0 + k].mean(axis=-1).reshape(-1) * OBSERVATION_SCALES["servo_setpoint"][0]
        print(f"| {run.name} | {len(rise):,} | {np.mean(rise > 0.01):.2%} | {np.mean(rise > 0.04):.2%} "
              f"| {rise.max() * 100:.1f} cm | {np.mean(servo > 1.2):.1%} | {first} |")


if __name__ == "__main__":
    main()
