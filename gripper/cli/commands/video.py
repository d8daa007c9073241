"""``gripper video``: render one scripted trial."""

from __future__ import annotations

from gripper.cli.inputs import (
    PIXELS,
    TRIALS_MAX,
    number,
    seed_option,
)
from gripper.cli.options import (
    EXIT_UNSTABLE,
    design,
    object_specs,
    protocol_and_noise,
    with_params,
    with_protocol,
)
from gripper.core.atomic import check_output_file


def add(sub) -> None:
    from gripper.objects.library import DEFAULT_OBJECTS
    from gripper.render.renderer import CAMERAS

    v = with_protocol(with_params(sub.add_parser(
        "video", help="render one scripted trial to MP4 or GIF (headless)",
        description="Run one scripted grasp trial (the benchmark's protocol and options), record its "
                    "state at the video rate and render it offscreen with MuJoCo (MUJOCO_GL=egl by "
                    "default), then write H.264 MP4 or GIF with mediapy.")))
    v.add_argument("--object", required=True, help="object name (" + ", ".join(DEFAULT_OBJECTS) + ") or mesh:PATH")
    seed_option(v, default=0)
    number(v, "--index", int, lo=0, hi=TRIALS_MAX - 1, default=0, help="trial index within the seed")
    v.add_argument("--out", required=True, metavar="FILE", help="output .mp4 or .gif")
    v.add_argument("--camera", default="front", help="camera preset: " + ", ".join(CAMERAS) + " (default front)")
    number(v, "--width", int, lo=PIXELS[0], hi=PIXELS[1], default=640, help="pixels")
    number(v, "--height", int, lo=PIXELS[0], hi=PIXELS[1], default=480, help="pixels")
    number(v, "--fps", float, lo=1, hi=240, default=30.0, help="frames per second")
    v.add_argument("--no-overlay", action="store_true", help="no text overlay (phase, time, cable tensions)")
    v.add_argument("--still", metavar="FILE.png", help="also write the first frame of the hold phase as PNG")
    v.set_defaults(func=run)


def run(args) -> int:
    from gripper.experiments.approach import check_fits_opening
    from gripper.objects.library import get_object
    from gripper.render.video import VIDEO_SUFFIXES, record_trial_video

    check_output_file(args.out, "--out", VIDEO_SUFFIXES)
    if args.still:
        check_output_file(args.still, "--still", (".png",))
    params = design(args)
    proto, noise = protocol_and_noise(args, params)
    obj = check_fits_opening(get_object(object_specs(args.object, "--object")[0]), params)
    res = record_trial_video(obj, args.out, seed=args.seed, index=args.index, params=params,
                             protocol=proto, noise=noise, width=args.width, height=args.height, fps=args.fps,
                             camera=args.camera, overlay=not args.no_overlay, still=args.still,
                             on_progress=lambda msg: print(msg, flush=True))  # stdout: stderr is for errors
    outcome = "error" if res["status"] == "error" else ("success" if res["success"] else
                                                        f"failed ({res['failed_phase']})")
    print(f"{res['trial_id']}: {outcome}; wrote {res['video']} ({res['frames']} frames, "
          f"{res['width']}x{res['height']} at {res['fps']:g} fps); simulate {res['simulate_s']:.1f} s, "
          f"render {res['render_s']:.1f} s ({res['render_fps']:.1f} frames/s), encode {res['encode_s']:.1f} s")
    return EXIT_UNSTABLE if res["status"] == "error" else 0
