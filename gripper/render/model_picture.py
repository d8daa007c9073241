"""The picture in each committed model's README (``models/<name>/<name>.png``): the gripper of
the committed ``scene.xml`` over the library's block, its fingers half closed.

The scene is the trials' (:func:`gripper.sim.scene.grasp_scene_spec` with the block); every
finger's drive is set to half its command range and the model is stepped 1 s, so the fingers
show how they curl; then it is drawn from a free camera beside the palm, multisampled.

Example:
    >>> from gripper.render.model_picture import write_model_picture
    >>> write_model_picture(GripperParams(), "soft_gripper.png")    # doctest: +SKIP
"""

from __future__ import annotations

from pathlib import Path

from gripper.core.params import GripperParams
from gripper.drives import drive_for
from gripper.render.renderer import FreeView, SceneRenderer

SETTLE_S = 1.0  # s at half command before the picture
SIZE = (640, 420)  # px


def write_model_picture(params: GripperParams, out: str | Path) -> Path:
    """Render the gripper of ``params`` (see the module docstring) to the PNG ``out``."""
    import mediapy
    import mujoco

    from gripper.sim.scene import grasp_scene_spec, trial_params

    p = trial_params(params)
    m = grasp_scene_spec(p, with_object=True).compile()
    d = mujoco.MjData(m)
    act = drive_for(p).actuator_ids(m)
    d.ctrl[act] = 0.5 * m.actuator_ctrlrange[act, 1]
    mujoco.mj_step(m, d, int(round(SETTLE_S / m.opt.timestep)))
    palm = d.xpos[m.body("palm").id]
    view = FreeView(lookat=(float(palm[0]), float(palm[1]), float(palm[2]) - 0.1), distance=0.42,
                    azimuth=130.0, elevation=-14.0)
    r = SceneRenderer(m, width=SIZE[0], height=SIZE[1], camera="front", view=view, antialias=True)
    try:
        out = Path(out)
        mediapy.write_image(str(out), r.render(d))
    finally:
        r.close()
    return out


__all__ = ["write_model_picture"]
