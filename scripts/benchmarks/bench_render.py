"""Rendering speed: frames per second at 640x480 with the headless backend (software EGL here),
median of --repeats runs over the recorded frames of one trial, and the video time of a default
trial (simulate + render + encode) for each --objects entry.

Run: .venv/bin/python scripts/bench_render.py [--repeats 3] [--objects block]
"""

import argparse
import os
import statistics
import tempfile
import time

import gripper  # noqa: F401  (registers the environments; the GL backend is chosen at the first render)
from gripper.experiments.trial import run_trial
from gripper.render.video import FrameRecorder, record_trial_video, render_frames


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--objects", default="block")
    ap.add_argument("--camera", default="front")
    args = ap.parse_args()
    print(f"MUJOCO_GL={os.environ.get('MUJOCO_GL')}")
    rec = FrameRecorder(fps=30)
    run_trial("block", 0, 0, frame_sink=rec)
    rates = []
    for _ in range(args.repeats):
        t0 = time.perf_counter()
        frames = render_frames(rec, width=640, height=480, camera=args.camera, overlay=True)
        rates.append(len(frames) / (time.perf_counter() - t0))
    print(f"render 640x480 ({len(frames)} frames, overlay on): median {statistics.median(rates):.1f} frames/s "
          f"(runs {', '.join(f'{r:.1f}' for r in rates)})")
    with tempfile.TemporaryDirectory() as tmp:
        for name in args.objects.split(","):
            t0 = time.perf_counter()
            res = record_trial_video(name, os.path.join(tmp, f"{name}.mp4"), camera=args.camera)
            total = time.perf_counter() - t0
            print(f"{name:<10} video of a default trial: {total:.1f} s ({res['frames']} frames: simulate "
                  f"{res['simulate_s']:.1f} s, render {res['render_s']:.1f} s, encode {res['encode_s']:.1f} s)")


if __name__ == "__main__":
    main()
