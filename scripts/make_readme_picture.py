"""The README's picture: the balloon held after the lift, seen from just below the palm.

One scripted balloon trial (seed 0, trial 0) records its states at 10 frames/s; the first state
of the hold phase is drawn with a free camera aimed between the fingers, multisampled.

Run: MUJOCO_GL=egl .venv/bin/python scripts/make_readme_picture.py [--out docs/grasp.png]
"""

import argparse

import mediapy

import gripper  # noqa: F401  (registers the environments; the GL backend is chosen at the first render)
from gripper.experiments.trial import run_trial
from gripper.render.renderer import FreeView, SceneRenderer
from gripper.render.video import FrameRecorder


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="docs/grasp.png")
    ap.add_argument("--object", default="balloon")
    args = ap.parse_args()
    import mujoco  # after gripper: the GL backend is chosen first

    rec = FrameRecorder(fps=10.0)
    run_trial(args.object, 0, 0, frame_sink=rec)
    m = rec.model
    d = mujoco.MjData(m)
    mujoco.mj_setState(m, d, rec.states[rec.phases.index("hold")], mujoco.mjtState.mjSTATE_FULLPHYSICS)
    mujoco.mj_forward(m, d)
    palm = d.xpos[m.body("palm").id]
    view = FreeView(lookat=(float(palm[0]), float(palm[1]), float(palm[2]) - 0.06), distance=0.26,
                    azimuth=120.0, elevation=-8.0)
    r = SceneRenderer(m, width=800, height=520, camera="top", view=view, antialias=True, shadow_size=2048)
    try:
        mediapy.write_image(args.out, r.render(d))
    finally:
        r.close()
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
