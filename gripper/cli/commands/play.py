"""``gripper play``: video of a trained policy's episode."""

from __future__ import annotations

from gripper.cli.inputs import (
    PIXELS,
    number,
    seed_option,
)
from gripper.cli.options import (
    needs_rl,
)
from gripper.core.atomic import check_output_file


def add(sub) -> None:
    from gripper.rl.config import EVAL_SEED

    pl = sub.add_parser("play", help="video of a trained policy's episode (needs the rl extra)",
                        description="Run one episode of a run folder's final policy (deterministic) and "
                                    "write its video (H.264 MP4 or GIF).")
    pl.add_argument("--run", required=True, metavar="DIR", help="run folder of 'gripper train'")
    pl.add_argument("--out", required=True, metavar="FILE", help="output .mp4 or .gif")
    seed_option(pl, help="episode seed", default=EVAL_SEED)
    pl.add_argument("--camera", default="front", help="camera preset (default front)")
    number(pl, "--width", int, lo=PIXELS[0], hi=PIXELS[1], default=640, help="pixels")
    number(pl, "--height", int, lo=PIXELS[0], hi=PIXELS[1], default=480, help="pixels")
    pl.set_defaults(func=run)


def play_policy(run, out, seed, width, height, camera) -> int:
    from gripper.rl.policy_video import record_policy_video
    from gripper.rl.training import load_policy

    cfg, act = load_policy(run)
    res = record_policy_video(act, cfg.env_kwargs(), out, seed=seed, width=width, height=height, camera=camera,
                              on_progress=lambda msg: print(msg, flush=True))  # stdout: stderr is for errors
    print(f"{res['object']}, seed {seed}: {'held' if res['success'] else 'not held'}; wrote {res['video']} "
          f"({res['frames']} frames at {res['fps']:g} fps)")
    return 0


def run(args) -> int:
    from gripper.render.video import VIDEO_SUFFIXES

    check_output_file(args.out, "--out", VIDEO_SUFFIXES)
    needs_rl("play")
    return play_policy(args.run, args.out, args.seed, args.width, args.height, args.camera)
