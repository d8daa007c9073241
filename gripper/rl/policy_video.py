"""A video of a policy's episode, through the package's video path (:mod:`gripper.render.video`).

Renders the single environment offscreen at every control step (50 frames/s of simulated time at
the 20 ms control period) with a text overlay (step, palm height, object rise, held time), and
writes H.264 MP4 or GIF atomically with ``mediapy``.

Example:
    >>> from gripper.rl.training import load_policy                              # doctest: +SKIP
    >>> from gripper.rl.policy_video import record_policy_video                  # doctest: +SKIP
    >>> cfg, act = load_policy("runs/train/ppo-s0")                              # doctest: +SKIP
    >>> record_policy_video(act, cfg.env_kwargs(), "ppo.mp4", seed=1_000_000)    # doctest: +SKIP
"""

from __future__ import annotations

import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from gripper.envs.registration import MAX_EPISODE_STEPS
from gripper.render.renderer import check_view
from gripper.render.video import ProgressLines, check_output_path, overlay_lines, write_video


def record_policy_video(act: Callable[[np.ndarray], np.ndarray], env_kwargs: dict[str, Any], out: str | Path, *,
                        seed: int, width: int = 640, height: int = 480, camera: str = "front",
                        overlay: bool = True, on_progress: Callable[[str], None] | None = None) -> dict[str, Any]:
    """Run one episode of ``act`` (a batch of observations to a batch of actions) with seed
    ``seed`` and write its video to ``out``; return the outcome and the video's figures.

    ``on_progress``: called with a line as each stage starts (run and render, encode) and with
    ``"rendering: 120/301 frames"`` lines during the episode (each tenth of the longest episode,
    at most one a second); the last says how many frames the episode had.
    """
    import gymnasium as gym

    from gripper.envs.registration import ENV_ID

    out = check_output_path(out)
    check_view(width, height, camera, prefix="--")
    env: Any = gym.make(f"gripper:{ENV_ID}", render_mode="rgb_array", width=width, height=height, camera=camera,
                   **env_kwargs)
    say = on_progress or (lambda msg: None)
    t0 = time.perf_counter()
    frames: list[np.ndarray] = []
    held = False
    try:
        obs, info = env.reset(seed=seed)
        u = env.unwrapped
        i_h = u.observation_structure["palm_height"][0]
        to_m = float(u.observation_divisor[i_h])  # the observation's palm height in SI units
        max_steps = getattr(env.spec, "max_episode_steps", None) or MAX_EPISODE_STEPS
        say(f"running the policy (seed {seed}) and rendering up to {max_steps + 1} frames "
            f"({width}x{height}, camera {camera}) ...")
        progress = ProgressLines(say, max_steps + 1)
        step, done = 0, False
        while True:
            img = env.render()
            if overlay:
                img = overlay_lines(img, [
                    f"{info['object']}  step {step:3d}  t = {step * u.config.control_period:4.2f} s",
                    f"palm {obs[i_h] * to_m:.3f} m  rise {info.get('object_height_m', 0.0) * 1e3:5.1f} mm  "
                    f"held {info.get('held_s', 0.0):.2f} s" + ("  SUCCESS" if held else "")])
            frames.append(img)
            progress.update(len(frames))
            if done:
                break
            obs, _, term, trunc, info = env.step(np.asarray(act(obs[None]))[0])
            held |= bool(info.get("is_success"))
            step += 1
            done = term or trunc
        fps = 1.0 / u.config.control_period
    finally:
        env.close()
    progress.finish(len(frames), "" if len(frames) > max_steps else f" (the episode ended after {step} steps)")
    t_run = time.perf_counter() - t0
    say(f"encoding {out.name} ...")
    write_video(np.stack(frames), out, fps)
    return {"video": str(out), "success": held, "object": info["object"], "frames": len(frames), "fps": fps,
            "seed": seed, "simulate_and_render_s": t_run}
